//! The VS Code extension (`editors/vscode/`): its TextMate grammar
//! tokenizes every example with no unscoped or illegal token (and does
//! flag a bad one), `npr lsp` works through vscode-jsonrpc (the library
//! vscode-languageclient talks through), and the manifest names files that
//! exist. Needs node and the extension's npm packages (`./setup.sh --tests` runs
//! `npm ci` there); without them the tests fail and say so.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn extension_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("editors/vscode")
}

fn node(args: &[&str]) -> Output {
    let dir = extension_dir();
    assert!(
        dir.join("node_modules/vscode-textmate").is_dir() && dir.join("node_modules/vscode-jsonrpc").is_dir(),
        "editors/vscode/node_modules is missing: run `./setup.sh --tests` (it runs `npm ci` in editors/vscode)"
    );
    Command::new("node")
        .args(args)
        .current_dir(&dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run node ({e}): install Node.js 18 or later (`./setup.sh --tests`)"))
}

fn describe(o: &Output) -> String {
    format!(
        "exit {:?}\nstdout:\n{}\nstderr:\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

#[test]
fn the_grammar_scopes_every_token_of_every_example() {
    let o = node(&["test/tokenize.js"]);
    assert!(o.status.success(), "{}", describe(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let examples = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples"))
        .expect("examples")
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "npr"))
        })
        .count();
    assert!(examples > 10, "examples/ has {examples} styles");
    // Every top-level example and examples/lib/ are tokenized.
    let counted: usize = out
        .split("ok: ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    assert!(counted > examples, "{out}");
}

#[test]
fn the_grammar_check_fails_on_a_token_it_cannot_scope() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("vscode-grammar");
    std::fs::create_dir_all(&dir).expect("dir");
    let bad = dir.join("bad.npr");
    std::fs::write(&bad, "style \"Bad\"\nparam x: float = 1.0 @ 2.0\n").expect("write");
    let o = node(&["test/tokenize.js", bad.to_str().expect("utf-8 path")]);
    assert!(!o.status.success(), "{}", describe(&o));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("bad.npr:2:22: illegal token \"@\""),
        "{}",
        describe(&o)
    );
}

#[test]
fn npr_lsp_speaks_the_clients_json_rpc() {
    let style = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/toon.npr");
    let o = node(&[
        "test/server.js",
        env!("CARGO_BIN_EXE_npr"),
        style.to_str().expect("utf-8 path"),
    ]);
    assert!(o.status.success(), "{}", describe(&o));
}

#[test]
fn the_manifest_names_files_that_exist() {
    let dir = extension_dir();
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("package.json")).expect("package.json")).expect("JSON");
    let contributes = &manifest["contributes"];
    let mut files = vec![manifest["main"].as_str().expect("main").to_string()];
    files.push(
        contributes["grammars"][0]["path"]
            .as_str()
            .expect("grammar")
            .to_string(),
    );
    files.push(
        contributes["languages"][0]["configuration"]
            .as_str()
            .expect("configuration")
            .to_string(),
    );
    for f in &files {
        assert!(dir.join(f).is_file(), "package.json names {f}, which does not exist");
    }
    assert_eq!(contributes["languages"][0]["extensions"][0], ".npr");
    for json in ["language-configuration.json", "syntaxes/npr.tmLanguage.json"] {
        let text = std::fs::read_to_string(dir.join(json)).expect("read");
        serde_json::from_str::<serde_json::Value>(&text).unwrap_or_else(|e| panic!("{json}: {e}"));
    }
    let o = node(&["--check", "extension.js"]);
    assert!(o.status.success(), "{}", describe(&o));
}
