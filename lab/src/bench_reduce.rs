//! `npr bench reduce`: the cost of a compute pass's per-object reduction
//! against the number of elements (vertices) and objects, next to a plain
//! copy kernel over the same position buffer in the same run, and the
//! reduction's error against a CPU f64 sum.
//!
//! The style reduces Σ px (the projected vertex in pixels) and the count per
//! object — the shape of Breslav et al.'s per-object sums (§3.2). Objects
//! are point sets with no triangles, so the render pass that reads the sums
//! draws nothing. Times are wall clock (submit + wait), not timestamps:
//! lavapipe's timestamps do not bracket compute work (they put a 12 MB copy
//! at 200 GB/s). Each frame of the style is timed next to a frame of the
//! same style without the compute pass (`NULL_STYLE`), and the copy kernel
//! next to an empty submit, interleaved round robin; the differences are
//! the reduction's and the copy's own cost.

use crate::bench::wait_idle;
use glam::{DVec3, DVec4};
use npr_runner::scene::{Mesh, Scene};
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};
use std::sync::Arc;
use std::time::Instant;

/// The benchmarked style.
pub const STYLE: &str = r#"style "Reduction benchmark"
pass sums: compute(vertices) {
  let px = project(position).xy * resolution
  reduce total: vec2 = sum(px)
  reduce count: float = sum(1.0)
}
pass show: render(scene) {
  out c: rg32float = sums.total / max(sums.count, 1.0)
}
output show.c
"#;

/// The same render pass without the compute pass: the frame the reduction adds to.
pub const NULL_STYLE: &str = r#"style "Reduction benchmark, no reduction"
pass show: render(scene) {
  out c: rg32float = vec2(1.0)
}
output show.c
"#;

/// A camera and light for the point clouds (and one template object).
const SCENE: &str = r#"
[camera]
position = [0.0, 0.0, 4.0]
target = [0.0, 0.0, 0.0]
fov = 40.0
[light]
direction = [0.0, 1.0, 1.0]
[[object]]
name = "template"
primitive = { kind = "plane", size = 1.0, subdivisions = 1 }
"#;

/// The image size: the render pass draws nothing, so only `resolution` matters.
const SIZE: u32 = 256;

/// One measured configuration.
#[derive(Debug, Clone)]
pub struct Row {
    pub elements: usize,
    pub objects: usize,
    /// Median wall ms a frame with the reduction takes more than one without.
    pub reduce_ms: f64,
    /// Median wall ms a copy of the same positions (12 bytes per element)
    /// takes more than an empty submit.
    pub copy_ms: f64,
    /// Largest |GPU − f64| / Σ|px| of Σpx over all objects and both components.
    pub reduce_rel_error: f64,
    /// The same for a sequential f32 sum on the CPU (what a naive loop gets).
    pub sequential_rel_error: f64,
}

