//! `npr`: the command-line front end — check, compile, render.
//!
//! Exit codes: 0 ok, 1 user error (diagnostics printed), 2 internal error.

mod bench_compile;
mod cli;

use clap::Parser;

fn main() {
    let args = cli::Cli::parse();
    let code = cli::run(args);
    std::process::exit(code);
}
