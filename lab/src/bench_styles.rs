//! `npr bench styles`: the frame cost of whole styles against a baseline
//! style (e.g. `examples/toon.npr`) on the same scene, in one run. Frames of
//! the styles and the baseline alternate, each style's renderer drawing its
//! frames in order (path-dependent styles see the same previous frames as
//! in a sequence); the figure is the ratio of medians (wall clock: submit
//! and wait).

use crate::bench::wait_idle;
use crate::bench_reduce::median;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};
use std::time::Instant;

/// One style's median frame time and its ratio to the baseline's.
#[derive(Debug, Clone)]
pub struct Row {
    pub name: String,
    pub frame_ms: f64,
    pub baseline_ms: f64,
}

/// `styles` (name, program) against `baseline`, `frames` frames each after
/// `warmup`, at `size`.
pub fn run(
    gpu: &Gpu,
    scene: &Scene,
    baseline: &StyleProgram,
    styles: &[(String, StyleProgram)],
    size: (u32, u32),
    (frames, warmup): (u32, u32),
) -> Result<Vec<Row>, RunError> {
    let mut base = npr_runner::Renderer::new(&gpu.device, &gpu.queue, baseline, scene)?;
    let mut renderers = styles
        .iter()
        .map(|(_, p)| npr_runner::Renderer::new(&gpu.device, &gpu.queue, p, scene))
        .collect::<Result<Vec<_>, _>>()?;
    let mut times = vec![Vec::new(); styles.len()];
    let mut base_times = Vec::new();
    for k in 0..warmup + frames {
        let spec = FrameSpec::animated(size.0, size.1, k, FrameSpec::DEFAULT_FPS, 0);
        let timed = |r: &mut npr_runner::Renderer| -> Result<f64, RunError> {
            let t = Instant::now();
            r.render(scene, &spec)?;
            wait_idle(gpu)?;
            Ok(t.elapsed().as_secs_f64())
        };
        let b = timed(&mut base)?;
        for (r, t) in renderers.iter_mut().zip(times.iter_mut()) {
            let s = timed(r)?;
            if k >= warmup {
                t.push(s);
            }
        }
        if k >= warmup {
            base_times.push(b);
        }
    }
    let baseline_ms = median(base_times) * 1e3;
    Ok(styles
        .iter()
        .zip(times)
        .map(|((name, _), t)| Row {
            name: name.clone(),
            frame_ms: median(t) * 1e3,
            baseline_ms,
        })
        .collect())
}

/// The rows as a Markdown table.
pub fn table(rows: &[Row], baseline: &str) -> String {
    let mut s = format!("| style | frame ms | {baseline} ms | × {baseline} |\n|---|---:|---:|---:|\n");
    for r in rows {
        s.push_str(&format!(
            "| {} | {:.2} | {:.2} | {:.2}× |\n",
            r.name,
            r.frame_ms,
            r.baseline_ms,
            r.frame_ms / r.baseline_ms.max(1e-9)
        ));
    }
    s
}
