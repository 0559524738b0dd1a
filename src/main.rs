//! `npr`: the command-line front end — check, compile, render, test.
//!
//! Exit codes: 0 ok, 1 user error (diagnostics printed), 2 internal error.

mod args;
mod bench;
mod bundled;
mod cli;
mod commands;
mod frame_pattern;
mod frame_range;
mod path_args;
mod printer;
mod reference;
mod set_params;
mod usage;
mod video;
mod watch;

fn main() {
    // A panic npr expects (naga's, a mesh reader's) is reported as a
    // diagnostic; Rust's own panic line above it would only confuse.
    npr_diag::panics::install_quiet_hook();
    let code = match usage::parse() {
        Ok(args) => commands::run(args),
        Err(code) => code,
    };
    std::process::exit(code);
}
