//! `npr bench lines`: the cost of `lines` passes (Klein et al. 2000 §5)
//! against the number of edges, and the wavy lines against LSA contours on
//! the same analytic scenes (a benchmark, never a test).
//!
//! Cost against edges: a sphere of n segments (2n(n/2 − 1) triangles) at
//! every size of `segments`, its silhouette drawn by a lines pass tested
//! against a kept depth. Per frame the strips are either rebuilt (the
//! object turns a little every frame, so the cache key changes) or reused
//! (nothing changes). The CPU build is the difference of the two
//! `Renderer::prepare` times; the frame is prepare, record, submit and GPU
//! wait. Both are the fastest of `frames` interleaved frames, and µs per
//! 1000 mesh edges shows whether the build is linear in the edges.
//!
//! Against LSA: the lines (straight, amplitude 0, 1 px wide; and wavy as
//! `examples/wavy_lines.npr` draws them) and LSA full with its density
//! filter, each with its own base pass (a kept-depth fill for the lines,
//! the G-buffer for LSA): cost over that base, and precision and recall
//! within 1 px against the analytic truth of `crate::contours`, minimum
//! over its scenes.

use crate::bench::{time_interleaved, wait_idle};
use crate::contours::{accuracy, builtin_scenes, ink_mask};
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};
use std::time::Instant;

/// A fill that keeps its depth, then a lines pass with `settings`, ink over white.
pub fn lines_style(settings: &str) -> String {
    format!(
        "style \"bench lines\"\n\
         pass shade: render(scene) {{\n  out color: rgba8unorm = #808080\n  depth: keep\n}}\n\
         pass ink: lines(scene) {{\n  {settings}\n  depth: test(shade, bias: 1px)\n  \
         out ink: rgba8unorm = vec4(0.0, 0.0, 0.0, 1.0) {{ blend: over }}\n  clear: #ffffff\n}}\n\
         output ink.ink\n"
    )
}

/// The base of the lines styles: the same fill, its colour as the output.
pub const LINES_BASE: &str = "style \"bench lines base\"\npass shade: render(scene) {\n  out color: rgba8unorm = #808080\n  depth: keep\n}\npass ink: image(shade) {\n  out c: rgba8unorm = vec4(1.0) + 0.0 * shade.color\n}\noutput ink.c\n";

/// Straight lines: silhouettes and creases, as exact as strips can be.
pub const STRAIGHT: &str = "silhouettes: true  creases: 30deg  width: 1px  amplitude: 0px";
/// The wavy lines of `examples/wavy_lines.npr`.
pub const WAVY: &str = "silhouettes: true  creases: 30deg  width: 2.5px  amplitude: 1.5px  wavelength: 28px";

/// One sphere's row of the cost table.
#[derive(Debug, Clone)]
pub struct EdgeRow {
    pub segments: u32,
    pub triangles: usize,
    pub mesh_edges: usize,
    /// Silhouette edges seen from the camera (what is drawn).
    pub silhouette_edges: usize,
    /// CPU seconds to build the strips (rebuilt − reused `prepare`).
    pub build_s: f64,
    pub frame_rebuilt_s: f64,
    pub frame_reused_s: f64,
}

fn sphere_scene(segments: u32, sources: &mut npr_diag::SourceMap) -> Result<npr_runner::scene::Scene, RunError> {
    let text = format!(
        "[camera]\nposition = [0.0, 0.4, 3.5]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = {{ kind = \"sphere\", radius = 1.0, segments = {segments}, rings = {} }}\n",
        (segments / 2).max(2)
    );
    let file = sources.add(format!("sphere{segments}.toml"), text.clone());
    npr_runner::scene::parse_scene(&text, file, std::path::Path::new(".")).map_err(RunError::User)
}

