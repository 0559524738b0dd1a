//! Diagnostics on open and change: the document compiled as `npr check`
//! compiles it (its `use`s and texture paths resolved against its
//! directory, every texture file opened as the runner will), every diagnostic with its code, message, help and notes;
//! spans become UTF-16 ranges. A diagnostic in a `use`d file is shown at the
//! start of the document, naming the file, with the real place as related
//! information.

use super::position::LineIndex;
use lsp_types::{Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, NumberOrString, Range};
use npr_compiler::{CompileError, CompileOptions};
use npr_diag::{Severity, SourceMap};
use std::path::Path;

pub fn check(path: &Path, text: &str) -> Vec<Diagnostic> {
    let mut sources = SourceMap::new();
    let dir = path.parent().unwrap_or(Path::new("."));
    let name = path.display().to_string();
    let options = match super::policy::for_document(path) {
        Ok(policy) => CompileOptions {
            paths: Some(policy),
            ..CompileOptions::default()
        },
        // The document's directory is gone (deleted under the editor):
        // that is the one thing to report.
        Err(d) => return vec![convert(&d, &sources, &name)],
    };
    let found = match npr_compiler::compile_source(&name, text, dir, &mut sources, &options) {
        Ok(c) => {
            let mut found = c.warnings.clone();
            found.extend(npr_test::texture_files::texture_file_errors(
                &c,
                npr_runner::texture_file::Depth::Header,
            ));
            found
        }
        Err(CompileError::User(d)) => d,
        Err(CompileError::Internal(e)) => vec![e.to_diagnostic()],
    };
    let root = sources.files().first().map(|f| f.name.clone()).unwrap_or_default();
    found.iter().map(|d| convert(d, &sources, &root)).collect()
}

pub(super) fn convert(d: &npr_diag::Diagnostic, sources: &SourceMap, root: &str) -> Diagnostic {
    let mut message = d.message.clone();
    let mut range = Range::default();
    let mut related = Vec::new();
    for label in &d.labels {
        let Some(file) = sources.get(label.span.file) else {
            continue;
        };
        let label_range = LineIndex::new(&file.text).range(label.span.start as usize, label.span.end as usize);
        let in_root = file.name == root;
        if label.primary && in_root {
            range = label_range;
            if !label.message.is_empty() {
                message = format!("{message}: {}", label.message);
            }
            continue;
        }
        if label.primary {
            let (line, col) = sources.line_col(label.span.file, label.span.start);
            message = format!("in {}:{line}:{col}: {message}", file.name);
        }
        // Secondary labels, and the primary one in a `use`d file.
        if let Some(uri) = super::uri::from_path(&absolute(&file.name)) {
            related.push(DiagnosticRelatedInformation {
                location: lsp_types::Location::new(uri, label_range),
                message: label.message.clone(),
            });
        }
    }
    for note in &d.notes {
        message.push_str(&format!("\nnote: {note}"));
    }
    if let Some(help) = &d.help {
        message.push_str(&format!("\nhelp: {help}"));
    }
    Diagnostic {
        range,
        severity: Some(match d.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
            Severity::Note => DiagnosticSeverity::INFORMATION,
        }),
        code: Some(NumberOrString::String(d.code.to_string())),
        source: Some("npr".into()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        ..Diagnostic::default()
    }
}

fn absolute(name: &str) -> std::path::PathBuf {
    let p = Path::new(name);
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        std::env::current_dir()
            .map(|d| d.join(p))
            .unwrap_or_else(|_| p.to_path_buf())
    }
}
