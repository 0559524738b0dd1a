//! Data-driven parser tests: every `cases/ok/*.npr` parses without
//! diagnostics (AST snapshot), every `cases/err/*.npr` reports at least one
//! error (rendered-diagnostics snapshot).

use dsl::{FileId, SourceMap};

#[test]
fn ok_cases_parse_cleanly() {
    insta::glob!("cases/ok/*.npr", |path| {
        let text = std::fs::read_to_string(path).expect("read case");
        let (ast, diags) = dsl::parse(FileId(0), &text);
        assert!(diags.is_empty(), "{}: {diags:?}", path.display());
        assert!(ast.style.is_some());
        insta::assert_debug_snapshot!(ast);
    });
}

#[test]
fn err_cases_report_errors() {
    insta::glob!("cases/err/*.npr", |path| {
        let text = std::fs::read_to_string(path).expect("read case");
        let mut sources = SourceMap::new();
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let file = sources.add(name, text.clone());
        let (_, diags) = dsl::parse(file, &text);
        assert!(diags.iter().any(|d| d.is_error()), "{}: no error", path.display());
        for d in &diags {
            for l in &d.labels {
                assert!(l.span.end as usize <= text.len());
            }
        }
        insta::assert_snapshot!(dsl::diagnostic::render(&diags, &sources, false));
    });
}
