//! Execute a compiled style on wgpu: pipelines, targets, uniforms, draws,
//! and read-back.
//!
//! A [`Renderer`] borrows a device and queue, so it works in someone else's
//! wgpu application as well as headless. It builds every pipeline once (the
//! cache lives as long as the renderer), allocates the physical textures of
//! the manifest (aliased targets share one), and re-allocates only when the
//! output size changes.

use crate::scene::{Mesh, Scene};
use crate::textures::{self, GpuTexture};
use crate::{animation, readback, RunError};
use abi::manifest::*;
use abi::{Format, FrameBlock};
use glam::Mat4;
use std::collections::BTreeMap;
use wgpu::util::DeviceExt;

pub const MAX_OUTPUT_SIZE: u32 = 16384;

/// Where and when to render.
#[derive(Debug, Clone, Copy)]
pub struct FrameSpec {
    pub width: u32,
    pub height: u32,
    pub time_s: f64,
    pub frame: u32,
    /// 0 = left (or mono), 1 = right.
    pub eye: u32,
}

impl FrameSpec {
    /// Frame 0 at t = 0 of `eye`, `width`×`height`: a still image.
    pub fn still(width: u32, height: u32, eye: u32) -> FrameSpec {
        FrameSpec {
            width,
            height,
            time_s: 0.0,
            frame: 0,
            eye,
        }
    }
}

struct GpuMesh {
    buffers: BTreeMap<Attribute, wgpu::Buffer>,
    index: wgpu::Buffer,
    index_count: u32,
    vertex_count: usize,
    /// For a time-varying primitive: the time its vertices were built for.
    built_for_s: Option<f64>,
}

struct PassPipeline {
    pipeline: wgpu::RenderPipeline,
    layout0: wgpu::BindGroupLayout,
}

pub struct Renderer<'d> {
    device: &'d wgpu::Device,
    queue: &'d wgpu::Queue,
    pub manifest: Manifest,
    pipelines: Vec<PassPipeline>,
    object_group: wgpu::BindGroup,
    /// Per pass, per object: group 1 with the object's uniforms and its
    /// per-object textures; empty for passes that read no such texture
    /// (they share `object_group`).
    pass_object_groups: Vec<Vec<wgpu::BindGroup>>,
    textures: Vec<GpuTexture>,
    linear_clamp: wgpu::Sampler,
    meshes: Vec<GpuMesh>,
    /// One per eye rendered in a frame (two for stereo styles).
    frame_buffers: Vec<wgpu::Buffer>,
    style_buffer: wgpu::Buffer,
    object_buffer: wgpu::Buffer,
    object_stride: u64,
    object_params: Vec<Vec<u8>>,
    object_models: Vec<Mat4>,
    object_tags: Vec<Vec<String>>,
    /// World-space bounds of the scene, for the light camera's depth range.
    scene_bounds: (glam::Vec3, glam::Vec3),
    /// Bounds of what `view(light)` passes draw (the shadow casters): the
    /// light camera's x, y extent.
    caster_bounds: (glam::Vec3, glam::Vec3),
    sized: Option<SizedResources>,
}

/// Everything that depends on the output size, built once per size: the
/// physical textures, and per pass its attachment views, depth view and
/// bind group (so a frame only writes uniforms and records draws).
struct SizedResources {
    width: u32,
    height: u32,
    /// Per eye: the physical textures.
    physical: Vec<Vec<wgpu::Texture>>,
    /// Per eye: per pass, its views and bind group.
    passes: Vec<Vec<SizedPass>>,
    /// Which eye's textures hold the requested image (`FrameSpec::eye` for
    /// stereo styles, else 0).
    output_slot: usize,
}

struct SizedPass {
    color_views: Vec<wgpu::TextureView>,
    depth_view: Option<wgpu::TextureView>,
    group0: wgpu::BindGroup,
}

/// Size of a target at `scale` of the output: at least 1 px, rounded to nearest.
pub fn scaled_size(width: u32, height: u32, scale: f64) -> (u32, u32) {
    let s = |v: u32| ((v as f64 * scale).round() as u32).max(1);
    (s(width), s(height))
}

/// A single-sample, single-mip 2D texture.
fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

