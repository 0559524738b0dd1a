//! `--schedule recompute` and `schedule: recompute` (issue 14's fused
//! neighbourhood stages): which image passes are computed in their
//! reader's tiles instead of stored, and why not, as the report says; the
//! reader's module (no binding of the target, the producer's function, the
//! computed tile); and that `auto` does none but reports what `recompute`
//! would do. Every module here passed naga's validation inside
//! `compile_source`; that the images equal the naive schedule's is
//! `tests/gpu/schedule_equivalence.rs`.

use npr_abi::manifest::{PassKindManifest, Resource};
use npr_compiler::schedule::Schedule;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::path::Path;

/// A G-buffer, a Sobel pass read around the pixel by one reader, and a
/// Sobel pass that two passes read.
const STYLE: &str = r#"style "recompute cases"
pass g: render(scene) {
  out d: r32float = depth
  out n: rgba16float = vec4(normal.world, 1.0)
}
/// Recomputed in `ink`'s tiles: its one reader reads it within 1 texel.
pass edges: image(g) {
  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)
}
/// Not recomputed: `ink` and `glow` read it.
pass shared: image(g) {
  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)
}
pass glow: image(shared) {
  out e: rgba16float = vec4(sobel(shared.e, screen_uv), 0.0, 0.0, 1.0)
}
pass ink: image(edges, shared, glow) {
  out c: rgba8unorm = vec4(sobel(edges.e, screen_uv), shared.e.r, sobel(glow.e, screen_uv), 1.0)
}
output ink.c
"#;

fn compile_style(text: &str, schedule: Schedule) -> Result<npr_compiler::Compiled, npr_compiler::CompileError> {
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        schedule,
        ..Default::default()
    };
    npr_compiler::compile_source("recompute.npr", text, Path::new("."), &mut sources, &opts)
}

fn compile(text: &str, schedule: Schedule) -> npr_compiler::Compiled {
    compile_style(text, schedule).unwrap_or_else(|e| panic!("{e:?}"))
}

/// The report's schedule lines for recomputation and tiling.
fn schedule_lines(c: &npr_compiler::Compiled) -> String {
    c.report
        .entries
        .iter()
        .filter(|e| e.action.ends_with("recomputed") || e.action.ends_with("tiled"))
        .map(|e| format!("{} {}: {}", e.action, e.what, e.why))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn recompute_computes_a_pass_read_around_the_pixel_by_one_reader_in_its_tiles() {
    let c = compile(STYLE, Schedule::Recompute);
    let lines = schedule_lines(&c);
    assert!(
        lines.contains("recomputed pass `edges`: in `ink`'s tiles: `ink` reads `edges.e` within 1 texel(s)"),
        "{lines}"
    );
    assert!(lines.contains("(1.27x its pixels)"), "{lines}");
    assert!(
        lines.contains("not recomputed pass `shared`: read by `glow` and `ink`"),
        "{lines}"
    );
    // `glow` is read by `ink` around the pixel: it is recomputed too, and
    // reads `shared`, a stored target, from its own textureLoads.
    assert!(lines.contains("recomputed pass `glow`"), "{lines}");
    insta::assert_snapshot!("recompute_report", lines);

    let manifest = &c.program().manifest;
    let names: Vec<&str> = manifest.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["g", "shared", "ink"], "edges and glow are not passes");
    let ink = manifest.passes.iter().find(|p| p.name == "ink").expect("ink");
    assert!(matches!(ink.kind, PassKindManifest::TiledImage { .. }));
    // Bound: the frame, `g.d` (read by the computed passes) and `shared.e`.
    let targets = ink
        .bindings
        .iter()
        .filter(|b| matches!(b.resource, Resource::Target { .. }))
        .count();
    assert_eq!(targets, 2, "{:?}", ink.bindings);

    let wgsl = c.shader("ink.wgsl").expect("ink pass");
    assert!(
        !wgsl.contains("var t_edges_e"),
        "no binding of a computed target:\n{wgsl}"
    );
    assert!(
        wgsl.contains("fn npr_compute_t_edges_e(q: vec2<i32>) -> vec4<f32>"),
        "{wgsl}"
    );
    // Its texel: the producer's expression at q, rounded as rgba16float.
    assert!(
        wgsl.contains("return npr_stored_rgba16float(vec4<f32>(npr_sobel__t_g_d(in.screen_uv), 0.0f, 0.0f, 1.0f));"),
        "{wgsl}"
    );
    assert!(
        wgsl.contains("var<workgroup> npr_tile_t_edges_e: array<vec4<f32>, 324>;"),
        "{wgsl}"
    );
    assert!(wgsl.contains("fn npr_sobel__t_edges_e(uv: vec2<f32>)"), "{wgsl}");
    assert!(wgsl.contains("npr_computed_dims_t_edges_e()"), "{wgsl}");
    let cs = &wgsl[wgsl.find("@compute").expect("entry")..];
    insta::assert_snapshot!("recompute_entry", cs);
}

