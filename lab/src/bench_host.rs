//! `npr bench host`: the CPU time of a host's frame through
//! `runner::embed::StyleRuntime::render` (prepare: uniforms, objects,
//! camera; encode: every pass and the present pass into the host's
//! encoder) for 1 to 1000 objects, against an independent minimal wgpu
//! program, written here with no npr code, that records the same number of
//! passes: per render pass of the style one pass drawing every object (its
//! uniform block at a dynamic offset, its vertex and index buffers), per
//! other pass and the present pass one fullscreen triangle, and uploads
//! every object's block each frame. npr's objects carry the tags the
//! style's render passes select, so its render passes draw every object too. Frames of the two alternate in one
//! run; each side's time is the median of its frames' CPU time on the
//! calling thread (`thread_cpu.rs`: a wall clock would also count the time
//! the thread waited for a core), GPU work excluded (the queue is drained
//! between frames, outside the timing).
//! [`spawn_row`]: the frame right after the host adds an object (issue 32).

use crate::thread_cpu;
use runner::embed::{Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use runner::scene::{primitives, Camera, Mesh};
use runner::{Gpu, RunError, StyleProgram};

/// One row: objects, npr's and the minimal program's median CPU µs per frame.
pub struct HostRow {
    pub objects: usize,
    /// Medians over the timed frames.
    pub npr_us: f64,
    pub minimal_us: f64,
    /// The median over frames of npr's time / the minimal program's in
    /// the same frame (the two run back to back, so a change of load
    /// during the run moves both): steadier than the ratio of medians.
    pub pair_ratio: f64,
}

const WGSL: &str = "
struct Object { model: mat4x4<f32> }
@group(0) @binding(0) var<uniform> object: Object;
@vertex fn vs_object(@location(0) p: vec3<f32>) -> @builtin(position) vec4<f32> {
    return object.model * vec4<f32>(p * 0.1, 1.0);
}
@vertex fn vs_full(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(f32((i << 1u) & 2u) * 2.0 - 1.0, 1.0 - f32(i & 2u) * 2.0, 0.0, 1.0);
}
@fragment fn fs() -> @location(0) vec4<f32> { return vec4<f32>(0.5, 0.5, 0.5, 1.0); }
";

/// The minimal program: its pipelines, one object buffer, one mesh.
struct Minimal {
    object_pipeline: wgpu::RenderPipeline,
    full_pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
    objects: wgpu::Buffer,
    positions: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    depth: wgpu::TextureView,
    color: wgpu::TextureView,
    blocks: Vec<u8>,
}

/// Bytes between objects' blocks (wgpu's minimum uniform offset alignment).
const STRIDE: u64 = 256;

impl Minimal {
    fn new(device: &wgpu::Device, objects: usize, size: u32, mesh: &runner::scene::Mesh) -> Minimal {
        use wgpu::util::DeviceExt;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: None,
            source: wgpu::ShaderSource::Wgsl(WGSL.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: None,
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: wgpu::BufferSize::new(64),
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str, buffers: &[Option<wgpu::VertexBufferLayout>], depth: bool| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: None,
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: Default::default(),
                depth_stencil: depth.then(|| wgpu::DepthStencilState {
                    format: wgpu::TextureFormat::Depth32Float,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::TextureFormat::Rgba8Unorm.into())],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let attributes = [wgpu::VertexAttribute {
            format: wgpu::VertexFormat::Float32x3,
            offset: 0,
            shader_location: 0,
        }];
        let vertex = wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &attributes,
        };
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: STRIDE * objects.max(1) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(64),
                }),
            }],
        });
        let texture = |format, usage| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: None,
                    size: wgpu::Extent3d {
                        width: size,
                        height: size,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        Minimal {
            object_pipeline: pipeline("vs_object", &[Some(vertex)], true),
            full_pipeline: pipeline("vs_full", &[], false),
            group,
            objects: buffer,
            positions: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(&mesh.positions),
                usage: wgpu::BufferUsages::VERTEX,
            }),
            indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
            index_count: mesh.indices.len() as u32,
            depth: texture(
                wgpu::TextureFormat::Depth32Float,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            ),
            color: texture(wgpu::TextureFormat::Rgba8Unorm, wgpu::TextureUsages::RENDER_ATTACHMENT),
            blocks: vec![0; STRIDE as usize * objects.max(1)],
        }
    }

    /// Upload every object's block and record the passes: what a host's
    /// own renderer does per frame.
    fn frame(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        models: &[glam::Mat4],
        passes: (usize, usize),
    ) {
        for (i, m) in models.iter().enumerate() {
            let at = i * STRIDE as usize;
            self.blocks[at..at + 64].copy_from_slice(bytemuck::bytes_of(&m.to_cols_array()));
        }
        queue.write_buffer(&self.objects, 0, &self.blocks);
        let (object_passes, fullscreen_passes) = passes;
        for _ in 0..object_passes {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.color,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth,
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
            pass.set_pipeline(&self.object_pipeline);
            for i in 0..models.len() {
                pass.set_bind_group(0, &self.group, &[(i as u64 * STRIDE) as u32]);
                pass.set_vertex_buffer(0, self.positions.slice(..));
                pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..self.index_count, 0, 0..1);
            }
        }
        for _ in 0..fullscreen_passes {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.color,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.full_pipeline);
            pass.set_bind_group(0, &self.group, &[0]);
            pass.draw(0..3, 0..1);
        }
    }
}