pub fn wgpu_format(f: Format) -> wgpu::TextureFormat {
    use wgpu::TextureFormat as T;
    match f {
        Format::R8unorm => T::R8Unorm,
        Format::Rg8unorm => T::Rg8Unorm,
        Format::Rgba8unorm => T::Rgba8Unorm,
        Format::Rgba8unormSrgb => T::Rgba8UnormSrgb,
        Format::R16float => T::R16Float,
        Format::Rg16float => T::Rg16Float,
        Format::Rgba16float => T::Rgba16Float,
        Format::R32float => T::R32Float,
        Format::Rg32float => T::Rg32Float,
        Format::Rgba32float => T::Rgba32Float,
    }
}

fn attribute_format(a: Attribute) -> (wgpu::VertexFormat, u64) {
    match a {
        Attribute::Position | Attribute::Normal => (wgpu::VertexFormat::Float32x3, 12),
        Attribute::Uv => (wgpu::VertexFormat::Float32x2, 8),
        Attribute::Tangent => (wgpu::VertexFormat::Float32x4, 16),
    }
}

/// E0403 for every object that lacks a vertex attribute the style reads.
pub fn check_scene(manifest: &Manifest, scene: &Scene) -> Vec<dsl::Diagnostic> {
    let required: Vec<crate::scene::Attribute> = manifest
        .scene_attributes
        .iter()
        .map(|a| match a {
            Attribute::Position => crate::scene::Attribute::Position,
            Attribute::Normal => crate::scene::Attribute::Normal,
            Attribute::Uv => crate::scene::Attribute::Uv,
            Attribute::Tangent => crate::scene::Attribute::Tangent,
        })
        .collect();
    let mut diags = scene.check_attributes(
        &required,
        &format!("style \"{}\" needs per-vertex data", manifest.style),
    );
    diags.extend(check_texture_bindings(manifest, scene));
    diags
}

/// E0405 where a scene binds an image to something that is not a per-object
/// texture param of the style, or a number or colour to one that is. Names
/// the style does not declare at all are left alone, as for numeric params
/// (one scene may serve several styles).
pub fn check_texture_bindings(manifest: &Manifest, scene: &Scene) -> Vec<dsl::Diagnostic> {
    use dsl::{codes, Diagnostic};
    let mut diags = Vec::new();
    let is_object_texture = |name: &str| manifest.textures.iter().any(|t| t.per_object && t.name == name);
    for o in &scene.objects {
        for (name, b) in &o.textures {
            if is_object_texture(name) {
                continue;
            }
            let what = if let Some(p) = manifest.params.iter().find(|p| p.name == *name) {
                format!("a {} param", p.ty)
            } else if manifest.textures.iter().any(|t| t.name == *name) {
                "a style-wide texture".to_string()
            } else {
                continue;
            };
            diags.push(
                Diagnostic::error(
                    codes::BAD_SCENE,
                    format!("object `{}` binds an image to `{name}`, which is {what}", o.name),
                )
                .with_primary(b.span, "an image binding")
                .with_help(format!(
                    "only `object param {name}: texture` params take images; give `{name}` a value of its type"
                )),
            );
        }
        for name in o.params.keys() {
            if !is_object_texture(name) {
                continue;
            }
            let mut d = Diagnostic::error(
                codes::BAD_SCENE,
                format!("object `{}` binds a value to texture param `{name}`", o.name),
            )
            .with_help(format!(
                "bind an image: `{name} = \"textures/file.png\"` or `{name} = {{ image = \"file.png\", srgb = false }}`"
            ));
            if let Some(s) = o.param_spans.get(name) {
                d = d.with_primary(*s, "not an image path");
            }
            diags.push(d);
        }
    }
    diags
}

