//! `npr bench patterns`: the cost of the dynamic 2D pattern tracker
//! (`examples/lib/dynamic_pattern.npr`, Breslav et al. 2007 §3.1–3.3)
//! against the samples per object and the objects, as a share of the frame
//! next to the shading pass, and the GPU's f32 solve against the f64 solve
//! of the same samples (`patterns_f64`): its error, and the CPU's time.
//!
//! Each object is a sphere in a grid over the screen, moved and turned a
//! little every frame. A frame of the tracker and a halftone shading pass is
//! timed next to a frame of the same shading pass with a fixed pattern
//! frame (`NULL_SHADE`), interleaved; the difference is the tracking (wall
//! clock: lavapipe's timestamps do not bracket compute work).

use crate::bench::wait_idle;
use crate::bench_reduce::median;
use crate::patterns_f64::{ids_f64, solve, View};
use glam::{DVec2, Mat4, Vec3};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};
use std::time::Instant;

// The tracker (`examples/lib/dynamic_pattern.npr`, as the examples `use`
// it) is the caller's to pass: it lies outside this package, which must
// build alone from the registry.

/// The halftone shading of `examples/halftone.npr`, without its LOD.
const SHADE: &str = r#"
pass shade: render(scene) {
  let tone = saturate(dot(normal, light.dir)) * 0.85 + 0.1
  let uv = pattern_uv(pattern.o, pattern.u, pattern.v)
  let cover = 1.0 - smoothstep(0.3, 0.36, length(fract(uv) - vec2(0.5)) / sqrt(max(1.0 - tone, 1e-3)))
  out color: rgba8unorm = vec4(vec3(1.0 - cover), 1.0)
}
output shade.color
"#;

/// The same shading with a fixed pattern frame: the frame without tracking.
pub const NULL_SHADE: &str = r#"style "Pattern benchmark, no tracking"
pass shade: render(scene) {
  let tone = saturate(dot(normal, light.dir)) * 0.85 + 0.1
  let uv = pattern_uv(vec2(0.0), vec2(10.4, 6.0), vec2(-6.0, 10.4))
  let cover = 1.0 - smoothstep(0.3, 0.36, length(fract(uv) - vec2(0.5)) / sqrt(max(1.0 - tone, 1e-3)))
  out color: rgba8unorm = vec4(vec3(1.0 - cover), 1.0)
}
output shade.color
"#;

/// `tracker` (the text of `examples/lib/dynamic_pattern.npr`) with
/// `samples` per object, and the shading pass.
pub fn style(tracker: &str, samples: u32) -> String {
    format!(
        "{}\n{SHADE}",
        tracker.replace("count: 400", &format!("count: {samples}"))
    )
}

/// The image size.
pub const SIZE: u32 = 256;

/// `objects` spheres in a grid over the screen, 6 m from the camera.
pub fn scene(objects: usize) -> Result<Scene, RunError> {
    let mut text = String::from(
        "[camera]\nposition = [0.0, 0.0, 6.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n[light]\ndirection = [0.3, 1.0, 1.0]\n\n",
    );
    let n = (objects as f64).sqrt().ceil() as usize;
    let step = 4.0 / n as f64;
    for o in 0..objects {
        text += &format!(
            "[[object]]\nprimitive = {{ kind = \"sphere\", radius = {:.4}, segments = 48, rings = 24 }}\ntranslate = [{:.4}, {:.4}, 0.0]\n\n",
            step * 0.4,
            -2.0 + step * ((o % n) as f64 + 0.5),
            -2.0 + step * ((o / n) as f64 + 0.5)
        );
    }
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("patterns-bench.toml", text.clone());
    npr_runner::scene::parse_scene(&text, file, std::path::Path::new(".")).map_err(RunError::User)
}

/// One measured configuration.
#[derive(Debug, Clone)]
pub struct Row {
    pub samples: u32,
    pub objects: usize,
    /// Samples drawn over all objects.
    pub drawn: usize,
    /// Median wall ms a frame with the tracker takes more than one without.
    pub tracking_ms: f64,
    /// Median wall ms of the frame with the tracker.
    pub frame_ms: f64,
    /// Largest |z_gpu − z_f64| / |z_f64| over the objects, after a motion.
    pub z_error: f64,
    /// CPU ms of the same solve in f64 (projection, weights, sums) for all
    /// objects, from samples drawn before.
    pub cpu_ms: f64,
}

/// Object `o`'s model in frame `k`: its grid place, drifting and turning.
fn model(base: Mat4, o: usize, k: u32) -> Mat4 {
    let t = k as f32 * 0.1 + o as f32;
    Mat4::from_translation(Vec3::new(0.03 * t.sin(), 0.02 * t.cos(), 0.05 * (0.7 * t).sin()))
        * base
        * Mat4::from_rotation_y(0.05 * k as f32)
}

