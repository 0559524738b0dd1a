//! An output npr could not write (an image, a report, a plot, a cache):
//! one diagnostic, E0503, whose help names what the cause asks for. Every
//! writer (the CLI, `npr-test`, `npr-lab`'s plots) reports with it, so a
//! user reads the same advice whichever command failed.

use crate::{codes, Diagnostic};
use std::path::Path;

/// An output that cannot be written: E0503.
/// The help says what the cause asks for: a directory to create, a
/// permission, or another name.
pub fn cannot_write(path: &Path, e: impl std::fmt::Display) -> Diagnostic {
    let text = e.to_string();
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    let help = if text.contains("Permission denied") || text.contains("Read-only") {
        "the directory is not writable here: choose another path, or change its permissions".to_string()
    } else if text.contains("No such file or directory") && parent.is_some_and(|p| !p.exists()) {
        format!(
            "the directory {} does not exist: create it first",
            parent.map(|p| p.display().to_string()).unwrap_or_default()
        )
    } else if text.contains("Is a directory") {
        "the path is a directory: give a file name".to_string()
    } else {
        "check that the directory exists and is writable".to_string()
    };
    Diagnostic::error(codes::CANNOT_WRITE, format!("cannot write {}: {text}", path.display())).with_help(help)
}
