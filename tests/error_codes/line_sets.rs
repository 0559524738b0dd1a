//! The diagnostics of line sets (decision 0056): an unknown edge type
//! (E0313), a crease without an angle in 0..180deg (E0314), a set that
//! selects nothing (E0315), two sets with one name (E0316), a set or its
//! values where there can be none (E0317), an unknown visibility (E0318)
//! and a dash that is not lengths in px (E0323, decision 0063). Every case
//! snapshots the rendered message.

use super::*;

/// A fill with a kept depth and a lines pass holding `sets`, whose output
/// is the drawing set's colour.
fn sets_style(sets: &str) -> String {
    style(&format!(
        "pass shade: render(scene) {{\n  out color: rgba8unorm = #808080\n  depth: keep\n}}\n\
         pass ink: lines(scene) {{\n{sets}\n  depth: test(shade, bias: 1px)\n  \
         out ink: rgba8unorm = line.color {{ blend: over }}\n  clear: #ffffff\n}}\n\
         output ink.ink\n"
    ))
}

#[test]
fn e0313_an_unknown_edge_type() {
    let text = sets_style("  set outline { edges: silhouette | bordr }");
    check("E0313", compile_errors(&text, &scratch("sets-unknown-edge")));
    let text = sets_style("  set outline { edges: silhouette(2) }");
    check_case(
        "E0313",
        "E0313_argument",
        compile_errors(&text, &scratch("sets-edge-argument")),
    );
}

#[test]
fn e0314_a_crease_without_a_good_angle() {
    let text = sets_style("  set detail { edges: crease(200deg) }");
    check("E0314", compile_errors(&text, &scratch("sets-crease-range")));
    let text = sets_style("  set detail { edges: crease(0.5) }");
    check_case(
        "E0314",
        "E0314_no_unit",
        compile_errors(&text, &scratch("sets-crease-unit")),
    );
    let text = sets_style("  set detail { edges: border | crease }");
    check_case(
        "E0314",
        "E0314_no_angle",
        compile_errors(&text, &scratch("sets-crease-none")),
    );
}

#[test]
fn e0315_a_set_that_selects_nothing() {
    let text = sets_style(
        "  set all { edges: silhouette | crease(30deg), priority: 1 }\n  set detail { edges: crease(45deg) }",
    );
    check("E0315", compile_errors(&text, &scratch("sets-shadowed")));
    let text = sets_style("  set outline { width: 2px }");
    check_case(
        "E0315",
        "E0315_no_edges",
        compile_errors(&text, &scratch("sets-no-edges")),
    );
}

#[test]
fn e0316_two_sets_with_one_name() {
    let text = sets_style("  set outline { edges: silhouette }\n  set outline { edges: border }");
    check("E0316", compile_errors(&text, &scratch("sets-duplicate")));
}

#[test]
fn e0317_a_set_where_there_can_be_none() {
    let text = style(
        "pass shade: render(scene) {\n  set outline { edges: silhouette }\n  out color: rgba8unorm = #808080\n}\noutput shade.color\n",
    );
    check("E0317", compile_errors(&text, &scratch("sets-in-render")));
    let text = sets_style("  silhouettes: true\n  set outline { edges: border }");
    check_case(
        "E0317",
        "E0317_beside_pass_edges",
        compile_errors(&text, &scratch("sets-beside-edges")),
    );
    let text = sets_style("  set outline { edges: border, colour: #ff0000 }");
    check_case(
        "E0317",
        "E0317_unknown_setting",
        compile_errors(&text, &scratch("sets-unknown-setting")),
    );
    let text = style(
        "pass ink: lines(scene) {\n  out ink: rgba8unorm = line.color { blend: over }\n  clear: #ffffff\n}\noutput ink.ink\n",
    );
    check_case(
        "E0317",
        "E0317_color_without_sets",
        compile_errors(&text, &scratch("sets-color-without")),
    );
}

#[test]
fn e0318_an_unknown_visibility() {
    let text = sets_style("  set hidden { edges: silhouette, visibility: hiden }");
    check("E0318", compile_errors(&text, &scratch("sets-hidden")));
    let text = sets_style("  set hidden { edges: silhouette, visibility: hidden(0) }");
    check_case(
        "E0318",
        "E0318_hidden_count",
        compile_errors(&text, &scratch("sets-hidden-count")),
    );
}

#[test]
fn e0323_a_dash_that_is_not_lengths_in_px() {
    let text = sets_style("  set hidden { edges: silhouette, visibility: hidden, dash: 6 }");
    check("E0323", compile_errors(&text, &scratch("sets-dash")));
    let text = sets_style("  set hidden { edges: silhouette, visibility: hidden, dash: dashes(6px, 0px) }");
    check_case(
        "E0323",
        "E0323_zero_gap",
        compile_errors(&text, &scratch("sets-dash-zero")),
    );
}