/// The fastest of `frames` (prepare seconds, frame seconds) with `turn` set
/// to whether the object turns every frame.
fn timed_frames(
    gpu: &Gpu,
    renderer: &mut npr_runner::Renderer,
    scene: &mut npr_runner::scene::Scene,
    size: u32,
    turn: bool,
    frames: u32,
) -> Result<(f64, f64), RunError> {
    let spec = FrameSpec::still(size, size, 0);
    let (mut prepare, mut frame) = (f64::INFINITY, f64::INFINITY);
    for k in 0..frames.max(1) {
        if turn {
            scene.objects[0].model = glam::Mat4::from_rotation_y(0.01 * (k + 1) as f32);
        }
        // Prepared once, then recorded and submitted as an embedder does
        // (`Renderer::render` would prepare a second time).
        let t = Instant::now();
        renderer.prepare(scene, &spec)?;
        prepare = prepare.min(t.elapsed().as_secs_f64());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder);
        gpu.queue.submit([encoder.finish()]);
        wait_idle(gpu)?;
        frame = frame.min(t.elapsed().as_secs_f64());
    }
    Ok((prepare, frame))
}

/// Cost against edges: one row per sphere resolution.
pub fn edge_rows(
    gpu: &Gpu,
    silhouettes: &StyleProgram,
    segments: &[u32],
    size: u32,
    frames: u32,
    mut progress: impl FnMut(&str),
) -> Result<Vec<EdgeRow>, RunError> {
    let mut rows = Vec::new();
    let mut sources = npr_diag::SourceMap::new();
    for &n in segments {
        progress(&format!("lines on a sphere of {n} segments"));
        let mut scene = sphere_scene(n, &mut sources)?;
        let mesh = scene.objects[0].mesh.clone();
        let edges = npr_runner::lines::edges::EdgeMesh::new(&mesh);
        let mut r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, silhouettes, &scene)?;
        r.render(&scene, &FrameSpec::still(size, size, 0))?;
        wait_idle(gpu)?;
        // Interleaved rounds, so load on the machine touches both alike.
        let (mut rebuilt, mut reused) = ((f64::INFINITY, f64::INFINITY), (f64::INFINITY, f64::INFINITY));
        for _ in 0..3 {
            let a = timed_frames(gpu, &mut r, &mut scene, size, true, frames)?;
            let b = timed_frames(gpu, &mut r, &mut scene, size, false, frames)?;
            rebuilt = (rebuilt.0.min(a.0), rebuilt.1.min(a.1));
            reused = (reused.0.min(b.0), reused.1.min(b.1));
        }
        let silhouette_edges = edges.silhouettes(glam::DVec3::new(0.0, 0.4, 3.5)).len();
        rows.push(EdgeRow {
            segments: n,
            triangles: mesh.indices.len() / 3,
            mesh_edges: edges.edges.len(),
            silhouette_edges,
            build_s: (rebuilt.0 - reused.0).max(0.0),
            frame_rebuilt_s: rebuilt.1,
            frame_reused_s: reused.1,
        });
    }
    Ok(rows)
}

/// Least-squares fit build_s ≈ fixed + per_edge · mesh_edges, and its R²
/// (1 for points on the line): whether the build is linear in the edges.
pub fn linear_fit(rows: &[EdgeRow]) -> Option<(f64, f64, f64)> {
    if rows.len() < 2 {
        return None;
    }
    let n = rows.len() as f64;
    let xs: Vec<f64> = rows.iter().map(|r| r.mesh_edges as f64).collect();
    let ys: Vec<f64> = rows.iter().map(|r| r.build_s).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    if sxx == 0.0 {
        return None;
    }
    let per_edge = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum::<f64>() / sxx;
    let fixed = my - per_edge * mx;
    let residual: f64 = xs
        .iter()
        .zip(&ys)
        .map(|(x, y)| (y - (fixed + per_edge * x)).powi(2))
        .sum();
    let total: f64 = ys.iter().map(|y| (y - my) * (y - my)).sum();
    let r2 = if total == 0.0 { 1.0 } else { 1.0 - residual / total };
    Some((fixed, per_edge, r2))
}