impl<'d> Renderer<'d> {
    /// Build pipelines and upload the scene. Diagnostics (E0403, E0401, E0404)
    /// come back as `RunError::User`.
    pub fn new(
        device: &'d wgpu::Device,
        queue: &'d wgpu::Queue,
        program: &crate::StyleProgram,
        scene: &Scene,
    ) -> Result<Renderer<'d>, RunError> {
        let manifest = program.manifest.clone();
        let diags = check_scene(&manifest, scene);
        if !diags.is_empty() {
            return Err(RunError::User(diags));
        }
        let textures = textures::load_all(device, queue, &manifest)?;
        let linear_clamp = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("npr linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let object_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("npr object"),
            entries: &[object_uniform_entry(manifest.object_uniform_size)],
        });
        let object_textures = textures::load_object_textures(device, queue, &manifest, scene)?;
        let mut pipelines = Vec::new();
        let mut pass_object_layouts = Vec::new();
        for pass in &manifest.passes {
            let wgsl = program
                .shaders
                .get(&pass.shader)
                .ok_or_else(|| RunError::Internal(format!("no shader `{}` for pass `{}`", pass.shader, pass.name)))?;
            // A pass reading per-object textures gets its own group 1 layout:
            // the shared dynamic-offset uniform at binding 0, then its textures.
            let own_layout = (!pass.object_bindings.is_empty()).then(|| {
                let mut entries = vec![object_uniform_entry(manifest.object_uniform_size)];
                entries.extend(pass.object_bindings.iter().map(layout_entry));
                device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(&pass.name),
                    entries: &entries,
                })
            });
            pipelines.push(build_pipeline(
                device,
                &manifest,
                pass,
                wgsl,
                own_layout.as_ref().unwrap_or(&object_layout),
            )?);
            pass_object_layouts.push(own_layout);
        }
        let meshes = scene
            .objects
            .iter()
            .map(|o| {
                let mut gpu = upload_mesh(device, &o.mesh);
                // `Object::mesh` is a time-varying primitive's geometry at t = 0.
                gpu.built_for_s = o.time_varying.map(|_| 0.0);
                gpu
            })
            .collect();
        let object_stride = manifest.object_uniform_size.div_ceil(OBJECT_STRIDE_ALIGN).max(1) * OBJECT_STRIDE_ALIGN;
        let object_count = scene.objects.len().max(1) as u64;
        let object_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("npr objects"),
            size: object_stride * object_count,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut object_params = Vec::new();
        let mut diags = Vec::new();
        for o in &scene.objects {
            object_params.push(animation::object_param_bytes(&manifest, o, &mut diags));
        }
        if !diags.is_empty() {
            return Err(RunError::User(diags));
        }
        let eyes = if manifest.is_stereo() { 2 } else { 1 };
        let frame_buffers = (0..eyes)
            .map(|e| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("npr frame, eye slot {e}")),
                    size: FRAME_UNIFORM_SIZE,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let style_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("npr style params"),
            size: manifest.style_uniform_size.max(16),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let object_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("npr object"),
            layout: &object_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &object_buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(manifest.object_uniform_size.max(16)),
                }),
            }],
        });
        // One group 1 per (pass reading object textures, object): the object's
        // bound image where it binds one, the declared default otherwise.
        let object_size = wgpu::BufferSize::new(manifest.object_uniform_size.max(16));
        let mut pass_object_groups = Vec::new();
        for (pass, layout) in manifest.passes.iter().zip(&pass_object_layouts) {
            let Some(layout) = layout else {
                pass_object_groups.push(Vec::new());
                continue;
            };
            let mut groups = Vec::new();
            for (oi, o) in scene.objects.iter().enumerate() {
                let gpu = |texture: usize| match object_textures.bound[oi].get(&texture) {
                    Some(i) => &object_textures.images[*i],
                    None => &textures[texture],
                };
                let views: Vec<Option<wgpu::TextureView>> = pass
                    .object_bindings
                    .iter()
                    .map(|b| match b.resource {
                        Resource::Texture { texture } => Some(gpu(texture).texture.create_view(&Default::default())),
                        _ => None,
                    })
                    .collect();
                let mut entries = vec![wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &object_buffer,
                        offset: 0,
                        size: object_size,
                    }),
                }];
                for (b, view) in pass.object_bindings.iter().zip(&views) {
                    let resource = match (&b.resource, view) {
                        (Resource::TextureSampler { texture }, _) => {
                            wgpu::BindingResource::Sampler(&gpu(*texture).sampler)
                        }
                        (Resource::Texture { .. }, Some(view)) => wgpu::BindingResource::TextureView(view),
                        _ => {
                            return Err(RunError::Internal(format!(
                                "pass `{}`: group 1 binding {} is not a per-object texture or sampler",
                                pass.name, b.binding
                            )))
                        }
                    };
                    entries.push(wgpu::BindGroupEntry {
                        binding: b.binding,
                        resource,
                    });
                }
                groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&format!("{} / {}", pass.name, o.name)),
                    layout,
                    entries: &entries,
                }));
            }
            pass_object_groups.push(groups);
        }
        Ok(Renderer {
            device,
            queue,
            pipelines,
            object_group,
            pass_object_groups,
            textures,
            linear_clamp,
            meshes,
            frame_buffers,
            style_buffer,
            object_buffer,
            object_stride,
            object_params,
            object_models: scene.objects.iter().map(|o| o.model).collect(),
            object_tags: scene.objects.iter().map(|o| o.tags.clone()).collect(),
            scene_bounds: scene.bounds(),
            caster_bounds: {
                // Objects any light-view pass draws; all of them when such a pass has no tag.
                let tags: Vec<Option<&String>> = manifest
                    .passes
                    .iter()
                    .filter_map(|p| match &p.kind {
                        PassKindManifest::Render {
                            tag, light_view: true, ..
                        } => Some(tag.as_ref()),
                        _ => None,
                    })
                    .collect();
                let drawn = scene.bounds_of(|o| tags.iter().any(|t| t.is_none_or(|t| o.tags.contains(t))));
                if drawn.0.is_finite() {
                    drawn
                } else {
                    scene.bounds()
                }
            },
            manifest,
            sized: None,
        })
    }

    fn ensure_size(&mut self, width: u32, height: u32) {
        if self
            .sized
            .as_ref()
            .is_some_and(|s| s.width == width && s.height == height)
        {
            return;
        }
        let slots = self.frame_buffers.len();
        let physical: Vec<Vec<wgpu::Texture>> = (0..slots).map(|_| self.create_physical(width, height)).collect();
        let mut depth: BTreeMap<(u32, u32), wgpu::Texture> = BTreeMap::new();
        let mut passes: Vec<Vec<SizedPass>> = Vec::new();
        for slot in 0..slots {
            let mut slot_passes = Vec::new();
            for (pi, pass) in self.manifest.passes.iter().enumerate() {
                let (w, h) = scaled_size(width, height, pass.scale);
                let view_of_target =
                    |t: usize| physical[slot][self.manifest.targets[t].physical].create_view(&Default::default());
                let color_views = pass.outputs.iter().map(|t| view_of_target(*t)).collect();
                let depth_view = matches!(pass.kind, PassKindManifest::Render { .. }).then(|| {
                    depth
                        .entry((w, h))
                        .or_insert_with(|| {
                            texture_2d(
                                self.device,
                                "npr depth",
                                (w, h),
                                wgpu::TextureFormat::Depth32Float,
                                wgpu::TextureUsages::RENDER_ATTACHMENT,
                            )
                        })
                        .create_view(&Default::default())
                });
                let views: Vec<(u32, wgpu::TextureView)> = pass
                    .bindings
                    .iter()
                    .filter_map(|b| match &b.resource {
                        Resource::Target { target, other_eye, .. } => {
                            // The other eye's copy lives in the other slot (stereo styles only).
                            let from = if *other_eye { (slot + 1) % slots } else { slot };
                            Some((
                                b.binding,
                                physical[from][self.manifest.targets[*target].physical]
                                    .create_view(&Default::default()),
                            ))
                        }
                        Resource::Texture { texture } => Some((
                            b.binding,
                            self.textures[*texture].texture.create_view(&Default::default()),
                        )),
                        _ => None,
                    })
                    .collect();
                let entries: Vec<wgpu::BindGroupEntry> = pass
                    .bindings
                    .iter()
                    .filter_map(|b| {
                        let resource = match &b.resource {
                            Resource::FrameUniforms => self.frame_buffers[slot].as_entire_binding(),
                            Resource::StyleUniforms => self.style_buffer.as_entire_binding(),
                            Resource::Target { .. } | Resource::Texture { .. } => wgpu::BindingResource::TextureView(
                                views.iter().find(|(n, _)| *n == b.binding).map(|(_, v)| v)?,
                            ),
                            Resource::TextureSampler { texture } => {
                                wgpu::BindingResource::Sampler(&self.textures[*texture].sampler)
                            }
                            Resource::LinearClampSampler => wgpu::BindingResource::Sampler(&self.linear_clamp),
                        };
                        Some(wgpu::BindGroupEntry {
                            binding: b.binding,
                            resource,
                        })
                    })
                    .collect();
                let group0 = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&pass.name),
                    layout: &self.pipelines[pi].layout0,
                    entries: &entries,
                });
                slot_passes.push(SizedPass {
                    color_views,
                    depth_view,
                    group0,
                });
            }
            passes.push(slot_passes);
        }
        self.sized = Some(SizedResources {
            width,
            height,
            physical,
            passes,
            output_slot: 0,
        });
    }

    /// One physical texture per `manifest.physical` entry, at `width`×`height` × its scale.
    fn create_physical(&self, width: u32, height: u32) -> Vec<wgpu::Texture> {
        self.manifest
            .physical
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let (w, h) = scaled_size(width, height, p.scale);
                texture_2d(
                    self.device,
                    &format!("npr physical #{i}"),
                    (w, h),
                    wgpu_format(p.format),
                    wgpu::TextureUsages::RENDER_ATTACHMENT
                        | wgpu::TextureUsages::TEXTURE_BINDING
                        | wgpu::TextureUsages::COPY_SRC,
                )
            })
            .collect()
    }

    /// The `Frame` uniform block of `eye` (`abi::FrameBlock`, `struct Frame` in WGSL).
    fn frame_block(&self, scene: &Scene, spec: &FrameSpec, eye: u32) -> FrameBlock {
        let pose = scene.camera.pose(spec.time_s);
        let aspect = spec.width as f32 / spec.height as f32;
        let view = pose.view(eye);
        let proj = pose.projection(aspect);
        let view_proj = proj * view;
        let cam = pose.position(eye);
        let l = scene.light.direction.normalize_or_zero();
        let c = scene.light.color;
        let light_view_proj =
            crate::scene::light_view_proj(scene.light.direction, self.caster_bounds, self.scene_bounds);
        let other_view_proj = proj * pose.view(1 - eye.min(1));
        let (left, right, forward) = (pose.position(0), pose.position(1), pose.forward());
        FrameBlock {
            view: view.to_cols_array_2d(),
            proj: proj.to_cols_array_2d(),
            view_proj: view_proj.to_cols_array_2d(),
            camera_pos: [cam.x, cam.y, cam.z, 1.0],
            light_dir: [l.x, l.y, l.z, scene.light.intensity],
            light_color: [c[0], c[1], c[2], 1.0],
            resolution: [spec.width as f32, spec.height as f32],
            time: spec.time_s as f32,
            frame_index: spec.frame as f32,
            eye: eye as f32,
            near: pose.near,
            far: pose.far,
            _pad: 0.0,
            light_view_proj: light_view_proj.to_cols_array_2d(),
            other_view_proj: other_view_proj.to_cols_array_2d(),
            // Age of Sail §3.2: a single (centre) camera for T_s/B_s in stereo; §3.3 eq. 12: P₀₀, P₁₁.
            center_view_proj: (proj * pose.center_view()).to_cols_array_2d(),
            focal: [proj.x_axis.x, proj.y_axis.y, 0.0, 0.0],
            eye_left: [left.x, left.y, left.z, 1.0],
            eye_right: [right.x, right.y, right.z, 1.0],
            camera_forward: [forward.x, forward.y, forward.z, 0.0],
        }
    }

    /// Write the per-frame, style and object uniforms for `spec`.
    fn write_uniforms(&self, scene: &Scene, spec: &FrameSpec) {
        let slots = self.frame_buffers.len() as u32;
        for slot in 0..slots {
            // A stereo style renders both eyes; otherwise the requested one.
            let eye = if slots == 2 { slot } else { spec.eye };
            let frame = self.frame_block(scene, spec, eye);
            self.queue
                .write_buffer(&self.frame_buffers[slot as usize], 0, bytemuck::bytes_of(&frame));
        }
        let style = animation::style_param_bytes(&self.manifest, spec.time_s, spec.height);
        if !style.is_empty() {
            self.queue.write_buffer(&self.style_buffer, 0, &style);
        }
        for (i, model) in self.object_models.iter().enumerate() {
            let normal_matrix = model.inverse().transpose();
            let normal_matrix = if normal_matrix.is_finite() {
                normal_matrix
            } else {
                Mat4::IDENTITY
            };
            let mut bytes: Vec<u8> = Vec::new();
            bytes.extend_from_slice(bytemuck::cast_slice(&model.to_cols_array()));
            bytes.extend_from_slice(bytemuck::cast_slice(&normal_matrix.to_cols_array()));
            bytes.extend_from_slice(&self.object_params[i]);
            self.queue
                .write_buffer(&self.object_buffer, i as u64 * self.object_stride, &bytes);
        }
    }

    /// Render one frame; every target stays on the GPU for [`Renderer::read_target`].
    pub fn render(&mut self, scene: &Scene, spec: &FrameSpec) -> Result<(), RunError> {
        self.prepare(scene, spec)?;
        let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("npr frame"),
        });
        self.encode(&mut encoder);
        self.queue.submit([encoder.finish()]);
        Ok(())
    }

    /// Record every pass of the style into `encoder` (after [`Renderer::prepare`]).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) {
        self.encode_passes(encoder, self.manifest.passes.len(), None);
    }

    /// Like [`Renderer::encode`], writing GPU timestamps at the beginning and
    /// end of pass `i` into `queries` slots `2i` and `2i + 1` (for benchmarks;
    /// the query set needs `2 × passes` slots and the device `TIMESTAMP_QUERY`).
    pub fn encode_timed(&self, encoder: &mut wgpu::CommandEncoder, queries: &wgpu::QuerySet) {
        self.encode_passes(encoder, self.manifest.passes.len(), Some(queries));
    }

    /// Size the targets and write the uniforms for `spec`; then [`Renderer::encode`]
    /// records the passes into your own command encoder.
    pub fn prepare(&mut self, scene: &Scene, spec: &FrameSpec) -> Result<(), RunError> {
        if spec.width == 0 || spec.height == 0 || spec.width > MAX_OUTPUT_SIZE || spec.height > MAX_OUTPUT_SIZE {
            return Err(RunError::Limit(format!(
                "image size {}x{} is outside 1..={MAX_OUTPUT_SIZE} (the 2D texture limit)",
                spec.width, spec.height
            )));
        }
        if self.frame_buffers.len() == 2 && spec.eye > 1 {
            return Err(RunError::Limit(format!(
                "eye {} does not exist: a stereo frame has eyes 0 and 1",
                spec.eye
            )));
        }
        self.ensure_size(spec.width, spec.height);
        if let Some(sized) = self.sized.as_mut() {
            sized.output_slot = if sized.physical.len() == 2 {
                spec.eye as usize
            } else {
                0
            };
        }
        self.update_time_varying_meshes(scene, spec.time_s)?;
        self.write_uniforms(scene, spec);
        Ok(())
    }

    /// Rebuilds the vertices of time-varying primitives (the ocean of Age of
    /// Sail §6.1) for `time_s` and writes them over the uploaded buffers; the
    /// vertex count and indices never change, so nothing is reallocated. A
    /// mesh already built for this time (another eye, a partial frame) is
    /// left alone.
    fn update_time_varying_meshes(&mut self, scene: &Scene, time_s: f64) -> Result<(), RunError> {
        for (index, object) in scene.objects.iter().enumerate() {
            let Some(primitive) = &object.time_varying else {
                continue;
            };
            let gpu = self.meshes.get_mut(index).ok_or_else(|| {
                RunError::Internal(format!(
                    "object `{}` is not in the scene this renderer was built for",
                    object.name
                ))
            })?;
            if gpu.built_for_s == Some(time_s) {
                continue;
            }
            let mesh = primitive.build_at(time_s);
            if mesh.vertex_count() != gpu.vertex_count || mesh.indices.len() as u32 != gpu.index_count {
                return Err(RunError::Internal(format!(
                    "object `{}` changed its vertex count over time ({} → {})",
                    object.name,
                    gpu.vertex_count,
                    mesh.vertex_count()
                )));
            }
            let write = |attribute: Attribute, bytes: &[u8]| {
                if let Some(buffer) = gpu.buffers.get(&attribute) {
                    self.queue.write_buffer(buffer, 0, bytes);
                }
            };
            write(Attribute::Position, bytemuck::cast_slice(&mesh.positions));
            write(Attribute::Normal, bytemuck::cast_slice(&mesh.normals));
            if let Some(uvs) = &mesh.uvs {
                write(Attribute::Uv, bytemuck::cast_slice(uvs));
            }
            if let Some(tangents) = &mesh.tangents {
                write(Attribute::Tangent, bytemuck::cast_slice(tangents));
            }
            gpu.built_for_s = Some(time_s);
        }
        Ok(())
    }

    /// Run the frame only up to (and including) the pass that writes `target`,
    /// and read it back: for targets whose texture a later pass reuses.
    pub fn render_until_target(
        &mut self,
        scene: &Scene,
        spec: &FrameSpec,
        target: usize,
    ) -> Result<readback::TargetImage, RunError> {
        let writer = self
            .manifest
            .passes
            .iter()
            .position(|p| p.outputs.contains(&target))
            .ok_or_else(|| RunError::Internal(format!("no pass writes target #{target}")))?;
        self.prepare(scene, spec)?;
        let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("npr partial frame"),
        });
        self.encode_passes(&mut encoder, writer + 1, None);
        self.queue.submit([encoder.finish()]);
        self.read_target(target)
    }

    fn encode_passes(&self, encoder: &mut wgpu::CommandEncoder, count: usize, queries: Option<&wgpu::QuerySet>) {
        let Some(sized) = self.sized.as_ref() else { return };
        // Stereo styles run each pass for both eyes before the next pass, so
        // a pass that reads `other_eye(...)` finds the other eye's target done.
        let slots = sized.passes.len();
        for (pi, pass) in self.manifest.passes.iter().enumerate().take(count) {
            for slot in 0..slots {
                let res = &sized.passes[slot][pi];
                let clear = wgpu::Color {
                    r: pass.clear[0],
                    g: pass.clear[1],
                    b: pass.clear[2],
                    a: pass.clear[3],
                };
                let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = res
                    .color_views
                    .iter()
                    .map(|v| {
                        Some(wgpu::RenderPassColorAttachment {
                            view: v,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Clear(clear),
                                store: wgpu::StoreOp::Store,
                            },
                        })
                    })
                    .collect();
                let mut rp = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&pass.name),
                    color_attachments: &attachments,
                    depth_stencil_attachment: res.depth_view.as_ref().map(|v| wgpu::RenderPassDepthStencilAttachment {
                        view: v,
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Discard,
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes: queries.map(|query_set| wgpu::RenderPassTimestampWrites {
                        query_set,
                        beginning_of_pass_write_index: (slot == 0).then_some(2 * pi as u32),
                        end_of_pass_write_index: (slot + 1 == slots).then_some(2 * pi as u32 + 1),
                    }),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                rp.set_pipeline(&self.pipelines[pi].pipeline);
                rp.set_bind_group(0, &res.group0, &[]);
                match &pass.kind {
                    PassKindManifest::Image => rp.draw(0..3, 0..1),
                    PassKindManifest::Render { tag, attributes, .. } => {
                        for (oi, mesh) in self.meshes.iter().enumerate() {
                            if let Some(tag) = tag {
                                if !self.object_tags[oi].iter().any(|t| t == tag) {
                                    continue;
                                }
                            }
                            let group = self.pass_object_groups[pi].get(oi).unwrap_or(&self.object_group);
                            rp.set_bind_group(1, group, &[(oi as u64 * self.object_stride) as u32]);
                            for (slot, a) in attributes.iter().enumerate() {
                                if let Some(buf) = mesh.buffers.get(a) {
                                    rp.set_vertex_buffer(slot as u32, buf.slice(..));
                                }
                            }
                            rp.set_index_buffer(mesh.index.slice(..), wgpu::IndexFormat::Uint32);
                            rp.draw_indexed(0..mesh.index_count, 0, 0..1);
                        }
                    }
                }
            }
        }
    }

    /// Read a logical target back to the CPU.
    pub fn read_target(&self, target: usize) -> Result<readback::TargetImage, RunError> {
        let sized = self
            .sized
            .as_ref()
            .ok_or_else(|| RunError::Internal("read before render".into()))?;
        let t = self
            .manifest
            .targets
            .get(target)
            .ok_or_else(|| RunError::Internal(format!("no target #{target}")))?;
        let (w, h) = scaled_size(sized.width, sized.height, t.scale);
        readback::read_texture(
            self.device,
            self.queue,
            &sized.physical[sized.output_slot][t.physical],
            w,
            h,
            t.format,
            &t.name,
        )
    }

    /// Read the style's final image.
    pub fn read_output(&self) -> Result<readback::TargetImage, RunError> {
        self.read_target(self.manifest.output)
    }

    /// Whether a target still holds its own contents at the end of the frame
    /// (false when a later target was aliased onto the same physical texture).
    pub fn target_survives_frame(&self, target: usize) -> bool {
        let phys = self.manifest.targets[target].physical;
        let last_writer = self
            .manifest
            .passes
            .iter()
            .flat_map(|p| p.outputs.iter())
            .rfind(|t| self.manifest.targets[**t].physical == phys);
        last_writer == Some(&target)
    }
}