/// A deterministic point in [-1, 1]³ (a 64-bit mix of the index).
fn point(i: u64) -> [f32; 3] {
    let mut x = i.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
    let mut next = || {
        x ^= x >> 33;
        x = x.wrapping_mul(0xFF51_AFD7_ED55_8CCD);
        x ^= x >> 33;
        ((x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) as f32
    };
    [next(), next(), next()]
}

/// `elements` points split evenly over `objects` objects without triangles.
pub fn scene(elements: usize, objects: usize) -> Result<Scene, RunError> {
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("reduce-bench.toml", SCENE.to_string());
    let mut scene = npr_runner::scene::parse_scene(SCENE, file, std::path::Path::new(".")).map_err(RunError::User)?;
    let template = scene
        .objects
        .pop()
        .ok_or_else(|| RunError::Internal("no template object".into()))?;
    let per = elements / objects.max(1);
    for o in 0..objects {
        let positions: Vec<[f32; 3]> = (0..per).map(|i| point((o * per + i) as u64)).collect();
        let mesh = Mesh {
            normals: vec![[0.0, 0.0, 1.0]; positions.len()],
            positions,
            uvs: None,
            tangents: None,
            indices: Vec::new(),
            source: format!("{per} points"),
            parts: None,
            edge_marks: None,
        };
        let mut object = template.clone();
        object.name = format!("points{o}");
        object.mesh = Arc::new(mesh);
        scene.objects.push(object);
    }
    Ok(scene)
}

/// Per object: Σ px in f64 and in sequential f32, and Σ|px| (the scale errors are relative to).
fn cpu_sums(scene: &Scene) -> Vec<([f64; 2], [f32; 2], f64)> {
    let pose = scene.camera.pose(0.0);
    let view_proj = (pose.projection(1.0) * pose.view(0)).as_dmat4();
    let view_proj32 = pose.projection(1.0) * pose.view(0);
    scene
        .objects
        .iter()
        .map(|o| {
            let model = o.model.as_dmat4();
            let mut exact = [0.0f64; 2];
            let mut naive = [0.0f32; 2];
            let mut scale = 0.0;
            for p in &o.mesh.positions {
                let w = model.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
                let c = view_proj * DVec4::new(w.x, w.y, w.z, 1.0);
                let px = [
                    (c.x / c.w * 0.5 + 0.5) * SIZE as f64,
                    (0.5 - c.y / c.w * 0.5) * SIZE as f64,
                ];
                let c32 = view_proj32 * (o.model * glam::Vec4::new(p[0], p[1], p[2], 1.0));
                let px32 = [
                    (c32.x / c32.w * 0.5 + 0.5) * SIZE as f32,
                    (0.5 - c32.y / c32.w * 0.5) * SIZE as f32,
                ];
                for k in 0..2 {
                    exact[k] += px[k];
                    naive[k] += px32[k];
                    scale += px[k].abs();
                }
            }
            (exact, naive, scale / 2.0)
        })
        .collect()
}

/// A compute kernel copying `floats` f32s from one storage buffer to
/// another (one invocation per float, workgroups of 256).
pub struct CopyKernel {
    pipeline: wgpu::ComputePipeline,
    group: wgpu::BindGroup,
    groups: (u32, u32),
}

impl CopyKernel {
    pub fn new(gpu: &Gpu, floats: usize) -> CopyKernel {
        let device = &gpu.device;
        let bytes = (floats.max(1) * 4) as u64;
        let buffer = |label: &str| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        let (src, dst) = (buffer("copy src"), buffer("copy dst"));
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("copy kernel"),
            source: wgpu::ShaderSource::Wgsl(
                "@group(0) @binding(0) var<storage, read> src: array<f32>;
@group(0) @binding(1) var<storage, read_write> dst: array<f32>;
@compute @workgroup_size(256)
fn copy(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * 65535u * 256u;
    if (i < arrayLength(&src)) {
        dst[i] = src[i];
    }
}"
                .into(),
            ),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("copy kernel"),
            layout: None,
            module: &module,
            entry_point: Some("copy"),
            compilation_options: Default::default(),
            cache: None,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("copy kernel"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: src.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: dst.as_entire_binding(),
                },
            ],
        });
        let n = (floats as u32).div_ceil(256).max(1);
        CopyKernel {
            pipeline,
            group,
            groups: (n.min(65535), n.div_ceil(65535)),
        }
    }

    /// Submit the copy (or, with `empty`, an empty command buffer) and wait.
    pub fn run(&self, gpu: &Gpu, empty: bool) -> Result<(), RunError> {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        if !empty {
            let mut cp = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("copy"),
                timestamp_writes: None,
            });
            cp.set_pipeline(&self.pipeline);
            cp.set_bind_group(0, &self.group, &[]);
            cp.dispatch_workgroups(self.groups.0, self.groups.1, 1);
        }
        gpu.queue.submit([encoder.finish()]);
        wait_idle(gpu)
    }
}

