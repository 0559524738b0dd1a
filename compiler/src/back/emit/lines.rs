//! `lines` passes (Klein et al. 2000, §5): the vertex shader that passes the
//! runner's strip vertices through (`npr_abi::lines::LineVertex`, already in NDC
//! with the view-space bias applied on the CPU) and writes the varyings a
//! lines fragment has: `screen_uv`, `line.s` and `line.across`. A bias in
//! window depth (`bias: 0.001`) is applied here, as render passes do.
//!
//! With `depth: test(pass)`, visibility is decided per vertex at the
//! undisplaced edge point, against the kept depth (`npr_abi::lines::
//! LINE_DEPTH_WGSL`): the edge is visible where any texel of the 3×3 around
//! it is at or behind the edge's (biased) depth. At a silhouette the texels
//! outside the rim are farther (background or a farther surface), so the
//! whole strip stays, wave and inner half included; an edge behind a
//! surface has that surface in every texel and is hidden. A fixed-function
//! test per fragment would compare the strip's fragments with the surface
//! they overlap, which inside a silhouette bulges towards the eye and hides
//! half the line. The fragment prologue is the render passes' one
//! (`screen_uv` from the pixel centre) and discards invisible fragments.

use super::expr::fmt_f32;
use super::Emitter;
use crate::ir::*;
use std::fmt::Write;

/// The per-vertex visibility test against the kept depth.
const VISIBILITY: &str = "// 1 where any texel of the 3x3 around the edge point is at or behind the
// edge (the texels outside a silhouette are farther), 0 where a nearer surface
// covers all of them (the edge is hidden).
fn npr_line_visible(edge_px: vec2<f32>, depth: f32) -> f32 {
    let last = vec2<i32>(textureDimensions(kept_depth)) - vec2<i32>(1);
    let centre = vec2<i32>(floor(edge_px));
    var farthest = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let texel = clamp(centre + vec2<i32>(dx, dy), vec2<i32>(0), last);
            farthest = max(farthest, textureLoad(kept_depth, texel, 0));
        }
    }
    return select(0.0, 1.0, depth <= farthest);
}

";

impl Emitter<'_> {
    pub(super) fn lines_vertex(&self, w: &mut String, lines: &LinesKind) {
        let tested = matches!(lines.depth, PassDepth::Test { .. });
        w.push_str(npr_abi::lines::LINE_VERTEX_WGSL);
        if tested {
            w.push_str(npr_abi::lines::LINE_DEPTH_WGSL);
            w.push('\n');
            w.push_str(VISIBILITY);
        }
        let with_sets = !lines.sets.is_empty();
        w.push_str(
            "struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(linear) screen_uv: vec2<f32>,
    // line.s: arc length along the chain, px (Klein et al. 2000 §5).
    @location(1) @interpolate(linear) line_s: f32,
    // line.across: -1 on one edge of the strip, +1 on the other.
    @location(2) @interpolate(linear) line_across: f32,
    // 1 where the edge is visible; fragments under 0.5 are discarded.
    @location(3) @interpolate(linear) line_visible: f32,
",
        );
        if with_sets {
            w.push_str("    // line.set: the index of the line set drawing the strip (decision 0056).\n    @location(4) @interpolate(flat) line_set: f32,\n");
        }
        w.push_str(
            "}

// The runner builds the strips on the CPU (screen-space px, so w = 1).
@vertex
fn vs_main(v: LineIn) -> Varyings {
    var out: Varyings;
    var clip = vec4<f32>(v.position.xyz, 1.0);
",
        );
        if let PassDepth::Test { bias_depth, span, .. } = lines.depth {
            if bias_depth > 0.0 {
                let _ = writeln!(
                    w,
                    "    // {}: {}: window depth lowered by the bias.\n    clip.z = max(clip.z - {}, 0.0);",
                    self.line_of(span),
                    self.snippet(span),
                    fmt_f32(bias_depth)
                );
            }
        }
        w.push_str(if tested {
            "    out.line_visible = npr_line_visible(v.line.xy, clip.z);\n"
        } else {
            "    out.line_visible = 1.0;\n"
        });
        w.push_str(
            "    out.clip = clip;
    out.screen_uv = clip.xy * vec2<f32>(0.5, -0.5) + vec2<f32>(0.5);
    out.line_s = v.position.w;
    out.line_across = v.line.z;
",
        );
        if with_sets {
            w.push_str("    out.line_set = v.line.w;\n");
        }
        w.push_str(
            "    return out;
}

",
        );
    }
}

/// The lines fragment prologue's own line: drop the fragments of hidden edges.
pub(super) const FRAGMENT_VISIBILITY: &str = "    if (in.line_visible < 0.5) {\n        discard;\n    }\n";
