//! `npr bench host`: the CPU time of a host's frame through
//! `npr_runner::embed::StyleRuntime::render` (prepare: uniforms, objects,
//! camera; encode: every pass and the present pass into the host's
//! encoder) and the host's `CommandEncoder::finish` (where wgpu 30
//! validates the recorded commands and records them for the driver) for
//! 1 to 1000 objects, against two independent wgpu programs
//! whose frames run no npr code, that record the same number of passes and
//! draw the same objects: `minimal.rs`, one target per pass, and
//! `pass_shaped.rs`, each pass with the style's pass's attachments,
//! vertex buffers, bindings (the targets it reads, textures, samplers)
//! and a pipeline of its own. npr's objects carry the tags
//! the style's render passes select, so its render passes draw every
//! object too. The three take turns, a block of frames each
//! ([`DEFAULT_BLOCK`]), the one that goes first rotating; each side's time
//! is the median of its frames' CPU time on the calling thread
//! (`thread_cpu.rs`: a wall clock would also count the time the thread
//! waited for a core), GPU work excluded (the queue is drained after each
//! frame, outside the timing).
//! [`spawn_row`]: the frame right after the host adds an object (issue 32).

use crate::thread_cpu;
use npr_runner::embed::{Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::scene::{primitives, Camera, Mesh};
use npr_runner::{Gpu, RunError, StyleProgram};

/// One row: objects, and the median CPU µs per frame of npr and of each baseline.
pub struct HostRow {
    pub objects: usize,
    /// Medians over the timed frames.
    pub npr_us: f64,
    pub minimal_us: f64,
    pub pass_shaped_us: f64,
    /// The median over `k` of npr's frame `k`'s time / each baseline's
    /// frame `k`'s (in the same round of blocks, so a change of load during
    /// the run moves both): steadier than the ratio of medians.
    pub pair_ratio_minimal: f64,
    pub pair_ratio_pass_shaped: f64,
}

/// Frames each side runs in a row before the next side's turn: as in an
/// application, whose renderer's frame follows its own last frame (with
/// the GPU's work in between), so each side's caches and allocator hold
/// what its own frames left. With `1` the sides alternate frame by frame
/// and each side's frame follows the other programs' (measured both ways
/// in docs/PERFORMANCE.md, "Fifth round").
pub const DEFAULT_BLOCK: u32 = 10;

mod minimal;
mod pass_shaped;

use minimal::Minimal;
use pass_shaped::PassShaped;

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
            npr_abi::manifest::PassKindManifest::Render { tag, .. } => tag.as_ref(),
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

/// The calling thread's CPU µs of `record` into a new encoder and of
/// finishing it: wgpu 30 defers its validation, resource tracking and the
/// driver's command recording from the pass calls to `finish`, which the
/// host calls every frame, so the frame's CPU cost is only known with it
/// (docs/PERFORMANCE.md, "Sixth round"). The frame is then submitted and
/// the GPU drained, untimed. An error wgpu reported
/// outside every scope (the baselines have none, and the device records
/// such errors instead of panicking) fails the bench here rather than
/// timing a broken frame.
fn timed(gpu: &Gpu, record: impl FnOnce(&mut wgpu::CommandEncoder) -> Result<(), RunError>) -> Result<f64, RunError> {
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let (us, recorded) = thread_cpu::time_us(|| record(&mut encoder).map(|()| encoder.finish()));
    gpu.queue.submit([recorded?]);
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| RunError::Internal(e.to_string()))?;
    gpu.watch.check(Ok(()))?;
    Ok(us)
}

/// [`timed`] of one `StyleRuntime::render` of `frame` into `view`.
fn timed_render(
    gpu: &Gpu,
    runtime: &mut StyleRuntime,
    frame: &Frame,
    view: &wgpu::TextureView,
) -> Result<f64, RunError> {
    timed(gpu, |encoder| {
        runtime
            .render(encoder, frame, Target::View(view))
            .map_err(|e| RunError::User(e.diagnostics()))
    })
}

/// A view of a `side`² texture of `format` that passes render into: the
/// host's target, and the baselines' targets and depth buffers.
fn target_view(device: &wgpu::Device, format: wgpu::TextureFormat, side: u32) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width: side,
                height: side,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

