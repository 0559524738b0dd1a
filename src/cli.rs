//! The command line: clap's definitions of every command and its
//! arguments (the exit codes are `exit.rs`'s). What each command does is in
//! `commands/` and `bench/`. Over 600 lines because it is one declarative
//! table, read top to bottom as `npr --help` prints it; splitting it by
//! command would scatter the shared argument groups.

use crate::path_args::PathArgs;
use clap::{Parser, Subcommand};
use npr_diag::printer::MessageFormat;
use npr_diag::sizes::parse_size;
use std::path::PathBuf;

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

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Parse and check a style; print diagnostics only.
    Check(CheckArgs),
    /// Compile a style to WGSL (one file per pass) plus manifest.json.
    Compile(CompileArgs),
    /// Render a style on a scene to an image.
    Render(Box<RenderArgs>),
    /// Run styles' tests, declared beside each style in
    /// `<style>.tests.toml`: golden images (FLIP or per pixel), every
    /// target finite, not blank, deterministic. Exit 0 when all pass, 1
    /// when one fails or its input is bad, 2 on an internal error.
    Test(TestArgs),
    /// Render on every change to the style, what it `use`s, the scene, its
    /// textures and meshes; a bad save prints diagnostics and keeps the last
    /// good image. Runs until interrupted.
    Watch {
        #[command(flatten)]
        live: LiveArgs,
        /// Output image (.png or .exr), written atomically.
        #[arg(short, long)]
        out: PathBuf,
    },
    /// A live window: the style on the scene at the display's rate, with
    /// orbit and fly cameras, time running or paused, stereo eyes side by
    /// side, the frame time in the title, and a rebuild on every save (a
    /// bad save prints diagnostics and keeps the last good frame). Needs a
    /// display (X11 or Wayland).
    #[command(after_help = npr_live::view::keys::help())]
    View(ViewArgs),
    /// Live authoring in the browser: a local web server with the rendered
    /// image, controls for the parameters, every pass, diagnostics in place
    /// and timings, re-rendered on every save. See docs/STUDIO.md.
    Studio {
        #[command(flatten)]
        live: LiveArgs,
        /// Address to bind; anything but a loopback address exposes the
        /// studio (and your files) to the network.
        #[arg(long, default_value = "127.0.0.1")]
        host: String,
        /// Port; 0 picks a free one. The address is printed at start.
        #[arg(long, default_value_t = 0)]
        port: u16,
    },
    /// Benchmarks; see docs/PERFORMANCE.md.
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Generate a tileable texture with npr's own generator (the same one
    /// `noise(...)` textures use) and write it as a 16-bit PNG.
    Texgen(TexgenArgs),
    /// Explain an error or warning code at length: what it means, a wrong
    /// example and the fixed one (`npr explain E0202`).
    Explain {
        /// The code, e.g. E0202 or W0301.
        code: String,
    },
    /// A language server over stdio for editors (diagnostics, hover,
    /// completion, go to definition, document symbols); see editors/vscode/.
    Lsp,
    /// Write the reference (operators, builtins, pass kinds, units,
    /// formats, error codes) as Markdown and a static HTML site.
    Doc {
        /// Output directory (created if missing).
        #[arg(short, long)]
        out: PathBuf,
        /// The examples directory the operators' demos render from (their
        /// scenes, textures and `use`d files); outside the repository, the
        /// copy built into npr.
        #[arg(long, default_value = "examples")]
        examples: PathBuf,
        /// The file with the committed `npr bench ops` table, whose rows
        /// are shown as the operators' speed against error; outside the
        /// repository, the copy built into npr.
        #[arg(long, default_value = crate::commands::doc::DEFAULT_PERFORMANCE)]
        performance: PathBuf,
    },
}

#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// The style (.npr) to check.
    pub style: PathBuf,
    /// Check as `npr render` will for this scene: its directory counts for
    /// the default root of the paths policy (docs/PATHS.md).
    #[arg(long)]
    pub scene: Option<PathBuf>,
    #[command(flatten)]
    pub paths: PathArgs,
    /// Set a parameter, typed like a default in the style: `--set bands=5`,
    /// `--set inflate=2px`, `--set base=#3080ff`, `--set beta=cubic`. Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
    pub set: Vec<String>,
    /// Print each target's proved value range, over every param's declared
    /// range, and whether it is finite (or what stops the proof).
    #[arg(long)]
    pub ranges: bool,
}

