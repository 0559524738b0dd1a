//! The independent baseline of `npr bench overhead`: a hand-written wgpu
//! program that draws a compiled style's WGSL passes at one output size.
//! It creates its own buffers, textures, views, samplers, layouts,
//! pipelines and bind groups with plain wgpu calls and shares no object and
//! no code with `npr_runner::exec`; it reads only the ABI (the manifest,
//! `npr_abi::FrameBlock`, `npr_abi::ObjectHead`) and the scene's CPU data (meshes,
//! model matrices, camera, light).
//!
//! Each frame ([`Baseline::frame`]) does what a program written for this
//! style would do: write the frame block and the object blocks (one
//! `write_buffer` each, into buffers made once), record every pass into one
//! encoder (render passes: one draw per object with its vertex buffers and
//! its block at a dynamic offset; image passes: one fullscreen triangle)
//! and submit. Nothing is allocated on the heap per frame except the
//! command encoder wgpu makes. The style block is written once, or every
//! frame when a parameter in it is animated.
//!
//! Only what `examples/rounded_shadows.npr` needs (and a little more) is
//! supported; `support.rs` says what is refused, `setup.rs` builds the wgpu
//! objects, `uniforms.rs` fills the blocks.

use super::setup::{self, Mesh};
use super::{support, uniforms, OverheadError};
use glam::Mat4;
use npr_abi::manifest::*;
use npr_abi::{Format, StyleProgram};
use npr_runner::scene::Scene;
use npr_runner::TargetImage;
use std::collections::BTreeMap;

/// Colour attachments one pass may have (the device's limit is at least 8).
const MAX_OUTPUTS: usize = 8;

enum Draw {
    /// A render pass: these objects, with these vertex attributes in location order.
    Objects {
        objects: Vec<usize>,
        attributes: Vec<Attribute>,
    },
    /// An image pass: one triangle over the viewport.
    Fullscreen,
}

struct Pass {
    name: String,
    pipeline: wgpu::RenderPipeline,
    group0: wgpu::BindGroup,
    outputs: Vec<wgpu::TextureView>,
    depth: Option<wgpu::TextureView>,
    clear: wgpu::Color,
    draw: Draw,
}

pub struct Baseline<'d> {
    device: &'d wgpu::Device,
    queue: &'d wgpu::Queue,
    size: (u32, u32),
    passes: Vec<Pass>,
    meshes: Vec<Mesh>,
    /// One texture per logical target (no aliasing), at its scaled size.
    targets: Vec<wgpu::Texture>,
    output: usize,
    output_format: Format,
    frame_buffer: wgpu::Buffer,
    /// `None` when the style has no style block.
    style_buffer: Option<wgpu::Buffer>,
    /// The style block, rewritten every frame when it is animated.
    style_bytes: Vec<u8>,
    style_animated: bool,
    /// For the parameters' keyframes.
    manifest: Manifest,
    object_buffer: wgpu::Buffer,
    object_group: wgpu::BindGroup,
    object_stride: u64,
    /// The object blocks, rewritten in place every frame.
    object_bytes: Vec<u8>,
    /// Per object, its parameter slots (constant: copied after the head).
    object_params: Vec<Vec<u8>>,
    light_view_proj: Mat4,
    /// The previous frame's view-projection and models (`previous_*`).
    previous: Option<(Mat4, Vec<Mat4>)>,
}

