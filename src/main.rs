//! `npr`: the command-line front end — check, compile, render.
//!
//! Exit codes: 0 ok, 1 user error (diagnostics printed), 2 internal error.

mod args;
mod bench;
mod cli;
mod commands;
mod describe;
mod live;
mod lsp;
mod path_args;
mod printer;
mod reference;
mod set_params;
mod studio;
mod texture_check;
mod usage;
mod watch;

fn main() {
    let code = match usage::parse() {
        Ok(args) => commands::run(args),
        Err(code) => code,
    };
    std::process::exit(code);
}