/// A baseline render pass's depth attachment: cleared to 1, discarded.
fn discarded_depth(view: &wgpu::TextureView) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: wgpu::LoadOp::Clear(1.0),
            store: wgpu::StoreOp::Discard,
        }),
        stencil_ops: None,
    }
}

/// Frame `k` (at 60 frames a second) of `objects` for npr, eye 0.
fn frame_at<'a>(camera: &'a Camera, objects: &'a [Instance], lights: &'a Lights, k: u32) -> Frame<'a> {
    Frame {
        camera,
        objects,
        lights,
        time_s: f64::from(k) / 60.0,
        frame_index: k,
        eye: 0,
    }
}

/// Binding 0: one 64-byte uniform block for the vertex stage, at a
/// dynamic offset or not.
fn block_entry(dynamic: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: wgpu::ShaderStages::VERTEX,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic,
            min_binding_size: wgpu::BufferSize::new(64),
        },
        count: None,
    }
}

/// Binding 0 reading the 64 bytes at `buffer`'s start (a dynamic offset
/// moves it).
fn block_binding(buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding: 0,
        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer,
            offset: 0,
            size: wgpu::BufferSize::new(64),
        }),
    }
}

/// A group layout of one 64-byte uniform block ([`block_entry`]).
fn uniform_layout(device: &wgpu::Device, dynamic: bool) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: None,
        entries: &[block_entry(dynamic)],
    })
}

/// The group of `layout` reading the 64 bytes at `buffer`'s start ([`block_binding`]).
fn uniform_group(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, buffer: &wgpu::Buffer) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout,
        entries: &[block_binding(buffer)],
    })
}

/// A baseline pass's colour attachment: cleared, stored.
fn cleared(view: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
            store: wgpu::StoreOp::Store,
        },
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The rows for `counts` objects, `frames` timed frames of each side
/// (after 3 untimed), in blocks of `block` frames ([`DEFAULT_BLOCK`]).
pub fn rows(
    gpu: &Gpu,
    program: &StyleProgram,
    counts: &[usize],
    size: u32,
    (frames, block): (u32, u32),
) -> Result<Vec<HostRow>, RunError> {
    let block = block.max(1);
    let (device, queue) = (&gpu.device, &gpu.queue);
    let mesh = primitives::sphere(1.0, 16, 8);
    let render_passes = program
        .manifest
        .passes
        .iter()
        .filter(|p| matches!(p.kind, npr_abi::manifest::PassKindManifest::Render { .. }))
        .count();
    let pass_tags = render_pass_tags(program);
    // The style's other passes and the present pass: one fullscreen triangle each.
    let passes = (render_passes, program.manifest.passes.len() - render_passes + 1);
    let view = target_view(device, wgpu::TextureFormat::Rgba8Unorm, size);
    let eye = glam::Vec3::new(0.0, 3.0, 5.0);
    let camera = Camera::looking_at(eye, glam::Vec3::ZERO);
    // The pass-shaped program's frame block: npr's camera (`Camera::looking_at`:
    // 40° high, near 0.1, far 100), made with glam.
    let view_proj = glam::Mat4::perspective_rh(40f32.to_radians(), 1.0, 0.1, 100.0)
        * glam::Mat4::look_at_rh(eye, glam::Vec3::ZERO, glam::Vec3::Y);
    let mut rows = Vec::new();
    for &n in counts {
        let (mut runtime, handle) = runtime_with(program, gpu, &mesh)?;
        let mut minimal = Minimal::new(device, n, size, &mesh);
        let mut pass_shaped = PassShaped::new(device, &program.manifest, n, size, &mesh)?;
        let lights = Lights::default();
        let mut instances = tagged_instances(handle, n, 0, &pass_tags);
        let mut models: Vec<glam::Mat4> = vec![glam::Mat4::IDENTITY; n];
        let mut times: [Vec<f64>; 3] = Default::default();
        // Each side's own frame count: its frame `k` poses the objects as the others' frame `k`.
        let mut next = [0u32; 3];
        let rounds = (frames + 3).div_ceil(block);
        for round in 0..rounds {
            // npr, the minimal program, the pass-shaped one: a block of
            // frames each, the first of the three rotating per round.
            for turn in 0..3 {
                let side = (turn + round as usize) % 3;
                for _ in 0..block {
                    let k = next[side];
                    if k >= frames + 3 {
                        break;
                    }
                    next[side] += 1;
                    let us = match side {
                        0 => {
                            for (i, o) in instances.iter_mut().enumerate() {
                                o.transform = model(i, n, k);
                            }
                            timed_render(gpu, &mut runtime, &frame_at(&camera, &instances, &lights, k), &view)?
                        }
                        _ => {
                            for (i, m) in models.iter_mut().enumerate() {
                                *m = model(i, n, k);
                            }
                            timed(gpu, |e| {
                                if side == 1 {
                                    minimal.frame(queue, e, &models, passes);
                                } else {
                                    pass_shaped.frame(queue, e, view_proj, &models);
                                }
                                Ok(())
                            })?
                        }
                    };
                    if k >= 3 {
                        times[side].push(us);
                    }
                }
            }
        }
        let [npr, own, shaped] = times;
        let pair = |other: &[f64]| median(npr.iter().zip(other).map(|(n, o)| n / o).collect());
        rows.push(HostRow {
            objects: n,
            pair_ratio_minimal: pair(&own),
            pair_ratio_pass_shaped: pair(&shaped),
            npr_us: median(npr),
            minimal_us: median(own),
            pass_shaped_us: median(shaped),
        });
    }
    Ok(rows)
}

