//! `docs/reference/` is what `npr doc` writes, byte for byte, and the
//! reference covers everything the metadata has. `UPDATE_REFERENCE_DOCS=1`
//! rewrites `docs/reference/` with `npr doc` instead of comparing.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

fn read_dir(dir: &Path) -> BTreeMap<String, String> {
    std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| {
            let e = e.expect("dir entry");
            let name = e.file_name().to_string_lossy().into_owned();
            let text = std::fs::read_to_string(e.path()).expect("a text file");
            (name, text)
        })
        .collect()
}

fn npr_doc(out: &Path) {
    let o = Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["doc", "-o"])
        .arg(out)
        .output()
        .expect("run npr doc");
    assert!(
        o.status.success(),
        "npr doc failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn committed_reference_matches_npr_doc() {
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference");
    if std::env::var_os("UPDATE_REFERENCE_DOCS").is_some() {
        npr_doc(&committed);
    }
    let fresh = Path::new(env!("CARGO_TARGET_TMPDIR")).join("reference-docs");
    let _ = std::fs::remove_dir_all(&fresh);
    npr_doc(&fresh);
    let want = read_dir(&fresh);
    let have = read_dir(&committed);
    assert_eq!(
        have.keys().collect::<Vec<_>>(),
        want.keys().collect::<Vec<_>>(),
        "docs/reference/ has other files than `npr doc` writes; run UPDATE_REFERENCE_DOCS=1 cargo test --workspace --test reference_docs"
    );
    for (name, text) in &want {
        assert!(
            have[name] == *text,
            "docs/reference/{name} differs from `npr doc`; run UPDATE_REFERENCE_DOCS=1 cargo test --workspace --test reference_docs"
        );
    }
}

#[test]
fn the_reference_covers_every_operator_builtin_and_code() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("reference-coverage");
    let _ = std::fs::remove_dir_all(&dir);
    npr_doc(&dir);
    let files = read_dir(&dir);
    let operators = &files["operators.md"];
    for op in stdlib::all() {
        assert!(
            operators.contains(&format!("## `{}`\n", op.name)),
            "{} has no section",
            op.name
        );
        assert!(operators.contains(op.reference), "{}'s source is missing", op.name);
        for p in op.params {
            assert!(
                operators.contains(&format!("| `{}` |", p.name)),
                "{}.{} has no row",
                op.name,
                p.name
            );
        }
        for s in op.specializations {
            assert!(
                operators.contains(&format!("compiles to `{}`", s.use_operator)),
                "{}'s specialization to {} is missing",
                op.name,
                s.use_operator
            );
        }
    }
    for (name, _) in compiler::ir::Intrinsic::TABLE {
        assert!(
            operators.contains(&format!("| `{name}` |")),
            "intrinsic {name} is missing"
        );
    }
    let builtins = &files["builtins.md"];
    for (spelling, _) in compiler::ir::Builtin::SPELLINGS {
        assert!(
            builtins.contains(&format!("| `{spelling}` |")),
            "builtin {spelling} is missing"
        );
    }
    let errors = &files["errors.md"];
    for (code, what) in dsl::codes::ALL {
        assert!(errors.contains(&format!("## {code}: {what}\n")), "{code} is missing");
    }
    for (name, _) in abi::Format::ALL {
        assert!(
            files["units.md"].contains(&format!("| `{name}` |")),
            "format {name} is missing"
        );
    }
    // Every page's HTML exists and links only to pages that exist.
    for name in files.keys() {
        let Some(stem) = name.strip_suffix(".md") else { continue };
        let page = &files[&format!("{stem}.html")];
        assert!(page.starts_with("<!DOCTYPE html>"), "{stem}.html");
        for link in page.split("href=\"").skip(1) {
            let target = link.split(['"', '#']).next().unwrap_or("");
            assert!(
                target.is_empty() || files.contains_key(target),
                "{stem}.html links to missing {target}"
            );
        }
    }
}