/// Object `i` of `n` at frame `k`: a grid, turning.
fn model(i: usize, n: usize, k: u32) -> glam::Mat4 {
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    let (x, z) = ((i % side) as f32, (i / side) as f32);
    let spacing = 4.0 / side as f32;
    glam::Mat4::from_translation(glam::Vec3::new(
        (x - side as f32 / 2.0) * spacing,
        0.0,
        (z - side as f32 / 2.0) * spacing,
    )) * glam::Mat4::from_rotation_y(0.05 * k as f32)
        * glam::Mat4::from_scale(glam::Vec3::splat(spacing * 0.4))
}

/// The tags the style's render passes select, each once: every object of
/// the bench carries them, so every render pass draws every object.
fn render_pass_tags(program: &StyleProgram) -> Vec<&String> {
    let mut tags: Vec<&String> = program
        .manifest
        .passes
        .iter()
        .filter_map(|p| match &p.kind {
            abi::manifest::PassKindManifest::Render { tag, .. } => tag.as_ref(),
            _ => None,
        })
        .collect();
    tags.dedup();
    tags
}

/// A runtime of `program` with `mesh` registered, and the mesh's handle.
fn runtime_with(program: &StyleProgram, gpu: &Gpu, mesh: &Mesh) -> Result<(StyleRuntime, MeshHandle), RunError> {
    let mut runtime =
        StyleRuntime::new(&gpu.device, &gpu.queue, program.clone()).map_err(|e| RunError::User(e.diagnostics()))?;
    let handle = runtime.add_mesh(mesh.clone());
    Ok((runtime, handle))
}

/// `count` objects of `handle` at frame `k`, each carrying every tag of
/// `tags` ([`render_pass_tags`]: Age of Sail's `depth: render(caster)`), so
/// each render pass draws every object, as the minimal program's do: the
/// same draws on both sides.
fn tagged_instances(handle: MeshHandle, count: usize, k: u32, tags: &[&String]) -> Vec<Instance> {
    (0..count)
        .map(|i| {
            tags.iter()
                .fold(Instance::new(handle, model(i, count, k)), |o, t| o.with_tag(t))
        })
        .collect()
}

/// The calling thread's CPU µs of one `StyleRuntime::render` of `frame`
/// into `view`; the frame is then submitted and the GPU drained, untimed.
fn timed_render(
    gpu: &Gpu,
    runtime: &mut StyleRuntime,
    frame: &Frame,
    view: &wgpu::TextureView,
) -> Result<f64, RunError> {
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let (us, rendered) = thread_cpu::time_us(|| runtime.render(&mut encoder, frame, Target::View(view)));
    rendered.map_err(|e| RunError::User(e.diagnostics()))?;
    gpu.queue.submit([encoder.finish()]);
    drain(&gpu.device)?;
    Ok(us)
}

/// Wait until the GPU has done what was submitted.
fn drain(device: &wgpu::Device) -> Result<(), RunError> {
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map(|_| ())
        .map_err(|e| RunError::Internal(e.to_string()))
}

