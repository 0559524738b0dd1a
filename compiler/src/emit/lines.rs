//! `lines` passes (Klein et al. 2000, §5): the vertex shader that passes the
//! runner's strip vertices through (`abi::lines::LineVertex`, already in NDC
//! with the view-space bias applied on the CPU) and writes the varyings a
//! lines fragment has: `screen_uv`, `line.s` and `line.across`. A bias in
//! window depth (`bias: 0.001`) is applied here, as render passes do. The
//! fragment prologue is the render passes' one (`screen_uv` from the pixel
//! centre).

use super::expr::fmt_f32;
use super::Emitter;
use crate::ir::*;
use std::fmt::Write;

impl Emitter<'_> {
    pub(super) fn lines_vertex(&self, w: &mut String, lines: &LinesKind) {
        w.push_str(abi::lines::LINE_VERTEX_WGSL);
        w.push_str(
            "
struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(linear) screen_uv: vec2<f32>,
    // line.s: arc length along the chain, px (Klein et al. 2000 §5).
    @location(1) @interpolate(linear) line_s: f32,
    // line.across: -1 on one edge of the strip, +1 on the other.
    @location(2) @interpolate(linear) line_across: f32,
}

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
        w.push_str(
            "    out.clip = clip;
    out.screen_uv = clip.xy * vec2<f32>(0.5, -0.5) + vec2<f32>(0.5);
    out.line_s = v.position.w;
    out.line_across = v.across;
    return out;
}

",
        );
    }
}
