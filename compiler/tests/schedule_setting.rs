//! The `schedule:` setting of an image pass (issue 14): `naive` and
//! `tiled` override `--schedule` for their pass under every run schedule,
//! `auto` leaves the pass to it, and the report says, per image pass, what
//! it got and why ("forced by `schedule: naive` at line L"). That the
//! images equal the naive schedule's is `tests/gpu/schedule_equivalence.rs`;
//! E0311 (a forced `tiled` the tiler refuses) is in `tests/error_codes/`.

use npr_abi::manifest::PassKindManifest;
use npr_compiler::schedule::Schedule;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::path::Path;

/// A G-buffer and five image passes. Unforced, `auto` would fuse `tone`
/// into `mix` and `mix` into `final`, and `tiled` would tile `edges` and
/// `folds`.
const STYLE: &str = r#"style "schedule settings"
pass g: render(scene) {
  out d: rgba16float = vec4(depth, 0.0, 0.0, 1.0)
  out n: rgba16float = vec4(normal.world, 1.0)
}
pass edges: image(g) {
  schedule: tiled
  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)
}
pass folds: image(g) {
  schedule: naive
  out b: rgba16float = vec4(sobel(g.n, screen_uv), 0.0, 0.0, 1.0)
}
pass tone: image(g) {
  schedule: auto
  out c: rgba16float = g.n * 0.5
}
pass mix: image(tone, edges, folds) {
  out c: rgba16float = tone.c + edges.e + folds.b
}
pass final: image(mix) {
  out c: rgba8unorm = mix.c
}
output final.c
"#;

fn compile(text: &str, schedule: Schedule) -> npr_compiler::Compiled {
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        schedule,
        ..Default::default()
    };
    npr_compiler::compile_source("settings.npr", text, Path::new("."), &mut sources, &opts)
        .unwrap_or_else(|e| panic!("{e:?}"))
}

/// The report's schedule lines (every image pass: `schedule` or `fused`,
/// then `tiled` / `not tiled`).
fn schedule_lines(c: &npr_compiler::Compiled) -> String {
    c.report
        .entries
        .iter()
        .filter(|e| ["schedule", "fused", "tiled", "not tiled"].contains(&e.action))
        .map(|e| format!("{} {}: {}", e.action, e.what, e.why))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The passes the manifest runs, each with whether it is tiled.
fn passes(c: &npr_compiler::Compiled) -> Vec<(String, bool)> {
    c.program()
        .manifest
        .passes
        .iter()
        .map(|p| (p.name.clone(), matches!(p.kind, PassKindManifest::TiledImage { .. })))
        .collect()
}

fn names(list: &[(&str, bool)]) -> Vec<(String, bool)> {
    list.iter().map(|(n, t)| (n.to_string(), *t)).collect()
}

#[test]
fn forced_passes_keep_their_schedule_under_every_run_schedule() {
    for schedule in Schedule::ALL {
        let c = compile(STYLE, schedule);
        let lines = schedule_lines(&c);
        let run = schedule.name();
        // Forced: the same under every `--schedule`.
        assert!(
            lines.contains("schedule pass `edges`: separate pass: forced by `schedule: tiled` at line 7"),
            "--schedule {run}:\n{lines}"
        );
        assert!(
            lines.contains("tiled pass `edges`: forced by `schedule: tiled` at line 7: compute over 16×16 tiles"),
            "--schedule {run}:\n{lines}"
        );
        assert!(
            lines.contains("schedule pass `folds`: separate pass: forced by `schedule: naive` at line 11"),
            "--schedule {run}:\n{lines}"
        );
        assert!(
            !lines.contains("tiled pass `folds`: compute"),
            "--schedule {run}:\n{lines}"
        );
        insta::assert_snapshot!(format!("report_{run}"), lines);
    }
    // `tone` (`schedule: auto`) and `mix` follow the run's schedule; `edges`
    // is tiled and `folds` is a fragment pass in every one.
    let expected = [
        (
            Schedule::Naive,
            names(&[
                ("g", false),
                ("edges", true),
                ("folds", false),
                ("tone", false),
                ("mix", false),
                ("final", false),
            ]),
        ),
        (
            Schedule::Auto,
            names(&[("g", false), ("edges", true), ("folds", false), ("final", false)]),
        ),
        (
            Schedule::Tiled,
            names(&[("g", false), ("edges", true), ("folds", false), ("final", false)]),
        ),
    ];
    for (schedule, want) in expected {
        assert_eq!(
            passes(&compile(STYLE, schedule)),
            want,
            "--schedule {}",
            schedule.name()
        );
    }
}

/// `schedule: naive` on a reader keeps its producer from being fused into
/// it, and on a producer keeps it out of its reader; `schedule: auto` is
/// the same as no setting.
#[test]
fn naive_blocks_fusion_both_ways_and_auto_is_no_setting() {
    let base = r#"style "chain"
pass g: render(scene) {
  out n: rgba16float = vec4(normal.world, 1.0)
}
pass a: image(g) {
  SETTING_A
  out c: rgba16float = g.n * 0.5
}
pass b: image(a) {
  SETTING_B
  out c: rgba16float = a.c + 0.25
}
pass final: image(b) {
  out c: rgba8unorm = b.c
}
output final.c
"#;
    let with = |a: &str, b: &str| base.replace("SETTING_A", a).replace("SETTING_B", b);
    let fused = |text: &str| -> Vec<String> {
        compile(text, Schedule::Auto)
            .report
            .entries
            .iter()
            .filter(|e| e.action == "fused")
            .map(|e| e.what.clone())
            .collect()
    };
    assert_eq!(fused(&with("", "")), ["pass `a`", "pass `b`"]);
    assert_eq!(
        fused(&with("schedule: auto", "schedule: auto")),
        ["pass `a`", "pass `b`"]
    );
    // `b` forced naive: `a` is not fused into it, nor `b` into `final`.
    let reader = compile(&with("", "schedule: naive"), Schedule::Auto);
    assert!(fused(&with("", "schedule: naive")).is_empty());
    let lines = schedule_lines(&reader);
    assert!(
        lines.contains(
            "schedule pass `a`: separate pass: its reader `b` is forced by `schedule: naive` at line 10, so nothing is fused into it"
        ),
        "{lines}"
    );
    // `a` forced naive: `b` still fuses into `final`.
    assert_eq!(fused(&with("schedule: naive", "")), ["pass `b`"]);
}

/// A pass from a `use`d file names that file in its report line.
#[test]
fn a_forced_pass_in_a_used_file_is_reported_with_its_file() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("schedule-setting-use");
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(
        dir.join("lib.npr"),
        "style \"lib\"\npass g: render(scene) {\n  out n: rgba16float = vec4(normal.world, 1.0)\n}\npass soft: image(g) {\n  schedule: naive\n  out c: rgba16float = g.n * 0.5\n}\n",
    )
    .expect("lib");
    let text =
        "style \"main\"\nuse \"lib.npr\"\npass final: image(soft) {\n  out c: rgba8unorm = soft.c\n}\noutput final.c\n";
    std::fs::write(dir.join("main.npr"), text).expect("main");
    let mut sources = SourceMap::new();
    let c = npr_compiler::compile_file(&dir.join("main.npr"), &mut sources, &CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    let lines = schedule_lines(&c);
    assert!(
        lines.contains("forced by `schedule: naive` at line 6 of ") && lines.contains("lib.npr"),
        "{lines}"
    );
}