impl<'d> Baseline<'d> {
    /// Build everything for `program` on `scene` at `size`; what the baseline
    /// does not support is [`OverheadError::Unsupported`].
    pub fn new(
        device: &'d wgpu::Device,
        queue: &'d wgpu::Queue,
        program: &StyleProgram,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Baseline<'d>, OverheadError> {
        program
            .validate()
            .map_err(|e| OverheadError::Wgpu(format!("the compiled style is inconsistent: {e}")))?;
        let m = &program.manifest;
        support::check(m, scene).map_err(OverheadError::Unsupported)?;
        if scene.objects.is_empty() || m.passes.is_empty() {
            return Err(OverheadError::Unsupported(
                "a scene without objects or a style without passes".into(),
            ));
        }
        if let Some(pass) = m.passes.iter().find(|p| p.outputs.len() > MAX_OUTPUTS) {
            return Err(OverheadError::Unsupported(format!(
                "more than {MAX_OUTPUTS} outputs (pass `{}`)",
                pass.name
            )));
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let targets: Vec<wgpu::Texture> = m
            .targets
            .iter()
            .map(|t| {
                setup::texture(
                    device,
                    &t.name,
                    setup::scaled(size, t.scale),
                    setup::texture_format(t.format),
                )
            })
            .collect();
        let uniform = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        let buffer = |label: &str, size: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: uniform,
                mapped_at_creation: false,
            })
        };
        let frame_buffer = buffer("frame", FRAME_UNIFORM_SIZE);
        let mut style_bytes = vec![0u8; m.style_uniform_size as usize];
        uniforms::style_block(m, 0.0, size.1, &mut style_bytes);
        let style_buffer = (!style_bytes.is_empty()).then(|| buffer("style", style_bytes.len() as u64));
        if let Some(b) = &style_buffer {
            queue.write_buffer(b, 0, &style_bytes);
        }
        let object_size = m.object_uniform_size.max(16);
        let object_stride = object_stride(m.object_uniform_size);
        let object_buffer = buffer("objects", object_stride * scene.objects.len() as u64);
        let (object_layout, object_group) = setup::object_group(device, &object_buffer, object_size);
        let linear_clamp = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let mut read_attributes: Vec<Attribute> = m
            .passes
            .iter()
            .filter_map(|p| match &p.kind {
                PassKindManifest::Render { attributes, .. } => Some(attributes.iter().copied()),
                _ => None,
            })
            .flatten()
            .collect();
        read_attributes.sort();
        read_attributes.dedup();
        let meshes: Vec<Mesh> = scene
            .objects
            .iter()
            .map(|o| setup::upload_mesh(device, &o.mesh, &read_attributes))
            .collect();
        let resources = setup::Group0Resources {
            frame: &frame_buffer,
            style: style_buffer.as_ref(),
            linear_clamp: &linear_clamp,
            targets: &targets,
        };
        let mut depth: BTreeMap<(u32, u32), wgpu::Texture> = BTreeMap::new();
        let mut passes = Vec::new();
        for pass in &m.passes {
            let (layout0, group0) = setup::group0(device, pass, &resources)?;
            let wgsl = &program.shaders[&pass.shader];
            let (draw, pipeline, depth_view) = match &pass.kind {
                PassKindManifest::Render { tag, attributes, .. } => {
                    let layouts = [Some(&layout0), Some(&object_layout)];
                    let pipeline = setup::pipeline(device, m, pass, wgsl, &layouts, Some(attributes))?;
                    let objects = (0..scene.objects.len())
                        .filter(|i| tag.as_ref().is_none_or(|t| scene.objects[*i].has_tag(t)))
                        .collect();
                    let pass_size = setup::scaled(size, pass.scale);
                    let depth_view = depth
                        .entry(pass_size)
                        .or_insert_with(|| {
                            setup::texture(device, "depth", pass_size, wgpu::TextureFormat::Depth32Float)
                        })
                        .create_view(&Default::default());
                    let draw = Draw::Objects {
                        objects,
                        attributes: attributes.clone(),
                    };
                    (draw, pipeline, Some(depth_view))
                }
                _ => {
                    let pipeline = setup::pipeline(device, m, pass, wgsl, &[Some(&layout0)], None)?;
                    (Draw::Fullscreen, pipeline, None)
                }
            };
            let [r, g, b, a] = pass.clear;
            passes.push(Pass {
                name: pass.name.clone(),
                pipeline,
                group0,
                outputs: pass
                    .outputs
                    .iter()
                    .map(|t| targets[*t].create_view(&Default::default()))
                    .collect(),
                depth: depth_view,
                clear: wgpu::Color { r, g, b, a },
                draw,
            });
        }
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(OverheadError::Wgpu(format!(
                "wgpu rejected the baseline's objects: {e}"
            )));
        }
        let (scene_lo, scene_hi) = scene.bounds();
        // No `view(light)` pass: the light camera covers the whole scene.
        let light_view_proj =
            npr_runner::scene::light_view_proj(scene.light.direction, (scene_lo, scene_hi), (scene_lo, scene_hi));
        Ok(Baseline {
            device,
            queue,
            size,
            passes,
            meshes,
            output: m.output,
            output_format: m.targets[m.output].format,
            targets,
            frame_buffer,
            style_animated: uniforms::style_is_animated(m),
            manifest: m.clone(),
            style_buffer,
            style_bytes,
            object_bytes: vec![0; (object_stride * scene.objects.len() as u64) as usize],
            object_params: scene.objects.iter().map(|o| uniforms::object_params(m, o)).collect(),
            object_buffer,
            object_group,
            object_stride,
            light_view_proj,
            previous: None,
        })
    }

    /// One frame at `time_s`: write the uniform blocks, record every pass,
    /// submit (the caller waits). `scene` must be the one the
    /// baseline was built for; its camera and model matrices are read again.
    pub fn frame(&mut self, scene: &Scene, time_s: f64, frame_index: u32) {
        self.write_uniforms(scene, time_s, frame_index);
        let commands = self.record();
        self.queue.submit([commands]);
    }

    /// The first step of [`Baseline::frame`]: the frame, object and
    /// (animated) style blocks, each with one `write_buffer`.
    pub fn write_uniforms(&mut self, scene: &Scene, time_s: f64, frame_index: u32) {
        let previous = self.previous.take();
        let block = uniforms::frame_block(
            scene,
            self.size,
            time_s,
            frame_index,
            self.light_view_proj,
            previous.as_ref().map(|p| p.0),
        );
        let stride = self.object_stride as usize;
        for (index, (o, block)) in scene
            .objects
            .iter()
            .zip(self.object_bytes.chunks_exact_mut(stride))
            .enumerate()
        {
            let previous_model = previous.as_ref().and_then(|p| p.1.get(index).copied());
            let head = uniforms::object_head(o.model, previous_model, index, o.mesh.vertex_count());
            let head = bytemuck::bytes_of(&head);
            block[..head.len()].copy_from_slice(head);
            let params = &self.object_params[index];
            block[head.len()..head.len() + params.len()].copy_from_slice(params);
        }
        // Keep this frame's for the next one, reusing the previous allocation.
        let mut models = previous.map(|p| p.1).unwrap_or_default();
        models.clear();
        models.extend(scene.objects.iter().map(|o| o.model));
        self.previous = Some((glam::Mat4::from_cols_array_2d(&block.view_proj), models));
        self.queue
            .write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&block));
        self.queue.write_buffer(&self.object_buffer, 0, &self.object_bytes);
        if let (true, Some(buffer)) = (self.style_animated, &self.style_buffer) {
            uniforms::style_block(&self.manifest, time_s, self.size.1, &mut self.style_bytes);
            self.queue.write_buffer(buffer, 0, &self.style_bytes);
        }
    }

    /// The second step of [`Baseline::frame`]: every pass recorded into
    /// one command buffer, for the caller to submit.
    pub fn record(&self) -> wgpu::CommandBuffer {
        let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("baseline frame"),
        });
        for pass in &self.passes {
            self.encode(&mut encoder, pass);
        }
        encoder.finish()
    }

    fn encode(&self, encoder: &mut wgpu::CommandEncoder, pass: &Pass) {
        let attachments: [Option<wgpu::RenderPassColorAttachment>; MAX_OUTPUTS] = std::array::from_fn(|i| {
            pass.outputs.get(i).map(|view| wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(pass.clear),
                    store: wgpu::StoreOp::Store,
                },
            })
        });
        let mut rp = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&pass.name),
            color_attachments: &attachments[..pass.outputs.len()],
            depth_stencil_attachment: pass.depth.as_ref().map(|view| wgpu::RenderPassDepthStencilAttachment {
                view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        rp.set_pipeline(&pass.pipeline);
        rp.set_bind_group(0, &pass.group0, &[]);
        match &pass.draw {
            Draw::Fullscreen => rp.draw(0..3, 0..1),
            Draw::Objects { objects, attributes } => {
                for &oi in objects {
                    let mesh = &self.meshes[oi];
                    rp.set_bind_group(1, &self.object_group, &[(oi as u64 * self.object_stride) as u32]);
                    for (slot, a) in attributes.iter().enumerate() {
                        rp.set_vertex_buffer(slot as u32, mesh.vertices[a].slice(..));
                    }
                    rp.set_index_buffer(mesh.index.slice(..), wgpu::IndexFormat::Uint32);
                    rp.draw_indexed(0..mesh.index_count, 0, 0..1);
                }
            }
        }
    }

    /// Read the style's output target back (after a frame).
    pub fn read_output(&self) -> Result<TargetImage, OverheadError> {
        let t = &self.targets[self.output];
        npr_runner::readback::read_texture(
            self.device,
            self.queue,
            t,
            t.width(),
            t.height(),
            self.output_format,
            "baseline output",
        )
        .map_err(OverheadError::Run)
    }
}