#[test]
fn auto_recomputes_nothing_and_reports_what_recompute_would() {
    let c = compile(STYLE, Schedule::Auto);
    let lines = schedule_lines(&c);
    assert!(!lines.lines().any(|l| l.starts_with("recomputed ")), "{lines}");
    assert!(
        lines.contains("not recomputed pass `edges`: `--schedule recompute` would compute it in `ink`'s tiles (1.27x its pixels) instead of storing `edges.e`"),
        "{lines}"
    );
    let program = c.program();
    let names: Vec<&str> = program.manifest.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["g", "edges", "shared", "glow", "ink"]);
}

/// `schedule: recompute` on a pass asks for it under every `--schedule`,
/// `naive` included, and the report says so.
#[test]
fn the_setting_recomputes_under_every_schedule() {
    let text = STYLE.replace(
        "pass edges: image(g) {\n",
        "pass edges: image(g) {\n  schedule: recompute\n",
    );
    for schedule in Schedule::ALL {
        let c = compile(&text, schedule);
        let lines = schedule_lines(&c);
        assert!(
            lines.contains("recomputed pass `edges`: forced by `schedule: recompute` at line 8: in `ink`'s tiles"),
            "--schedule {}: {lines}",
            schedule.name()
        );
        assert!(
            lines.contains("tiled pass `ink`: it computes a target in its tiles"),
            "--schedule {}: {lines}",
            schedule.name()
        );
    }
}

/// Each reason a pass is not recomputed, as `--schedule recompute` reports
/// it (E0312's help gives the same reasons for a forced pass:
/// `tests/error_codes/passes.rs`).
#[test]
fn each_refusal_is_reported_with_its_reason() {
    const G: &str =
        "style \"case\"\npass g: render(scene) {\n  out d: r32float = depth\n  out n: rgba16float = vec4(normal.world, 1.0)\n}\n";
    let cases = [
        (
            "output",
            "pass e: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\noutput e.c\n",
            "`e.c` is the style's output",
        ),
        (
            "sampled",
            "pass e: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass r: image(e) {\n  out c: rgba8unorm = sample(e.c, screen_uv + vec2(0.01, 0.0))\n}\noutput r.c\n",
            "`r` passes `e.c` to `sample`, which reads it anywhere",
        ),
        (
            "anywhere",
            "pass e: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass r: image(e, g) {\n  out c: rgba8unorm = warp(e.c, g.n.xy)\n}\noutput r.c\n",
            "`r` passes `e.c` to `warp`, which reads it anywhere",
        ),
        (
            "scale",
            "pass e: image(g) scale 1/2 {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass r: image(e) {\n  out c: rgba8unorm = vec4(sobel(e.c, screen_uv))\n}\noutput r.c\n",
            "`r` runs at scale 1, this pass at 0.5",
        ),
        (
            "reader cannot tile",
            "pass e: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass r: image(e) {\n  out c: r16float = sobel(e.c, screen_uv)\n}\noutput r.c\n",
            "its reader `r` cannot be tiled with it: `c` is r16float, which a compute shader cannot store",
        ),
        (
            "reader forced",
            "pass e: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass r: image(e) {\n  schedule: naive\n  out c: rgba8unorm = vec4(sobel(e.c, screen_uv))\n}\noutput r.c\n",
            "its reader `r` is forced by `schedule: naive` at line 10",
        ),
        (
            "previous frame",
            "pass e: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass r: image(e) {\n  out c: rgba8unorm = vec4(sobel(e.c, screen_uv)) + previous(e.c)\n}\noutput r.c\n",
            "`r` reads `e.c` from the previous frame",
        ),
        (
            "two targets",
            "pass e: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n  out k: rgba16float = vec4(sobel(g.d, screen_uv) * 2.0)\n}\npass r: image(e) {\n  out c: rgba8unorm = vec4(sobel(e.c, screen_uv), sobel(e.k, screen_uv), 0.0, 1.0)\n}\noutput r.c\n",
            "it writes 2 live targets, and a recomputed tile holds one",
        ),
    ];
    for (name, body, reason) in cases {
        let text = format!("{G}{body}");
        let c = compile(&text, Schedule::Recompute);
        let lines = schedule_lines(&c);
        let line = lines
            .lines()
            .find(|l| l.starts_with("not recomputed pass `e`"))
            .unwrap_or_else(|| panic!("{name}: no line for `e`:\n{lines}"));
        assert!(line.contains(reason), "{name}: {line}");
    }
}

/// A pass that computes a target in its tiles is not itself computed in
/// its reader's: one level.
#[test]
fn recomputation_is_one_level_deep() {
    let text = "style \"chain\"\npass g: render(scene) {\n  out d: r32float = depth\n}\npass a: image(g) {\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass b: image(a) {\n  out c: rgba16float = vec4(sobel(a.c, screen_uv))\n}\npass r: image(b) {\n  out c: rgba8unorm = vec4(sobel(b.c, screen_uv))\n}\noutput r.c\n";
    let c = compile(text, Schedule::Recompute);
    let lines = schedule_lines(&c);
    assert!(lines.contains("recomputed pass `a`: in `b`'s tiles"), "{lines}");
    assert!(
        lines.contains(
            "not recomputed pass `b`: it computes `a.c` in its own tiles, and recomputation is one level deep"
        ),
        "{lines}"
    );
}
