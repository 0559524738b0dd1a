//! `npr bench overhead`: the runner's cost per frame against an independent
//! hand-written wgpu program that draws the same WGSL passes
//! ([`baseline::Baseline`], which shares no object and no code with the
//! runner's executors). A benchmark, never a test; the test of the baseline
//! (`tests/gpu/bench_overhead.rs`) only checks that it draws the same image.
//!
//! Before timing, both draw one frame and their output images are compared
//! (as [`same_image`] does): the baseline must do the same work, so a difference
//! over 1/255 is an error, not a figure. Then runner frames
//! (`Renderer::render` + GPU wait) and baseline frames (uniform writes,
//! recording, submit + GPU wait) alternate in one run, the order swapped
//! every round so neither side always follows the other, after warm-up
//! frames of both. Reported: median, minimum and spread (10th and 90th
//! percentiles, maximum) per side, the ratios of the medians and of the
//! minima, and the median of the per-round ratios (each round's two frames
//! ran back to back, so that one is least affected by load drift). A second
//! set of rounds times the CPU steps of a frame on both sides (uniform
//! writes, recording, submit), which is where the runner's own work is.

pub mod baseline;
pub(crate) mod setup;
mod support;
mod uniforms;

use crate::bench::wait_idle;
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram, TargetImage};
use std::time::Instant;

/// The largest per-channel difference between the two images that counts as
/// the same image: one step of an 8-bit channel (and f32 rounding).
pub const SAME_IMAGE: f32 = 1.0 / 255.0 + 1e-6;

#[derive(Debug)]
pub enum OverheadError {
    /// The style or scene needs something the baseline does not do.
    Unsupported(String),
    /// The baseline's image is not the runner's: it is not doing the same work.
    Mismatch(ImageDiff),
    /// wgpu refused the baseline's objects, or the program is inconsistent.
    Wgpu(String),
    /// The runner failed.
    Run(RunError),
}

impl std::fmt::Display for OverheadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OverheadError::Unsupported(what) => {
                write!(f, "the independent baseline does not implement {what}")
            }
            OverheadError::Mismatch(d) => write!(f, "the baseline's image differs from the runner's: {d}"),
            OverheadError::Wgpu(m) => write!(f, "baseline: {m}"),
            OverheadError::Run(e) => write!(f, "runner: {e}"),
        }
    }
}

impl std::error::Error for OverheadError {}

impl From<RunError> for OverheadError {
    fn from(e: RunError) -> OverheadError {
        OverheadError::Run(e)
    }
}

/// How far apart two output images are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageDiff {
    pub width: u32,
    pub height: u32,
    /// The largest absolute difference of any channel (as floats; unorm / 255).
    pub max_abs: f32,
    /// Where it is.
    pub at: (u32, u32),
    /// Texels with any difference.
    pub texels_differing: usize,
}

impl std::fmt::Display for ImageDiff {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "max |diff| {:.6} at ({}, {}), {} of {}x{} texels differ",
            self.max_abs, self.at.0, self.at.1, self.texels_differing, self.width, self.height
        )
    }
}

/// Compare two images of the same size and format, texel by texel.
pub fn image_diff(a: &TargetImage, b: &TargetImage) -> Result<ImageDiff, OverheadError> {
    if (a.width, a.height, a.format) != (b.width, b.height, b.format) {
        return Err(OverheadError::Wgpu(format!(
            "output {}x{} {} against {}x{} {}",
            a.width,
            a.height,
            a.format.name(),
            b.width,
            b.height,
            b.format.name()
        )));
    }
    let mut d = ImageDiff {
        width: a.width,
        height: a.height,
        max_abs: 0.0,
        at: (0, 0),
        texels_differing: 0,
    };
    for y in 0..a.height {
        for x in 0..a.width {
            let (p, q) = (a.texel(x, y), b.texel(x, y));
            let diff = p.iter().zip(&q).map(|(u, v)| (u - v).abs()).fold(0.0f32, f32::max);
            if diff > 0.0 || diff.is_nan() {
                d.texels_differing += 1;
            }
            if diff > d.max_abs || diff.is_nan() {
                d.max_abs = if diff.is_nan() { f32::INFINITY } else { diff };
                d.at = (x, y);
            }
        }
    }
    Ok(d)
}

fn spec((width, height): (u32, u32), frame: u32) -> FrameSpec {
    FrameSpec::animated(width, height, frame, FrameSpec::DEFAULT_FPS, 0)
}

