//! The executor of `render(tag)` passes: draws every object (with the tag;
//! which ones is found once per scene, [`RenderScene`]) with its own vertex buffers, one object block per draw at a
//! dynamic offset into group 1, into the pass's targets and a depth buffer:
//! its own, cleared per pass (stored with `depth: keep`), or with `depth:
//! test(other)` the one `other` kept, loaded and tested, never written. A
//! pass that reads `patch.weight` draws each blended patch over its faces
//! and n-ring (Breslav et al. 2007 §3.6), every other pass its own faces.
//!
//! The draws are the same every frame until the size or the scene changes
//! (only the buffers' contents move): they are recorded once into a render
//! bundle ([`RenderPassExec::record_draws`], kept in the `SizedPass`) that
//! each frame's pass executes. wgpu validates a bundle's commands when it
//! is made, so a frame's pass records one command instead of two per
//! object, and `finish` replays them without validating them again
//! (decision 0048; docs/PERFORMANCE.md, "Sixth round").

use super::bind::{self, ObjectResources};
use super::common::{self, EncodeContext, Timestamps};
use super::meshes::attribute_format;
use super::sized::SizedPass;
use crate::gpu_count::Create;
use crate::RunError;
use npr_abi::manifest::*;

pub(super) struct RenderPassExec {
    name: String,
    clear: wgpu::Color,
    /// Draw only objects with this tag; `None` draws every object.
    tag: Option<String>,
    /// Vertex attributes in location order (one buffer each).
    attributes: Vec<Attribute>,
    /// The formats of the pass's outputs, as its pipeline was made for
    /// (a bundle states the attachments it draws into).
    color_formats: Vec<Option<wgpu::TextureFormat>>,
    pipeline: wgpu::RenderPipeline,
    /// What happens to the depth attachment at the beginning and end of the pass.
    depth_ops: wgpu::Operations<f32>,
    pub(super) layout0: wgpu::BindGroupLayout,
    /// The pass's own group 1 layout when it reads per-object textures
    /// (`bind::pass_object_layout`): the pipeline's, kept for the groups of
    /// every scene.
    object_layout: Option<wgpu::BindGroupLayout>,
    /// The scene's part, made by [`RenderPassExec::bind_scene`].
    scene: RenderScene,
}

/// What one scene gives a render pass.
#[derive(Default)]
pub(super) struct RenderScene {
    /// Per object: group 1 with the object's uniforms and its per-object
    /// textures; empty when the pass reads no such texture (it uses the
    /// shared group, `EncodeContext::object_group`).
    object_groups: Vec<wgpu::BindGroup>,
    /// The objects the pass draws (those with its tag), in scene order:
    /// found once per scene rather than by comparing tags every frame.
    drawn: Vec<usize>,
}

/// The pipeline's depth state and the attachment's operations of a depth
/// mode. Own and kept depths are cleared to 1 and written where a fragment
/// is nearer (`Less`); only a kept one is stored. A test loads the kept
/// depth and passes fragments at or in front of it (`LessEqual`, so the
/// same surface drawn again passes), writes nothing (the kept depth stays
/// the scene's for every pass that tests it, and what a test pass draws
/// never hides itself), and stores it unchanged; `bias: N px` is the
/// slope-scaled bias (towards the camera, so negative in wgpu's terms).
fn depth_state(mode: &DepthMode) -> (wgpu::DepthStencilState, wgpu::Operations<f32>) {
    let (write, compare, bias, load, store) = match mode {
        DepthMode::Own => (
            true,
            wgpu::CompareFunction::Less,
            wgpu::DepthBiasState::default(),
            wgpu::LoadOp::Clear(1.0),
            wgpu::StoreOp::Discard,
        ),
        DepthMode::Keep => (
            true,
            wgpu::CompareFunction::Less,
            wgpu::DepthBiasState::default(),
            wgpu::LoadOp::Clear(1.0),
            wgpu::StoreOp::Store,
        ),
        DepthMode::Test { bias_px, .. } | DepthMode::TestInput { bias_px, .. } => (
            false,
            wgpu::CompareFunction::LessEqual,
            wgpu::DepthBiasState {
                constant: 0,
                slope_scale: -(*bias_px as f32),
                clamp: 0.0,
            },
            wgpu::LoadOp::Load,
            wgpu::StoreOp::Store,
        ),
    };
    (
        wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(write),
            depth_compare: Some(compare),
            stencil: Default::default(),
            bias,
        },
        wgpu::Operations { load, store },
    )
}