/// The table: objects, the three sides' µs, npr's ratio to each baseline.
pub fn table(rows: &[HostRow]) -> String {
    let mut t = String::from(
        "| objects | npr host path (µs/frame) | minimal wgpu, one target per pass (µs/frame) | \
         pass-shaped wgpu (µs/frame) | npr / minimal: ratio of medians (per frame) | \
         npr / pass-shaped: ratio of medians (per frame) |\n\
         |---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        t.push_str(&format!(
            "| {} | {:.0} | {:.0} | {:.0} | {:.2} ({:.2}) | {:.2} ({:.2}) |\n",
            r.objects,
            r.npr_us,
            r.minimal_us,
            r.pass_shaped_us,
            r.npr_us / r.minimal_us,
            r.pair_ratio_minimal,
            r.npr_us / r.pass_shaped_us,
            r.pair_ratio_pass_shaped,
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
    let view = target_view(&gpu.device, wgpu::TextureFormat::Rgba8Unorm, size);
    let camera = Camera::looking_at(glam::Vec3::new(0.0, 3.0, 5.0), glam::Vec3::ZERO);
    let lights = Lights::default();
    // As in `rows`: every object carries the tags the render passes select.
    let tags = render_pass_tags(program);
    // One timed frame of `count` objects: µs of `render`, GPU work drained after.
    let timed_frame = |runtime: &mut StyleRuntime, handle, count: usize, k: u32| -> Result<f64, RunError> {
        let instances = tagged_instances(handle, count, k, &tags);
        timed_render(gpu, runtime, &frame_at(&camera, &instances, &lights, k), &view)
    };
    let new_runtime = || runtime_with(program, gpu, &mesh);
    let (mut runtime, handle) = new_runtime()?;
    for k in 0..3 {
        timed_frame(&mut runtime, handle, objects, k)?;
    }
    let (mut spawn, mut steady, mut fresh) = (Vec::new(), Vec::new(), Vec::new());
    for s in 0..spawns {
        let k = 3 + 3 * s;
        spawn.push(timed_frame(&mut runtime, handle, objects + 1, k)?);
        timed_frame(&mut runtime, handle, objects, k + 1)?;
        steady.push(timed_frame(&mut runtime, handle, objects, k + 2)?);
        let (mut other, other_handle) = new_runtime()?;
        fresh.push(timed_frame(&mut other, other_handle, objects + 1, k)?);
    }
    Ok(SpawnRow {
        objects,
        spawn_us: median(spawn),
        steady_us: median(steady),
        new_runtime_us: median(fresh),
    })
}
