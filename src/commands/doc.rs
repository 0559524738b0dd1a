//! `npr doc -o DIR`: the reference (`crate::reference`) written into DIR as
//! Markdown and HTML, with each operator's demo image rendered by the
//! runner into `DIR/img/` (`crate::reference::images`) and the committed
//! `npr bench ops` figures (`crate::reference::figures`), every file
//! atomically in one sync.

use npr_diag::exit::EXIT_OK;
use npr_diag::printer::Printer;
use npr_diag::writes::cannot_write;
use std::path::Path;

/// `--performance`'s default; when it is not here, the copy built into npr.
pub const DEFAULT_PERFORMANCE: &str = "docs/PERFORMANCE.md";

pub fn run(out: &Path, examples: &Path, performance: &Path, printer: &Printer) -> i32 {
    // The repository's files where npr runs in it; else those built into
    // npr (`crate::bundled`), so an installed npr writes its reference.
    let examples = match crate::bundled::resolve(examples) {
        Ok(e) => e,
        Err(e) => return printer.fail(cannot_write(&std::env::temp_dir(), e)),
    };
    let examples = examples.as_path();
    let performance_text = match std::fs::read_to_string(performance) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound && performance == Path::new(DEFAULT_PERFORMANCE) => {
            Ok(crate::bundled::PERFORMANCE_MD.to_string())
        }
        other => other,
    };
    let figures = match performance_text
        .map_err(|e| e.to_string())
        .and_then(|text| crate::reference::figures::Figures::parse(&text))
    {
        Ok(f) => f,
        Err(e) => {
            return printer.fail(
                npr_diag::Diagnostic::error(
                    npr_diag::codes::BAD_ARGUMENT_VALUE,
                    format!("--performance {}: {e}", performance.display()),
                )
                .with_help("run `npr doc` in the repository, or give the file with `--performance PATH`"),
            )
        }
    };
    let images = match crate::reference::images::render_all(examples, printer) {
        Ok(i) => i,
        Err(code) => return code,
    };
    if let Err(e) = std::fs::create_dir_all(out.join("img")) {
        return printer.fail(cannot_write(out, e));
    }
    let files = crate::reference::files(&figures);
    let writes: Vec<(std::path::PathBuf, &[u8])> = files
        .iter()
        .map(|(name, text)| (out.join(name), text.as_bytes()))
        .chain(images.iter().map(|(name, png)| (out.join(name), png.as_slice())))
        .collect();
    match npr_runner::output::write_all_atomic(&writes) {
        Ok(()) => {
            eprintln!(
                "wrote {} files of the reference and {} demo images into {}",
                files.len(),
                images.len(),
                out.display()
            );
            EXIT_OK
        }
        Err(e) => printer.fail(cannot_write(out, e)),
    }
}