/// Measure every (samples, objects) pair; `progress` gets a line per pair.
pub fn run(
    gpu: &Gpu,
    tracker: &str,
    null: &StyleProgram,
    compile: impl Fn(&str) -> Result<StyleProgram, RunError>,
    (samples, objects): (&[u32], &[usize]),
    frames: u32,
    progress: impl Fn(&str),
) -> Result<Vec<Row>, RunError> {
    let mut rows = Vec::new();
    for &n in samples {
        let program = compile(&style(tracker, n))?;
        let ids_target = program
            .manifest
            .targets
            .iter()
            .position(|t| t.name == "ids.id")
            .ok_or_else(|| RunError::Internal("the tracker has no `ids.id`".into()))?;
        for &m in objects {
            let started = Instant::now();
            let mut scene = scene(m)?;
            let bases: Vec<Mat4> = scene.objects.iter().map(|o| o.model).collect();
            let mut with = npr_runner::Renderer::new(&gpu.device, &gpu.queue, &program, &scene)?;
            let mut without = npr_runner::Renderer::new(&gpu.device, &gpu.queue, null, &scene)?;
            let mut frame = 0u32;
            let render = |r: &mut npr_runner::Renderer, scene: &mut Scene, k: u32| -> Result<(), RunError> {
                for (o, object) in scene.objects.iter_mut().enumerate() {
                    object.model = model(bases[o], o, k);
                }
                let spec = FrameSpec::animated(SIZE, SIZE, k, FrameSpec::DEFAULT_FPS, 0);
                r.render(scene, &spec)?;
                wait_idle(gpu)
            };
            render(&mut with, &mut scene, frame)?;
            render(&mut without, &mut scene, frame)?;
            let (mut t_with, mut t_without) = (Vec::new(), Vec::new());
            for _ in 0..frames.max(1) {
                frame += 1;
                let t = Instant::now();
                render(&mut with, &mut scene, frame)?;
                t_with.push(t.elapsed().as_secs_f64());
                let t = Instant::now();
                render(&mut without, &mut scene, frame)?;
                t_without.push(t.elapsed().as_secs_f64());
            }
            // Accuracy: one more frame, against f64 from both ID images.
            let ids_before = ids_f64(&with.read_target(ids_target)?);
            let u_before = frame_u(&with)?;
            frame += 1;
            render(&mut with, &mut scene, frame)?;
            let ids_now = ids_f64(&with.read_target(ids_target)?);
            let u_now = frame_u(&with)?;
            let pose = scene.camera.pose(0.0);
            let view_proj = (pose.projection(1.0) * pose.view(0)).as_dmat4();
            // The samples are drawn before the clock starts: they are the
            // solve's input, drawn once when an object is loaded (as the
            // runner draws the GPU's), not part of a frame's solve. Drawing
            // them (the grid search of `samples::stratified`) costs 10–30×
            // the solve; timed with it, as it once was, the solve looked up
            // to 100× slower than it is.
            let drawn_samples: Vec<_> = (0..scene.objects.len())
                .map(|o| {
                    npr_runner::scene::samples::stratified(
                        &scene.objects[o].mesh,
                        n as usize,
                        npr_runner::scene::samples::object_seed(1, o),
                    )
                })
                .collect();
            let drawn = drawn_samples.iter().map(|s| s.samples.len()).sum();
            let cpu = Instant::now();
            let mut z_error = 0.0f64;
            for ((o, object), samples) in scene.objects.iter().enumerate().zip(&drawn_samples) {
                let (before, now) = (
                    View {
                        model: model(bases[o], o, frame - 1).as_dmat4(),
                        view_proj,
                        ids: &ids_before,
                    },
                    View {
                        model: model(bases[o], o, frame).as_dmat4(),
                        view_proj,
                        ids: &ids_now,
                    },
                );
                if let Some((_, _, z)) = solve(
                    &object.mesh,
                    samples,
                    (&before, &now),
                    (SIZE, SIZE),
                    (o as f64 + 1.0, 2.0, true),
                ) {
                    let z = DVec2::from(z);
                    let tracked = cdiv(u_now[o], u_before[o]);
                    z_error = z_error.max((tracked - z).length() / z.length());
                }
            }
            let cpu_ms = cpu.elapsed().as_secs_f64() * 1e3;
            let (a, b) = (median(t_with), median(t_without));
            let row = Row {
                samples: n,
                objects: m,
                drawn,
                tracking_ms: (a - b) * 1e3,
                frame_ms: a * 1e3,
                z_error,
                cpu_ms,
            };
            progress(&format!(
                "{n} samples × {m} objects: tracking {:.3} ms of {:.3} ms in {:.1} s",
                row.tracking_ms,
                row.frame_ms,
                started.elapsed().as_secs_f64()
            ));
            rows.push(row);
        }
    }
    Ok(rows)
}

/// Every object's `pattern.u`.
fn frame_u(r: &npr_runner::Renderer) -> Result<Vec<DVec2>, RunError> {
    Ok(r.read_object_values("pattern")?
        .iter()
        .map(|v| DVec2::new(v[1][0] as f64, v[1][1] as f64))
        .collect())
}

fn cdiv(a: DVec2, b: DVec2) -> DVec2 {
    DVec2::new(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / b.length_squared()
}

/// The rows as a Markdown table.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| samples / object | objects | samples drawn | tracking ms | share of frame | ns / sample | rel. error of z (f32 GPU vs f64) | f64 CPU ms |\n|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {} | {:.3} | {:.0} % | {:.1} | {:.1e} | {:.2} |\n",
            r.samples,
            r.objects,
            r.drawn,
            r.tracking_ms,
            100.0 * r.tracking_ms / r.frame_ms.max(1e-9),
            r.tracking_ms * 1e6 / r.drawn.max(1) as f64,
            r.z_error,
            r.cpu_ms
        ));
    }
    s
}
