//! `--schedule tiled` (issue 14): which image passes run as compute over
//! workgroup tiles, and why not, as the report says; the tiled module's
//! shape (its tiles, their load functions, the storage outputs); and that
//! `auto` tiles nothing but reports what `tiled` would tile. Every module
//! here passed naga's validation inside `compile_source`; that the images
//! equal the naive schedule's is `tests/gpu/schedule_equivalence.rs`.

use npr_compiler::schedule::Schedule;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::path::Path;

/// One G-buffer and five image passes, each a case of the tiling rule.
const STYLE: &str = r#"style "tiling cases"
pass g: render(scene) {
  out d: rgba16float = vec4(depth, 0.0, 0.0, 1.0)
  out n: rgba16float = vec4(normal.world, 1.0)
}
/// Tiled: Sobel reads `g.d` within 1 texel.
pass edges: image(g) {
  out e: rgba16float = vec4(sobel(g.d, screen_uv), 0.0, 0.0, 1.0)
}
/// Not tiled: compute cannot store rg16float (core WebGPU).
pass narrow: image(g) {
  out e: rg16float = vec2(sobel(g.n, screen_uv), 0.0)
}
/// Not tiled: a 30-texel apron (3σ) needs 92448 bytes of workgroup memory.
pass wide: image(g) {
  out e: rgba16float = gaussian(g.n, screen_uv, sigma: 10.0, axis: 0)
}
/// Not tiled: reads only at the pixel.
pass point: image(g) {
  out e: rgba16float = g.n * 0.5
}
/// Reads every target around the pixel (so none fuses into it), four
/// 1-texel tiles of 4, 2, 4 and 4 channels: 18144 bytes, not tiled either.
pass final: image(edges, narrow, wide, point) {
  out c: rgba8unorm = vec4(sobel(edges.e, screen_uv) + sobel(narrow.e, screen_uv), sobel(wide.e, screen_uv), sobel(point.e, screen_uv), 1.0)
}
output final.c
"#;

fn compile(schedule: Schedule) -> npr_compiler::Compiled {
    compile_text("tiling.npr", STYLE, schedule)
}

/// Style `text`, named `name`, compiled under `schedule`.
fn compile_text(name: &str, text: &str, schedule: Schedule) -> npr_compiler::Compiled {
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        schedule,
        ..Default::default()
    };
    npr_compiler::compile_source(name, text, Path::new("."), &mut sources, &opts).unwrap_or_else(|e| panic!("{e:?}"))
}