#[derive(clap::Args, Debug)]
pub struct CompileArgs {
    /// The style (.npr) to compile.
    pub style: PathBuf,
    #[command(flatten)]
    pub paths: PathArgs,
    /// Output directory (WGSL per pass, manifest.json, report.txt), or a
    /// file ending in `.nprb`: one bundle of the manifest, the WGSL and the
    /// image files the style reads, for programs that ship styles without
    /// the compiler (`npr render --compiled`, bevy_mod_npr).
    #[arg(short, long)]
    pub out: PathBuf,
    /// Print what was removed, folded or kept, and why, then each target's
    /// proved value range (what `npr check --ranges` prints).
    #[arg(long)]
    pub report: bool,
    /// Keep parameters as uniforms (for live tweaking) instead of folding them.
    #[arg(long)]
    pub keep_params: bool,
    /// How the passes run; `--report` says what each pass got and why. An
    /// image pass's `schedule: naive | tiled` setting overrides it for that
    /// pass.
    #[arg(long, value_enum, default_value = "auto")]
    pub schedule: ScheduleArg,
    /// Write the IR after each compiler stage into OUT/ir/.
    #[arg(long)]
    pub dump_ir: bool,
    /// Print the time taken by each compiler stage.
    #[arg(long)]
    pub time_passes: bool,
    /// Compile for this scene (TOML): `scene_has(tag)` folds, and what
    /// only absent objects need is removed (see --report).
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Set a parameter, typed like a default in the style: `--set bands=5`,
    /// `--set inflate=2px`, `--set base=#3080ff`, `--set beta=cubic`. Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
    pub set: Vec<String>,
}

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// The style (.npr); compiled for the scene.
    #[arg(required_unless_present = "compiled")]
    pub style: Option<PathBuf>,
    #[command(flatten)]
    pub paths: PathArgs,
    /// Run a directory written by `npr compile -o DIR`, or a bundle written
    /// by `npr compile -o FILE.nprb`, instead of a style (its manifest is
    /// validated first).
    #[arg(long, value_name = "DIR|FILE.nprb", conflicts_with_all = ["style", "keep_params"])]
    pub compiled: Option<PathBuf>,
    /// Scene file (TOML). A style that only reads host inputs needs none;
    /// its camera turns normals between world and view space.
    #[arg(long, required_unless_present_any = ["input", "inputs"])]
    pub scene: Option<PathBuf>,
    /// A host input of the style (`texture NAME = input(...)`) from an
    /// image file (PNG: sRGB colour; EXR: linear; depth as the distance
    /// along the view axis in metres, 1e10 or more for the background).
    /// Repeatable.
    #[arg(long, value_name = "NAME=FILE")]
    pub input: Vec<String>,
    /// Every host input from one multi-layer EXR, by layer name: Blender's
    /// `<ViewLayer>.Combined`, `.Depth`, `.Normal` (Blender's Z-up world),
    /// `.IndexOB` and `.Vector` for colour, depth, normal, id and motion
    /// inputs; `--map` for others.
    #[arg(long, value_name = "FILE.exr")]
    pub inputs: Option<PathBuf>,
    /// With --inputs: the EXR layer holding input NAME. Repeatable.
    #[arg(long, value_name = "NAME=LAYER", requires = "inputs")]
    pub map: Vec<String>,
    /// Output image (.png or .exr); without it, `<style>.png` in the current
    /// directory (none with --dump-passes or --checkpoints alone). With --frames, `{frame}`
    /// in the name is replaced by the frame number (otherwise `_NNNN` is
    /// appended); a .mp4, .webm or .gif is one video of the frames.
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// Output size, WIDTHxHEIGHT (default 512x512; a style over host
    /// inputs renders at their size).
    #[arg(long, value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Time in seconds (for animated parameters and cameras). A style that
    /// reads `previous(...)` or keeps `state` in a compute pass depends on
    /// earlier frames: it is rendered by
    /// replaying frames 0..=round(time × fps) at --fps (so the frame equals
    /// the same frame of a --frames sequence), and the last one is written.
    #[arg(long, default_value_t = 0.0)]
    pub time: f64,
    /// Render frames at --fps: A..B (B exclusive), A-B (B inclusive, as
    /// render farms write it) or one frame N. A style that reads
    /// `previous(...)` or keeps `state` first replays frames 0..A without
    /// writing them.
    #[arg(long, value_name = "A..B|A-B|N")]
    pub frames: Option<String>,
    /// Render only chunk I (from 0) of N contiguous chunks of --frames, for
    /// schedulers that give a task an index (Kubernetes indexed jobs, Slurm
    /// arrays).
    #[arg(long, value_name = "I/N", requires = "frames")]
    pub chunk: Option<String>,
    /// Frames per second: the times of --frames, and of the frames a
    /// style that reads `previous(...)` replays.
    #[arg(long, default_value_t = npr_runner::FrameSpec::DEFAULT_FPS)]
    pub fps: f64,
    /// Which eye to render for stereo cameras (0 = left, 1 = right).
    #[arg(long, default_value_t = 0)]
    pub eye: u32,
    /// Write every target as an image, plus a contact sheet, into DIR.
    /// Implies `--schedule naive` unless one is given, so every declared
    /// target exists (auto would leave fused targets out).
    #[arg(long)]
    pub dump_passes: Option<PathBuf>,
    /// Write every target of the frame as a named layer of one EXR (-o
    /// NAME.exr; float targets kept as float), for compositors. Implies
    /// `--schedule naive` unless one is given, as --dump-passes does.
    #[arg(long, requires = "out")]
    pub layers: bool,
    /// A directory of state checkpoints for a style that reads
    /// `previous(...)` or keeps `state`: the render starts from the latest
    /// checkpoint at or before its first frame (instead of replaying from
    /// frame 0) and writes one for the frame after its last, where the next
    /// chunk starts.
    #[arg(long, value_name = "DIR", requires = "frames")]
    pub checkpoints: Option<PathBuf>,
    /// With --checkpoints, also write one at every multiple of K frames (a
    /// first pass without -o then prepares every chunk's start).
    #[arg(long, value_name = "K", requires = "checkpoints", value_parser = clap::value_parser!(u32).range(1..))]
    pub checkpoint_every: Option<u32>,
    /// How the passes run (default: auto; naive with --dump-passes).
    #[arg(long, value_enum, conflicts_with = "compiled")]
    pub schedule: Option<ScheduleArg>,
    /// Keep parameters as uniforms instead of folding them into the shaders
    /// (the image is the same; what `npr studio` does to tweak them live).
    #[arg(long)]
    pub keep_params: bool,
    /// Set a parameter, typed like a default in the style: `--set bands=5`,
    /// `--set inflate=2px`, `--set base=#3080ff`, `--set beta=cubic`. Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE", conflicts_with = "compiled", value_parser = crate::set_params::parse_set_arg)]
    pub set: Vec<String>,
}

