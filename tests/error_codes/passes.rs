//! Error codes of passes (E03xx, W0301, W0302): cycles, formats, outputs, pass
//! kinds, compute state, blending and depth tests, passes over pixels,
//! art-map filters and rip-maps, and the `schedule:` setting. A filter's
//! arguments are in `param_settings.rs`.

use super::*;

#[test]
fn e0301_pass_cycle() {
    let text = style(
        "pass a: image(b) {\n  out x: r8unorm = b.y\n}\npass b: image(a) {\n  out y: r8unorm = a.x\n}\noutput b.y\n",
    );
    check("E0301", compile_errors(&text, &scratch("e0301")));
}

#[test]
fn e0301_a_pass_reading_its_own_target_is_told_about_previous() {
    let text = style("pass acc: image() {\n  out c: r8unorm = acc.c * 0.9\n}\noutput acc.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("e0301-self"));
    assert!(rendered.contains("previous(acc.<target>)"), "{rendered}");
    check_case("E0301", "E0301_self_read", (diags, rendered));
}

#[test]
fn previous_takes_one_pass_target() {
    let text = style("pass acc: image() {\n  out c: r8unorm = previous(0.5)\n}\noutput acc.c\n");
    check_case(
        "E0103",
        "E0103_previous_not_a_target",
        compile_errors(&text, &scratch("prev-arg")),
    );
}

#[test]
fn previous_of_a_target_that_does_not_exist() {
    let text = style("pass acc: image() {\n  out c: r8unorm = previous(acc.d)\n}\noutput acc.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("prev-missing"));
    let code = diags.first().expect("a diagnostic").code;
    check_case(code, "previous_unknown_target", (diags, rendered));
    let text = style("pass acc: image() {\n  out c: r8unorm = previous(nosuch.c)\n}\noutput acc.c\n");
    check_case(
        "E0101",
        "previous_unknown_pass",
        compile_errors(&text, &scratch("prev-missing-pass")),
    );
}

#[test]
fn e0302_format_mismatch() {
    let text =
        style("pass p: render(scene) {\n  out color: rgba8unorm = lambert(normal, light.dir)\n}\noutput p.color\n");
    check("E0302", compile_errors(&text, &scratch("e0302")));
}

#[test]
fn e0303_no_output() {
    let text = style("pass p: render(scene) {\n  out color: rgba8unorm = vec4(1.0)\n}\n");
    check("E0303", compile_errors(&text, &scratch("e0303")));
    // A style of nothing but its header: E0303 at the header, not an
    // internal error (found by tests/general/fuzz_compiler.rs).
    check_case(
        "E0303",
        "header_only",
        compile_errors("style \"S\"\n", &scratch("e0303-header-only")),
    );
}

#[test]
fn e0304_bad_pass_input() {
    let text = style("pass g: render(scene) {\n  out n: rgba16float = vec4(normal, 1.0)\n}\npass p: image() {\n  out color: rgba8unorm = g.n\n}\noutput p.color\n");
    check("E0304", compile_errors(&text, &scratch("e0304")));
}

/// A vertex pass summing a bool, a state read before its declaration, a
/// reduction in a render pass, and a compute pass nobody reads.
const SUMS: &str = "pass sums: compute(vertices) {\n  reduce n: float = sum(1.0)\n}\n";

#[test]
fn e0205_a_reduction_over_a_type_it_cannot_sum() {
    let text = style(
        "pass sums: compute(vertices) {\n  reduce lit: float = sum(normal.y > 0.0)\n}\npass shade: render(scene) {\n  out c: r32float = sums.lit\n}\noutput shade.c\n",
    );
    check("E0205", compile_errors(&text, &scratch("e0205")));
}

#[test]
fn e0205_a_per_object_value_of_a_type_it_cannot_have() {
    let text = style(
        "pass sums: compute(vertices) {\n  reduce n: int = sum(1)\n}\npass shade: render(scene) {\n  out c: r32float = sums.n\n}\noutput shade.c\n",
    );
    check_case("E0205", "E0205_type", compile_errors(&text, &scratch("e0205t")));
}

#[test]
fn e0305_state_read_before_it_is_declared() {
    let text = style(&format!(
        "{SUMS}pass follow: compute(objects) {{\n  let twice = 2.0 * origin\n  state origin: float = sums.n\n  origin = twice\n}}\npass shade: render(scene) {{\n  out c: r32float = follow.origin\n}}\noutput shade.c\n"
    ));
    check("E0305", compile_errors(&text, &scratch("e0305")));
}

#[test]
fn e0305_a_state_that_is_never_updated() {
    let text = style(
        "pass follow: compute(objects) {\n  state origin: vec2 = vec2(0.0)\n}\npass shade: render(scene) {\n  out c: rg32float = follow.origin\n}\noutput shade.c\n",
    );
    check_case("E0305", "E0305_not_updated", compile_errors(&text, &scratch("e0305u")));
}

#[test]
fn e0306_a_statement_the_pass_kind_does_not_have() {
    let text = style(
        "pass shade: render(scene) {\n  reduce n: float = sum(1.0)\n  out c: r32float = 1.0\n}\noutput shade.c\n",
    );
    check("E0306", compile_errors(&text, &scratch("e0306")));
}

#[test]
fn w0301_a_compute_pass_nobody_reads() {
    let text = style(&format!(
        "{SUMS}pass shade: render(scene) {{\n  out c: r32float = 1.0\n}}\noutput shade.c\n"
    ));
    check("W0301", compile_warnings(&text));
}

#[test]
fn w0302_patch_weight_without_a_depth_test_against_an_earlier_pass() {
    let shade = "pass shade: render(scene) {\n  let s = pow(patch.weight, 0.5)\n  out c: rgba8unorm = vec4(0.2, 0.2, 0.2, s) { blend: over }\n  clear: #ffffff\n}\noutput shade.c\n";
    let (diags, rendered) = compile_warnings(&style(shade));
    // Pointing at the `patch.weight` read: line 3, column 15 of the case.
    assert!(rendered.contains("case.npr:3:15"), "{rendered}");
    check("W0302", (diags, rendered));
    // `depth: keep` is the pass's own buffer too.
    let kept = shade.replace("{\n  let s", "{\n  depth: keep\n  let s");
    let (diags, rendered) = compile_warnings(&style(&kept));
    check_case("W0302", "W0302_depth_keep", (diags, rendered));
    // A depth test against an earlier pass's kept depth: no warning.
    let ids = "pass ids: render(scene) {\n  out id: r32float = object.id\n  depth: keep\n}\n";
    let tested = shade.replace("{\n  let s", "{\n  depth: test(ids)\n  let s");
    let (diags, rendered) = compile_warnings(&style(&format!("{ids}{tested}")));
    assert!(diags.is_empty(), "{rendered}");
}

#[test]
fn e0307_blend_on_a_format_that_cannot_be_blended() {
    let text = style("pass p: image() {\n  out sum: rgba32float = vec4(0.25) { blend: add }\n}\noutput p.sum\n");
    check("E0307", compile_errors(&text, &scratch("e0307")));
}

#[test]
fn unknown_blend_mode_suggests_one() {
    let text = style("pass p: render(scene) {\n  out c: rgba8unorm = #ff000080 { blend: ovr }\n}\noutput p.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("blend-unknown"));
    assert!(rendered.contains("did you mean `over`?"), "{rendered}");
    check_case("E0103", "E0103_unknown_blend_mode", (diags, rendered));
}

/// A scene pass and a line pass over it, `depth` setting of each given.
fn depth_passes(gbuffer_depth: &str, lines_depth: &str) -> String {
    style(&format!(
        "pass gbuffer: render(scene) {{\n  out c: rgba8unorm = #808080\n{gbuffer_depth}}}\n\
         pass lines: render(scene) {{\n  out ink: rgba8unorm = #000000 {{ blend: over }}\n  depth: {lines_depth}\n}}\n\
         pass final: image(gbuffer, lines) {{\n  out color: rgba8unorm = gbuffer.c * lines.ink\n}}\noutput final.color\n"
    ))
}

#[test]
fn e0308_depth_test_against_a_pass_that_keeps_no_depth() {
    let text = depth_passes("", "test(gbuffer, bias: 1px)");
    let (diags, rendered) = compile_errors(&text, &scratch("e0308"));
    assert!(rendered.contains("add `depth: keep` to pass `gbuffer`"), "{rendered}");
    check("E0308", (diags, rendered));
}

#[test]
fn depth_test_against_an_unknown_pass_suggests_one() {
    let text = depth_passes("  depth: keep\n", "test(gbufer)");
    let (diags, rendered) = compile_errors(&text, &scratch("depth-unknown"));
    assert!(rendered.contains("did you mean `gbuffer`?"), "{rendered}");
    check_case("E0101", "E0101_depth_test_unknown_pass", (diags, rendered));
}

#[test]
fn a_cycle_through_a_depth_test_suggests_previous_on_the_target_read() {
    let text = style("pass a: render(scene) {\n  out c: rgba8unorm = b.ink\n  depth: keep\n}\npass b: render(scene) {\n  out ink: rgba8unorm = #000000\n  depth: test(a)\n}\noutput b.ink\n");
    let (diags, rendered) = compile_errors(&text, &scratch("depth-cycle"));
    assert!(rendered.contains("`previous(b.<target>)` in `a`"), "{rendered}");
    check_case("E0301", "E0301_depth_cycle", (diags, rendered));
}

#[test]
fn depth_test_across_pass_sizes() {
    let text = depth_passes("  depth: keep\n", "test(gbuffer)")
        .replace("pass lines: render(scene) {", "pass lines: render(scene) scale 1/2 {");
    check_case(
        "E0304",
        "E0304_depth_test_other_scale",
        compile_errors(&text, &scratch("depth-scale")),
    );
}

/// An ID pass, a pass over its pixels with `kind_args`, and a render pass reading it.
fn pixel_passes(id_format: &str, kind_args: &str) -> String {
    style(&format!(
        "pass ids: render(scene) {{\n  out id: {id_format} = object.id\n}}\n\
         pass cover: compute({kind_args}) {{\n  reduce area: float = sum(1.0)\n}}\n\
         pass shade: render(scene) {{\n  out c: rgba8unorm = vec4(vec3(cover.area / 1000.0), 1.0)\n}}\noutput shade.c\n"
    ))
}

#[test]
fn e0309_pixels_of_a_target_that_is_not_an_id_target() {
    let text = pixel_passes("r16float", "pixels, ids.id");
    let (diags, rendered) = compile_errors(&text, &scratch("e0309"));
    assert!(rendered.contains("out id: r32float = object.id"), "{rendered}");
    check("E0309", (diags, rendered));
}

/// A filter style with `passes` after its header and level input.
pub(crate) const FILTER_HEAD: &str = "style \"Filter\"\ntexture level = filter_input()\n";

#[test]
fn e0310_a_filter_with_a_render_pass() {
    let text = format!(
        "{FILTER_HEAD}pass lit: render(scene) {{\n  out c: rgba8unorm = vec4(level.rgb, 1.0)\n}}\noutput lit.c\n"
    );
    check("E0310", compile_errors(&text, &scratch("e0310")));
}

#[test]
fn e0310_an_art_map_whose_filter_reads_no_level() {
    let dir = scratch("e0310_no_level");
    std::fs::write(
        dir.join("not_a_filter.npr"),
        "style \"Not a filter\"\npass p: image() {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n",
    )
    .unwrap();
    image::RgbaImage::new(4, 4).save(dir.join("src.png")).unwrap();
    let text = style(
        "texture t = artmap(image(\"src.png\"), filter: \"not_a_filter.npr\")\n\
         pass p: render(scene) {\n  out c: rgba8unorm = sample_biased(t, uv)\n}\noutput p.c\n",
    );
    let (d, r) = compile_errors(&text, &dir);
    check_case(
        "E0310",
        "E0310_no_level",
        (d, r.replace(&dir.display().to_string(), "<dir>")),
    );
}

#[test]
fn e0310_an_art_map_inside_a_filter() {
    let dir = scratch("e0310_nested");
    image::RgbaImage::new(4, 4).save(dir.join("src.png")).unwrap();
    let text = format!(
        "{FILTER_HEAD}texture inner = artmap(image(\"src.png\"), filter: \"case.npr\")\n\
         pass p: image() {{\n  out c: rgba16float = level\n}}\noutput p.c\n"
    );
    // The filter it names is itself (found on disk, loaded as a filter).
    std::fs::write(dir.join("case.npr"), &text).unwrap();
    check_case("E0310", "E0310_nested", compile_errors(&text, &dir));
}

/// A G-buffer pass for the `schedule:` cases: depth and normals.
const SCHEDULE_GBUFFER: &str =
    "pass g: render(scene) {\n  out d: r32float = depth\n  out n: rgba16float = vec4(normal.world, 1.0)\n}\n";

/// Each (name, pass text after the G-buffer, reason) case fails with
/// `code`, its help giving the reason; its rendered message is snapshot
/// `<code>_<name>`.
fn check_reasons(code: &str, cases: &[(&str, &str, &str)]) {
    for (name, body, reason) in cases {
        let text = style(&format!("{SCHEDULE_GBUFFER}{body}"));
        let (d, r) = compile_errors(&text, &scratch(&format!("{}_{name}", code.to_lowercase())));
        assert!(r.contains(reason), "{name}: {r}");
        check_case(code, &format!("{code}_{name}"), (d, r));
    }
}

/// `text` fails with `code` under every `--schedule`: a forced `schedule:`
/// wins over the run's schedule, and its refusal with it.
fn same_code_under_every_schedule(code: &str, text: &str, dir: &Path) {
    for schedule in npr_compiler::schedule::Schedule::ALL {
        let mut sources = SourceMap::new();
        let opts = CompileOptions {
            schedule,
            ..CompileOptions::default()
        };
        match npr_compiler::compile_source("case.npr", text, dir, &mut sources, &opts) {
            Err(CompileError::User(d)) => assert_eq!(d[0].code, code, "--schedule {}", schedule.name()),
            _ => panic!("--schedule {}: not {code}", schedule.name()),
        }
    }
}

/// `schedule: tiled` on a pass the tiler refuses is an error at the
/// setting whose help gives the tiler's reason, under every `--schedule`
/// (the default `auto` here; `naive` below), never a fragment pass instead.
#[test]
fn e0311_schedule_tiled_on_a_pass_compute_cannot_store() {
    let text = style(&format!(
        "{SCHEDULE_GBUFFER}pass edges: image(g) {{\n  schedule: tiled\n  out e: r16float = sobel(g.d, screen_uv)\n}}\noutput edges.e\n"
    ));
    let (d, r) = compile_errors(&text, &scratch("e0311"));
    assert!(
        r.contains("`e` is r16float, which a compute shader cannot store"),
        "{r}"
    );
    check("E0311", (d, r));
    same_code_under_every_schedule("E0311", &text, &scratch("e0311"));
}

#[test]
fn e0311_the_hint_gives_each_reason_of_the_tiler() {
    let cases = [
        (
            "blends",
            "pass over: image(g) {\n  schedule: tiled\n  out c: rgba8unorm = vec4(sobel(g.d, screen_uv)) { blend: over }\n}\noutput over.c\n",
            "blends into its target",
        ),
        (
            "derivatives",
            "texture grain = noise(size: 16, octaves: 1, seed: 1, kind: value)\npass grainy: image(g) {\n  schedule: tiled\n  out c: rgba16float = vec4(sobel(g.d, screen_uv)) * grain\n}\noutput grainy.c\n",
            "samples a texture as a value, which takes screen derivatives",
        ),
        (
            "pointwise",
            "pass point: image(g) {\n  schedule: tiled\n  out c: rgba16float = g.n * 0.5\n}\noutput point.c\n",
            "no operator reads a target around the pixel",
        ),
        (
            "memory",
            "pass wide: image(g) {\n  schedule: tiled\n  out c: rgba16float = gaussian(g.n, screen_uv, sigma: 10.0, axis: 0)\n}\noutput wide.c\n",
            "its tiles need 92448 bytes of workgroup memory",
        ),
    ];
    check_reasons("E0311", &cases);
}

/// `schedule: recompute` on a pass its reader cannot compute in its tiles
/// is an error at the setting, under every `--schedule`, whose help gives
/// the reason; never a stored target instead.
#[test]
fn e0312_schedule_recompute_on_the_output() {
    let text = style(&format!(
        "{SCHEDULE_GBUFFER}pass edges: image(g) {{\n  schedule: recompute\n  out e: rgba16float = vec4(sobel(g.d, screen_uv))\n}}\noutput edges.e\n"
    ));
    let (d, r) = compile_errors(&text, &scratch("e0312"));
    assert!(r.contains("`edges.e` is the style's output"), "{r}");
    check("E0312", (d, r));
    same_code_under_every_schedule("E0312", &text, &scratch("e0312"));
}

#[test]
fn e0312_the_hint_gives_the_reason() {
    let cases = [
        (
            "two_readers",
            "pass e: image(g) {\n  schedule: recompute\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass a: image(e) {\n  out c: rgba16float = vec4(sobel(e.c, screen_uv))\n}\npass b: image(e, a) {\n  out c: rgba8unorm = vec4(sobel(e.c, screen_uv) + sobel(a.c, screen_uv))\n}\noutput b.c\n",
            "read by `a` and `b`: each would compute it in its own tiles",
        ),
        (
            "reader_untileable",
            "pass e: image(g) {\n  schedule: recompute\n  out c: rgba16float = vec4(sobel(g.d, screen_uv))\n}\npass r: image(e) {\n  out c: r16float = sobel(e.c, screen_uv)\n}\noutput r.c\n",
            "its reader `r` cannot be tiled with it: `c` is r16float, which a compute shader cannot store",
        ),
        (
            "derivatives",
            "texture grain = noise(size: 16, octaves: 1, seed: 1, kind: value)\npass e: image(g) {\n  schedule: recompute\n  out c: rgba16float = vec4(sobel(g.d, screen_uv)) * grain\n}\npass r: image(e) {\n  out c: rgba8unorm = vec4(sobel(e.c, screen_uv))\n}\noutput r.c\n",
            "it samples a texture as a value, which takes screen derivatives",
        ),
    ];
    check_reasons("E0312", &cases);
}

/// The `schedule:` setting itself: a schedule's name, once, in an image pass.
#[test]
fn e0103_bad_schedule_settings() {
    let unknown = style(&format!(
        "{SCHEDULE_GBUFFER}pass p: image(g) {{\n  schedule: tiles\n  out c: rgba16float = g.n\n}}\noutput p.c\n"
    ));
    check_case(
        "E0103",
        "E0103_unknown_schedule",
        compile_errors(&unknown, &scratch("schedule_unknown")),
    );
    let render = style("pass g: render(scene) {\n  schedule: naive\n  out c: rgba8unorm = vec4(1.0)\n}\noutput g.c\n");
    check_case(
        "E0103",
        "E0103_schedule_on_a_render_pass",
        compile_errors(&render, &scratch("schedule_render")),
    );
    let twice = style(&format!(
        "{SCHEDULE_GBUFFER}pass p: image(g) {{\n  schedule: naive\n  schedule: tiled\n  out c: rgba16float = g.n\n}}\noutput p.c\n"
    ));
    check_case(
        "E0103",
        "E0103_schedule_twice",
        compile_errors(&twice, &scratch("schedule_twice")),
    );
}

/// A rip-map is read only by `sample_ripmap`, and `sample_ripmap` reads
/// only a rip-map (`compiler/src/front/texture_uses.rs`).
#[test]
fn e0201_rip_maps_and_sample_ripmap_go_together() {
    let dir = scratch("e0201_ripmap");
    image::RgbaImage::new(4, 4).save(dir.join("src.png")).unwrap();
    std::fs::write(
        dir.join("f.npr"),
        format!("{FILTER_HEAD}pass p: image() {{\n  out c: rgba16float = level\n}}\noutput p.c\n"),
    )
    .unwrap();
    let ripmap_read_by_sample = style(
        "texture t = ripmap(image(\"src.png\"), filter: \"f.npr\")\n\
         pass p: render(scene) {\n  out c: rgba8unorm = sample(t, uv)\n}\noutput p.c\n",
    );
    check_case(
        "E0201",
        "E0201_ripmap_read_by_sample",
        compile_errors(&ripmap_read_by_sample, &dir),
    );
    let sample_ripmap_of_an_image = style(
        "texture t = image(\"src.png\")\n\
         pass p: render(scene) {\n  out c: rgba8unorm = sample_ripmap(t, uv)\n}\noutput p.c\n",
    );
    check_case(
        "E0201",
        "E0201_sample_ripmap_of_an_image",
        compile_errors(&sample_ripmap_of_an_image, &dir),
    );
}

#[test]
fn a_pass_over_pixels_without_its_id_target() {
    let text = pixel_passes("r32float", "pixels");
    let (diags, rendered) = compile_errors(&text, &scratch("pixels-no-target"));
    assert!(rendered.contains("compute(pixels, ids.id)"), "{rendered}");
    check_case("E0304", "E0304_pixels_without_id_target", (diags, rendered));
}

#[test]
fn a_target_where_a_pass_kind_takes_a_name() {
    let text = pixel_passes("r32float", "vertices, ids.id");
    let (diags, rendered) = compile_errors(&text, &scratch("kind-arg-field"));
    assert!(
        rendered.contains("expected a tag, found the target `ids.id`"),
        "{rendered}"
    );
    check_case("E0304", "E0304_target_as_kind_argument", (diags, rendered));
}

#[test]
fn a_pass_over_pixels_of_an_unknown_pass_suggests_one() {
    let text = pixel_passes("r32float", "pixels, idz.id");
    let (diags, rendered) = compile_errors(&text, &scratch("pixels-unknown"));
    assert!(rendered.contains("did you mean `ids`?"), "{rendered}");
    check_case("E0101", "E0101_pixels_of_unknown_pass", (diags, rendered));
}

#[test]
fn a_fragment_builtin_in_a_pass_over_vertices() {
    // `screen_uv` is a fragment's; a vertex has none (this once reached naga as E9001).
    let text = style(
        "pass sums: compute(vertices) {\n  reduce s: vec2 = sum(screen_uv)\n}\n\
         pass shade: render(scene) {\n  out c: rgba8unorm = vec4(sums.s, 0.0, 1.0)\n}\noutput shade.c\n",
    );
    let (diags, rendered) = compile_errors(&text, &scratch("vertices-screen-uv"));
    assert!(rendered.contains("`screen_uv` is not available"), "{rendered}");
    check_case("E0304", "E0304_screen_uv_over_vertices", (diags, rendered));
}

#[test]
fn geometry_in_a_pass_over_pixels() {
    let text = pixel_passes("r32float", "pixels, ids.id").replace("sum(1.0)", "sum(normal.x)");
    let (diags, rendered) = compile_errors(&text, &scratch("pixels-normal"));
    assert!(rendered.contains("no geometry in a pass over pixels"), "{rendered}");
    check_case("E0304", "E0304_normal_over_pixels", (diags, rendered));
}

#[test]
fn geometry_in_an_image_pass_names_the_input_that_would_give_it() {
    // No `input(normal, view)`: `normal.view` stays a render pass's.
    let text = style(
        "texture z = input(depth)\npass p: image() {\n  out c: rgba8unorm = vec4(normal.view, 1.0)\n}\noutput p.c\n",
    );
    let (diags, rendered) = compile_errors(&text, &scratch("image-normal-no-input"));
    assert!(rendered.contains("`texture n = input(normal, view)`"), "{rendered}");
    check_case("E0304", "E0304_normal_in_image_pass_without_input", (diags, rendered));
}

#[test]
fn position_in_an_image_pass_over_two_depth_inputs_is_ambiguous() {
    let text = style(
        "texture a = input(depth)\ntexture b = input(depth)\n\
         pass p: image() {\n  out c: rgba8unorm = vec4(position.view / 1m, 1.0)\n}\noutput p.c\n",
    );
    let (diags, rendered) = compile_errors(&text, &scratch("image-two-depths"));
    assert!(rendered.contains("any of the inputs `a`, `b`"), "{rendered}");
    check_case("E0304", "E0304_builtin_over_two_inputs", (diags, rendered));
}

/// A style over inputs whose pass `ink` tests its depth with `depth`.
fn input_depth_passes(ink_header: &str, depth: &str) -> String {
    style(&format!(
        "texture color_in = input(color, display)\ntexture depth_in = input(depth)\n\
         {ink_header} {{\n  out c: rgba8unorm = #000000\n  depth: {depth}\n  clear: #ffffff\n}}\n\
         pass final: image(ink) {{\n  out color: rgba8unorm = sample(color_in, screen_uv) * ink.c\n}}\noutput final.color\n"
    ))
}

#[test]
fn e0319_depth_test_against_a_colour_input() {
    let text = input_depth_passes("pass ink: render(scene)", "test(color_in, bias: 1px)");
    let (diags, rendered) = compile_errors(&text, &scratch("e0319"));
    assert!(
        rendered.contains("`depth_in`"),
        "the help names the depth input: {rendered}"
    );
    check("E0319", (diags, rendered));
}

#[test]
fn e0320_depth_test_against_the_hosts_depth_at_another_scale() {
    let text = input_depth_passes("pass ink: render(scene) scale 1/2", "test(depth_in)");
    check("E0320", compile_errors(&text, &scratch("e0320")));
}

#[test]
fn a_depth_test_against_the_hosts_depth_compiles() {
    let text = input_depth_passes("pass ink: render(scene)", "test(depth_in, bias: 1px)");
    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_source(
        "case.npr",
        &text,
        &scratch("input-depth-ok"),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"));
    let manifest = &compiled.program().manifest;
    let ink = manifest.passes.iter().find(|p| p.name == "ink").expect("pass ink");
    let input = manifest
        .textures
        .iter()
        .position(|t| t.name == "depth_in")
        .expect("depth_in");
    assert!(
        matches!(
            ink.kind,
            npr_abi::manifest::PassKindManifest::Render {
                depth: npr_abi::manifest::DepthMode::TestInput { input: i, .. },
                ..
            } if i == input
        ),
        "{:?}",
        ink.kind
    );
}

#[test]
fn e0321_uv_in_an_image_pass_over_a_hosts_frame() {
    let text = style(
        "texture c = input(color, linear)\ntexture z = input(depth)\n\
         pass p: image() {\n  out c: rgba8unorm = vec4(uv, 0.0, 1.0)\n}\noutput p.c\n",
    );
    let (diags, rendered) = compile_errors(&text, &scratch("e0321"));
    assert!(rendered.contains("screen_uv"), "the help offers screen_uv: {rendered}");
    check("E0321", (diags, rendered));
}