/// Draw frame `frame` with both and compare the outputs; over
/// [`SAME_IMAGE`] is [`OverheadError::Mismatch`].
fn compare(
    runner: &mut npr_runner::Renderer,
    baseline: &mut baseline::Baseline,
    scene: &npr_runner::scene::Scene,
    size: (u32, u32),
    frame: u32,
) -> Result<ImageDiff, OverheadError> {
    let s = spec(size, frame);
    runner.render(scene, &s)?;
    let ours = runner.read_output()?;
    baseline.frame(scene, s.time_s, s.frame);
    let theirs = baseline.read_output()?;
    let d = image_diff(&ours, &theirs)?;
    if d.max_abs > SAME_IMAGE {
        return Err(OverheadError::Mismatch(d));
    }
    Ok(d)
}

/// Build the runner and the baseline for `program` on `scene` at `size`,
/// draw `frames` (at 24 frames per second) with each in turn, and compare
/// their output images after each; the largest difference is returned.
pub fn same_image(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    size: (u32, u32),
    frames: &[u32],
) -> Result<ImageDiff, OverheadError> {
    let mut r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    let mut b = baseline::Baseline::new(&gpu.device, &gpu.queue, program, scene, size)?;
    let mut worst: Option<ImageDiff> = None;
    for &f in frames {
        let d = compare(&mut r, &mut b, scene, size, f)?;
        if worst.is_none_or(|w| d.max_abs > w.max_abs) {
            worst = Some(d);
        }
    }
    worst.ok_or_else(|| OverheadError::Wgpu("no frame to compare".into()))
}

/// Seconds per frame of one side: order statistics over the timed frames.
#[derive(Debug, Clone, Copy)]
pub struct Spread {
    pub median: f64,
    pub min: f64,
    pub p10: f64,
    pub p90: f64,
    pub max: f64,
}

impl Spread {
    pub fn of(values: &[f64]) -> Spread {
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let at = |q: f64| {
            v.get(((v.len().max(1) - 1) as f64 * q).round() as usize)
                .copied()
                .unwrap_or(0.0)
        };
        Spread {
            median: at(0.5),
            min: at(0.0),
            p10: at(0.1),
            p90: at(0.9),
            max: at(1.0),
        }
    }
}

/// Median CPU seconds of the steps of a frame (timed separately from the
/// frames of [`Overhead::runner`] and [`Overhead::baseline`]).
#[derive(Debug, Clone, Copy)]
pub struct Steps {
    /// Runner: `Renderer::prepare`; baseline: `write_uniforms`.
    pub uniforms: f64,
    /// A command encoder, every pass recorded into it, `finish`.
    pub record: f64,
    /// `Queue::submit`.
    pub submit: f64,
}

/// The result of [`overhead`].
#[derive(Debug, Clone)]
pub struct Overhead {
    pub width: u32,
    pub height: u32,
    pub passes: usize,
    pub warmup: u32,
    pub frames: u32,
    /// The check before timing.
    pub diff: ImageDiff,
    /// `Renderer::render` + GPU wait.
    pub runner: Spread,
    /// The baseline's frame + GPU wait.
    pub baseline: Spread,
    /// Until `render` / the baseline's frame returned (uniforms, recording,
    /// submit), before the wait.
    pub runner_cpu: Spread,
    pub baseline_cpu: Spread,
    /// Per round: runner frame / baseline frame.
    pub paired: Spread,
    /// The CPU steps of a frame, from a second set of rounds.
    pub runner_steps: Steps,
    pub baseline_steps: Steps,
}

impl Overhead {
    pub fn ratio_of_medians(&self) -> f64 {
        self.runner.median / self.baseline.median.max(1e-12)
    }

    pub fn ratio_of_minima(&self) -> f64 {
        self.runner.min / self.baseline.min.max(1e-12)
    }

