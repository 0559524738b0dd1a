//! Command definitions (clap) and their implementations.

use crate::args::{parse_frames, parse_size};
use clap::{Parser, Subcommand, ValueEnum};
use compiler::{CompileError, CompileOptions, Compiled};
use dsl::{codes, Diagnostic, SourceMap};
use runner::schedule::FrameRequest;
use runner::{FrameSpec, Gpu, Renderer, RunError, StyleProgram};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

pub const EXIT_OK: i32 = 0;
pub const EXIT_USER: i32 = 1;
pub const EXIT_INTERNAL: i32 = 2;

#[derive(Parser, Debug)]
#[command(
    name = "npr",
    version,
    about = "Style language and shader-graph compiler for non-photorealistic rendering"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// How to print diagnostics.
    #[arg(long, global = true, value_enum, default_value_t = MessageFormat::Human)]
    pub message_format: MessageFormat,
}

#[derive(Copy, Clone, Debug, ValueEnum, PartialEq, Eq)]
pub enum MessageFormat {
    Human,
    Json,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Parse and check a style; print diagnostics only.
    Check {
        style: PathBuf,
        /// Set a parameter, typed like a default in the style: `--set bands=5`,
        /// `--set inflate=2px`, `--set base=#3080ff`, `--set beta=cubic`. Repeatable.
        #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
        set: Vec<String>,
    },
    /// Compile a style to WGSL (one file per pass) plus manifest.json.
    Compile {
        style: PathBuf,
        /// Output directory.
        #[arg(short, long)]
        out: PathBuf,
        /// Print what was removed, folded or kept, and why.
        #[arg(long)]
        report: bool,
        /// Keep parameters as uniforms (for live tweaking) instead of folding them.
        #[arg(long)]
        keep_params: bool,
        /// Write the IR after each compiler stage into OUT/ir/.
        #[arg(long)]
        dump_ir: bool,
        /// Print the time taken by each compiler stage.
        #[arg(long)]
        time_passes: bool,
        /// Compile for this scene (TOML): `scene_has(tag)` folds, and what
        /// only absent objects need is removed (see --report).
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Set a parameter, typed like a default in the style: `--set bands=5`,
        /// `--set inflate=2px`, `--set base=#3080ff`, `--set beta=cubic`. Repeatable.
        #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
        set: Vec<String>,
    },
    /// Render a style on a scene to an image.
    Render {
        /// The style (.npr); compiled for the scene.
        #[arg(required_unless_present = "compiled")]
        style: Option<PathBuf>,
        /// Run a directory written by `npr compile -o DIR` instead of a style
        /// (its manifest is validated first).
        #[arg(long, value_name = "DIR", conflicts_with_all = ["style", "keep_params"])]
        compiled: Option<PathBuf>,
        /// Scene file (TOML).
        #[arg(long)]
        scene: PathBuf,
        /// Output image (.png or .exr). With --frames, `{frame}` in the name is
        /// replaced by the frame number (otherwise `_NNNN` is appended).
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Output size, WIDTHxHEIGHT.
        #[arg(long, default_value = "512x512", value_parser = parse_size)]
        size: (u32, u32),
        /// Time in seconds (for animated parameters and cameras). A style that
        /// reads `previous(...)` or keeps `state` in a compute pass depends on
        /// earlier frames: it is rendered by
        /// replaying frames 0..=round(time × fps) at --fps (so the frame equals
        /// the same frame of a --frames sequence), and the last one is written.
        #[arg(long, default_value_t = 0.0)]
        time: f64,
        /// Render frames A..B (exclusive) at --fps. A style that reads
        /// `previous(...)` or keeps `state` first replays frames 0..A without
        /// writing them.
        #[arg(long, value_parser = parse_frames)]
        frames: Option<(u32, u32)>,
        #[arg(long, default_value_t = 24.0)]
        fps: f64,
        /// Which eye to render for stereo cameras (0 = left, 1 = right).
        #[arg(long, default_value_t = 0)]
        eye: u32,
        /// Write every target as an image, plus a contact sheet, into DIR.
        #[arg(long)]
        dump_passes: Option<PathBuf>,
        #[arg(long)]
        keep_params: bool,
        /// Set a parameter, typed like a default in the style: `--set bands=5`,
        /// `--set inflate=2px`, `--set base=#3080ff`, `--set beta=cubic`. Repeatable.
        #[arg(long = "set", value_name = "NAME=VALUE", conflicts_with = "compiled", value_parser = crate::set_params::parse_set_arg)]
        set: Vec<String>,
    },
    /// Render on every change to the style, what it `use`s, the scene, its
    /// textures and meshes; a bad save prints diagnostics and keeps the last
    /// good image. Runs until interrupted.
    Watch {
        style: PathBuf,
        /// Scene file (TOML).
        #[arg(long)]
        scene: PathBuf,
        /// Output size, WIDTHxHEIGHT.
        #[arg(long, default_value = "512x512", value_parser = parse_size)]
        size: (u32, u32),
        /// Time in seconds (for animated parameters and cameras).
        #[arg(long, default_value_t = 0.0)]
        time: f64,
        #[arg(long, default_value_t = 24.0)]
        fps: f64,
        /// Which eye to render for stereo cameras (0 = left, 1 = right).
        #[arg(long, default_value_t = 0)]
        eye: u32,
        /// Output image (.png or .exr), written atomically.
        #[arg(short, long)]
        out: PathBuf,
        /// Set a parameter, typed like a default in the style (see `npr render --help`). Repeatable.
        #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
        set: Vec<String>,
    },
    /// Live authoring in the browser: a local web server with the rendered
    /// image, controls for the parameters, every pass, diagnostics in place
    /// and timings, re-rendered on every save. See docs/STUDIO.md.
    Studio {
        style: PathBuf,
        /// Scene file (TOML).
        #[arg(long)]
        scene: PathBuf,
        /// Output size, WIDTHxHEIGHT.
        #[arg(long, default_value = "512x512", value_parser = parse_size)]
        size: (u32, u32),
        /// Time in seconds (for animated parameters and cameras).
        #[arg(long, default_value_t = 0.0)]
        time: f64,
        #[arg(long, default_value_t = 24.0)]
        fps: f64,
        /// Which eye to render for stereo cameras (0 = left, 1 = right).
        #[arg(long, default_value_t = 0)]
        eye: u32,
        /// Address to bind; anything but a loopback address exposes the
        /// studio (and your files) to the network.
        #[arg(long, default_value = "127.0.0.1")]
        host: String,
        /// Port; 0 picks a free one. The address is printed at start.
        #[arg(long, default_value_t = 0)]
        port: u16,
        /// Set a parameter, typed like a default in the style (see `npr render --help`). Repeatable.
        #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
        set: Vec<String>,
    },
    /// Benchmarks; see docs/PERFORMANCE.md.
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Generate a tileable texture with npr's own generator (the same one
    /// `noise(...)` textures use) and write it as a 16-bit PNG.
    Texgen {
        /// Output PNG.
        #[arg(short, long)]
        out: PathBuf,
        /// Width and height in texels.
        #[arg(long, default_value_t = 256)]
        size: u32,
        #[arg(long, default_value_t = 4)]
        octaves: u32,
        #[arg(long, default_value_t = 1)]
        seed: u32,
        /// Channels with independent noise (1: grey, 2: a warp-vector field in r, g).
        #[arg(long, default_value_t = 1)]
        channels: u32,
        /// Lattice cells across the texture at the first octave.
        #[arg(long, default_value_t = 4)]
        frequency: u32,
        /// `value` or `gradient` noise, or `paint`: an 8-bit painterly colour
        /// map around `--color` (Age of Sail §5.2 lit/shadow textures).
        #[arg(long, default_value = "gradient")]
        kind: String,
        /// Base colour `#rrggbb` of a `paint` map.
        #[arg(long)]
        color: Option<String>,
    },
}

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Compile time of our front end and code generation against naga's own
    /// parse + validate of the WGSL we emit, measured in the same run.
    ///
    /// `--cold` instead times whole `npr compile` processes (wall clock, as a
    /// user runs them) and naga's share of each.
    Compile {
        styles: Vec<PathBuf>,
        #[arg(long, default_value_t = 50)]
        iterations: u32,
        /// Spawn a fresh `npr compile` process per run and time its wall clock.
        #[arg(long)]
        cold: bool,
        /// Processes per style with `--cold`.
        #[arg(long, default_value_t = 10)]
        runs: u32,
    },
    /// Operator cost against a plain texture-sample pass, per variant, in one run.
    Ops {
        #[arg(long, default_value = "examples/scenes/spheres.toml")]
        scene: PathBuf,
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        #[arg(long, default_value_t = 20)]
        frames: u32,
    },
    /// Contour methods (LSA base/full and each extension, Sobel,
    /// normal+depth): image-stage cost against a passthrough pass over the
    /// same G-buffer, pixel throughput, and precision/recall against
    /// analytic ground truth, per resolution.
    Contours {
        /// Square image sizes, comma-separated.
        #[arg(long, default_value = "128,256,512", value_delimiter = ',')]
        sizes: Vec<u32>,
        #[arg(long, default_value_t = 10)]
        frames: u32,
    },
    /// A compute pass's per-object reduction (Σ px and a count over each
    /// object's vertices): GPU time against elements and objects, against a
    /// copy kernel over the same positions, and its error against f64.
    Reduce {
        /// Total elements (vertices), comma-separated.
        #[arg(long, default_value = "1000,10000,100000,1000000", value_delimiter = ',')]
        elements: Vec<usize>,
        /// Object counts the elements are split over, comma-separated.
        #[arg(long, default_value = "1,10,100", value_delimiter = ',')]
        objects: Vec<usize>,
        #[arg(long, default_value_t = 10)]
        frames: u32,
    },
    /// A compute pass over the pixels of an ID image (`compute(pixels, ids.id)`):
    /// cost against the image size and the objects on screen, a copy kernel
    /// over as many floats in the same run, and the error against f64.
    Pixels {
        /// Square image sizes, comma-separated.
        #[arg(long, default_value = "128,256,512,1024", value_delimiter = ',')]
        sizes: Vec<u32>,
        /// Object counts (spheres in a grid over the screen), comma-separated.
        #[arg(long, default_value = "1,10,100", value_delimiter = ',')]
        objects: Vec<usize>,
        #[arg(long, default_value_t = 10)]
        frames: u32,
    },
    /// The dynamic 2D pattern tracker (examples/lib/dynamic_pattern.npr):
    /// cost against samples per object and objects, as a share of the frame,
    /// and the GPU's solve against f64 (error, and the CPU's time).
    Patterns {
        /// Samples per object, comma-separated.
        #[arg(long, default_value = "100,1000,10000,100000", value_delimiter = ',')]
        samples: Vec<u32>,
        /// Object counts (spheres in a grid), comma-separated.
        #[arg(long, default_value = "1,10", value_delimiter = ',')]
        objects: Vec<usize>,
        #[arg(long, default_value_t = 10)]
        frames: u32,
    },
    /// Whole styles' frame time against a baseline style on one scene, in one run
    /// (each style's frames in order, so path-dependent styles are measured as they render).
    Styles {
        styles: Vec<PathBuf>,
        #[arg(long, default_value = "examples/toon.npr")]
        baseline: PathBuf,
        #[arg(long)]
        scene: PathBuf,
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        #[arg(long, default_value_t = 20)]
        frames: u32,
    },
    /// GPU time of each pass of a style (timestamp queries), as a share of the frame.
    Passes {
        style: PathBuf,
        #[arg(long)]
        scene: PathBuf,
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        #[arg(long, default_value_t = 30)]
        frames: u32,
    },
    /// The runner's per-frame work against itself: `Renderer::render`
    /// (uniform updates, recording, submit, wait) against `Renderer::encode`
    /// of the same renderer — its own pipelines and bind groups recorded and
    /// submitted with no uniform writes. Not an independent comparison; that
    /// is `npr bench overhead`.
    Frame {
        style: PathBuf,
        #[arg(long)]
        scene: PathBuf,
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        #[arg(long, default_value_t = 60)]
        frames: u32,
    },
    /// Runner overhead per frame against an independent hand-written wgpu
    /// program drawing the same WGSL passes with its own pipelines, bind
    /// groups, buffers and textures. Both images are compared first (equal
    /// within 1/255, or it stops); then frames of the two alternate in one run.
    Overhead {
        #[arg(long, default_value = "examples/rounded_shadows.npr")]
        style: PathBuf,
        #[arg(long, default_value = "examples/scenes/spot.toml")]
        scene: PathBuf,
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        /// Timed rounds (one frame of each per round).
        #[arg(long, default_value_t = 60)]
        frames: u32,
        /// Untimed frames of each before the rounds.
        #[arg(long, default_value_t = 5)]
        warmup: u32,
    },
}

