//! How a program built on npr reports to a terminal: diagnostics printed
//! as text for people (coloured when stderr is a terminal) or as one JSON
//! object per line (`--message-format json`), and the exit code a refused
//! input gives ([`crate::exit`]). `npr`'s commands, the live view and
//! studio (`npr-live`) and the style tests print through it.

use crate::exit::EXIT_USER;
use crate::{Diagnostic, SourceMap};
use std::io::IsTerminal;

/// How diagnostics are printed: for people, or one JSON object per line.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum MessageFormat {
    Human,
    Json,
}

/// Where and how diagnostics go: `--message-format`, and colour when stderr
/// is a terminal.
pub struct Printer {
    pub format: MessageFormat,
    color: bool,
}

impl Printer {
    /// Colour when stderr is a terminal.
    pub fn new(format: MessageFormat) -> Self {
        Printer {
            format,
            color: std::io::stderr().is_terminal(),
        }
    }

    pub fn diagnostics(&self, diags: &[Diagnostic], sources: &SourceMap) {
        if diags.is_empty() {
            return;
        }
        match self.format {
            MessageFormat::Json => print!("{}", crate::diagnostic::render_json(diags, sources)),
            MessageFormat::Human => eprint!("{}", crate::diagnostic::render(diags, sources, self.color)),
        }
    }

    /// Print one diagnostic that points into no file (a command-line value,
    /// an output path, the device) and give the user-error exit code.
    pub fn fail(&self, d: Diagnostic) -> i32 {
        self.diagnostics(&[d], &SourceMap::new());
        EXIT_USER
    }

    /// [`Printer::fail`] for a check of the arguments.
    pub fn check(&self, checked: Result<(), Diagnostic>) -> Result<(), i32> {
        checked.map_err(|d| self.fail(d))
    }
}
