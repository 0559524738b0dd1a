//! The GPU benchmarks' commands: operators, contours, reductions, pixel
//! passes, whole styles, passes and runner overhead, each against its
//! baseline in the same run.

use super::{compile_builtin, compile_builtin_scheduled, plot, plotted, scene_style_gpu, scene_styles_gpu};
use crate::printer::{compile, headless_gpu, load_scene};
use npr_compiler::schedule::Schedule;
use npr_compiler::{CompileOptions, Compiled};
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK, EXIT_USER};
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_runner::{Gpu, RunError, StyleProgram};
use std::path::{Path, PathBuf};

/// `npr bench overhead`: the runner against the independent baseline.
pub(super) fn overhead(
    style: &Path,
    scene_path: &Path,
    size: (u32, u32),
    (frames, warmup): (u32, u32),
    printer: &Printer,
) -> i32 {
    let mut sources = SourceMap::new();
    let (scene, compiled, gpu) = match scene_style_gpu(style, scene_path, &mut sources, printer) {
        Ok(t) => t,
        Err(code) => return code,
    };
    match npr_lab::bench_overhead::overhead(&gpu, &compiled.program(), &scene, size, frames, warmup) {
        Ok(r) => {
            println!(
                "device: {}, {}x{}, style {} ({} pass(es)), scene {}",
                gpu.describe(),
                size.0,
                size.1,
                style.display(),
                r.passes,
                scene_path.display()
            );
            println!(
                "{} rounds of one frame each (order alternating) after {} warm-up frames; images before timing: {}",
                r.frames, r.warmup, r.diff
            );
            print!("{}", r.table());
            EXIT_OK
        }
        Err(npr_lab::bench_overhead::OverheadError::Run(e)) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            if e.is_user_error() {
                EXIT_USER
            } else {
                EXIT_INTERNAL
            }
        }
        Err(e @ npr_lab::bench_overhead::OverheadError::Unsupported(_)) => {
            printer.fail(Diagnostic::error(codes::BENCH_UNSUPPORTED, e.to_string()))
        }
        Err(e) => {
            // The baseline disagreeing with the runner is a bug in one of them.
            printer.diagnostics(&[Diagnostic::error(codes::INTERNAL, e.to_string())], &SourceMap::new());
            EXIT_INTERNAL
        }
    }
}

pub(super) fn ops(scene_path: &Path, size: (u32, u32), frames: u32, plot: Option<&Path>, printer: &Printer) -> i32 {
    let mut sources = SourceMap::new();
    let scene = match load_scene(scene_path, &mut sources, printer) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let variants = npr_lab::bench_ops::variants();
    let mut programs = Vec::new();
    for v in &variants {
        let text = npr_lab::bench_ops::style(v);
        match compile_builtin(v.name, &text, &mut sources, printer) {
            Ok(p) => programs.push((v.name, p)),
            Err(code) => return code,
        }
    }
    // Frame-level round robin over all variants, so load changes hit every variant alike.
    let progs: Vec<&StyleProgram> = programs.iter().map(|(_, p)| p).collect();
    let best = match npr_lab::bench::time_interleaved(&gpu, &progs, &scene, size, frames) {
        Ok(t) => t,
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            return EXIT_INTERNAL;
        }
    };
    println!(
        "device: {}, {}x{}, scene {}",
        gpu.describe(),
        size.0,
        size.1,
        scene_path.display()
    );
    let rows = npr_lab::bench_ops::rows(&variants, &best);
    print!("{}", npr_lab::bench_ops::table(&rows));
    let subtitle = format!(
        "{}, {}x{}, scene {}, fastest of {frames} interleaved frames",
        gpu.describe(),
        size.0,
        size.1,
        scene_path.display()
    );
    plotted(|| plot::figures::ops(&rows, &subtitle), plot, printer)
}