    /// A Markdown table of both sides and the ratios.
    pub fn table(&self) -> String {
        let ms = |s: f64| format!("{:.3}", s * 1e3);
        let row = |name: &str, s: &Spread, cpu: &Spread| {
            format!(
                "| {name} | {} | {} | {} – {} | {} | {} |\n",
                ms(s.median),
                ms(s.min),
                ms(s.p10),
                ms(s.p90),
                ms(s.max),
                ms(cpu.median)
            )
        };
        let mut t = String::from(
            "| program | median (ms/frame) | min | p10 – p90 | max | until submit returns, median (ms) |\n|---|---:|---:|---:|---:|---:|\n",
        );
        t += &row("runner (`Renderer::render` + wait)", &self.runner, &self.runner_cpu);
        t += &row("independent wgpu program (+ wait)", &self.baseline, &self.baseline_cpu);
        let us = |s: f64| format!("{:.1}", s * 1e6);
        t += "\n| CPU per frame, median (µs) | uniforms | record | submit |\n|---|---:|---:|---:|\n";
        for (name, s) in [
            ("runner (`prepare`, `encode`)", &self.runner_steps),
            ("independent wgpu program", &self.baseline_steps),
        ] {
            t += &format!(
                "| {name} | {} | {} | {} |\n",
                us(s.uniforms),
                us(s.record),
                us(s.submit)
            );
        }
        t += &format!(
            "\nratio runner / baseline: medians {:.3}x, minima {:.3}x, per-round pairs median {:.3}x (p10 {:.3}x, p90 {:.3}x)\n",
            self.ratio_of_medians(),
            self.ratio_of_minima(),
            self.paired.median,
            self.paired.p10,
            self.paired.p90
        );
        t
    }
}

/// Time `frames` rounds of one runner frame and one baseline frame each
/// (order alternating), after the image check and `warmup` frames of both.
pub fn overhead(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    size: (u32, u32),
    frames: u32,
    warmup: u32,
) -> Result<Overhead, OverheadError> {
    let mut r = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    let mut b = baseline::Baseline::new(&gpu.device, &gpu.queue, program, scene, size)?;
    let diff = compare(&mut r, &mut b, scene, size, 0)?;
    let wait = || wait_idle(gpu);
    for f in 0..warmup {
        r.render(scene, &spec(size, f))?;
        wait()?;
        let s = spec(size, f);
        b.frame(scene, s.time_s, s.frame);
        wait()?;
    }
    let frames = frames.max(1);
    let (mut ours, mut theirs, mut ours_cpu, mut theirs_cpu) = (vec![], vec![], vec![], vec![]);
    for round in 0..frames {
        let s = spec(size, warmup + round);
        for side in [round % 2, 1 - round % 2] {
            let t = Instant::now();
            if side == 0 {
                r.render(scene, &s)?;
            } else {
                b.frame(scene, s.time_s, s.frame);
            }
            let submitted = t.elapsed().as_secs_f64();
            wait()?;
            let total = t.elapsed().as_secs_f64();
            let (times, cpu) = if side == 0 {
                (&mut ours, &mut ours_cpu)
            } else {
                (&mut theirs, &mut theirs_cpu)
            };
            times.push(total);
            cpu.push(submitted);
        }
    }
    let paired: Vec<f64> = ours.iter().zip(&theirs).map(|(a, b)| a / b.max(1e-12)).collect();
    // The CPU steps, in more rounds of both (the GPU work waited for, untimed).
    let (mut ours_steps, mut theirs_steps) = (vec![], vec![]);
    for round in 0..frames {
        let s = spec(size, warmup + frames + round);
        for side in [round % 2, 1 - round % 2] {
            let t = Instant::now();
            if side == 0 {
                r.prepare(scene, &s)?;
            } else {
                b.write_uniforms(scene, s.time_s, s.frame);
            }
            let uniforms = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let commands = if side == 0 {
                let mut encoder = gpu.device.create_command_encoder(&Default::default());
                r.encode(&mut encoder);
                encoder.finish()
            } else {
                b.record()
            };
            let record = t.elapsed().as_secs_f64();
            let t = Instant::now();
            gpu.queue.submit([commands]);
            let submit = t.elapsed().as_secs_f64();
            wait()?;
            let steps = if side == 0 { &mut ours_steps } else { &mut theirs_steps };
            steps.push([uniforms, record, submit]);
        }
    }
    let median_steps = |v: &[[f64; 3]]| {
        let m = |i: usize| Spread::of(&v.iter().map(|s| s[i]).collect::<Vec<_>>()).median;
        Steps {
            uniforms: m(0),
            record: m(1),
            submit: m(2),
        }
    };
    Ok(Overhead {
        width: size.0,
        height: size.1,
        passes: program.manifest.passes.len(),
        warmup,
        frames,
        diff,
        runner: Spread::of(&ours),
        baseline: Spread::of(&theirs),
        runner_cpu: Spread::of(&ours_cpu),
        baseline_cpu: Spread::of(&theirs_cpu),
        paired: Spread::of(&paired),
        runner_steps: median_steps(&ours_steps),
        baseline_steps: median_steps(&theirs_steps),
    })
}