/// Group 1, binding 0: the object's uniform block at a dynamic offset.
fn object_uniform_entry(object_uniform_size: u64) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: true,
            min_binding_size: wgpu::BufferSize::new(object_uniform_size.max(16)),
        },
        count: None,
    }
}

/// The layout entry of one manifest binding (group 0, or group 1 after the object block).
fn layout_entry(b: &Binding) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: b.binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: match &b.resource {
            Resource::FrameUniforms | Resource::StyleUniforms => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            Resource::Target { filterable, .. } => wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float {
                    filterable: *filterable,
                },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            Resource::Texture { .. } => wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            Resource::TextureSampler { .. } | Resource::LinearClampSampler => {
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)
            }
        },
        count: None,
    }
}

fn build_pipeline(
    device: &wgpu::Device,
    manifest: &Manifest,
    pass: &PassManifest,
    wgsl: &str,
    object_layout: &wgpu::BindGroupLayout,
) -> Result<PassPipeline, RunError> {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = pass.bindings.iter().map(layout_entry).collect();
    let layout0 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(&pass.name),
        entries: &entries,
    });
    let is_render = matches!(pass.kind, PassKindManifest::Render { .. });
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> = if is_render {
        vec![Some(&layout0), Some(object_layout)]
    } else {
        vec![Some(&layout0)]
    };
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&pass.name),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(&pass.shader),
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    let attributes: Vec<Attribute> = match &pass.kind {
        PassKindManifest::Render { attributes, .. } => attributes.clone(),
        PassKindManifest::Image => Vec::new(),
    };
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
    let targets: Vec<Option<wgpu::ColorTargetState>> = pass
        .outputs
        .iter()
        .map(|t| {
            Some(wgpu::ColorTargetState {
                format: wgpu_format(manifest.targets[*t].format),
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })
        })
        .collect();
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(&pass.name),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(&pass.vertex_entry),
            compilation_options: Default::default(),
            buffers: &buffers,
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: is_render.then_some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(&pass.fragment_entry),
            compilation_options: Default::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    });
    if let Some(err) = pollster::block_on(scope.pop()) {
        return Err(RunError::Internal(format!(
            "pipeline for pass `{}` rejected by wgpu: {err}",
            pass.name
        )));
    }
    Ok(PassPipeline { pipeline, layout0 })
}