pub(super) fn contours(sizes: &[u32], frames: u32, plot: Option<&Path>, printer: &Printer) -> i32 {
    if sizes.contains(&0) {
        return printer.fail(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            "--sizes 0: an image is at least 1 pixel wide",
        ));
    }
    for s in sizes {
        if let Err(code) = printer.check(npr_diag::sizes::check_size((*s, *s))) {
            return code;
        }
    }
    let mut sources = SourceMap::new();
    // Every variant as declared (naive); each method again under `auto`
    // where the compiler's schedule changes its passes, under `tiled`
    // where it tiles, and under `recompute` where it recomputes.
    let mut programs = Vec::new();
    for (name, text, measure) in npr_lab::bench_contours::variants() {
        match compile_builtin_scheduled(name, &text, Schedule::Naive, &mut sources, printer) {
            Ok((p, _)) => programs.push((name.to_string(), p, measure)),
            Err(code) => return code,
        }
        if measure {
            for schedule in [Schedule::Auto, Schedule::Tiled, Schedule::Recompute] {
                let label = schedule.name();
                match compile_builtin_scheduled(name, &text, schedule, &mut sources, printer) {
                    // `tiled` only where it tiles (else it is `auto`),
                    // `recompute` only where it recomputes (else `tiled`).
                    Ok((p, changes))
                        if changes.any()
                            && match schedule {
                                Schedule::Tiled => changes.tiled > 0,
                                Schedule::Recompute => changes.recomputed > 0,
                                Schedule::Naive | Schedule::Auto => true,
                            } =>
                    {
                        programs.push((format!("{name} [{label}: {changes}]"), p, measure))
                    }
                    Ok(_) => {}
                    Err(code) => return code,
                }
            }
        }
    }
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    match npr_lab::bench_contours::run(&gpu, &programs, sizes, frames, |m| eprintln!("{m}")) {
        Ok(rows) => {
            println!(
                "device: {}, fastest of {frames} interleaved frames per variant",
                gpu.describe()
            );
            println!("{}", npr_lab::bench_contours::table(&rows));
            let mut distinct = sizes.to_vec();
            distinct.sort_unstable();
            distinct.dedup();
            if distinct.len() > 1 {
                println!("image stage against pixels, least squares over the sizes (1.00 = linear):");
                println!(
                    "{}",
                    npr_lab::bench_contours::slope_table(&npr_lab::bench_contours::slopes(&rows))
                );
            }
            let subtitle = format!("{}, fastest of {frames} interleaved frames", gpu.describe());
            plotted(|| plot::figures::contours(&rows, &subtitle), plot, printer)
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            EXIT_INTERNAL
        }
    }
}

/// `npr bench reduce`: see `npr_lab::bench_reduce`.
pub(super) fn reduce(elements: &[usize], objects: &[usize], frames: u32, printer: &Printer) -> i32 {
    if let Some(bad) = elements.iter().chain(objects).find(|n| **n == 0 || **n > 10_000_000) {
        return printer.fail(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("count {bad} is outside 1..=10000000"),
        ));
    }
    with_and_without(
        ("reduce.npr", npr_lab::bench_reduce::STYLE),
        npr_lab::bench_reduce::NULL_STYLE,
        frames,
        printer,
        |gpu, programs| {
            npr_lab::bench_reduce::run(gpu, programs, elements, objects, frames, |m| eprintln!("{m}"))
                .map(|rows| npr_lab::bench_reduce::table(&rows))
        },
    )
}

/// `npr bench pixels`: see `npr_lab::bench_reduce_pixels`.
pub(super) fn pixels(sizes: &[u32], objects: &[usize], frames: u32, printer: &Printer) -> i32 {
    if let Some(bad) = sizes.iter().find(|s| **s == 0 || **s > 8192) {
        return printer.fail(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("size {bad} is outside 1..=8192"),
        ));
    }
    if let Some(bad) = objects.iter().find(|n| **n == 0 || **n > 10_000) {
        return printer.fail(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("object count {bad} is outside 1..=10000"),
        ));
    }
    with_and_without(
        ("pixels.npr", npr_lab::bench_reduce_pixels::STYLE),
        npr_lab::bench_reduce_pixels::NULL_STYLE,
        frames,
        printer,
        |gpu, programs| {
            npr_lab::bench_reduce_pixels::run(gpu, programs, sizes, objects, frames, |m| eprintln!("{m}"))
                .map(|rows| npr_lab::bench_reduce_pixels::table(&rows))
        },
    )
}

