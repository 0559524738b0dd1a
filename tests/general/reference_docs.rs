//! `docs/reference/` is what `npr doc` writes: its text files byte for
//! byte, its demo images (`img/`, rendered by the runner on lavapipe)
//! within [`IMAGE_TOLERANCE`], since another CPU's lavapipe may round the
//! last bit differently; and the reference covers everything the metadata
//! has. `UPDATE_REFERENCE_DOCS=1` rewrites `docs/reference/` with `npr doc`
//! instead of comparing.

use npr_lab::harness::{compare_with_golden_file, Tolerance};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// How far a demo image may be from the committed one: every channel
/// within 16/255, except at most 2% of the pixels (245 of a 128 × 96
/// image: an edge of ink moved by a pixel where another CPU rounds a
/// threshold the other way). Differences are written to
/// `target/npr-test-output/<operator>.{actual,diff}.png`.
const IMAGE_TOLERANCE: Tolerance = Tolerance::PerPixel {
    max_abs: 16,
    outlier_fraction: 0.02,
};

/// The text files directly in `dir` (the pages and the stylesheet).
fn read_dir(dir: &Path) -> BTreeMap<String, String> {
    std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| {
            let e = e.expect("dir entry");
            if e.file_type().expect("file type").is_dir() {
                return None;
            }
            let name = e.file_name().to_string_lossy().into_owned();
            let text = std::fs::read_to_string(e.path()).expect("a text file");
            Some((name, text))
        })
        .collect()
}

/// The names of the demo images in `dir/img/`.
fn image_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir.join("img"))
        .unwrap_or_else(|e| panic!("{}/img: {e}", dir.display()))
        .map(|e| e.expect("dir entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
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
        "docs/reference/ has other files than `npr doc` writes; run UPDATE_REFERENCE_DOCS=1 cargo test --workspace --test general reference_docs::"
    );
    for (name, text) in &want {
        assert!(
            have[name] == *text,
            "docs/reference/{name} differs from `npr doc`; run UPDATE_REFERENCE_DOCS=1 cargo test --workspace --test general reference_docs::"
        );
    }
    let images = image_names(&fresh);
    assert_eq!(
        image_names(&committed),
        images,
        "docs/reference/img/ has other images than `npr doc` renders; run UPDATE_REFERENCE_DOCS=1 cargo test --workspace --test general reference_docs::"
    );
    let mut failed = Vec::new();
    for name in &images {
        let actual = image::open(fresh.join("img").join(name))
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .to_rgba8();
        let c = compare_with_golden_file(&actual, &committed.join("img").join(name), IMAGE_TOLERANCE, false);
        if !c.passed {
            failed.push(format!("img/{name}: {} (written: {:?})", c.summary, c.written));
        }
    }
    assert!(
        failed.is_empty(),
        "demo images differ from docs/reference/img/ beyond the tolerance (if the change is meant, run UPDATE_REFERENCE_DOCS=1 cargo test --workspace --test general reference_docs::):\n{}",
        failed.join("\n")
    );
}

#[test]
fn the_reference_covers_every_operator_builtin_and_code() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("reference-coverage");
    let _ = std::fs::remove_dir_all(&dir);
    npr_doc(&dir);
    let files = read_dir(&dir);
    let operators = &files["operators.md"];
    for op in npr_stdlib::all() {
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
    for (name, _) in npr_compiler::ir::Intrinsic::TABLE {
        assert!(
            operators.contains(&format!("| `{name}` |")),
            "intrinsic {name} is missing"
        );
    }
    let images = image_names(&dir);
    for def in npr_stdlib::ops::ALL {
        let name = def.op.name;
        match def.demo {
            npr_stdlib::ops::Demo::Render(d) => {
                assert!(images.contains(&format!("{name}.png")), "{name} has no image");
                assert!(
                    operators.contains(&format!("![{}](img/{name}.png)", d.shows)),
                    "{name}'s image is not shown with its alt text"
                );
                let png = image::open(dir.join("img").join(format!("{name}.png"))).expect("a PNG");
                assert_eq!(
                    (png.width(), png.height()),
                    npr_stdlib::ops::DEMO_SIZE,
                    "{name}'s image size"
                );
                assert!(
                    operators_html(&files).contains(&format!("<img src=\"img/{name}.png\"")),
                    "{name}'s image is not in operators.html"
                );
            }
            npr_stdlib::ops::Demo::NoDemo(why) => {
                assert!(operators.contains(why), "{name}: the reason for no demo is missing");
            }
            npr_stdlib::ops::Demo::Missing => panic!("{name} has no demo (see stdlib/tests/completeness.rs)"),
        }
    }
    let builtins = &files["builtins.md"];
    for (spelling, _) in npr_compiler::ir::Builtin::SPELLINGS {
        assert!(
            builtins.contains(&format!("| `{spelling}` |")),
            "builtin {spelling} is missing"
        );
    }
    let errors = &files["errors.md"];
    for (code, what) in npr_diag::codes::ALL {
        assert!(errors.contains(&format!("## {code}: {what}\n")), "{code} is missing");
    }
    for (name, _) in npr_abi::Format::ALL {
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

fn operators_html(files: &BTreeMap<String, String>) -> &str {
    &files["operators.html"]
}

/// Every style the guide shows (colours, recipes) compiles on a scene of
/// `examples/` without a diagnostic, and the guide answers what it says it
/// does: colours and alpha, each texture source, and each recipe.
#[test]
fn every_style_the_guide_shows_compiles_cleanly() {
    let guide = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference/guide.md"))
        .expect("docs/reference/guide.md");
    for heading in [
        "## Colours and alpha",
        "## Colour ramps (`gradient`)",
        "## Texture sources",
        "### Thicker ink lines",
        "### A paper texture",
        "### A cast shadow",
        "### Read the previous frame",
    ] {
        assert!(guide.contains(heading), "the guide lacks `{heading}`");
    }
    let passes = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference/passes.md"))
        .expect("docs/reference/passes.md");
    for setting in [
        "`clear: #rrggbb`",
        "`depth: keep`",
        "{ blend: over }",
        "`schedule: naive",
    ] {
        assert!(passes.contains(setting), "passes.md lacks {setting}");
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("guide-styles");
    std::fs::create_dir_all(&dir).expect("scratch");
    let mut styles = 0;
    for (i, block) in guide.split("```npr\n").skip(1).enumerate() {
        let text = block.split("```").next().expect("a closed block");
        let path = dir.join(format!("style{i}.npr"));
        std::fs::write(&path, text).expect("write");
        let o = Command::new(env!("CARGO_BIN_EXE_npr"))
            .arg("check")
            .arg(&path)
            .arg("--scene")
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/spheres.toml"))
            .output()
            .expect("run npr check");
        let stderr = String::from_utf8_lossy(&o.stderr);
        let clean = !stderr.contains("warning[") && !stderr.contains("error[");
        assert!(o.status.success() && clean, "{text}\n{stderr}");
        styles += 1;
    }
    assert_eq!(styles, 6, "the colour and gradient examples and four recipes");
}
