//! `npr check` and `npr render` open every texture file of a compiled style
//! the way the runner will (`npr_runner::texture_file`), and report what it
//! would refuse at the `image("…")` in the style that names the file.
//! `check` decodes each file whole, so corrupt data past a good header is
//! refused there too; `render` and the language server read headers (the
//! render's own decode reports the rest at the same place).

use npr_compiler::Compiled;
use npr_diag::Diagnostic;

/// E0401/E0404 for every texture file that cannot be used, each pointing at
/// the path in the style; `depth` says how far each file is opened
/// (`npr_runner::texture_file::Depth`).
pub fn texture_file_errors(c: &Compiled, depth: npr_runner::texture_file::Depth) -> Vec<Diagnostic> {
    npr_runner::texture_file::check_files(&c.manifest, depth)
        .into_iter()
        .map(|(i, d)| match c.texture_spans.get(i) {
            Some(span) => d.with_primary(*span, "this file"),
            None => d,
        })
        .collect()
}