pub fn edge_table(rows: &[EdgeRow]) -> String {
    let mut out = String::from(
        "| segments | triangles | mesh edges | silhouette edges | strip build (ms) | µs per 1000 mesh edges | frame, rebuilt (ms) | frame, reused (ms) |\n|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        out.push_str(&format!(
            "| {} | {} | {} | {} | {:.3} | {:.1} | {:.2} | {:.2} |\n",
            r.segments,
            r.triangles,
            r.mesh_edges,
            r.silhouette_edges,
            r.build_s * 1e3,
            r.build_s * 1e6 / (r.mesh_edges as f64 / 1000.0),
            r.frame_rebuilt_s * 1e3,
            r.frame_reused_s * 1e3
        ));
    }
    if let Some((fixed, per_edge, r2)) = linear_fit(rows) {
        out.push_str(&format!(
            "\nbuild ≈ {:.3} ms + {:.2} µs per 1000 mesh edges (least squares, R² = {r2:.4})\n",
            fixed * 1e3,
            per_edge * 1e9,
        ));
    }
    out
}

/// One sphere's row of the CPU-against-compute classification table.
#[derive(Debug, Clone)]
pub struct ClassifyRow {
    pub segments: u32,
    pub mesh_edges: usize,
    pub silhouette_edges: usize,
    /// `EdgeMesh::silhouettes` (one facing test per face, then per edge).
    pub cpu_s: f64,
    /// `GpuSilhouettes::classify`: eye written, dispatch, flags copied back,
    /// GPU waited for, bits unpacked into edge indices.
    pub gpu_s: f64,
    /// The same round trip without the dispatch (copy, wait, map): the
    /// fixed cost of asking the GPU mid-frame.
    pub read_back_s: f64,
    /// The one-time upload of the planes and edge faces and the pipeline.
    pub gpu_setup_s: f64,
    /// Chaining the silhouette edges, which follows either way on the CPU.
    pub chain_s: f64,
    /// Whether both gave the same edges at every eye timed.
    pub same: bool,
}

/// Silhouette classification on the CPU against the compute pass, fastest
/// of `frames` interleaved eyes (a slow turn around the sphere, so every
/// frame classifies anew), one row per sphere resolution.
pub fn classify_rows(
    gpu: &Gpu,
    segments: &[u32],
    frames: u32,
    mut progress: impl FnMut(&str),
) -> Result<Vec<ClassifyRow>, RunError> {
    let mut sources = npr_diag::SourceMap::new();
    let mut rows = Vec::new();
    for &n in segments {
        progress(&format!("silhouette classification, sphere of {n} segments"));
        let scene = sphere_scene(n, &mut sources)?;
        let edges = npr_runner::lines::edges::EdgeMesh::new(&scene.objects[0].mesh);
        let t = Instant::now();
        let gpu_classes = crate::silhouettes_gpu::GpuSilhouettes::new(gpu, &edges)?;
        wait_idle(gpu)?;
        let gpu_setup_s = t.elapsed().as_secs_f64();
        gpu_classes.classify(gpu, glam::DVec3::new(0.0, 0.4, 3.5))?; // warm-up
        let (mut cpu_s, mut gpu_s, mut chain_s) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
        let mut read_back_s = f64::INFINITY;
        let (mut same, mut silhouette_edges) = (true, 0);
        for k in 0..frames.max(1) {
            let a = 0.01 * f64::from(k + 1);
            let eye = glam::DVec3::new(3.5 * a.sin(), 0.4, 3.5 * a.cos());
            let t = Instant::now();
            let cpu = edges.silhouettes(eye);
            cpu_s = cpu_s.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let on_gpu = gpu_classes.classify(gpu, eye)?;
            gpu_s = gpu_s.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            gpu_classes.read_back_only(gpu)?;
            read_back_s = read_back_s.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let chains = edges.chain(&cpu);
            chain_s = chain_s.min(t.elapsed().as_secs_f64());
            std::hint::black_box(chains);
            same &= cpu == on_gpu;
            silhouette_edges = cpu.len();
        }
        rows.push(ClassifyRow {
            segments: n,
            mesh_edges: edges.edges.len(),
            silhouette_edges,
            cpu_s,
            gpu_s,
            read_back_s,
            gpu_setup_s,
            chain_s,
            same,
        });
    }
    Ok(rows)
}

