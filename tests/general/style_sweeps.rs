//! `npr test --sweep`: every parameter across its declared range, on the
//! hard scenes npr ships. A style made unstable on purpose (a range that
//! admits a division by zero) must be reported with the one `npr render`
//! line that reproduces it, on a style that declares no tests and through
//! a test's `sweep = true`; a few examples must sweep clean.

use crate::common::cli::{npr, scratch};
use std::path::Path;
use std::process::{Command, Output};

/// `0.5 / k` in a float target that the 8-bit output reads only through a
/// comparison: at `k = 0` the target holds Inf and the output hides it.
const UNSTABLE: &str = "style \"Unstable\"\n/// A divisor whose declared range admits zero.\nparam k: float = 1.0 in 0..2\npass g: render(scene) {\n  out v: rgba16float = vec4(0.5 / k, normal.y * 0.5 + 0.5, 0.5, 1.0)\n  clear: #000000\n}\npass show: image(g) {\n  out c: rgba8unorm = if g.v.r > 100.0 { #ff0000 } else { vec4(g.v.g, 0.3, 0.6, 1.0) }\n}\noutput show.c\n";

const SCENE: &str = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n\n[[object]]\nname = \"ball\"\nprimitive = { kind = \"sphere\", radius = 0.8, segments = 16, rings = 8 }\n";

fn npr_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(args)
        .current_dir(dir)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr")
}

fn report(o: &Output) -> serde_json::Value {
    let text = String::from_utf8_lossy(&o.stdout);
    serde_json::from_str(text.trim()).unwrap_or_else(|e| {
        panic!(
            "{e}: no JSON report in stdout:\n{text}\nstderr:\n{}",
            String::from_utf8_lossy(&o.stderr)
        )
    })
}

fn sweep_failures(report: &serde_json::Value) -> Vec<serde_json::Value> {
    report["tests"]
        .as_array()
        .expect("tests")
        .iter()
        .flat_map(|t| t["failures"].as_array().cloned().unwrap_or_default())
        .filter(|f| f["check"] == "sweep")
        .collect()
}

#[test]
fn a_range_admitting_a_division_by_zero_is_reported_with_its_reproduction() {
    let dir = scratch("style_sweeps", "unstable");
    std::fs::write(dir.join("unstable.npr"), UNSTABLE).expect("style");
    // No test file: the hard scenes alone.
    let o = npr_in(
        &dir,
        &["test", "unstable.npr", "--sweep", "--format", "json", "--out", "out"],
    );
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(&o);
    assert_eq!(r["tests"][0]["id"], "unstable.npr::@sweep");
    let found = sweep_failures(&r);
    // k = 0 and nothing else: 0.5, 1, 1.5 and 2 are finite.
    assert_eq!(found.len(), 1, "{found:#?}");
    let message = found[0]["message"].as_str().expect("message");
    // Every case but the speck 400 m away, which covers no pixel.
    assert!(message.starts_with("k=0: finite on 9 of 10 case(s)"), "{message}");
    assert!(!message.contains("tiny_far"), "{message}");
    assert!(message.contains("target `g.v`"), "{message}");
    // The cheapest case of the ten: the 1x1 image.
    let line = found[0]["reproduce"].as_str().expect("a reproduction");
    assert_eq!(
        line,
        "npr render unstable.npr --scene out/hard_scenes/small.toml --size 1x1 --schedule naive --keep-params --set k=0 -o sweep.png"
    );
    // The line runs as written (the hard scene is where it says).
    let words: Vec<&str> = line.split(' ').skip(1).collect();
    let o = npr_in(&dir, &words);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.join("sweep.png").is_file());

    // Declared in a test: the sweep runs on that test's own scene.
    std::fs::write(dir.join("scene.toml"), SCENE).expect("scene");
    std::fs::write(
        dir.join("unstable.tests.toml"),
        "[[test]]\nname = \"ball\"\nscene = \"scene.toml\"\nsize = \"24x24\"\nsweep = true\n",
    )
    .expect("tests");
    let o = npr_in(&dir, &["test", "unstable.npr", "--format", "json"]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(&o);
    let found = sweep_failures(&r);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(
        found[0]["reproduce"],
        "npr render unstable.npr --scene scene.toml --size 24x24 --schedule naive --keep-params --set k=0 -o sweep.png"
    );
}

/// The planted style (issue 49): five params, non-finite only
/// when the first is at the top of its range and the last at the bottom.
/// The old sweep moved only neighbouring pairs and passed it; the covering
/// array renders every pair of ends, and the row that fails is reduced to
/// the pair.
const FIRST_AND_LAST: &str = "style \"First and last\"\nparam a: float = 0.5 in 0..1\nparam b: float = 0.5 in 0..1\nparam c: float = 0.5 in 0..1\nparam d: float = 0.5 in 0..1\nparam e: float = 0.5 in 0..1\npass g: render(scene) {\n  out v: rgba16float = vec4(0.5 / (1.0 - a + e), normal.y * 0.5 + 0.5, b * c * d, 1.0)\n  clear: #000000\n}\npass show: image(g) {\n  out c: rgba8unorm = if g.v.r > 100.0 { #ff0000 } else { vec4(g.v.g, g.v.b, 0.6, 1.0) }\n}\noutput show.c\n";

#[test]
fn a_pair_that_is_not_neighbours_is_found_and_named() {
    let dir = scratch("style_sweeps", "first_and_last");
    std::fs::write(dir.join("planted.npr"), FIRST_AND_LAST).expect("style");
    std::fs::write(dir.join("scene.toml"), SCENE).expect("scene");
    std::fs::write(
        dir.join("planted.tests.toml"),
        "[[test]]\nname = \"ball\"\nscene = \"scene.toml\"\nsize = \"16x16\"\nsweep = true\n",
    )
    .expect("tests");
    let o = npr_in(&dir, &["test", "planted.npr", "--format", "json"]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(&o);
    let found = sweep_failures(&r);
    assert_eq!(found.len(), 1, "{found:#?}");
    let message = found[0]["message"].as_str().expect("message");
    assert!(
        message.starts_with("a=1 e=0:") || message.starts_with("a=1, e=0:"),
        "{message}"
    );
    assert_eq!(
        found[0]["reproduce"],
        "npr render planted.npr --scene scene.toml --size 16x16 --schedule naive --keep-params --set a=1 --set e=0 -o sweep.png"
    );
}

/// Examples chosen for their kinds of parameter (ints, colours, px, enums,
/// bools) and their cost: the sweep of every example is in
/// docs/PERFORMANCE.md.
#[test]
fn a_few_examples_sweep_clean() {
    let out = scratch("style_sweeps", "examples");
    let out = out.to_str().expect("a UTF-8 path");
    let o = npr(&[
        "test",
        "examples/toon.npr",
        "examples/outline.npr",
        "examples/sobel_outline.npr",
        "--sweep",
        "--filter",
        "@sweep",
        "--format",
        "json",
        "--out",
        out,
    ]);
    let r = report(&o);
    let ids: Vec<&str> = r["tests"]
        .as_array()
        .expect("tests")
        .iter()
        .map(|t| t["id"].as_str().expect("id"))
        .collect();
    assert_eq!(
        ids,
        [
            "examples/outline.npr::@sweep",
            "examples/sobel_outline.npr::@sweep",
            "examples/toon.npr::@sweep"
        ]
    );
    assert!(sweep_failures(&r).is_empty(), "{r:#}");
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
}