#[derive(clap::Args, Debug)]
pub struct TestArgs {
    /// Styles (.npr), their test files (.tests.toml), or directories to
    /// search for test files.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Accept the current images as the goldens: write each test's golden
    /// instead of comparing (only for tests whose other checks pass).
    #[arg(long)]
    pub bless: bool,
    /// How to report the run.
    #[arg(long, value_enum, default_value = "human")]
    pub format: npr_test::report::ReportFormat,
    /// Write the report to FILE instead of stdout.
    #[arg(short = 'o', long = "report", value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Where a failing test's images go (actual, diff, FLIP error map).
    #[arg(long = "out", value_name = "DIR", default_value = "target/npr-test")]
    pub out: PathBuf,
    /// Run only shard i of n (`2/4`): the tests sorted by id, every n-th.
    #[arg(long, value_name = "i/n")]
    pub shard: Option<String>,
    /// Run only the tests whose id (`style.npr::name`) contains SUBSTR.
    #[arg(long, value_name = "SUBSTR")]
    pub filter: Option<String>,
    /// Also sweep each style's parameters across their declared ranges on
    /// its tests' scenes and on the hard scenes npr ships (a style without
    /// tests on the hard scenes alone): one more test per style,
    /// `style.npr::@sweep`, reporting each combination that puts NaN or Inf
    /// in a target, blanks the image or fails, with an `npr render` line
    /// that reproduces it.
    #[arg(long)]
    pub sweep: bool,
    /// Instead of checking, measure the tests that declare `variants`: each
    /// variant's frame cost (a ratio to a passthrough) against its FLIP
    /// difference from the test's reference variant, as a table.
    #[arg(long, conflicts_with_all = ["bless", "sweep"])]
    pub bench: bool,
    /// With --bench, also draw the table as an SVG speed-against-error plot.
    #[arg(long, value_name = "PATH.svg", requires = "bench")]
    pub plot: Option<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct TexgenArgs {
    /// Output PNG.
    #[arg(short, long)]
    pub out: PathBuf,
    /// Width and height in texels.
    #[arg(long, default_value_t = 256)]
    pub size: u32,
    /// Octaves of noise summed, each at twice the previous frequency.
    #[arg(long, default_value_t = 4)]
    pub octaves: u32,
    /// The generator's seed: another seed, another noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// Channels with independent noise (1: grey, 2: a warp-vector field in r, g).
    #[arg(long, default_value_t = 1)]
    pub channels: u32,
    /// Lattice cells across the texture at the first octave.
    #[arg(long, default_value_t = 4)]
    pub frequency: u32,
    /// `value` or `gradient` noise, or `paint`: an 8-bit painterly colour
    /// map around `--color` (Age of Sail §5.2 lit/shadow textures).
    #[arg(long, default_value = "gradient")]
    pub kind: String,
    /// Base colour `#rrggbb` of a `paint` map.
    #[arg(long)]
    pub color: Option<String>,
}

/// `--schedule`: how the compiler runs the declared passes (`npr_compiler::schedule`),
/// except the image passes whose `schedule: naive | tiled` setting forces theirs.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScheduleArg {
    /// Every declared pass as written, each target stored.
    Naive,
    /// The compiler's schedule: image passes read only at their reader's
    /// own pixel are fused into it (the same image).
    Auto,
    /// `auto`, and every image pass whose operators read around the pixel
    /// runs as compute over workgroup tiles (the same image). Not `auto`'s
    /// choice: on lavapipe the tiles are slower (docs/PERFORMANCE.md).
    Tiled,
    /// `tiled`, and each neighbourhood pass whose one reader reads it
    /// around the pixel is computed in that reader's tiles instead of
    /// stored (the same image). Not `auto`'s choice: slower on lavapipe.
    Recompute,
}