impl RenderPassExec {
    pub fn build(
        device: &wgpu::Device,
        manifest: &Manifest,
        pass: &PassManifest,
        shader: common::PassShader,
        (tag, attributes): (Option<&String>, &[Attribute]),
        depth_mode: &DepthMode,
        shared_object_layout: &wgpu::BindGroupLayout,
    ) -> Result<RenderPassExec, RunError> {
        let layout0 = bind::group0_layout(device, pass);
        let own_layout = bind::pass_object_layout(device, pass, manifest.object_uniform_size);
        let vertex_attrs: Vec<[wgpu::VertexAttribute; 1]> = attributes
            .iter()
            .enumerate()
            .map(|(loc, a)| {
                [wgpu::VertexAttribute {
                    format: attribute_format(*a).0,
                    offset: 0,
                    shader_location: loc as u32,
                }]
            })
            .collect();
        let buffers: Vec<Option<wgpu::VertexBufferLayout>> = attributes
            .iter()
            .zip(&vertex_attrs)
            .map(|(a, attrs)| {
                Some(wgpu::VertexBufferLayout {
                    array_stride: attribute_format(*a).1,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: attrs,
                })
            })
            .collect();
        let (depth, depth_ops) = depth_state(depth_mode);
        let pipeline = common::render_pipeline(
            device,
            manifest,
            pass,
            shader,
            &[&layout0, own_layout.as_ref().unwrap_or(shared_object_layout)],
            &buffers,
            Some(depth),
        )?;
        Ok(RenderPassExec {
            name: pass.name.clone(),
            clear: common::clear_color(pass),
            tag: tag.cloned(),
            attributes: attributes.to_vec(),
            color_formats: pass
                .outputs
                .iter()
                .map(|t| Some(super::sized::wgpu_format(manifest.targets[*t].format)))
                .collect(),
            pipeline,
            depth_ops,
            layout0,
            object_layout: own_layout,
            scene: RenderScene::default(),
        })
    }

    /// The pass's group 1 per object of `objects`' scene, made with the
    /// layout its pipeline was built with (a scene change keeps the
    /// pipeline), and the objects it draws.
    pub fn bind_scene(
        &self,
        device: &wgpu::Device,
        pass: &PassManifest,
        objects: &ObjectResources,
    ) -> Result<RenderScene, RunError> {
        let drawn = objects
            .scene
            .objects
            .iter()
            .enumerate()
            .filter(|(_, o)| self.tag.as_ref().is_none_or(|tag| o.has_tag(tag)))
            .map(|(i, _)| i)
            .collect();
        Ok(RenderScene {
            object_groups: bind::pass_object_groups(device, pass, self.object_layout.as_ref(), objects)?,
            drawn,
        })
    }

    /// Take the part [`RenderPassExec::bind_scene`] made.
    pub fn set_scene(&mut self, scene: RenderScene) {
        self.scene = scene;
    }

    /// The pass's draws for `sized` and the current scene, as a render
    /// bundle that [`RenderPassExec::encode`] executes every frame until
    /// the size or the scene changes.
    pub fn record_draws(&self, device: &wgpu::Device, sized: &SizedPass, ctx: &EncodeContext) -> wgpu::RenderBundle {
        let mut bundle = device.make_render_bundle_encoder(&wgpu::RenderBundleEncoderDescriptor {
            label: Some(&self.name),
            color_formats: &self.color_formats,
            // The pass's depth attachment is written or loaded and stored
            // (`depth_state`), never read-only.
            depth_stencil: sized.depth_view.as_ref().map(|_| wgpu::RenderBundleDepthStencil {
                format: wgpu::TextureFormat::Depth32Float,
                depth_read_only: false,
                stencil_read_only: true,
            }),
            sample_count: 1,
            multiview: None,
        });
        self.draw(&mut bundle, sized, ctx);
        bundle.finish(&wgpu::RenderBundleDescriptor {
            label: Some(&self.name),
        })
    }

    /// Set the pipeline and groups and draw every object the pass draws.
    fn draw<'a>(&'a self, rp: &mut impl wgpu::util::RenderEncoder<'a>, sized: &'a SizedPass, ctx: &EncodeContext<'a>) {
        rp.set_pipeline(&self.pipeline);
        rp.set_bind_group(0, Some(&sized.group0), &[]);
        // The index buffer of the mesh whose buffers the pass holds: objects
        // of one mesh share its buffers (`meshes.rs`), bound once for a run of them.
        let mut bound: Option<&wgpu::Buffer> = None;
        for &oi in &self.scene.drawn {
            let Some(mesh) = ctx.meshes.get(oi) else { continue };
            // §3.6: a pass reading `patch.weight` draws a blended patch over its n-ring.
            let mesh = mesh.drawn_by(&self.attributes);
            let group = self.scene.object_groups.get(oi).unwrap_or(ctx.object_group);
            rp.set_bind_group(1, Some(group), &[(oi as u64 * ctx.object_stride) as u32]);
            if bound != Some(&mesh.index) {
                for (slot, a) in self.attributes.iter().enumerate() {
                    if let Some(buf) = mesh.buffers.get(a) {
                        rp.set_vertex_buffer(slot as u32, Some(buf.slice(..)));
                    }
                }
                rp.set_index_buffer(mesh.index.slice(..), wgpu::IndexFormat::Uint32);
                bound = Some(&mesh.index);
            }
            rp.draw_indexed(0..mesh.index_count, 0, 0..1);
        }
    }

    /// Begin the pass and execute its recorded draws; a pass encoded
    /// without them (`Renderer::encode` called with no `prepare` after a
    /// scene change) records the same draws into the pass itself.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        sized: &SizedPass,
        ctx: &EncodeContext,
        timestamps: Option<&Timestamps>,
    ) {
        let depth = sized.depth_view.as_ref().map(|v| (v, self.depth_ops));
        let mut rp = common::begin_render_pass(encoder, &self.name, self.clear, sized, depth, timestamps);
        match &sized.draws {
            Some(draws) => rp.execute_bundles([draws]),
            None => self.draw(&mut rp, sized, ctx),
        }
    }
}
