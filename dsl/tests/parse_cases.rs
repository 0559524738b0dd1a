//! Data-driven parser tests: every `cases/ok/*.npr` parses without
//! diagnostics (AST snapshot), every `cases/err/*.npr` reports at least one
//! error (rendered-diagnostics snapshot).

use npr_diag::{FileId, SourceMap};

#[test]
fn ok_cases_parse_cleanly() {
    insta::glob!("cases/ok/*.npr", |path| {
        let text = std::fs::read_to_string(path).expect("read case");
        let (ast, diags) = npr_dsl::parse(FileId(0), &text);
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
        let (_, diags) = npr_dsl::parse(file, &text);
        assert!(diags.iter().any(|d| d.is_error()), "{}: no error", path.display());
        for d in &diags {
            for l in &d.labels {
                assert!(l.span.end as usize <= text.len());
            }
        }
        insta::assert_snapshot!(npr_diag::diagnostic::render(&diags, &sources, false));
    });
}

/// "expected X, found Y" where Y is one of the X: the message would
/// contradict itself.
fn contradiction(message: &str) -> Option<String> {
    let rest = message.strip_prefix("expected ")?;
    let (expected, found) = rest.rsplit_once(", found ")?;
    let found = found.strip_prefix('`')?.strip_suffix('`')?;
    expected.contains(&format!("`{found}`")).then(|| message.to_string())
}

#[test]
fn no_syntax_message_says_expected_x_found_x() {
    // Every ok case with one punctuation character or keyword-ending
    // character removed: the messages must never contradict themselves,
    // and the primary label must lie within the text.
    let mut checked = 0;
    insta::glob!("cases/ok/*.npr", |path| {
        let text = std::fs::read_to_string(path).expect("read case");
        for (i, c) in text.char_indices() {
            if !":=(){},.".contains(c) {
                continue;
            }
            let broken = format!("{}{}", &text[..i], &text[i + c.len_utf8()..]);
            let (_, diags) = npr_dsl::parse(FileId(0), &broken);
            for d in diags.iter().filter(|d| d.code == npr_diag::codes::SYNTAX) {
                assert!(
                    contradiction(&d.message).is_none(),
                    "{}: removing {c:?} at {i}: {}",
                    path.display(),
                    d.message
                );
                let span = d.primary_span().expect("a primary label");
                assert!(span.end as usize <= broken.len() && span.start <= span.end);
                checked += 1;
            }
        }
    });
    assert!(checked > 100, "only {checked} syntax errors checked");
}

#[test]
fn the_old_contradictions_are_gone() {
    // `expected `out` ... found `out`` (a missing `:` in an `out`), and
    // `expected a type, found `float`` (a missing `=`).
    for (text, want) in [
        (
            "style \"S\"\npass p: render(scene) {\n  out c rgba8unorm = vec4(1.0)\n}\n",
            "expected `:`, found `rgba8unorm`",
        ),
        ("style \"S\"\nparam a: float 1.0\n", "expected `=`, found `1.0`"),
    ] {
        let (_, diags) = npr_dsl::parse(FileId(0), text);
        assert_eq!(diags.len(), 1, "{diags:?}");
        assert_eq!(diags[0].message, want);
    }
}

#[test]
fn spans_end_where_their_construct_ends() {
    // A declaration whose last part is optional (`in lo..hi`) stops at its
    // last token, not at the comment and blank lines pest skipped after it.
    let text = "style \"S\"\nparam a: float = 1.0   // note\n\n/* block */\nparam b: float = 2.0 in 0..4\n\n";
    let (ast, diags) = npr_dsl::parse(FileId(0), text);
    assert!(diags.is_empty(), "{diags:?}");
    let spans: Vec<&str> = ast
        .items
        .iter()
        .map(|i| match i {
            npr_dsl::ast::Item::Param(p) => &text[p.span.range()],
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(spans, ["param a: float = 1.0", "param b: float = 2.0 in 0..4"]);
}
