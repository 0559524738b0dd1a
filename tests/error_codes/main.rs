//! Every error code has a case here that triggers it, and a snapshot of its
//! rendered message (rustc style, no colour). A completeness check makes sure
//! no code in `npr_diag::codes::ALL` is left without a case.

use npr_compiler::{CompileError, CompileOptions};
use npr_diag::{Diagnostic, SourceMap};
use std::path::{Path, PathBuf};

mod command_line;
mod files;
mod host;
mod inputs;
mod line_sets;
mod lines;
mod param_settings;
mod passes;
mod ranges;
mod syntax_names_types;

/// A scratch directory for cases that need files on disk.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("error-codes").join(name);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Compile `text` (as `case.npr` in `dir`) and return the rendered diagnostics.
fn compile_errors(text: &str, dir: &Path) -> (Vec<Diagnostic>, String) {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source("case.npr", text, dir, &mut sources, &CompileOptions::default()) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(CompileError::User(d)) => {
            let r = npr_diag::diagnostic::render(&d, &sources, false);
            (d, r)
        }
        Err(CompileError::Internal(e)) => panic!("internal error instead of a user error: {e}"),
    }
}

fn scene_errors(toml: &str, dir: &Path) -> (Vec<Diagnostic>, String) {
    let mut sources = SourceMap::new();
    let path = dir.join("scene.toml");
    std::fs::write(&path, toml).expect("write scene");
    match npr_runner::scene::load_scene(&path, &mut sources) {
        Ok(_) => panic!("expected a scene error for:\n{toml}"),
        Err(d) => {
            let r = npr_diag::diagnostic::render(&d, &sources, false);
            (d, r.replace(&dir.display().to_string(), "<dir>"))
        }
    }
}

/// Assert the first diagnostic has `code`, a primary label, and snapshot the rendering.
fn check(code: &str, (diags, rendered): (Vec<Diagnostic>, String)) {
    check_case(code, code, (diags, rendered));
}

/// [`check`] for a further case of a code, snapshot under `name`.
fn check_case(code: &str, name: &str, (diags, rendered): (Vec<Diagnostic>, String)) {
    let first = diags.first().expect("at least one diagnostic");
    assert_eq!(first.code, code, "wrong code; rendered:\n{rendered}");
    let severity = if first.is_error() { "error" } else { "warning" };
    assert!(rendered.contains(&format!("{severity}[{code}]")), "{rendered}");
    insta::assert_snapshot!(name, rendered);
}

/// Run the `npr` binary from the repository root and return the diagnostic
/// code of its first error line (looked up in `npr_diag::codes::ALL`) with its
/// whole stderr, scratch paths replaced by `<dir>`.
fn cli_errors(args: &[&str], dir: &Path) -> (Vec<Diagnostic>, String) {
    cli_errors_with_env(args, dir, &[])
}

/// [`cli_errors`] with environment variables set for the run.
fn cli_errors_with_env(args: &[&str], dir: &Path, env: &[(&str, &Path)]) -> (Vec<Diagnostic>, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(args)
        .envs(env.iter().copied())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr");
    let stderr = String::from_utf8_lossy(&o.stderr).replace(&dir.display().to_string(), "<dir>");
    assert_eq!(o.status.code(), Some(1), "npr {args:?}: {stderr}");
    let code = stderr
        .split("error[")
        .nth(1)
        .and_then(|rest| rest.split(']').next())
        .and_then(|c| npr_diag::codes::ALL.iter().find(|(k, _)| *k == c))
        .map_or("none", |(k, _)| k);
    (vec![Diagnostic::error(code, "")], stderr)
}

/// Compile `text`, which must succeed, and return its rendered warnings.
fn compile_warnings(text: &str) -> (Vec<Diagnostic>, String) {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source(
        "case.npr",
        text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) {
        Ok(c) => {
            let r = npr_diag::diagnostic::render(&c.warnings, &sources, false);
            (c.warnings, r)
        }
        Err(CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(CompileError::Internal(e)) => panic!("internal error: {e}"),
    }
}

const HEADER: &str = "style \"Case\"\n";

fn style(body: &str) -> String {
    format!("{HEADER}{body}")
}

const SIMPLE_PASS: &str =
    "pass p: render(scene) {\n  out color: rgba8unorm = vec4(1.0, 0.5, 0.2, 1.0)\n}\noutput p.color\n";

#[test]
fn every_code_has_a_case() {
    // Whitespace removed, so rustfmt's line breaks do not matter.
    let cases: String = [
        include_str!("main.rs"),
        include_str!("syntax_names_types.rs"),
        include_str!("passes.rs"),
        include_str!("files.rs"),
        include_str!("lines.rs"),
        include_str!("line_sets.rs"),
        include_str!("command_line.rs"),
        include_str!("param_settings.rs"),
        include_str!("host.rs"),
        include_str!("ranges.rs"),
        include_str!("inputs.rs"),
    ]
    .concat()
    .chars()
    .filter(|c| !c.is_whitespace())
    .collect();
    // Every file of this directory is in the list above.
    let here = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/error_codes");
    let files = std::fs::read_dir(&here).expect("tests/error_codes").count();
    assert_eq!(
        files,
        11 + usize::from(here.join("snapshots").exists()),
        "a case file is not listed"
    );
    for (code, _) in npr_diag::codes::ALL {
        if let Some((_, file)) = ELSEWHERE.iter().find(|(c, _)| c == code) {
            // Its case needs what this binary has not: a snapshot of the
            // rendered message there.
            let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(file)).expect("case file");
            assert!(
                text.contains(&format!("assert_snapshot!(\"{code}")),
                "error code {code} has no snapshot case in {file}"
            );
            continue;
        }
        let needle = format!("check(\"{code}\"");
        assert!(
            cases.contains(&needle),
            "error code {code} has no test case in tests/error_codes/"
        );
    }
}

/// Codes only a Bevy app gives (the camera's prepasses, its MSAA): their
/// cases, with a snapshot of each rendered message, are in bevy_mod_npr's
/// headless tests, which run a Bevy app.
const ELSEWHERE: &[(&str, &str)] = &[
    ("E0608", "bevy_mod_npr/tests/headless/post.rs"),
    ("E0609", "bevy_mod_npr/tests/headless/post.rs"),
];

#[test]
fn several_errors_are_reported_in_one_run() {
    let text = style("param a: float = 1.0 in 0..0.5\nparam b: px = 3m\npass p: render(scene) {\n  out color: r8unorm = lambrt(normal, light.dir)\n}\noutput p.color\n");
    let (d, _) = compile_errors(&text, &scratch("multi"));
    let codes: Vec<&str> = d.iter().map(|d| d.code).collect();
    assert!(
        codes.contains(&"E0203") && codes.contains(&"E0202") && codes.contains(&"E0102"),
        "{codes:?}"
    );
}
