//! `npr bench`: each benchmark's command (argument limits, the styles it
//! compiles, the device, its table); the measuring is in `lab`.

mod artmaps;
mod compile;
mod gpu;
mod host;
mod http_client;
mod lines;
mod patterns;
mod studio;

use crate::cli::BenchCommand;
use crate::printer::{compile, headless_gpu, load_scene};
use npr_compiler::schedule::Schedule;
use npr_compiler::{CompileError, CompileOptions, Compiled};
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK};
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_lab::plot;
use npr_runner::{Gpu, StyleProgram};
use std::path::Path;

/// `cmd` with each style and scene under `examples/` that is not here
/// read from the bundled copy (`crate::bundled`), so that every benchmark
/// runs from any directory.
fn bundled_paths(mut cmd: BenchCommand) -> std::io::Result<BenchCommand> {
    for path in cmd.input_paths_mut() {
        *path = crate::bundled::resolve(path)?;
    }
    Ok(cmd)
}

pub fn run(cmd: BenchCommand, printer: &Printer) -> i32 {
    let cmd = match bundled_paths(cmd) {
        Ok(c) => c,
        Err(e) => return printer.fail(npr_diag::writes::cannot_write(&std::env::temp_dir(), e)),
    };
    // A bad `--plot` path is refused before minutes of measuring.
    if let Some(path) = cmd.plot() {
        if let Err(code) = printer.check(plot::check_path(path)) {
            return code;
        }
    }
    match cmd {
        BenchCommand::Compile {
            styles,
            iterations,
            cold,
            runs,
        } => {
            let table = if cold {
                compile::cold(&styles, runs)
            } else {
                compile::in_process(&styles, iterations)
            };
            match table {
                Ok(t) => {
                    print!("{t}");
                    EXIT_OK
                }
                Err(e) => printer
                    .fail(Diagnostic::error(codes::BENCH_UNSUPPORTED, "the benchmark could not run").with_note(e)),
            }
        }
        BenchCommand::Artmaps {
            sizes,
            size,
            frames,
            plot,
        } => artmaps::run(&sizes, size, frames, plot.as_deref(), printer),
        BenchCommand::Lines {
            segments,
            size,
            frames,
            plot,
        } => lines::run(&segments, size, frames, plot.as_deref(), printer),
        BenchCommand::Ops {
            scene,
            size,
            frames,
            plot,
        } => gpu::ops(&scene, size, frames, plot.as_deref(), printer),
        BenchCommand::Contours { sizes, frames, plot } => gpu::contours(&sizes, frames, plot.as_deref(), printer),
        BenchCommand::Reduce {
            elements,
            objects,
            frames,
        } => gpu::reduce(&elements, &objects, frames, printer),
        BenchCommand::Pixels { sizes, objects, frames } => gpu::pixels(&sizes, &objects, frames, printer),
        BenchCommand::Patterns {
            samples,
            objects,
            frames,
            plot,
        } => patterns::run(&samples, &objects, frames, plot.as_deref(), printer),
        BenchCommand::Styles {
            styles,
            baseline,
            scene,
            size,
            frames,
        } => gpu::styles(&styles, &baseline, &scene, size, frames, printer),
        BenchCommand::Passes {
            style,
            scene,
            size,
            frames,
            schedule,
        } => {
            let schedules: Vec<Schedule> = schedule.into_iter().map(Schedule::from).collect();
            gpu::passes(&style, &scene, size, frames, &schedules, printer)
        }
        BenchCommand::Studio {
            style,
            scene,
            size,
            frames,
            edits,
            param,
            values,
        } => match values.as_slice() {
            [a, b] => studio::run(
                &studio::StudioBench {
                    style: &style,
                    scene: &scene,
                    size,
                    frames,
                    edits,
                    param: &param,
                    values: (a, b),
                },
                printer,
            ),
            _ => printer.fail(Diagnostic::error(codes::USAGE, "--values takes two values, `A,B`")),
        },
        BenchCommand::Host {
            style,
            objects,
            size,
            frames,
            block,
        } => host::run(&style, &objects, size, (frames, block), printer),
        BenchCommand::Overhead {
            style,
            scene,
            size,
            frames,
            warmup,
        } => gpu::overhead(&style, &scene, size, (frames, warmup), printer),
        BenchCommand::Frame {
            style,
            scene,
            size,
            frames,
            keep_params,
        } => {
            let mut sources = SourceMap::new();
            let opts = CompileOptions {
                keep_params,
                ..Default::default()
            };
            let c = match compile(&style, &mut sources, &opts, printer) {
                Ok(c) => c,
                Err(code) => return code,
            };
            let scene = match load_scene(&scene, &mut sources, printer) {
                Ok(s) => s,
                Err(code) => return code,
            };
            let gpu = match headless_gpu(printer) {
                Ok(g) => g,
                Err(code) => return code,
            };
            match npr_lab::bench::frame_overhead(&gpu, &c.program(), &scene, size, frames) {
                Ok(r) => {
                    println!("device: {}", gpu.describe());
                    println!("{}", r.table());
                    EXIT_OK
                }
                Err(e) => {
                    printer.diagnostics(&e.diagnostics(), &sources);
                    EXIT_INTERNAL
                }
            }
        }
    }
}

