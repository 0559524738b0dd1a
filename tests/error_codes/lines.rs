//! The diagnostics of `lines` passes (Klein et al. 2000 §5): their settings'
//! units, ranges and affine form, the crease threshold, depth modes, and
//! the builtins a lines fragment has or lacks. Every case snapshots the
//! rendered message.

use super::*;

/// A fill with a kept depth and a lines pass with `settings`, whose output
/// is `value`.
fn lines_style(settings: &str, value: &str) -> String {
    style(&format!(
        "param w: px = 2px\n\
         pass shade: render(scene) {{\n  out color: rgba8unorm = #808080\n  depth: keep\n}}\n\
         pass ink: lines(scene) {{\n  {settings}\n  out ink: rgba8unorm = {value} {{ blend: over }}\n  clear: #ffffff\n}}\n\
         output ink.ink\n"
    ))
}

const BLACK: &str = "vec4(0.0, 0.0, 0.0, 1.0)";

#[test]
fn a_width_without_px() {
    let text = lines_style("width: 2", BLACK);
    check_case(
        "E0202",
        "lines_width_without_px",
        compile_errors(&text, &scratch("lines-width-unit")),
    );
}

#[test]
fn a_setting_that_is_not_affine() {
    let text = lines_style("amplitude: w * (time * 1Hz)", BLACK);
    check_case(
        "E0103",
        "lines_not_affine",
        compile_errors(&text, &scratch("lines-affine")),
    );
    let text = lines_style("width: max(w, 1px)", BLACK);
    check_case(
        "E0103",
        "lines_not_affine_call",
        compile_errors(&text, &scratch("lines-affine-call")),
    );
}

#[test]
fn settings_out_of_range() {
    let text = lines_style("taper: 0.8", BLACK);
    check_case(
        "E0203",
        "lines_taper_out_of_range",
        compile_errors(&text, &scratch("lines-taper")),
    );
    let text = lines_style("creases: 200deg", BLACK);
    check_case(
        "E0203",
        "lines_crease_out_of_range",
        compile_errors(&text, &scratch("lines-crease")),
    );
}

#[test]
fn a_crease_threshold_without_deg() {
    let text = lines_style("creases: 40", BLACK);
    check_case(
        "E0202",
        "lines_crease_without_deg",
        compile_errors(&text, &scratch("lines-crease-unit")),
    );
    let text = lines_style("creases: of", BLACK);
    check_case(
        "E0103",
        "lines_crease_misspelt_off",
        compile_errors(&text, &scratch("lines-crease-off")),
    );
}

#[test]
fn a_setting_written_twice() {
    let text = lines_style("width: 2px\n  width: 3px", BLACK);
    check_case(
        "E0003",
        "lines_setting_twice",
        compile_errors(&text, &scratch("lines-twice")),
    );
}

#[test]
fn a_lines_pass_cannot_keep_a_depth() {
    let text = lines_style("depth: keep", BLACK);
    check_case(
        "E0103",
        "lines_depth_keep",
        compile_errors(&text, &scratch("lines-keep")),
    );
}

#[test]
fn a_lines_pass_tests_a_kept_depth() {
    let text = lines_style("depth: test(ink)", BLACK).replace("  depth: keep\n", "");
    let (diags, rendered) = compile_errors(&text, &scratch("lines-test-own"));
    check_case(diags[0].code, "lines_depth_test_itself", (diags, rendered));
    let text = lines_style("depth: test(shade)", BLACK).replace("  depth: keep\n", "");
    check_case(
        "E0308",
        "lines_depth_not_kept",
        compile_errors(&text, &scratch("lines-not-kept")),
    );
}

#[test]
fn surface_values_in_a_lines_fragment() {
    let text = lines_style("width: 2px", "vec4(normal, 1.0)");
    check_case(
        "E0304",
        "lines_reads_normal",
        compile_errors(&text, &scratch("lines-normal")),
    );
}

#[test]
fn line_values_outside_a_lines_pass() {
    let text = style("pass p: image() {\n  out c: r8unorm = line.s\n}\noutput p.c\n");
    check_case(
        "E0304",
        "line_s_in_an_image_pass",
        compile_errors(&text, &scratch("line-s-image")),
    );
}

#[test]
fn a_lines_setting_on_a_render_pass() {
    let text = style("pass p: render(scene) {\n  out c: rgba8unorm = #000000\n  width: 2px\n}\noutput p.c\n");
    check_case(
        "E0103",
        "lines_setting_on_render",
        compile_errors(&text, &scratch("lines-on-render")),
    );
}

#[test]
fn a_misspelt_lines_setting() {
    let text = lines_style("wavelenght: 20px", BLACK);
    check_case(
        "E0103",
        "lines_setting_misspelt",
        compile_errors(&text, &scratch("lines-misspelt")),
    );
}
