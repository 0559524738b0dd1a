//! The range analysis's warnings on everything npr ships (issue 49): every
//! example and every stdlib operator's demo compiles with exactly the
//! warnings docs/RANGES.md lists, true or false, so that a new false alarm
//! (or a new true one) is seen and measured.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::path::Path;

/// The range codes.
const CODES: &[&str] = &["W0203", "W0204", "W0205", "W0206", "W0207", "W0208", "W0209", "W0210"];

/// `file:line code` of each range warning compiling `path` (or `text` as
/// a file in `examples/`).
fn warnings(path: &Path, text: Option<&str>) -> Vec<String> {
    let mut sources = SourceMap::new();
    let opts = CompileOptions::default();
    let compiled = match text {
        Some(t) => npr_compiler::compile_source("demo.npr", t, path, &mut sources, &opts),
        None => npr_compiler::compile_file(path, &mut sources, &opts),
    };
    let compiled = compiled.unwrap_or_else(|e| panic!("{} does not compile: {e:?}", path.display()));
    compiled
        .warnings
        .iter()
        .filter(|d| CODES.contains(&d.code))
        .map(|d| {
            let span = d.primary_span().expect("a span");
            let file = sources.get(span.file).expect("file");
            let (line, _) = sources.line_col(span.file, span.start as u32);
            let name = Path::new(&file.name)
                .file_name()
                .expect("name")
                .to_string_lossy()
                .to_string();
            format!("{name}:{line} {}", d.code)
        })
        .collect()
}

#[test]
fn the_shipped_styles_warn_only_where_docs_ranges_says() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut found = Vec::new();
    let mut files: Vec<_> = std::fs::read_dir(&examples)
        .expect("examples")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "npr"))
        .collect();
    files.sort();
    for f in &files {
        for w in warnings(f, None) {
            found.push(format!("{}: {w}", f.file_name().expect("name").to_string_lossy()));
        }
    }
    for def in npr_stdlib::ops::ALL {
        if let npr_stdlib::ops::Demo::Render(d) = def.demo {
            for w in warnings(&examples, Some(d.style)) {
                found.push(format!("demo of {}: {w}", def.op.name));
            }
        }
    }
    // False alarms: dynamic_pattern's normalize(cross(n, axis away from n))
    // (a relation across an `if`). True: ocean's atan2 of a ray straight up.
    let mut expected = Vec::new();
    for user in ["halftone", "hatching", "painterly", "stipple"] {
        expected.push(format!("{user}.npr: dynamic_pattern.npr:52 W0208"));
        expected.push(format!("{user}.npr: dynamic_pattern.npr:83 W0208"));
    }
    expected.push("ocean.npr: ocean.npr:135 W0209".to_string());
    expected.sort();
    found.sort();
    assert_eq!(found, expected, "update docs/RANGES.md's table with what changed");
}
