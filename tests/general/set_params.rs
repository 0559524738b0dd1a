//! `--set name=value` through the `npr` binary: a set value renders exactly
//! like the same value written as the default in the file (folded, and
//! kept as a uniform with `--keep-params`), later `--set`s win, and each
//! mistake is a diagnostic pointing into the `--set` argument (snapshots).

use crate::common;

use common::cli::npr;
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("set-params").join(name);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn render(style: &Path, extra: &[&str], out: &Path) -> Vec<u8> {
    let mut args = vec![
        "render",
        style.to_str().expect("utf-8 path"),
        "--scene",
        "examples/scenes/spot.toml",
        "--size",
        "64x64",
        "-o",
        out.to_str().expect("utf-8 path"),
    ];
    args.extend_from_slice(extra);
    let o = npr(&args);
    assert!(
        o.status.success(),
        "npr {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    std::fs::read(out).expect("rendered image")
}

/// examples/toon.npr (which names no file) with `bands` 5 and `base`
/// #3080ff written as defaults, in a scratch directory.
fn edited_toon() -> PathBuf {
    let text = std::fs::read_to_string("examples/toon.npr").expect("toon.npr");
    let edited = text
        .replace("param bands: int = 3 in 1..8", "param bands: int = 5 in 1..8")
        .replace("param base: color = #e07a3a", "param base: color = #3080ff");
    assert_ne!(
        text, edited,
        "examples/toon.npr no longer declares the defaults this test edits"
    );
    let path = scratch("edited").join("toon.npr");
    std::fs::write(&path, edited).expect("write edited copy");
    path
}

#[test]
fn a_set_value_renders_like_the_same_default_in_the_file() {
    let dir = scratch("same-as-file");
    let edited = edited_toon();
    let toon = Path::new("examples/toon.npr");
    let sets = ["--set", "bands=5", "--set", "base=#3080ff"];
    let from_file = render(&edited, &[], &dir.join("file.png"));
    let from_set = render(toon, &sets, &dir.join("set.png"));
    let plain = render(toon, &[], &dir.join("plain.png"));
    assert_eq!(from_set, from_file, "--set must fold exactly like a written default");
    assert_ne!(from_set, plain, "the set values must change the image");
    // Kept as uniforms, the values reach the shaders through the style block.
    let mut kept = sets.to_vec();
    kept.push("--keep-params");
    let kept_set = render(toon, &kept, &dir.join("kept.png"));
    let kept_file = render(&edited_toon(), &["--keep-params"], &dir.join("kept_file.png"));
    assert_eq!(kept_set, kept_file);
}

#[test]
fn the_last_set_of_a_name_wins() {
    let dir = scratch("last-wins");
    let toon = Path::new("examples/toon.npr");
    let twice = render(toon, &["--set", "bands=2", "--set", "bands=5"], &dir.join("twice.png"));
    let once = render(toon, &["--set", "bands=5"], &dir.join("once.png"));
    assert_eq!(twice, once);
}

/// The rendered diagnostics of a failing `npr check` (exit 1).
fn check_errors(style: &str, sets: &[&str]) -> String {
    let mut args = vec!["check", style];
    for s in sets {
        args.push("--set");
        args.push(s);
    }
    let o = npr(&args);
    let stderr = String::from_utf8_lossy(&o.stderr).to_string();
    assert_eq!(o.status.code(), Some(1), "npr {args:?}: {stderr}");
    stderr
}

#[test]
fn an_unknown_name_gets_did_you_mean() {
    let r = check_errors("examples/toon.npr", &["bnds=5"]);
    assert!(r.contains("error[E0101]") && r.contains("did you mean `bands`?"), "{r}");
    insta::assert_snapshot!("set_unknown_name", r);
}

#[test]
fn a_value_of_the_wrong_type_is_e0201() {
    let r = check_errors("examples/toon.npr", &["bands=2.5", "base=#12"]);
    assert!(r.contains("error[E0201]") && r.contains("--set:1:7"), "{r}");
    insta::assert_snapshot!("set_wrong_type", r);
}

#[test]
fn a_value_of_the_wrong_unit_is_e0202() {
    let r = check_errors("examples/age_of_sail.npr", &["inflate=2m"]);
    assert!(r.contains("error[E0202]"), "{r}");
    insta::assert_snapshot!("set_wrong_unit", r);
}

#[test]
fn a_value_outside_the_declared_range_is_e0203() {
    let r = check_errors("examples/toon.npr", &["bands=99"]);
    assert!(r.contains("error[E0203]") && r.contains("outside 1..8"), "{r}");
    insta::assert_snapshot!("set_out_of_range", r);
}

#[test]
fn an_enum_variant_gets_did_you_mean_and_a_per_object_param_is_refused() {
    let r = check_errors("examples/age_of_sail.npr", &["beta=cubc", "breakup=1"]);
    assert!(r.contains("did you mean `cubic`?") && r.contains("error[E0502]"), "{r}");
    insta::assert_snapshot!("set_enum_and_per_object", r);
}

#[test]
fn a_set_without_a_value_is_a_usage_error() {
    let o = npr(&["check", "examples/toon.npr", "--set", "bands"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr.contains("E0501") && stderr.contains("NAME=VALUE"), "{stderr}");
}

/// `--set g="p:#colour, ..."` gives the shaders of the same stops written
/// in the file.
#[test]
fn a_set_gradient_is_the_gradient_written_in_the_file() {
    let dir = crate::common::cli::scratch("set-params", "gradient");
    let original = std::fs::read_to_string("examples/toon_ramp.npr").expect("toon_ramp.npr");
    let decl = original
        .lines()
        .find(|l| l.starts_with("param shading: gradient"))
        .expect("the gradient's line");
    let edited = original.replace(
        decl,
        "param shading: gradient = gradient(stop(0.0, #102030), stop(0.5, #ff8800), stop(1.0, #ffffff))",
    );
    std::fs::write(dir.join("edited.npr"), edited).expect("write");
    let compile = |style: &str, out: &str, set: Option<&str>| {
        let mut args = vec!["compile", style, "-o", out];
        if let Some(s) = set {
            args.extend(["--set", s]);
        }
        let o = crate::common::cli::npr(&args);
        assert_eq!(o.status.code(), Some(0), "{}", crate::common::cli::stderr(&o));
        std::fs::read_to_string(std::path::Path::new(out).join("shade.wgsl")).expect("shade.wgsl")
    };
    let set = compile(
        "examples/toon_ramp.npr",
        dir.join("set").to_str().expect("utf-8"),
        Some("shading=0:#102030, 0.5:#ff8800, 1:#ffffff"),
    );
    let written = compile(
        dir.join("edited.npr").to_str().expect("utf-8"),
        dir.join("written").to_str().expect("utf-8"),
        None,
    );
    // Comments name the file each line came from.
    let body = |w: &str| {
        w.lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(body(&set), body(&written));
    assert!(
        set.contains("vec4<f32>(1.0f, 0.53333336f, 0.0f, 1.0f)"),
        "the set stop's colour: {set}"
    );
}
