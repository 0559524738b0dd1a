//! The command line as clap parses it, with npr's exit codes: `--help` and
//! `--version` print and exit 0; every other clap error is a usage error,
//! E0501, exit 1 (clap's own exit code, 2, is npr's internal-error code).
//! clap's message is kept whole; the code goes where rustc puts it,
//! `error[E0501]: ...`, or into a JSON diagnostic with
//! `--message-format json`.

use crate::cli::Cli;
use clap::Parser;
use npr_diag::exit::{EXIT_OK, EXIT_USER};
use npr_diag::{codes, Diagnostic};

/// The parsed command line, or the exit code after printing why there is none.
pub fn parse() -> Result<Cli, i32> {
    parse_from(std::env::args_os())
}

/// [`parse`] of given arguments (the first is the program name).
pub fn parse_from<I, T>(args: I) -> Result<Cli, i32>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let args: Vec<std::ffi::OsString> = args.into_iter().map(Into::into).collect();
    Cli::try_parse_from(&args).map_err(|e| {
        // Help and version go to stdout and are not errors.
        if !e.use_stderr() {
            let _ = e.print();
            return EXIT_OK;
        }
        let d = diagnostic(&e);
        if wants_json(&args) {
            print!(
                "{}",
                npr_diag::diagnostic::render_json(&[d], &npr_diag::SourceMap::new())
            );
        } else {
            eprint!("{}", rendered(&e));
        }
        EXIT_USER
    })
}

/// `npr` or `npr bench` alone: clap prints the help, which is no error message.
fn is_missing_command(e: &clap::Error) -> bool {
    e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
}

const MISSING_COMMAND: &str = "a command is missing";

/// clap's rendering with the code after `error`.
fn rendered(e: &clap::Error) -> String {
    let text = e.render().to_string();
    if is_missing_command(e) {
        return format!("{text}\nerror[{}]: {MISSING_COMMAND}\n", codes::USAGE);
    }
    match text.strip_prefix("error: ") {
        Some(rest) => format!("error[{}]: {rest}", codes::USAGE),
        None => format!("error[{}]: {text}", codes::USAGE),
    }
}

/// The usage error as a diagnostic: clap's first line as the message, the
/// rest (usage line, hints) as notes.
fn diagnostic(e: &clap::Error) -> Diagnostic {
    let text = e.render().to_string();
    if is_missing_command(e) {
        return Diagnostic::error(codes::USAGE, MISSING_COMMAND).with_note(text);
    }
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let first = lines.next().unwrap_or("bad command line");
    let mut d = Diagnostic::error(codes::USAGE, first.strip_prefix("error: ").unwrap_or(first));
    for l in lines {
        d = d.with_note(l.trim().to_string());
    }
    d
}

/// Whether the command line asked for JSON diagnostics, read from the raw
/// arguments because they did not parse.
fn wants_json(args: &[std::ffi::OsString]) -> bool {
    let args: Vec<&str> = args.iter().filter_map(|a| a.to_str()).collect();
    args.windows(2).any(|w| w == ["--message-format", "json"]) || args.contains(&"--message-format=json")
}
