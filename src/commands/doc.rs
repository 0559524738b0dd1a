//! `npr doc -o DIR`: the reference (`crate::reference`) written into DIR as
//! Markdown and HTML, every file atomically in one sync.

use crate::cli::EXIT_OK;
use crate::printer::{cannot_write, Printer};
use std::path::Path;

pub fn run(out: &Path, printer: &Printer) -> i32 {
    if let Err(e) = std::fs::create_dir_all(out) {
        return printer.fail(cannot_write(out, e));
    }
    let files = crate::reference::files();
    let writes: Vec<(std::path::PathBuf, &[u8])> = files
        .iter()
        .map(|(name, text)| (out.join(name), text.as_bytes()))
        .collect();
    match runner::output::write_all_atomic(&writes) {
        Ok(()) => {
            eprintln!("wrote {} files of the reference into {}", files.len(), out.display());
            EXIT_OK
        }
        Err(e) => printer.fail(cannot_write(out, e)),
    }
}