impl BenchCommand {
    /// The style and scene files the benchmark reads.
    fn input_paths_mut(&mut self) -> Vec<&mut std::path::PathBuf> {
        match self {
            BenchCommand::Compile { styles, .. } => styles.iter_mut().collect(),
            BenchCommand::Styles {
                styles,
                baseline,
                scene,
                ..
            } => styles.iter_mut().chain([baseline, scene]).collect(),
            BenchCommand::Ops { scene, .. } => vec![scene],
            BenchCommand::Passes { style, scene, .. }
            | BenchCommand::Studio { style, scene, .. }
            | BenchCommand::Frame { style, scene, .. }
            | BenchCommand::Overhead { style, scene, .. } => vec![style, scene],
            BenchCommand::Host { style, .. } => vec![style],
            _ => Vec::new(),
        }
    }

    /// The `--plot` file of the benchmarks that draw one.
    fn plot(&self) -> Option<&Path> {
        match self {
            BenchCommand::Artmaps { plot, .. }
            | BenchCommand::Lines { plot, .. }
            | BenchCommand::Ops { plot, .. }
            | BenchCommand::Contours { plot, .. }
            | BenchCommand::Patterns { plot, .. } => plot.as_deref(),
            _ => None,
        }
    }
}

/// Writes `figure` when `--plot` was given: the exit code of the command.
fn plotted(figure: impl FnOnce() -> plot::Figure, path: Option<&Path>, printer: &Printer) -> i32 {
    match path {
        Some(path) => match write_plot(&figure(), path, printer) {
            Ok(()) => EXIT_OK,
            Err(code) => code,
        },
        None => EXIT_OK,
    }
}

/// Writes a `--plot` figure and says where, or prints why not: a figure
/// that cannot be drawn is npr's failure (exit 2), a path that cannot be
/// written the user's (exit 1).
pub(crate) fn write_plot(figure: &plot::Figure, path: &Path, printer: &Printer) -> Result<(), i32> {
    match plot::write(figure, path) {
        Ok(()) => {
            eprintln!("plot written to {}", path.display());
            Ok(())
        }
        Err(d) if d.code == codes::INTERNAL => {
            printer.diagnostics(&[d], &SourceMap::new());
            Err(EXIT_INTERNAL)
        }
        Err(d) => Err(printer.fail(d)),
    }
}