pub fn classify_table(rows: &[ClassifyRow]) -> String {
    let mut out = String::from(
        "| segments | mesh edges | silhouette edges | CPU classify (ms) | compute classify + read-back (ms) | of which the read-back alone (ms) | compute / CPU | CPU + chain (ms) | compute + chain (ms) | compute setup, once (ms) | same edges |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for r in rows {
        out.push_str(&format!(
            "| {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.2} | {:.3} | {:.3} | {:.1} | {} |\n",
            r.segments,
            r.mesh_edges,
            r.silhouette_edges,
            r.cpu_s * 1e3,
            r.gpu_s * 1e3,
            r.read_back_s * 1e3,
            r.gpu_s / r.cpu_s,
            (r.cpu_s + r.chain_s) * 1e3,
            (r.gpu_s + r.chain_s) * 1e3,
            r.gpu_setup_s * 1e3,
            if r.same { "yes" } else { "no" }
        ));
    }
    out
}

/// One method's row of the comparison.
#[derive(Debug, Clone)]
pub struct MethodRow {
    pub name: &'static str,
    pub frame_s: f64,
    /// Frame time over its base pass's.
    pub method_s: f64,
    pub min_precision: f64,
    pub min_recall: f64,
}

/// The methods compared: (name, program, index of its base in `bases`).
pub struct Methods<'a> {
    pub methods: Vec<(&'static str, &'a StyleProgram, usize)>,
    pub bases: Vec<&'a StyleProgram>,
}

/// Cost on [`crate::bench_contours::timing_scene`] and accuracy on the
/// analytic scenes, at `size`².
pub fn method_rows(
    gpu: &Gpu,
    methods: &Methods,
    size: u32,
    frames: u32,
    mut progress: impl FnMut(&str),
) -> Result<Vec<MethodRow>, RunError> {
    let mut sources = npr_diag::SourceMap::new();
    let timing = crate::bench_contours::timing_scene(&mut sources)?;
    progress(&format!("timing the methods at {size}x{size}"));
    let mut programs: Vec<&StyleProgram> = methods.bases.clone();
    programs.extend(methods.methods.iter().map(|m| m.1));
    let best = time_interleaved(gpu, &programs, &timing, (size, size), frames)?;
    let scenes = builtin_scenes();
    let loaded: Vec<_> = scenes
        .iter()
        .map(|s| s.scene(&mut sources).map_err(RunError::User))
        .collect::<Result<_, _>>()?;
    let mut rows = Vec::new();
    for (i, (name, program, base)) in methods.methods.iter().enumerate() {
        progress(&format!("accuracy of {name}"));
        let (mut min_p, mut min_r) = (1.0f64, 1.0f64);
        for (s, scene) in scenes.iter().zip(&loaded) {
            let img = npr_runner::render_frame(gpu, program, scene, &FrameSpec::still(size, size, 0))?;
            let a = accuracy(&ink_mask(&img, 0.5), &s.truth(size, size), 1);
            min_p = min_p.min(a.precision);
            min_r = min_r.min(a.recall);
        }
        let frame_s = best[methods.bases.len() + i];
        rows.push(MethodRow {
            name,
            frame_s,
            method_s: frame_s - best[*base],
            min_precision: min_p,
            min_recall: min_r,
        });
    }
    Ok(rows)
}

pub fn method_table(rows: &[MethodRow]) -> String {
    let mut out = String::from(
        "| method | frame (ms) | over its base pass (ms) | min precision | min recall |\n|---|---:|---:|---:|---:|\n",
    );
    for r in rows {
        out.push_str(&format!(
            "| {} | {:.2} | {:.2} | {:.3} | {:.3} |\n",
            r.name,
            r.frame_s * 1e3,
            r.method_s * 1e3,
            r.min_precision,
            r.min_recall
        ));
    }
    out
}