/// A benchmark of a built-in style against the same frame without the
/// measured pass (`null`): both compiled, the device opened, `run` measures
/// and returns its table, which is printed under the device's name.
fn with_and_without(
    (name, style): (&str, &str),
    null: &str,
    frames: u32,
    printer: &Printer,
    run: impl FnOnce(&Gpu, (&StyleProgram, &StyleProgram)) -> Result<String, RunError>,
) -> i32 {
    let mut sources = SourceMap::new();
    let mut programs = Vec::new();
    for (name, text) in [(name, style), ("null.npr", null)] {
        match compile_builtin(name, text, &mut sources, printer) {
            Ok(p) => programs.push(p),
            Err(code) => return code,
        }
    }
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    match run(&gpu, (&programs[0], &programs[1])) {
        Ok(table) => {
            println!(
                "device: {}, median of {frames} interleaved frames (wall clock)",
                gpu.describe()
            );
            println!("{table}");
            EXIT_OK
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            EXIT_INTERNAL
        }
    }
}

/// `npr bench styles`: see `npr_lab::bench_styles`.
pub(super) fn styles(
    styles: &[PathBuf],
    baseline: &Path,
    scene_path: &Path,
    size: (u32, u32),
    frames: u32,
    printer: &Printer,
) -> i32 {
    let mut sources = SourceMap::new();
    let (scene, base, gpu) = match scene_style_gpu(baseline, scene_path, &mut sources, printer) {
        Ok(t) => t,
        Err(code) => return code,
    };
    let opts = CompileOptions {
        scene: Some(scene.summary(&scene_path.display().to_string())),
        ..Default::default()
    };
    let mut programs = Vec::new();
    for s in styles {
        match compile(s, &mut sources, &opts, printer) {
            Ok(c) => programs.push((s.display().to_string(), c.program())),
            Err(code) => return code,
        }
    }
    match npr_lab::bench_styles::run(&gpu, &scene, &base.program(), &programs, size, (frames, 5)) {
        Ok(rows) => {
            println!(
                "device: {}, {}x{}, median of {frames} interleaved frames (wall clock)",
                gpu.describe(),
                size.0,
                size.1
            );
            println!(
                "{}",
                npr_lab::bench_styles::table(&rows, &baseline.display().to_string())
            );
            EXIT_OK
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            EXIT_INTERNAL
        }
    }
}

/// `npr bench passes`: each pass's GPU time and its share of the frame,
/// under each schedule, and the totals against the first schedule's.
pub(super) fn passes(
    style: &Path,
    scene_path: &Path,
    size: (u32, u32),
    frames: u32,
    schedules: &[Schedule],
    printer: &Printer,
) -> i32 {
    let mut sources = SourceMap::new();
    let (scene, compiled, gpu) = match scene_styles_gpu(style, scene_path, schedules, &mut sources, printer) {
        Ok(t) => t,
        Err(code) => return code,
    };
    println!(
        "device: {}, {}x{}, style {}, scene {}, median of {frames} frames",
        gpu.describe(),
        size.0,
        size.1,
        style.display(),
        scene_path.display()
    );
    // Every schedule is measured in this run, frames interleaved, so the
    // totals compare (docs/PERFORMANCE.md: ratios from one run).
    let programs: Vec<StyleProgram> = compiled.iter().map(Compiled::program).collect();
    let all_times = match npr_lab::bench::pass_times_interleaved(&gpu, &programs, &scene, size, frames) {
        Ok(t) => t,
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            return if e.is_user_error() { EXIT_USER } else { EXIT_INTERNAL };
        }
    };
    let mut totals = Vec::new();
    for ((schedule, c), times) in schedules.iter().zip(&compiled).zip(all_times) {
        let total: f64 = times.iter().map(|t| t.ms).sum();
        let changes = super::ScheduleChanges::of(c);
        if schedules.len() > 1 {
            println!("\nschedule `{}` ({changes}):", schedule.name());
        }
        println!("| pass | scale | GPU ms | share of frame |");
        println!("|---|---:|---:|---:|");
        for (t, p) in times.iter().zip(&c.manifest.passes) {
            println!(
                "| {} | {} | {:.3} | {:.1}% |",
                t.name,
                p.scale,
                t.ms,
                100.0 * t.ms / total.max(1e-12)
            );
        }
        println!("| **all passes** | | {total:.3} | 100% |");
        totals.push((schedule.name(), changes, c.manifest.passes.len(), total));
    }
    if let [(first, _, _, base), _, ..] = totals.as_slice() {
        println!("\n| schedule | changes | passes | GPU ms, all passes | / {first} |");
        println!("|---|---|---:|---:|---:|");
        for (name, changes, passes, total) in &totals {
            println!(
                "| {name} | {changes} | {passes} | {total:.3} | {:.2} |",
                total / base.max(1e-12)
            );
        }
    }
    EXIT_OK
}