impl From<ScheduleArg> for npr_compiler::schedule::Schedule {
    fn from(s: ScheduleArg) -> Self {
        match s {
            ScheduleArg::Naive => npr_compiler::schedule::Schedule::Naive,
            ScheduleArg::Auto => npr_compiler::schedule::Schedule::Auto,
            ScheduleArg::Tiled => npr_compiler::schedule::Schedule::Tiled,
            ScheduleArg::Recompute => npr_compiler::schedule::Schedule::Recompute,
        }
    }
}

/// What `npr watch` and `npr studio` share: the style and scene they watch
/// and the frame they render.
#[derive(clap::Args, Debug)]
pub struct LiveArgs {
    /// The style (.npr), rebuilt on every save.
    pub style: PathBuf,
    #[command(flatten)]
    pub paths: PathArgs,
    /// Scene file (TOML).
    #[arg(long)]
    pub scene: PathBuf,
    /// Output size, WIDTHxHEIGHT.
    #[arg(long, default_value = "512x512", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Time in seconds (for animated parameters and cameras).
    #[arg(long, default_value_t = 0.0)]
    pub time: f64,
    /// Frames per second: the times of --frames, and of the frames a
    /// style that reads `previous(...)` replays.
    #[arg(long, default_value_t = npr_runner::FrameSpec::DEFAULT_FPS)]
    pub fps: f64,
    /// Which eye to render for stereo cameras (0 = left, 1 = right).
    #[arg(long, default_value_t = 0)]
    pub eye: u32,
    /// How the passes run (default: auto for `watch`; naive for `studio`,
    /// whose thumbnails show every declared target only then).
    #[arg(long, value_enum)]
    pub schedule: Option<ScheduleArg>,
    /// Set a parameter, typed like a default in the style (see `npr render --help`). Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
    pub set: Vec<String>,
}

