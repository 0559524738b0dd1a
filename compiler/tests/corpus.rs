//! The compiler test corpus: every `tests/in/*.npr` compiles, and its report,
//! manifest and WGSL (every pass) are one snapshot per file, so a change in
//! what the compiler emits for any construct shows up as a reviewed diff.
//!
//! A file whose first comment lines contain `scene tags = a, b` is compiled
//! for a scene whose objects carry exactly those tags (`scene_has`).

use npr_abi::SceneSummary;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

fn corpus() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/in");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("compiler/tests/in exists")
        .map(|e| e.expect("readable corpus dir").path())
        .filter(|p| p.extension().is_some_and(|x| x == "npr"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "the corpus lost files: {files:?}");
    files
}

/// The scene a corpus file asks for in its header comment, if any.
fn scene_of(text: &str) -> Option<SceneSummary> {
    let line = text
        .lines()
        .take_while(|l| l.starts_with("//"))
        .find_map(|l| l.split_once("scene tags = ").map(|(_, tags)| tags))?;
    let tags = line
        .split(',')
        .map(|t| {
            t.trim()
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect::<String>()
        })
        .filter(|t| !t.is_empty())
        .collect();
    Some(SceneSummary {
        tags,
        name: "corpus scene".into(),
    })
}

fn snapshot_text(path: &Path) -> String {
    let text = std::fs::read_to_string(path).expect("readable corpus file");
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let options = CompileOptions {
        scene: scene_of(&text),
        ..CompileOptions::default()
    };
    let mut sources = SourceMap::new();
    let compiled = match npr_compiler::compile_file(path, &mut sources, &options) {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => {
            panic!("{name}:\n{}", npr_diag::diagnostic::render(&d, &sources, false))
        }
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{name}: {e}\n{}", e.wgsl.clone().unwrap_or_default()),
    };
    let mut manifest = compiled.manifest.clone();
    // Absolute paths differ between machines.
    manifest.source = format!("compiler/tests/in/{name}");
    let mut out = String::new();
    let _ = writeln!(out, "==== report\n{}", compiled.report.render().trim_end());
    let _ = writeln!(
        out,
        "==== manifest.json\n{}",
        serde_json::to_string_pretty(&manifest).expect("manifest serializes")
    );
    for (file, wgsl) in &compiled.shaders {
        let _ = writeln!(out, "==== {file}\n{}", wgsl.trim_end());
    }
    out
}

#[test]
fn corpus_snapshots() {
    for path in corpus() {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        insta::assert_snapshot!(name.clone(), snapshot_text(&path));
    }
}

#[test]
fn scene_header_is_read() {
    let s = scene_of("// a\n// scene tags = hero, prop\nstyle \"x\"").expect("a scene");
    assert_eq!(s.tags.into_iter().collect::<Vec<_>>(), ["hero", "prop"]);
    assert!(scene_of("style \"x\"\n// scene tags = a").is_none());
}