pub(crate) struct Printer {
    format: MessageFormat,
    color: bool,
}

impl Printer {
    pub(crate) fn diagnostics(&self, diags: &[Diagnostic], sources: &SourceMap) {
        if diags.is_empty() {
            return;
        }
        match self.format {
            MessageFormat::Json => print!("{}", dsl::diagnostic::render_json(diags, sources)),
            MessageFormat::Human => eprint!("{}", dsl::diagnostic::render(diags, sources, self.color)),
        }
    }

    /// Print one diagnostic that points into no file (a command-line value,
    /// an output path, the device) and give the user-error exit code.
    pub(crate) fn fail(&self, d: Diagnostic) -> i32 {
        self.diagnostics(&[d], &SourceMap::new());
        EXIT_USER
    }

    /// [`Printer::fail`] for a check of the arguments.
    fn check(&self, checked: Result<(), Diagnostic>) -> Result<(), i32> {
        checked.map_err(|d| self.fail(d))
    }
}

/// An output that cannot be written: E0503.
fn cannot_write(path: &Path, e: impl std::fmt::Display) -> Diagnostic {
    Diagnostic::error(codes::CANNOT_WRITE, format!("cannot write {}: {e}", path.display()))
        .with_help("check that the directory exists and is writable")
}

pub fn run(cli: Cli) -> i32 {
    let printer = Printer {
        format: cli.message_format,
        color: std::io::stderr().is_terminal(),
    };
    let mut sources = SourceMap::new();
    match cli.command {
        Command::Check { style, set } => {
            match crate::set_params::compile(&style, &set, &mut sources, &CompileOptions::default(), &printer) {
                Ok(c) => {
                    printer.diagnostics(&c.warnings, &sources);
                    let texture_errors = crate::texture_check::texture_file_errors(&c);
                    if !texture_errors.is_empty() {
                        printer.diagnostics(&texture_errors, &sources);
                        return EXIT_USER;
                    }
                    if printer.format == MessageFormat::Human {
                        eprintln!(
                            "ok: style \"{}\": {} pass(es), {} target(s)",
                            c.manifest.style,
                            c.manifest.passes.len(),
                            c.manifest.targets.len()
                        );
                    }
                    EXIT_OK
                }
                Err(code) => code,
            }
        }
        Command::Compile {
            style,
            out,
            report,
            keep_params,
            dump_ir,
            time_passes,
            scene,
            set,
        } => {
            if out.exists() && !out.is_dir() {
                return printer.fail(
                    Diagnostic::error(
                        codes::CANNOT_WRITE,
                        format!("-o {}: a file of that name exists", out.display()),
                    )
                    .with_help("`npr compile -o` names a directory, for the WGSL files and manifest.json"),
                );
            }
            let scene = match scene.map(|s| load_scene_summary(&s, &mut sources)).transpose() {
                Ok(s) => s,
                Err(diags) => {
                    printer.diagnostics(&diags, &sources);
                    return EXIT_USER;
                }
            };
            let opts = CompileOptions {
                keep_params,
                dump_ir,
                scene,
                ..Default::default()
            };
            let c = match crate::set_params::compile(&style, &set, &mut sources, &opts, &printer) {
                Ok(c) => c,
                Err(code) => return code,
            };
            printer.diagnostics(&c.warnings, &sources);
            if let Err(e) = write_compiled(&c, &out) {
                return printer.fail(cannot_write(&out, e));
            }
            if report {
                print!("{}", c.report.render());
            }
            if time_passes {
                let total: f64 = c.timings.iter().map(|(_, d)| d.as_secs_f64()).sum();
                for (stage, d) in &c.timings {
                    println!("{stage:<24} {:>9.3} ms", d.as_secs_f64() * 1e3);
                }
                println!("{:<24} {:>9.3} ms", "total", total * 1e3);
            }
            eprintln!("compiled {} pass(es) into {}", c.shaders.len(), out.display());
            EXIT_OK
        }
        Command::Bench(cmd) => bench(cmd, &printer),
        Command::Watch {
            style,
            scene,
            size,
            time,
            fps,
            eye,
            out,
            set,
        } => crate::watch::run(
            crate::watch::WatchArgs {
                inputs: crate::live::build::Inputs {
                    style,
                    scene,
                    sets: set,
                    keep_params: false,
                },
                out,
                size,
                time,
                fps,
                eye,
            },
            &printer,
        ),
        Command::Studio {
            style,
            scene,
            size,
            time,
            fps,
            eye,
            host,
            port,
            set,
        } => crate::studio::run(
            crate::studio::StudioArgs {
                inputs: crate::live::build::Inputs {
                    style,
                    scene,
                    sets: set,
                    keep_params: true,
                },
                size,
                time,
                fps,
                eye,
                host,
                port,
            },
            &printer,
        ),
        Command::Texgen {
            out,
            size,
            octaves,
            seed,
            channels,
            frequency,
            kind,
            color,
        } => {
            let kind = match crate::args::texgen_kind(&kind) {
                Ok(k) => k,
                Err(d) => return printer.fail(d),
            };
            let paint = kind == crate::args::TexgenKind::Paint;
            if let Err(code) = printer.check(crate::args::check_texgen(size, channels, octaves, frequency, paint)) {
                return code;
            }
            let gradient = match kind {
                crate::args::TexgenKind::Noise { gradient } => gradient,
                crate::args::TexgenKind::Paint => {
                    return match crate::args::paint_color(color.as_deref()) {
                        Ok(base) => texgen_paint(&out, size, seed, base, &printer),
                        Err(d) => printer.fail(d),
                    }
                }
            };
            let spec = abi::NoiseSpec {
                size,
                octaves,
                seed,
                gradient,
                channels,
                frequency,
            };
            let written = runner::texgen::write_png16(&runner::texgen::generate(&spec), &out);
            report_written(
                written,
                &out,
                &format!("{size}x{size}, {channels} channel(s)"),
                &printer,
            )
        }
        Command::Render {
            style,
            compiled,
            scene,
            out,
            size,
            time,
            frames,
            fps,
            eye,
            dump_passes,
            keep_params,
            set,
        } => {
            if let Err(code) = printer
                .check(crate::args::check_size(size))
                .and_then(|()| printer.check(crate::args::check_time(time, fps)))
            {
                return code;
            }
            let scene_name = scene.display().to_string();
            let scene = match load_scene(&scene, &mut sources, &printer) {
                Ok(s) => s,
                Err(code) => return code,
            };
            if let Err(code) = printer.check(crate::args::check_eye(eye, scene.camera.is_stereo())) {
                return code;
            }
            let program = match (compiled, style) {
                (Some(dir), _) => match StyleProgram::load_dir(&dir) {
                    Ok(p) => p,
                    Err(e) => {
                        return printer.fail(
                            Diagnostic::error(codes::BAD_COMPILED_DIR, format!("{}: {e}", dir.display()))
                                .with_help("give a directory written by `npr compile -o DIR`"),
                        )
                    }
                },
                (None, Some(style)) => {
                    // Compile for this scene, so nothing the scene cannot use is run.
                    let opts = CompileOptions {
                        keep_params,
                        scene: Some(scene.summary(&scene_name)),
                        ..Default::default()
                    };
                    let c = match crate::set_params::compile(&style, &set, &mut sources, &opts, &printer) {
                        Ok(c) => c,
                        Err(code) => return code,
                    };
                    printer.diagnostics(&c.warnings, &sources);
                    let texture_errors = crate::texture_check::texture_file_errors(&c);
                    if !texture_errors.is_empty() {
                        printer.diagnostics(&texture_errors, &sources);
                        return EXIT_USER;
                    }
                    c.program()
                }
                (None, None) => {
                    return printer.fail(Diagnostic::error(codes::USAGE, "give a style or --compiled DIR"));
                }
            };
            printer.diagnostics(&runner::scene_warnings(&program.manifest, &scene), &sources);
            let request = match frames {
                Some((start, end)) => FrameRequest::Range { start, end },
                None => FrameRequest::At { time_s: time },
            };
            let count = runner::schedule::frame_count(request, fps, program.manifest.is_path_dependent());
            if let Err(code) = printer.check(crate::args::check_frame_count(count as usize)) {
                return code;
            }
            let gpu = match headless_gpu(&printer) {
                Ok(g) => g,
                Err(code) => return code,
            };
            match render(
                &gpu,
                &program,
                &scene,
                size,
                time,
                frames,
                fps,
                eye,
                out.as_deref(),
                dump_passes.as_deref(),
            ) {
                Ok(()) => EXIT_OK,
                Err(e) => {
                    printer.diagnostics(&e.diagnostics(), &sources);
                    if e.is_user_error() {
                        EXIT_USER
                    } else {
                        EXIT_INTERNAL
                    }
                }
            }
        }
    }
}

