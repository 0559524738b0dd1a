//! Frame-time measurements for `npr bench frame` and `npr bench passes`
//! (benchmarks, never tests; per-pass timestamps are `npr_runner::pass_timer`).
//!
//! Ratios are taken in one run with interleaved samples, so machine load
//! affects both sides alike.

use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};
use std::time::Instant;

pub struct FrameOverhead {
    pub width: u32,
    pub height: u32,
    pub frames: u32,
    /// Median seconds per frame of `Renderer::render` + GPU wait.
    pub runner_s: f64,
    /// Median seconds per frame of the bare passes + GPU wait.
    pub bare_s: f64,
}

impl FrameOverhead {
    pub fn table(&self) -> String {
        format!(
            "| size | frames | runner (ms/frame) | bare passes (ms/frame) | ratio |\n|---|---:|---:|---:|---:|\n| {}x{} | {} | {:.3} | {:.3} | {:.3}x |",
            self.width,
            self.height,
            self.frames,
            self.runner_s * 1e3,
            self.bare_s * 1e3,
            self.runner_s / self.bare_s.max(1e-12)
        )
    }
}

/// Block until the GPU has finished everything submitted.
pub fn wait_idle(gpu: &Gpu) -> Result<(), RunError> {
    npr_runner::readback::wait_idle(&gpu.device)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

pub fn frame_overhead(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    (width, height): (u32, u32),
    frames: u32,
) -> Result<FrameOverhead, RunError> {
    let mut r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    let wait = || wait_idle(gpu);
    let spec = |frame: u32| FrameSpec::animated(width, height, frame, FrameSpec::DEFAULT_FPS, 0);
    // Warm up: pipelines compiled, textures allocated.
    r.render(scene, &spec(0))?;
    wait()?;
    let mut ours = Vec::new();
    let mut bare = Vec::new();
    for f in 0..frames.max(1) {
        let t = Instant::now();
        r.render(scene, &spec(f))?;
        wait()?;
        ours.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        r.encode(&mut encoder);
        gpu.queue.submit([encoder.finish()]);
        wait()?;
        bare.push(t.elapsed().as_secs_f64());
    }
    Ok(FrameOverhead {
        width,
        height,
        frames,
        runner_s: median(ours),
        bare_s: median(bare),
    })
}

/// Median seconds per frame of `program` (render + GPU wait), after one warm-up frame.
pub fn frame_time(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    (width, height): (u32, u32),
    frames: u32,
) -> Result<f64, RunError> {
    let mut r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    let wait = || wait_idle(gpu);
    let spec = FrameSpec::still(width, height, 0);
    r.render(scene, &spec)?;
    wait()?;
    let mut times = Vec::new();
    for _ in 0..frames.max(1) {
        let t = Instant::now();
        r.render(scene, &spec)?;
        wait()?;
        times.push(t.elapsed().as_secs_f64());
    }
    Ok(median(times))
}

/// Seconds per frame (render + GPU wait) of each program: frames interleaved
/// round robin after one warm-up frame each; the fastest frame is reported,
/// the figure least disturbed by other work on a shared CPU (lavapipe).
pub fn time_interleaved(
    gpu: &Gpu,
    programs: &[&StyleProgram],
    scene: &npr_runner::scene::Scene,
    (width, height): (u32, u32),
    frames: u32,
) -> Result<Vec<f64>, RunError> {
    let spec = FrameSpec::still(width, height, 0);
    let wait = || wait_idle(gpu);
    let mut renderers = Vec::new();
    for p in programs {
        let mut r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, p, scene)?;
        r.render(scene, &spec)?;
        wait()?;
        renderers.push(r);
    }
    let mut times = vec![Vec::new(); renderers.len()];
    for _ in 0..frames.max(1) {
        for (i, r) in renderers.iter_mut().enumerate() {
            let t = Instant::now();
            r.render(scene, &spec)?;
            wait()?;
            times[i].push(t.elapsed().as_secs_f64());
        }
    }
    Ok(times
        .into_iter()
        .map(|v| v.into_iter().fold(f64::INFINITY, f64::min))
        .collect())
}

/// GPU time of each pass of a style, from timestamp queries.
#[derive(Debug, Clone)]
pub struct PassTime {
    pub name: String,
    /// Median GPU milliseconds per frame.
    pub ms: f64,
}

/// Per-pass GPU times (median over `frames`, after a warm-up frame), read
/// from timestamps written at the beginning and end of every pass.
pub fn pass_times(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    size: (u32, u32),
    frames: u32,
) -> Result<Vec<PassTime>, RunError> {
    let mut all = pass_times_interleaved(gpu, std::slice::from_ref(program), scene, size, frames)?;
    all.pop()
        .ok_or_else(|| RunError::Internal("pass_times_interleaved returned no program".into()))
}

/// [`pass_times`] of several programs (the same style under different
/// schedules, say), their frames interleaved so that a change of load
/// falls on all of them alike; one list per program, in order.
pub fn pass_times_interleaved(
    gpu: &Gpu,
    programs: &[StyleProgram],
    scene: &npr_runner::scene::Scene,
    (width, height): (u32, u32),
    frames: u32,
) -> Result<Vec<Vec<PassTime>>, RunError> {
    let spec = FrameSpec::still(width, height, 0);
    let mut timed = Vec::new();
    for program in programs {
        let passes = program.manifest.passes.len();
        let timer = npr_runner::pass_timer::PassTimer::new(gpu, passes).ok_or_else(|| {
            RunError::Limit(format!(
                "{} has no timestamp queries: per-pass times cannot be measured",
                gpu.describe()
            ))
        })?;
        let r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
        timed.push((timer, r, vec![Vec::new(); passes]));
    }
    for frame in 0..=frames.max(1) {
        for (timer, r, per_pass) in timed.iter_mut() {
            let ms = timer.frame(gpu, r, scene, &spec)?;
            // Frame 0 warms up pipelines and caches; it is not counted.
            if frame > 0 {
                for (times, t) in per_pass.iter_mut().zip(ms) {
                    times.push(t);
                }
            }
        }
    }
    Ok(timed
        .into_iter()
        .map(|(_, r, per_pass)| {
            r.manifest()
                .passes
                .iter()
                .zip(per_pass)
                .map(|(p, times)| PassTime {
                    name: p.name.clone(),
                    ms: median(times),
                })
                .collect()
        })
        .collect())
}