/// The report's tiling lines, one per image pass.
fn tiling_lines(c: &npr_compiler::Compiled) -> String {
    c.report
        .entries
        .iter()
        .filter(|e| e.action == "tiled" || e.action == "not tiled")
        .map(|e| format!("{} {}: {}", e.action, e.what, e.why))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn tiled_schedule_says_which_passes_tile_and_why_not() {
    let c = compile(Schedule::Tiled);
    let lines = tiling_lines(&c);
    assert!(lines.contains("tiled pass `edges`"), "{lines}");
    assert!(lines.contains("not tiled pass `narrow`: `e` is rg16float"), "{lines}");
    assert!(
        lines.contains("not tiled pass `wide`: its tiles need 92448 bytes"),
        "{lines}"
    );
    assert!(
        lines.contains("not tiled pass `point`: no operator reads a target around the pixel"),
        "{lines}"
    );
    assert!(
        lines.contains("not tiled pass `final`: its tiles need 18176 bytes"),
        "{lines}"
    );
    insta::assert_snapshot!("tiled_report", lines);
    let kinds: Vec<(String, bool)> = c
        .program()
        .manifest
        .passes
        .iter()
        .map(|p| {
            (
                p.name.clone(),
                matches!(p.kind, npr_abi::manifest::PassKindManifest::TiledImage { .. }),
            )
        })
        .collect();
    assert!(kinds.contains(&("edges".to_string(), true)), "{kinds:?}");
    assert_eq!(kinds.iter().filter(|(_, t)| *t).count(), 1, "{kinds:?}");
}

#[test]
fn a_tiled_module_loads_its_tile_and_stores_rounded_outputs() {
    let c = compile(Schedule::Tiled);
    let wgsl = c.shader("edges.wgsl").expect("edges pass");
    // The tile (16 + 2·1)² texels, its load function, and Sobel's copy on
    // the binding, whose textureLoad goes through the tile.
    assert!(
        wgsl.contains("var<workgroup> npr_tile_t_g_d: array<vec4<f32>, 324>;"),
        "{wgsl}"
    );
    assert!(wgsl.contains("fn npr_sobel__t_g_d(uv: vec2<f32>)"), "{wgsl}");
    assert!(wgsl.contains("npr_tile_load_t_g_d(q, 0)"), "{wgsl}");
    assert!(
        !wgsl.contains("fn npr_sobel(src: texture_2d<f32>"),
        "the generic copy is dropped:\n{wgsl}"
    );
    // One pixel per invocation, stored after rgba16float's rounding.
    assert!(wgsl.contains("@compute @workgroup_size(16, 16, 1)"), "{wgsl}");
    assert!(
        wgsl.contains("textureStore(npr_out_e, px, npr_stored_rgba16float(o.o_e));"),
        "{wgsl}"
    );
    assert!(wgsl.contains("override npr_f16_stores_truncate: bool;"), "{wgsl}");
    let manifest = &c.program().manifest;
    let edges = manifest.passes.iter().find(|p| p.name == "edges").expect("edges");
    assert!(edges.device_half_rounding, "its f16 stores use the measured rounding");
    let cs = &wgsl[wgsl.find("@compute").expect("entry")..];
    insta::assert_snapshot!("tiled_entry", cs);
}

/// A tile keeps the target's channels alone: Sobel on an `r32float` depth
/// target keeps one `f32` per texel (1296 bytes, a quarter of a `vec4`
/// tile) and gives its reads back as `textureLoad` would, `(d, 0, 0, 1)`.
#[test]
fn a_tile_keeps_only_its_targets_channels() {
    let style = r#"style "depth tile"
pass g: render(scene) {
  out d: r32float = depth
}
pass edges: image(g) {
  out e: rgba16float = vec4(sobel(g.d, screen_uv))
}
output edges.e
"#;
    let c = compile_text("depth.npr", style, Schedule::Tiled);
    let lines = tiling_lines(&c);
    assert!(lines.contains("(1296 bytes)"), "{lines}");
    let wgsl = c.shader("edges.wgsl").expect("edges pass");
    assert!(
        wgsl.contains("var<workgroup> npr_tile_t_g_d: array<f32, 324>;"),
        "{wgsl}"
    );
    assert!(
        wgsl.contains("npr_tile_t_g_d[k] = textureLoad(t_g_d, q, 0).x;"),
        "{wgsl}"
    );
    assert!(
        wgsl.contains("return vec4<f32>(npr_tile_t_g_d[k.y * 18 + k.x], 0.0, 0.0, 1.0);"),
        "{wgsl}"
    );
}

#[test]
fn auto_tiles_nothing_and_reports_what_tiled_would() {
    let c = compile(Schedule::Auto);
    let lines = tiling_lines(&c);
    assert!(!lines.lines().any(|l| l.starts_with("tiled ")), "{lines}");
    assert!(
        lines.contains("not tiled pass `edges`: `--schedule tiled` would keep 5184 bytes"),
        "{lines}"
    );
    assert!(c
        .program()
        .manifest
        .passes
        .iter()
        .all(|p| !matches!(p.kind, npr_abi::manifest::PassKindManifest::TiledImage { .. })));
}

/// A texture read as a value is sampled with `textureSample`, which a
/// compute shader has no derivatives for: the pass is not tiled (it was,
/// and naga refused the module: E9001), though the typechecker leaves the
/// read typed as the texture, as an operator's texture argument is.
#[test]
fn a_texture_read_as_a_value_is_not_tiled() {
    let style = r#"style "grain"
texture grain = noise(size: 16, octaves: 1, seed: 1, kind: value)
pass g: render(scene) {
  out d: r32float = depth
}
pass grainy: image(g) {
  out c: rgba16float = vec4(sobel(g.d, screen_uv)) * grain
}
output grainy.c
"#;
    let c = compile_text("grain.npr", style, Schedule::Tiled);
    let lines = tiling_lines(&c);
    assert_eq!(
        lines,
        "not tiled pass `grainy`: it samples a texture as a value, which takes screen derivatives"
    );
}