fn upload_mesh(device: &wgpu::Device, mesh: &Mesh) -> GpuMesh {
    let mut buffers = BTreeMap::new();
    let mk = |label: &str, data: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: if data.is_empty() { &[0u8; 16] } else { data },
            // COPY_DST: time-varying primitives are rewritten per frame.
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        })
    };
    buffers.insert(
        Attribute::Position,
        mk("positions", bytemuck::cast_slice(&mesh.positions)),
    );
    buffers.insert(Attribute::Normal, mk("normals", bytemuck::cast_slice(&mesh.normals)));
    if let Some(uv) = &mesh.uvs {
        buffers.insert(Attribute::Uv, mk("uvs", bytemuck::cast_slice(uv)));
    }
    if let Some(t) = &mesh.tangents {
        buffers.insert(Attribute::Tangent, mk("tangents", bytemuck::cast_slice(t)));
    }
    let index = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("indices"),
        contents: if mesh.indices.is_empty() {
            &[0u8; 16]
        } else {
            bytemuck::cast_slice(&mesh.indices)
        },
        usage: wgpu::BufferUsages::INDEX,
    });
    GpuMesh {
        buffers,
        index,
        index_count: mesh.indices.len() as u32,
        vertex_count: mesh.positions.len(),
        built_for_s: None,
    }
}