/// Compile a style the benchmarks carry in their source: any error in it is
/// npr's (the internal exit code), printed with its diagnostics.
pub(crate) fn compile_builtin(
    name: &str,
    text: &str,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<StyleProgram, i32> {
    compile_builtin_in(name, text, Path::new("."), sources, printer)
}

/// [`compile_builtin`] under `schedule`, with the number of passes fused.
/// Benchmarks compile `naive` by default: their baselines (a second
/// passthrough pass, a null pass) are declared passes that fusion would
/// remove; `npr bench contours` adds the `auto` rows where the schedule
/// changes the passes.
pub(crate) fn compile_builtin_scheduled(
    name: &str,
    text: &str,
    schedule: Schedule,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<(StyleProgram, ScheduleChanges), i32> {
    compile_builtin_with(name, text, Path::new("."), schedule, sources, printer)
}

/// [`compile_builtin`] with its relative paths (textures, filters)
/// resolved against `dir`.
pub(crate) fn compile_builtin_in(
    name: &str,
    text: &str,
    dir: &Path,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<StyleProgram, i32> {
    compile_builtin_with(name, text, dir, Schedule::Naive, sources, printer).map(|(p, _)| p)
}

/// What the schedule changed in a compiled style: passes fused into their
/// reader, and image passes run as workgroup tiles (the report's entries).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ScheduleChanges {
    pub fused: usize,
    pub tiled: usize,
    /// Passes computed in their reader's tiles.
    pub recomputed: usize,
}

impl ScheduleChanges {
    /// The changes a compilation's report lists.
    pub fn of(c: &Compiled) -> ScheduleChanges {
        let count = |action: &str| c.report.entries.iter().filter(|e| e.action == action).count();
        ScheduleChanges {
            fused: count("fused"),
            tiled: count("tiled"),
            recomputed: count("recomputed"),
        }
    }

    pub fn any(self) -> bool {
        self.fused + self.tiled + self.recomputed > 0
    }
}

impl std::fmt::Display for ScheduleChanges {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} fused, {} tiled", self.fused, self.tiled)?;
        if self.recomputed > 0 {
            write!(f, ", {} recomputed", self.recomputed)?;
        }
        Ok(())
    }
}

fn compile_builtin_with(
    name: &str,
    text: &str,
    dir: &Path,
    schedule: Schedule,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<(StyleProgram, ScheduleChanges), i32> {
    let opts = CompileOptions {
        schedule,
        ..Default::default()
    };
    match npr_compiler::compile_source(name, text, dir, sources, &opts) {
        Ok(c) => Ok((c.program(), ScheduleChanges::of(&c))),
        Err(CompileError::User(d)) => {
            printer.diagnostics(&d, sources);
            Err(EXIT_INTERNAL)
        }
        Err(CompileError::Internal(e)) => {
            printer.diagnostics(&[e.to_diagnostic()], sources);
            Err(EXIT_INTERNAL)
        }
    }
}

/// What the benchmarks of one style on one scene need: the scene, the style
/// compiled for it, and the headless GPU; or the exit code, with the
/// diagnostics printed.
pub(crate) fn scene_style_gpu(
    style: &Path,
    scene_path: &Path,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<(npr_runner::scene::Scene, Compiled, Gpu), i32> {
    let (scene, mut compiled, gpu) = scene_styles_gpu(style, scene_path, &[Schedule::default()], sources, printer)?;
    let compiled = compiled.pop().ok_or(EXIT_INTERNAL)?;
    Ok((scene, compiled, gpu))
}

/// [`scene_style_gpu`] with the style compiled once per schedule, in order.
pub(crate) fn scene_styles_gpu(
    style: &Path,
    scene_path: &Path,
    schedules: &[Schedule],
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<(npr_runner::scene::Scene, Vec<Compiled>, Gpu), i32> {
    let scene = load_scene(scene_path, sources, printer)?;
    let mut compiled = Vec::new();
    for &schedule in schedules {
        let opts = CompileOptions {
            scene: Some(scene.summary(&scene_path.display().to_string())),
            schedule,
            ..Default::default()
        };
        compiled.push(compile(style, sources, &opts, printer)?);
    }
    Ok((scene, compiled, headless_gpu(printer)?))
}