/// `npr view`: the style and scene it watches, and what a test or a
/// benchmark pins (size, time, a fixed number of frames).
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// The style (.npr) to show; saving it reloads the window.
    pub style: PathBuf,
    #[command(flatten)]
    pub paths: PathArgs,
    /// Scene file (TOML).
    #[arg(long)]
    pub scene: PathBuf,
    /// Size of the image of each eye, WIDTHxHEIGHT: the window's inner
    /// size (twice as wide for a stereo style, eyes side by side). The
    /// window can be resized.
    #[arg(long, default_value = "512x512", value_parser = parse_size)]
    pub size: (u32, u32),
    /// The style's time at start, in seconds.
    #[arg(long, default_value_t = 0.0)]
    pub time: f64,
    /// Start with time paused (space runs it).
    #[arg(long)]
    pub paused: bool,
    /// Frames a second of the style's `frame` counter and of one-frame time steps.
    #[arg(long, default_value_t = npr_runner::FrameSpec::DEFAULT_FPS)]
    pub fps: f64,
    /// Render N frames, print their mean frame time and exit (a benchmark).
    #[arg(long, value_name = "N")]
    pub frames: Option<u32>,
    /// Present as fast as frames render instead of at the display's rate
    /// (for measuring; the image may tear).
    #[arg(long)]
    pub no_vsync: bool,
    /// How the passes run (default: auto).
    #[arg(long, value_enum)]
    pub schedule: Option<ScheduleArg>,
    /// Set a parameter, typed like a default in the style (see `npr render --help`). Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = crate::set_params::parse_set_arg)]
    pub set: Vec<String>,
}

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Compile time of our front end and code generation against naga's own
    /// parse + validate of the WGSL we emit, measured in the same run.
    ///
    /// `--cold` instead times whole `npr compile` processes (wall clock, as a
    /// user runs them) and naga's share of each.
    Compile {
        /// Styles (.npr) to measure.
        styles: Vec<PathBuf>,
        /// Timed compilations per style.
        #[arg(long, default_value_t = 50)]
        iterations: u32,
        /// Spawn a fresh `npr compile` process per run and time its wall clock.
        #[arg(long)]
        cold: bool,
        /// Processes per style with `--cold`.
        #[arg(long, default_value_t = 10)]
        runs: u32,
    },
    /// Art-maps and rip-maps (Klein et al. 2000 §4.2): build time per filter,
    /// source size and level (cache bypassed), and the frame time of reading
    /// a plain mipped image, an art-map, `sample_biased` and `sample_ripmap`
    /// against a pass that reads no texture, on examples/scenes/gallery.toml
    /// (the copy built into npr outside the repository).
    Artmaps {
        /// Square source sizes, comma-separated.
        #[arg(long, default_value = "256,512,1024", value_delimiter = ',')]
        sizes: Vec<u32>,
        /// Image size of the sampling table.
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 20)]
        frames: u32,
        /// Also draw the figures into this SVG file (speed against error;
        /// cost against size, log–log): see docs/PERFORMANCE.md.
        #[arg(long, value_name = "PATH.svg")]
        plot: Option<PathBuf>,
    },
    /// Lines passes (Klein et al. 2000 §5): strip build and frame time
    /// against a sphere's edge count (rebuilt every frame, and reused),
    /// silhouette classification on the CPU against a compute pass with its
    /// read-back, and straight and wavy lines against LSA contours: cost over each
    /// method's base pass, precision and recall within 1 px on the analytic
    /// scenes of `npr bench contours`.
    Lines {
        /// Sphere resolutions (segments; rings are half), comma-separated.
        #[arg(long, default_value = "16,32,64,128,256", value_delimiter = ',')]
        segments: Vec<u32>,
        /// Square image size.
        #[arg(long, default_value_t = 256)]
        size: u32,
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 20)]
        frames: u32,
        /// Also draw the figures into this SVG file (speed against error;
        /// cost against size, log–log): see docs/PERFORMANCE.md.
        #[arg(long, value_name = "PATH.svg")]
        plot: Option<PathBuf>,
    },
    /// Operator cost against a plain texture-sample pass, per variant, in one run.
    Ops {
        /// Scene file (TOML).
        #[arg(long, default_value = "examples/scenes/spheres.toml")]
        scene: PathBuf,
        /// Image size, WIDTHxHEIGHT.
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 20)]
        frames: u32,
        /// Also draw the figures into this SVG file (speed against error;
        /// cost against size, log–log): see docs/PERFORMANCE.md.
        #[arg(long, value_name = "PATH.svg")]
        plot: Option<PathBuf>,
    },
    /// Contour methods (LSA base/full and each extension, Sobel,
    /// normal+depth): image-stage cost against a passthrough pass over the
    /// same G-buffer, pixel throughput, and precision/recall against
    /// analytic ground truth, per resolution; then, over the sizes, each
    /// method's image stage against pixels (least squares: ns per pixel,
    /// and the log–log exponent, 1.00 for linear).
    Contours {
        /// Square image sizes, comma-separated.
        #[arg(long, default_value = "128,256,512", value_delimiter = ',')]
        sizes: Vec<u32>,
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 10)]
        frames: u32,
        /// Also draw the figures into this SVG file (speed against error;
        /// cost against size, log–log): see docs/PERFORMANCE.md.
        #[arg(long, value_name = "PATH.svg")]
        plot: Option<PathBuf>,
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
        /// Timed frames per measurement.
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
        /// Timed frames per measurement.
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
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 10)]
        frames: u32,
        /// Also draw the figures into this SVG file (speed against error;
        /// cost against size, log–log): see docs/PERFORMANCE.md.
        #[arg(long, value_name = "PATH.svg")]
        plot: Option<PathBuf>,
    },
    /// Whole styles' frame time against a baseline style on one scene, in one run
    /// (each style's frames in order, so path-dependent styles are measured as they render).
    Styles {
        /// Styles (.npr) to measure.
        styles: Vec<PathBuf>,
        /// The style every other is compared with.
        #[arg(long, default_value = "examples/toon.npr")]
        baseline: PathBuf,
        /// Scene file (TOML).
        #[arg(long)]
        scene: PathBuf,
        /// Image size, WIDTHxHEIGHT.
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 20)]
        frames: u32,
    },
    /// GPU time of each pass of a style (timestamp queries), as a share of the frame.
    Passes {
        /// The style (.npr) to measure.
        style: PathBuf,
        /// Scene file (TOML).
        #[arg(long)]
        scene: PathBuf,
        /// Image size, WIDTHxHEIGHT.
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 30)]
        frames: u32,
        /// Schedules to compile the style under, comma-separated (e.g.
        /// `naive,auto`): each is measured in the same run, and the frame
        /// totals are compared with the first's.
        #[arg(long, value_enum, value_delimiter = ',', default_value = "auto")]
        schedule: Vec<ScheduleArg>,
    },
    /// `npr studio` end to end over HTTP and its event stream: slider →
    /// new image and save → new image against `npr render`'s own frame
    /// time in the same run, and the studio's memory across edits.
    Studio {
        /// The style (.npr) to measure.
        style: PathBuf,
        /// Scene file (TOML).
        #[arg(long)]
        scene: PathBuf,
        /// Image size, WIDTHxHEIGHT.
        #[arg(long, default_value = "512x512", value_parser = parse_size)]
        size: (u32, u32),
        /// Frames of the `npr render` reference.
        #[arg(long, default_value_t = 20)]
        frames: u32,
        /// Edits in all, alternating slider moves and saves.
        #[arg(long, default_value_t = 100)]
        edits: u32,
        /// The parameter the slider moves.
        #[arg(long)]
        param: String,
        /// The two values it alternates between, `A,B` (as `--set` writes them).
        #[arg(long, value_delimiter = ',', required = true)]
        values: Vec<String>,
    },
    /// The runner's per-frame work against itself: `Renderer::render`
    /// (uniform updates, recording, submit, wait) against `Renderer::encode`
    /// of the same renderer — its own pipelines and bind groups recorded and
    /// submitted with no uniform writes. Not an independent comparison; that
    /// is `npr bench overhead`.
    Frame {
        /// The style (.npr) to measure.
        style: PathBuf,
        /// Scene file (TOML).
        #[arg(long)]
        scene: PathBuf,
        /// Image size, WIDTHxHEIGHT.
        #[arg(long, default_value = "256x256", value_parser = parse_size)]
        size: (u32, u32),
        /// Timed frames per measurement.
        #[arg(long, default_value_t = 60)]
        frames: u32,
        /// Compile with parameters kept as uniforms, as `npr view` and the
        /// studio do (so its frame time compares with theirs).
        #[arg(long)]
        keep_params: bool,
    },
    /// CPU time per frame of a host driving a style (`npr_runner::embed`:
    /// prepare and encode, and the host's `CommandEncoder::finish`, where
    /// wgpu does the work the pass calls defer) for several object counts,
    /// against two independent wgpu programs recording the same number of
    /// passes (minimal, and shaped as the style's), in one run.
    Host {
        /// The style (.npr) the host drives.
        #[arg(long, default_value = "examples/age_of_sail.npr")]
        style: PathBuf,
        /// Object counts, comma-separated.
        #[arg(long, default_value = "1,10,100,1000", value_delimiter = ',')]
        objects: Vec<usize>,
        /// Square image size. Small by default: only the GPU's work
        /// depends on it, and that is not timed; on a software rasterizer
        /// it runs on the CPU and a large image evicts the caches between
        /// frames, which no GPU does.
        #[arg(long, default_value_t = 16)]
        size: u32,
        /// Timed frames per count (the median is reported).
        #[arg(long, default_value_t = 50)]
        frames: u32,
        /// Frames each program runs in a row before the next one's turn
        /// (1: they alternate frame by frame).
        #[arg(long, default_value_t = npr_lab::bench_host::DEFAULT_BLOCK)]
        block: u32,
    },
    /// Runner overhead per frame against an independent hand-written wgpu
    /// program drawing the same WGSL passes with its own pipelines, bind
    /// groups, buffers and textures. Both images are compared first (equal
    /// within 1/255, or it stops); then frames of the two alternate in one run.
    Overhead {
        /// The style (.npr) to measure.
        #[arg(long, default_value = "examples/rounded_shadows.npr")]
        style: PathBuf,
        /// Scene file (TOML).
        #[arg(long, default_value = "examples/scenes/spot.toml")]
        scene: PathBuf,
        /// Image size, WIDTHxHEIGHT.
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

#[cfg(test)]
mod tests {
    use super::Cli;
    use clap::CommandFactory;

    /// `path arg` for every argument of `cmd` and its subcommands, at any
    /// depth, whose `--help` shows no text.
    fn without_help(cmd: &clap::Command, path: &str, out: &mut Vec<String>) {
        if cmd.get_about().is_none() && cmd.get_long_about().is_none() && !path.is_empty() {
            out.push(format!("npr{path} (the command itself)"));
        }
        for a in cmd.get_arguments() {
            let id = a.get_id().as_str();
            if a.is_hide_set() || matches!(id, "help" | "version") {
                continue;
            }
            let text = a
                .get_long_help()
                .or(a.get_help())
                .map(|t| t.to_string())
                .unwrap_or_default();
            if text.trim().is_empty() {
                out.push(format!("npr{path} <{id}>"));
            }
        }
        for s in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
            without_help(s, &format!("{path} {}", s.get_name()), out);
        }
    }

    #[test]
    fn every_argument_of_every_subcommand_has_help_text() {
        let mut missing = Vec::new();
        without_help(&Cli::command(), "", &mut missing);
        assert!(
            missing.is_empty(),
            "no help text in `--help` for:\n{}",
            missing.join("\n")
        );
    }
}