fn bench(cmd: BenchCommand, printer: &Printer) -> i32 {
    match cmd {
        BenchCommand::Compile {
            styles,
            iterations,
            cold,
            runs,
        } => {
            let table = if cold {
                crate::bench_compile::cold(&styles, runs)
            } else {
                crate::bench_compile::in_process(&styles, iterations)
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
        BenchCommand::Ops { scene, size, frames } => bench_ops(&scene, size, frames, printer),
        BenchCommand::Contours { sizes, frames } => bench_contours(&sizes, frames, printer),
        BenchCommand::Reduce {
            elements,
            objects,
            frames,
        } => bench_reduce(&elements, &objects, frames, printer),
        BenchCommand::Pixels { sizes, objects, frames } => bench_pixels(&sizes, &objects, frames, printer),
        BenchCommand::Patterns {
            samples,
            objects,
            frames,
        } => crate::bench_patterns::run(&samples, &objects, frames, printer),
        BenchCommand::Styles {
            styles,
            baseline,
            scene,
            size,
            frames,
        } => bench_styles(&styles, &baseline, &scene, size, frames, printer),
        BenchCommand::Passes {
            style,
            scene,
            size,
            frames,
        } => bench_passes(&style, &scene, size, frames, printer),
        BenchCommand::Overhead {
            style,
            scene,
            size,
            frames,
            warmup,
        } => bench_overhead(&style, &scene, size, (frames, warmup), printer),
        BenchCommand::Frame {
            style,
            scene,
            size,
            frames,
        } => {
            let mut sources = SourceMap::new();
            let c = match compile(&style, &mut sources, &CompileOptions::default(), printer) {
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
            match lab::bench::frame_overhead(&gpu, &c.program(), &scene, size, frames) {
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

/// `npr bench overhead`: the runner against the independent baseline.
fn bench_overhead(
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
    match lab::bench_overhead::overhead(&gpu, &compiled.program(), &scene, size, frames, warmup) {
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
        Err(lab::bench_overhead::OverheadError::Run(e)) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            if e.is_user_error() {
                EXIT_USER
            } else {
                EXIT_INTERNAL
            }
        }
        Err(e @ lab::bench_overhead::OverheadError::Unsupported(_)) => {
            printer.fail(Diagnostic::error(codes::BENCH_UNSUPPORTED, e.to_string()))
        }
        Err(e) => {
            // The baseline disagreeing with the runner is a bug in one of them.
            printer.diagnostics(&[Diagnostic::error(codes::INTERNAL, e.to_string())], &SourceMap::new());
            EXIT_INTERNAL
        }
    }
}

fn bench_ops(scene_path: &Path, size: (u32, u32), frames: u32, printer: &Printer) -> i32 {
    let mut sources = SourceMap::new();
    let scene = match load_scene(scene_path, &mut sources, printer) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let variants = lab::bench_ops::variants();
    let mut programs = Vec::new();
    for v in &variants {
        let text = lab::bench_ops::style(v);
        match compile_builtin(v.name, &text, &mut sources, printer) {
            Ok(p) => programs.push((v.name, p)),
            Err(code) => return code,
        }
    }
    // Frame-level round robin over all variants, so load changes hit every variant alike.
    let progs: Vec<&StyleProgram> = programs.iter().map(|(_, p)| p).collect();
    let best = match lab::bench::time_interleaved(&gpu, &progs, &scene, size, frames) {
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
    println!("| variant | ms/frame | cost vs plain sample | scale error | anisotropy | contrast error |");
    println!("|---|---:|---:|---:|---:|---:|");
    for (i, (name, _)) in programs.iter().enumerate() {
        let errors = match &variants[i].model {
            Some(m) => {
                let (scale, aniso, contrast) = lab::bench_ops::errors(m);
                format!("{scale:.3} | {aniso:.1}° | {contrast:.3}")
            }
            None => "— | — | —".to_string(),
        };
        println!(
            "| {name} | {:.3} | {:.2}x | {errors} |",
            best[i] * 1e3,
            best[i] / best[0]
        );
    }
    EXIT_OK
}

fn bench_contours(sizes: &[u32], frames: u32, printer: &Printer) -> i32 {
    if sizes.contains(&0) {
        return printer.fail(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            "--sizes 0: an image is at least 1 pixel wide",
        ));
    }
    for s in sizes {
        if let Err(code) = printer.check(crate::args::check_size((*s, *s))) {
            return code;
        }
    }
    let mut sources = SourceMap::new();
    let mut programs = Vec::new();
    for (name, text, measure) in lab::bench_contours::variants() {
        match compile_builtin(name, &text, &mut sources, printer) {
            Ok(p) => programs.push((name, p, measure)),
            Err(code) => return code,
        }
    }
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    match lab::bench_contours::run(&gpu, &programs, sizes, frames, |m| eprintln!("{m}")) {
        Ok(rows) => {
            println!("device: {}, {frames} frames per median", gpu.describe());
            println!("{}", lab::bench_contours::table(&rows));
            EXIT_OK
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            EXIT_INTERNAL
        }
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
    match compiler::compile_source(name, text, Path::new("."), sources, &CompileOptions::default()) {
        Ok(c) => Ok(c.program()),
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

/// `npr bench reduce`: see `lab::bench_reduce`.
fn bench_reduce(elements: &[usize], objects: &[usize], frames: u32, printer: &Printer) -> i32 {
    if let Some(bad) = elements.iter().chain(objects).find(|n| **n == 0 || **n > 10_000_000) {
        return printer.fail(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("count {bad} is outside 1..=10000000"),
        ));
    }
    with_and_without(
        ("reduce.npr", lab::bench_reduce::STYLE),
        lab::bench_reduce::NULL_STYLE,
        frames,
        printer,
        |gpu, programs| {
            lab::bench_reduce::run(gpu, programs, elements, objects, frames, |m| eprintln!("{m}"))
                .map(|rows| lab::bench_reduce::table(&rows))
        },
    )
}

/// `npr bench pixels`: see `lab::bench_reduce_pixels`.
fn bench_pixels(sizes: &[u32], objects: &[usize], frames: u32, printer: &Printer) -> i32 {
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
        ("pixels.npr", lab::bench_reduce_pixels::STYLE),
        lab::bench_reduce_pixels::NULL_STYLE,
        frames,
        printer,
        |gpu, programs| {
            lab::bench_reduce_pixels::run(gpu, programs, sizes, objects, frames, |m| eprintln!("{m}"))
                .map(|rows| lab::bench_reduce_pixels::table(&rows))
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

/// `npr bench styles`: see `lab::bench_styles`.
fn bench_styles(
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
    match lab::bench_styles::run(&gpu, &scene, &base.program(), &programs, size, (frames, 5)) {
        Ok(rows) => {
            println!(
                "device: {}, {}x{}, median of {frames} interleaved frames (wall clock)",
                gpu.describe(),
                size.0,
                size.1
            );
            println!("{}", lab::bench_styles::table(&rows, &baseline.display().to_string()));
            EXIT_OK
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            EXIT_INTERNAL
        }
    }
}

/// `npr bench passes`: each pass's GPU time and its share of the frame.
fn bench_passes(style: &Path, scene_path: &Path, size: (u32, u32), frames: u32, printer: &Printer) -> i32 {
    let mut sources = SourceMap::new();
    let (scene, compiled, gpu) = match scene_style_gpu(style, scene_path, &mut sources, printer) {
        Ok(t) => t,
        Err(code) => return code,
    };
    let program = compiled.program();
    let times = match lab::bench::pass_times(&gpu, &program, &scene, size, frames) {
        Ok(t) => t,
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            return if e.is_user_error() { EXIT_USER } else { EXIT_INTERNAL };
        }
    };
    let total: f64 = times.iter().map(|t| t.ms).sum();
    println!(
        "device: {}, {}x{}, style {}, scene {}, median of {frames} frames",
        gpu.describe(),
        size.0,
        size.1,
        style.display(),
        scene_path.display()
    );
    println!("| pass | scale | GPU ms | share of frame |");
    println!("|---|---:|---:|---:|");
    for (t, p) in times.iter().zip(&compiled.manifest.passes) {
        println!(
            "| {} | {} | {:.3} | {:.1}% |",
            t.name,
            p.scale,
            t.ms,
            100.0 * t.ms / total.max(1e-12)
        );
    }
    println!("| **all passes** | | {total:.3} | 100% |");
    EXIT_OK
}

/// What the benchmarks of one style on one scene need: the scene, the style
/// compiled for it, and the headless GPU; or the exit code, with the
/// diagnostics printed.
fn scene_style_gpu(
    style: &Path,
    scene_path: &Path,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<(runner::scene::Scene, Compiled, Gpu), i32> {
    let scene = load_scene(scene_path, sources, printer)?;
    let opts = CompileOptions {
        scene: Some(scene.summary(&scene_path.display().to_string())),
        ..Default::default()
    };
    let compiled = compile(style, sources, &opts, printer)?;
    Ok((scene, compiled, headless_gpu(printer)?))
}

pub(crate) fn compile(
    style: &Path,
    sources: &mut SourceMap,
    opts: &CompileOptions,
    printer: &Printer,
) -> Result<Compiled, i32> {
    report_compile(compiler::compile_file(style, sources, opts), sources, printer)
}

/// Print a failed compile's diagnostics (and the rejected WGSL of an
/// internal error); the error is the exit code.
pub(crate) fn report_compile(
    result: Result<Compiled, CompileError>,
    sources: &SourceMap,
    printer: &Printer,
) -> Result<Compiled, i32> {
    match result {
        Ok(c) => Ok(c),
        Err(CompileError::User(diags)) => {
            printer.diagnostics(&diags, sources);
            Err(EXIT_USER)
        }
        Err(CompileError::Internal(e)) => {
            printer.diagnostics(&[e.to_diagnostic()], sources);
            if let Some(w) = &e.wgsl {
                eprintln!("--- generated WGSL ---\n{w}");
            }
            Err(EXIT_INTERNAL)
        }
    }
}

/// A headless GPU, or the exit code after saying why there is none.
pub(crate) fn headless_gpu(printer: &Printer) -> Result<Gpu, i32> {
    Gpu::headless().map_err(|e| printer.fail(e.to_diagnostic()))
}

/// Load a scene, or print its diagnostics and give the user-error exit code.
fn load_scene(path: &Path, sources: &mut SourceMap, printer: &Printer) -> Result<runner::scene::Scene, i32> {
    runner::scene::load_scene(path, sources).map_err(|d| {
        printer.diagnostics(&d, sources);
        EXIT_USER
    })
}

/// Load a scene only for what the compiler may know of it (its tags).
fn load_scene_summary(path: &Path, sources: &mut SourceMap) -> Result<abi::SceneSummary, Vec<Diagnostic>> {
    runner::scene::load_scene(path, sources).map(|s| s.summary(&path.display().to_string()))
}

fn write_compiled(c: &Compiled, out: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(out)?;
    let manifest = serde_json::to_string_pretty(&c.manifest).map_err(std::io::Error::other)?;
    let report = c.report.render();
    let mut files: Vec<(PathBuf, &[u8])> = c
        .shaders
        .iter()
        .map(|(file, wgsl)| (out.join(file), wgsl.as_bytes()))
        .collect();
    files.push((out.join("manifest.json"), manifest.as_bytes()));
    files.push((out.join("report.txt"), report.as_bytes()));
    for (i, (stage, text)) in c.dumps.iter().enumerate() {
        files.push((out.join("ir").join(format!("{i:02}_{stage}.txt")), text.as_bytes()));
    }
    // Synced together: one journal commit rather than one per file (a cold
    // `npr compile` spent 8 of its 18 ms in 14 sequential fsyncs).
    runner::output::write_all_atomic(&files)
}

fn frame_path(out: &Path, frame: u32) -> PathBuf {
    let s = out.to_string_lossy();
    if s.contains("{frame}") {
        return PathBuf::from(s.replace("{frame}", &format!("{frame:04}")));
    }
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "frame".into());
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_else(|| "png".into());
    out.with_file_name(format!("{stem}_{frame:04}.{ext}"))
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn render(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &runner::scene::Scene,
    (width, height): (u32, u32),
    time: f64,
    frames: Option<(u32, u32)>,
    fps: f64,
    eye: u32,
    out: Option<&Path>,
    dump: Option<&Path>,
) -> Result<(), RunError> {
    let mut r = Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    let io = |e: std::io::Error, p: &Path| RunError::User(vec![cannot_write(p, e)]);
    let request = match frames {
        Some((start, end)) => FrameRequest::Range { start, end },
        None => FrameRequest::At { time_s: time },
    };
    let path_dependent = program.manifest.is_path_dependent();
    let schedule = runner::schedule::schedule(request, fps, path_dependent);
    let replayed = schedule.iter().filter(|f| !f.write).count();
    if replayed > 0 {
        eprintln!(
            "note: the style reads `previous(...)` or keeps `state`, so its frames depend on earlier ones: replaying {replayed} frame(s) from frame 0 at {fps} fps"
        );
    }
    let bar = if schedule.len() > 1 {
        let b = indicatif::ProgressBar::new(schedule.len() as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} frames {elapsed_precise} eta {eta}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        Some(b)
    } else {
        None
    };
    for scheduled in &schedule {
        let frame = scheduled.frame;
        r.render(
            scene,
            &FrameSpec {
                width,
                height,
                time_s: scheduled.time_s,
                frame,
                eye,
            },
        )?;
        if !scheduled.write {
            if let Some(b) = &bar {
                b.inc(1);
            }
            continue;
        }
        if let Some(out) = out {
            let path = if frames.is_some() {
                frame_path(out, frame)
            } else {
                out.to_path_buf()
            };
            let img = r.read_output()?;
            runner::output::write_target(&img, &path).map_err(|e| io(e, &path))?;
            if frames.is_none() {
                eprintln!(
                    "wrote {} ({}x{}, {})",
                    path.display(),
                    img.width,
                    img.height,
                    gpu.describe()
                );
            }
        }
        if let Some(b) = &bar {
            b.inc(1);
        }
    }
    if let Some(b) = bar {
        b.finish();
    }
    if let Some(dir) = dump {
        // A path-dependent style's dump is of the last frame rendered (its
        // history intact); others render the requested time afresh.
        let images = match schedule.last().filter(|_| path_dependent) {
            Some(last) => {
                let spec = FrameSpec {
                    width,
                    height,
                    time_s: last.time_s,
                    frame: last.frame,
                    eye,
                };
                read_all_targets(&mut r, scene, &spec)?
            }
            None => dump_all_targets(&mut r, scene, width, height, time, eye)?,
        };
        let written = runner::output::dump_targets(&images, dir).map_err(|e| io(e, dir))?;
        eprintln!("wrote {} files into {}", written.len(), dir.display());
    }
    Ok(())
}

/// Read every target. Targets aliased onto a texture that a later pass
/// reuses are captured by re-running the frame up to the pass that wrote
/// them (by rendering with aliasing-aware reads: render, read the survivors,
/// and for the others render again and read right after their pass).
pub fn dump_all_targets(
    r: &mut Renderer,
    scene: &runner::scene::Scene,
    width: u32,
    height: u32,
    time: f64,
    eye: u32,
) -> Result<Vec<runner::TargetImage>, RunError> {
    let spec = FrameSpec {
        width,
        height,
        time_s: time,
        frame: 0,
        eye,
    };
    r.render(scene, &spec)?;
    read_all_targets(r, scene, &spec)
}

/// Read every target of the frame `spec` that `r` has just rendered;
/// aliased targets are captured by partial re-renders of that same frame
/// (which neither begin a new frame nor change any history texture).
pub fn read_all_targets(
    r: &mut Renderer,
    scene: &runner::scene::Scene,
    spec: &FrameSpec,
) -> Result<Vec<runner::TargetImage>, RunError> {
    let count = r.manifest.targets.len();
    // Read every survivor of the full frame first: a partial re-render
    // overwrites the textures that aliased targets share with them.
    let mut images: Vec<Option<runner::TargetImage>> = Vec::with_capacity(count);
    for t in 0..count {
        images.push(if r.target_survives_frame(t) {
            Some(r.read_target(t)?)
        } else {
            None
        });
    }
    for (t, image) in images.iter_mut().enumerate() {
        if image.is_none() {
            *image = Some(r.render_until_target(scene, spec, t)?);
        }
    }
    Ok(images.into_iter().flatten().collect())
}

/// Say what `npr texgen` wrote, or why it could not: the exit code.
fn report_written(result: std::io::Result<()>, out: &Path, what: &str, printer: &Printer) -> i32 {
    match result {
        Ok(()) => {
            eprintln!("wrote {} ({what})", out.display());
            EXIT_OK
        }
        Err(e) => printer.fail(cannot_write(out, e)),
    }
}

/// `npr texgen --kind paint --color "#rrggbb"`: [`runner::texgen::paint_map`] as an 8-bit PNG.
fn texgen_paint(out: &std::path::Path, size: u32, seed: u32, base: [f64; 3], printer: &Printer) -> i32 {
    let map = runner::texgen::paint_map(size, base, seed);
    let image = image::RgbaImage::from_fn(map.width, map.height, |x, y| {
        image::Rgba(map.pixels[(y * map.width + x) as usize])
    });
    report_written(
        runner::output::write_png8(&image, out),
        out,
        &format!("{size}x{size} paint map"),
        printer,
    )
}
