//! What each command does: [`run`] hands the parsed command line to the
//! module of its command and returns the exit code.

mod check;
mod checkpoints;
mod compile;
pub(crate) mod doc;
pub(crate) mod dump;
mod explain;
pub(crate) mod frame_sink;
pub(crate) mod render;
pub(crate) mod render_inputs;
mod test;
mod texgen;

use crate::cli::{Cli, Command};
use npr_diag::printer::Printer;
use npr_live::build::Inputs;

pub fn run(cli: Cli) -> i32 {
    let printer = Printer::new(cli.message_format);
    match cli.command {
        Command::Check(args) => check::run(&args, &printer),
        Command::Compile(args) => compile::run(args, &printer),
        Command::Render(args) => render::run(*args, &printer),
        Command::Texgen(args) => texgen::run(args, &printer),
        Command::Test(args) => test::run(args, &printer),
        Command::Explain { code } => explain::run(&code, &printer),
        Command::Lsp => npr_lsp::run(),
        Command::Doc {
            out,
            examples,
            performance,
        } => doc::run(&out, &examples, &performance, &printer),
        Command::Bench(cmd) => crate::bench::run(cmd, &printer),
        Command::Watch { live, out } => crate::watch::run(
            crate::watch::WatchArgs {
                inputs: Inputs {
                    style: live.style,
                    scene: live.scene,
                    sets: live.set,
                    keep_params: false,
                    paths: live.paths.choice(),
                    schedule: live.schedule.map_or(npr_compiler::schedule::Schedule::Auto, Into::into),
                },
                out,
                size: live.size,
                time: live.time,
                fps: live.fps,
                eye: live.eye,
            },
            &printer,
        ),
        Command::View(args) => npr_live::view::run(
            npr_live::view::ViewOptions {
                inputs: Inputs {
                    style: args.style,
                    scene: args.scene,
                    sets: args.set,
                    // Parameters stay uniforms, so the keys step them without a recompile.
                    keep_params: true,
                    paths: args.paths.choice(),
                    schedule: args.schedule.map_or(npr_compiler::schedule::Schedule::Auto, Into::into),
                },
                size: args.size,
                time: args.time,
                paused: args.paused,
                fps: args.fps,
                frames: args.frames,
                vsync: !args.no_vsync,
            },
            &printer,
        ),
        Command::Studio { live, host, port } => npr_live::studio::run(
            npr_live::studio::StudioArgs {
                inputs: Inputs {
                    style: live.style,
                    scene: live.scene,
                    sets: live.set,
                    keep_params: true,
                    paths: live.paths.choice(),
                    // Every declared target has a thumbnail.
                    schedule: live
                        .schedule
                        .map_or(npr_compiler::schedule::Schedule::Naive, Into::into),
                },
                size: live.size,
                time: live.time,
                fps: live.fps,
                eye: live.eye,
                host,
                port,
            },
            &printer,
        ),
    }
}