/// The median (the upper one of an even count); `v` must not be empty.
pub(crate) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Seconds `f` takes.
pub(crate) fn timed(f: impl FnOnce() -> Result<(), RunError>) -> Result<f64, RunError> {
    let t = Instant::now();
    f()?;
    Ok(t.elapsed().as_secs_f64())
}

/// Median wall ms a frame of `with` takes more than one of `without`, and
/// a run of `copy` more than an empty submit: after one warm-up each, the
/// four interleaved round robin for `frames` rounds.
pub(crate) fn against_copy(
    gpu: &Gpu,
    (with, without): (&mut npr_runner::Renderer, &mut npr_runner::Renderer),
    (scene, spec): (&Scene, &FrameSpec),
    copy: &CopyKernel,
    frames: u32,
) -> Result<(f64, f64), RunError> {
    with.render(scene, spec)?;
    without.render(scene, spec)?;
    copy.run(gpu, false)?;
    let mut t = [Vec::new(), Vec::new(), Vec::new(), Vec::new()];
    for _ in 0..frames.max(1) {
        t[0].push(timed(|| {
            with.render(scene, spec)?;
            wait_idle(gpu)
        })?);
        t[1].push(timed(|| {
            without.render(scene, spec)?;
            wait_idle(gpu)
        })?);
        t[2].push(timed(|| copy.run(gpu, false))?);
        t[3].push(timed(|| copy.run(gpu, true))?);
    }
    let [a, b, c, d] = t.map(median);
    Ok(((a - b) * 1e3, (c - d) * 1e3))
}

/// Measure every (elements, objects) pair; `progress` gets a line per pair.
pub fn run(
    gpu: &Gpu,
    (program, null): (&StyleProgram, &StyleProgram),
    elements: &[usize],
    objects: &[usize],
    frames: u32,
    progress: impl Fn(&str),
) -> Result<Vec<Row>, RunError> {
    let mut rows = Vec::new();
    for &e in elements {
        for &o in objects {
            if e < o {
                continue;
            }
            let started = Instant::now();
            let scene = scene(e, o)?;
            let spec = FrameSpec::still(SIZE, SIZE, 0);
            let mut with = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, &scene)?;
            let mut without = npr_runner::Renderer::new(&gpu.device, &gpu.queue, null, &scene)?;
            let copy = CopyKernel::new(gpu, 3 * (e / o) * o);
            let (reduce_ms, copy_ms) = against_copy(gpu, (&mut with, &mut without), (&scene, &spec), &copy, frames)?;
            // Accuracy: one frame's sums against f64.
            let values = with.read_object_values("sums")?;
            let cpu = cpu_sums(&scene);
            let (mut tree, mut naive) = (0.0f64, 0.0f64);
            for (v, (exact, seq, scale)) in values.iter().zip(&cpu) {
                for k in 0..2 {
                    tree = tree.max((v[0][k] as f64 - exact[k]).abs() / scale);
                    naive = naive.max((seq[k] as f64 - exact[k]).abs() / scale);
                }
            }
            progress(&format!(
                "{e} elements, {o} objects: {reduce_ms:.3} ms (copy {copy_ms:.3} ms) in {:.1} s",
                started.elapsed().as_secs_f64()
            ));
            rows.push(Row {
                elements: e,
                objects: o,
                reduce_ms,
                copy_ms,
                reduce_rel_error: tree,
                sequential_rel_error: naive,
            });
        }
    }
    Ok(rows)
}

/// The rows as a Markdown table: time, ns per element, against the copy, error.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| elements | objects | reduce ms | ns / element | copy ms | reduce ÷ copy | rel. error (tree, f32) | rel. error (sequential f32) |\n|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {:.3} | {:.2} | {:.3} | {:.1}× | {:.1e} | {:.1e} |\n",
            r.elements,
            r.objects,
            r.reduce_ms,
            r.reduce_ms * 1e6 / r.elements as f64,
            r.copy_ms,
            r.reduce_ms / r.copy_ms.max(1e-9),
            r.reduce_rel_error,
            r.sequential_rel_error
        ));
    }
    s
}