/// A view of the `size`² texture a host renders into.
fn host_target(device: &wgpu::Device, size: u32) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The rows for `counts` objects, `frames` timed frames each (after 3 untimed).
pub fn rows(
    gpu: &Gpu,
    program: &StyleProgram,
    counts: &[usize],
    size: u32,
    frames: u32,
) -> Result<Vec<HostRow>, RunError> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    let mesh = primitives::sphere(1.0, 16, 8);
    let render_passes = program
        .manifest
        .passes
        .iter()
        .filter(|p| matches!(p.kind, abi::manifest::PassKindManifest::Render { .. }))
        .count();
    let pass_tags = render_pass_tags(program);
    // The style's other passes and the present pass: one fullscreen triangle each.
    let passes = (render_passes, program.manifest.passes.len() - render_passes + 1);
    let view = host_target(device, size);
    let mut rows = Vec::new();
    for &n in counts {
        let (mut runtime, handle) = runtime_with(program, gpu, &mesh)?;
        let mut minimal = Minimal::new(device, n, size, &mesh);
        let camera = Camera::looking_at(glam::Vec3::new(0.0, 3.0, 5.0), glam::Vec3::ZERO);
        let lights = Lights::default();
        let mut instances = tagged_instances(handle, n, 0, &pass_tags);
        let mut models: Vec<glam::Mat4> = vec![glam::Mat4::IDENTITY; n];
        let (mut npr, mut own) = (Vec::new(), Vec::new());
        for k in 0..frames + 3 {
            for (i, o) in instances.iter_mut().enumerate() {
                o.transform = model(i, n, k);
            }
            for (i, m) in models.iter_mut().enumerate() {
                *m = model(i, n, k);
            }
            let frame = Frame {
                camera: &camera,
                objects: &instances,
                lights: &lights,
                time_s: f64::from(k) / 60.0,
                frame_index: k,
                eye: 0,
            };
            let npr_us = timed_render(gpu, &mut runtime, &frame, &view)?;
            let mut encoder = device.create_command_encoder(&Default::default());
            let (own_us, ()) = thread_cpu::time_us(|| minimal.frame(queue, &mut encoder, &models, passes));
            queue.submit([encoder.finish()]);
            drain(device)?;
            if k >= 3 {
                npr.push(npr_us);
                own.push(own_us);
            }
        }
        rows.push(HostRow {
            objects: n,
            pair_ratio: median(npr.iter().zip(&own).map(|(n, o)| n / o).collect()),
            npr_us: median(npr),
            minimal_us: median(own),
        });
    }
    Ok(rows)
}

/// The table: objects, npr's µs, the minimal program's µs, their ratio.
pub fn table(rows: &[HostRow]) -> String {
    let mut t = String::from(
        "| objects | npr host path (µs/frame) | minimal wgpu (µs/frame) | ratio of medians | ratio per frame (median) |\n\
         |---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        t.push_str(&format!(
            "| {} | {:.0} | {:.0} | {:.2} | {:.2} |\n",
            r.objects,
            r.npr_us,
            r.minimal_us,
            r.npr_us / r.minimal_us,
            r.pair_ratio
        ));
    }
    t
}

/// What a scene change costs a host (issue 32: a game spawning an object):
/// median CPU µs of a frame right after one object is added to `objects`
/// (`StyleRuntime::render`, which makes the scene-level resources anew),
/// of a steady frame, and of a new runtime's first frame of the same
/// objects: what the frame after an addition cost when a scene change
/// built the renderer anew (before `Renderer::set_scene`).
pub struct SpawnRow {
    pub objects: usize,
    pub spawn_us: f64,
    pub steady_us: f64,
    pub new_runtime_us: f64,
}

/// [`SpawnRow`] over `spawns` additions (each removed again, untimed).
pub fn spawn_row(
    gpu: &Gpu,
    program: &StyleProgram,
    objects: usize,
    size: u32,
    spawns: u32,
) -> Result<SpawnRow, RunError> {
    let mesh = primitives::sphere(1.0, 16, 8);
    let view = host_target(&gpu.device, size);
    let camera = Camera::looking_at(glam::Vec3::new(0.0, 3.0, 5.0), glam::Vec3::ZERO);
    let lights = Lights::default();
    // As in `rows`: every object carries the tags the render passes select.
    let tags = render_pass_tags(program);
    // One timed frame of `count` objects: µs of `render`, GPU work drained after.
    let timed = |runtime: &mut StyleRuntime, handle, count: usize, k: u32| -> Result<f64, RunError> {
        let instances = tagged_instances(handle, count, k, &tags);
        let frame = Frame {
            camera: &camera,
            objects: &instances,
            lights: &lights,
            time_s: f64::from(k) / 60.0,
            frame_index: k,
            eye: 0,
        };
        timed_render(gpu, runtime, &frame, &view)
    };
    let new_runtime = || runtime_with(program, gpu, &mesh);
    let (mut runtime, handle) = new_runtime()?;
    for k in 0..3 {
        timed(&mut runtime, handle, objects, k)?;
    }
    let (mut spawn, mut steady, mut fresh) = (Vec::new(), Vec::new(), Vec::new());
    for s in 0..spawns {
        let k = 3 + 3 * s;
        spawn.push(timed(&mut runtime, handle, objects + 1, k)?);
        timed(&mut runtime, handle, objects, k + 1)?;
        steady.push(timed(&mut runtime, handle, objects, k + 2)?);
        let (mut other, other_handle) = new_runtime()?;
        fresh.push(timed(&mut other, other_handle, objects + 1, k)?);
    }
    Ok(SpawnRow {
        objects,
        spawn_us: median(spawn),
        steady_us: median(steady),
        new_runtime_us: median(fresh),
    })
}
