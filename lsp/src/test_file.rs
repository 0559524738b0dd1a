//! Diagnostics of a style's test file (`<style>.tests.toml`) on open and
//! change: the buffer read as `npr test` reads the file (E0407 with its
//! spans), then each test's `set` and each variant's values typed against
//! the style's parameters by a compile of the style, as `npr test` types
//! them when it runs (E0101, E0201, E0203...), each pointing at the value
//! in the buffer. Errors of the style itself belong to the style's own
//! document and are not repeated here; the scene is not loaded (a test's
//! meshes may be large), so what depends on it is left to `npr test`.

use lsp_types::Diagnostic;
use npr_compiler::{CompileError, CompileOptions};
use npr_test::declare;
use npr_test::run::param_settings;
use std::path::Path;

/// Whether `path` is a style's test file.
pub fn is_test_file(path: &Path) -> bool {
    path.to_string_lossy().ends_with(declare::SUFFIX)
}

pub fn check(path: &Path, text: &str) -> Vec<Diagnostic> {
    let file = match declare::read_text(path, text) {
        Ok(f) => f,
        Err((found, sources)) => return convert(&found, &sources),
    };
    let mut out = Vec::new();
    for test in &file.tests {
        let mut sets = vec![test.sets.clone()];
        sets.extend(test.variants.iter().map(|v| v.sets.clone()));
        for sets in sets.into_iter().filter(|s| !s.is_empty()) {
            let mut sources = file.sources.clone();
            let opts = CompileOptions {
                settings: param_settings(&sets, &sources),
                paths: super::policy::for_document(&file.style).ok(),
                ..Default::default()
            };
            if let Err(CompileError::User(found)) = npr_compiler::compile_file(&file.style, &mut sources, &opts) {
                // Only what points into this buffer: the settings' errors.
                let in_buffer: Vec<npr_diag::Diagnostic> = found
                    .into_iter()
                    .filter(|d| d.primary_span().is_some_and(|s| s.file == sets[0].0.span.file))
                    .collect();
                out.extend(convert(&in_buffer, &sources));
            }
        }
    }
    out.dedup_by(|a, b| a.range == b.range && a.message == b.message);
    out
}

fn convert(found: &[npr_diag::Diagnostic], sources: &npr_diag::SourceMap) -> Vec<Diagnostic> {
    let root = sources.files().first().map(|f| f.name.clone()).unwrap_or_default();
    found
        .iter()
        .map(|d| super::diagnostics::convert(d, sources, &root))
        .collect()
}
