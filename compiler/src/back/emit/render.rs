//! Render passes: the attributes a pass needs, the vertex shader (projection
//! with the pass's view, `vertex { inflate, shadow_warp }`, screen-space
//! tangent frames) and its varyings, and the fragment prologue that
//! recomputes `screen_uv` from the pixel centre.

use super::expr::fmt_f32;
use super::helpers::{PROJECT_DIR_HELPER, UNIT_HELPER};
use super::uses::Uses;
use super::{Emitter, PassCtx};
use crate::ir::*;
use npr_abi::manifest::Attribute;
use std::collections::BTreeSet;
use std::fmt::Write;

/// The vertex attributes a render pass reads, in vertex-buffer order.
pub(super) fn attributes(vertex: &VertexModifiers, uses: &Uses) -> Vec<Attribute> {
    let builtins = &uses.builtins;
    let mut attributes = vec![Attribute::Position];
    let needs_normal = vertex.inflate.is_some()
        || builtins.iter().any(|b| {
            matches!(
                b,
                Builtin::NormalWorld | Builtin::NormalView | Builtin::BitangentScreen | Builtin::BitangentScreenCenter
            )
        });
    if needs_normal {
        attributes.push(Attribute::Normal);
    }
    if builtins.contains(&Builtin::Uv) || uses.texture_as_value {
        attributes.push(Attribute::Uv);
    }
    // Screen-space tangent frames (Age of Sail §3.2) need the tangent attribute.
    if builtins.contains(&Builtin::Tangent) || builtins.iter().any(|b| is_screen_frame(*b)) {
        attributes.push(Attribute::Tangent);
    }
    // Breslav et al. 2007 §3.6: reading the weight is what makes the runner
    // draw each patch over its n-ring (see `npr_abi::Attribute::PatchWeight`).
    if builtins.contains(&Builtin::PatchWeight) {
        attributes.push(Attribute::PatchWeight);
    }
    attributes
}

/// The fragment shader's opening: the screen position from the fragment's
/// pixel centre rather than the interpolated clip.xy / clip.w: exact, and
/// defined on triangles the rasterizer clipped at the eye plane, where the
/// varying is not.
pub(super) fn fragment_prologue(w: &mut String, scale: f64) {
    let _ = writeln!(
        w,
        "@fragment\nfn fs_main(in_raw: Varyings) -> FragOut {{\n    var in = in_raw;\n    in.screen_uv = in_raw.clip.xy / {};",
        pass_size_wgsl(scale)
    );
}

impl Emitter<'_> {
    /// `VertexIn`, `Varyings` and `vs_main` of a render pass: project with
    /// the pass's view, apply its vertex modifiers, write the varyings.
    pub(super) fn render_vertex(
        &self,
        w: &mut String,
        pass: &Pass,
        (view, vertex): (PassView, &VertexModifiers),
        attributes: &[Attribute],
        builtins: &BTreeSet<Builtin>,
        ctx: &mut PassCtx,
    ) {
        let roots = vertex.roots();
        let vert_nodes = &self.ir.reachable(&roots);
        w.push_str("struct VertexIn {\n");
        for (loc, a) in attributes.iter().enumerate() {
            let ty = match a {
                // `attributes` lists no previous position (compute passes only).
                Attribute::Position | Attribute::Normal | Attribute::PreviousPosition => "vec3<f32>",
                Attribute::Uv => "vec2<f32>",
                Attribute::Tangent => "vec4<f32>",
                Attribute::PatchWeight => "f32",
            };
            let _ = writeln!(w, "    @location({loc}) {}: {ty},", a.name());
        }
        w.push_str("}\n\nstruct Varyings {\n    @builtin(position) clip: vec4<f32>,\n    @location(0) position_world: vec3<f32>,\n    @location(1) @interpolate(linear) screen_uv: vec2<f32>,\n");
        let has = |a: Attribute| attributes.contains(&a);
        if has(Attribute::Normal) {
            w.push_str("    @location(2) normal_world: vec3<f32>,\n");
        }
        if has(Attribute::Uv) {
            w.push_str("    @location(3) uv: vec2<f32>,\n");
        }
        if has(Attribute::Tangent) {
            w.push_str("    @location(4) tangent: vec4<f32>,\n");
        }
        if has(Attribute::PatchWeight) {
            w.push_str("    @location(5) patch_weight: f32,\n");
        }
        for (b, loc, field) in SCREEN_FRAME_VARYINGS {
            if builtins.contains(b) {
                let _ = writeln!(w, "    @location({loc}) {field}: vec2<f32>,");
            }
        }
        w.push_str("}\n\n");
        w.push_str(UNIT_HELPER);
        let screen_frame: Vec<&(Builtin, u32, &str)> = SCREEN_FRAME_VARYINGS
            .iter()
            .filter(|(b, _, _)| builtins.contains(b))
            .collect();
        if !screen_frame.is_empty() {
            w.push_str(PROJECT_DIR_HELPER);
        }
        w.push_str("@vertex\nfn vs_main(v: VertexIn) -> Varyings {\n    var out: Varyings;\n");
        let view_proj = match view {
            PassView::Camera => "frame.view_proj",
            PassView::Light => "frame.light_view_proj",
        };
        let _ = writeln!(
            w,
            "    let world = object.model * vec4<f32>(v.position, 1.0);\n    out.position_world = world.xyz;\n    var clip = {view_proj} * world;"
        );
        if has(Attribute::Normal) {
            w.push_str("    out.normal_world = (object.normal_matrix * vec4<f32>(v.normal, 0.0)).xyz;\n");
        }
        if let Some(inflate) = vertex.inflate {
            ctx.named.clear();
            self.emit_lets(w, pass, vert_nodes, &self.value_uses(vert_nodes, &roots), ctx);
            let width = self.expr(inflate, ctx);
            let _ = writeln!(
                w,
                "    // {}: vertex {{ inflate: {} }}",
                self.line_of(self.ir.expr(inflate).span),
                self.snippet(self.ir.expr(inflate).span)
            );
            let _ = writeln!(
                w,
                "    // Age of Sail §4.1: push the vertex along its screen-space projected normal by a width in px.\n    let pass_size = frame.resolution * {scale};\n    let n_clip = ({view_proj} * vec4<f32>(out.normal_world, 0.0)).xy;\n    let n_px = n_clip * pass_size;\n    let n_len = length(n_px);\n    if (n_len > 1e-8) {{\n        clip = vec4<f32>(clip.xy + (n_px / n_len) * ({width}) * 2.0 / pass_size * clip.w, clip.zw);\n    }}",
                scale = fmt_f32(pass.scale)
            );
        }
        if let Some(k) = vertex.shadow_warp {
            if vertex.inflate.is_none() {
                ctx.named.clear();
                self.emit_lets(w, pass, vert_nodes, &self.value_uses(vert_nodes, &roots), ctx);
            }
            let k = self.expr(k, ctx);
            let _ = writeln!(
                w,
                "    // Age of Sail §5, depth pass: warp light-space x, y with a sigmoid, so texels\n    // concentrate near the centre; `shadow()` applies the same warp when it looks up.\n    let warp_k = max({k}, 0.0);\n    if (warp_k > 1e-4) {{\n        let ndc = clip.xy / clip.w;\n        clip = vec4<f32>(tanh(warp_k * ndc) / tanh(warp_k) * clip.w, clip.zw);\n    }}"
            );
        }
        if has(Attribute::Uv) {
            w.push_str("    out.uv = v.uv;\n");
        }
        if has(Attribute::PatchWeight) {
            w.push_str("    out.patch_weight = v.patch_weight;\n");
        }
        if has(Attribute::Tangent) {
            w.push_str(
                "    out.tangent = vec4<f32>((object.model * vec4<f32>(v.tangent.xyz, 0.0)).xyz, v.tangent.w);\n",
            );
        }
        if !screen_frame.is_empty() {
            // Age of Sail §3.2: T_s, B_s from the un-inflated position, in px of this pass per metre.
            let _ = writeln!(
                w,
                "    // Age of Sail §3.2 (eqs. 9-10): screen-space projections of the unit tangent and bitangent.\n    let frame_size = frame.resolution * {};\n    let t_world = npr_unit((object.model * vec4<f32>(v.tangent.xyz, 0.0)).xyz);",
                fmt_f32(pass.scale)
            );
            if screen_frame
                .iter()
                .any(|(b, _, _)| matches!(b, Builtin::BitangentScreen | Builtin::BitangentScreenCenter))
            {
                // Mesh convention: w · cross(n, t) points along -v, so +v is -w · cross(n, t).
                w.push_str("    let b_world = npr_unit(-v.tangent.w * cross(npr_unit(out.normal_world), t_world));\n");
            }
            for (b, _, field) in &screen_frame {
                let (dir, matrix) = match b {
                    Builtin::TangentScreen => ("t_world", "frame.view_proj"),
                    Builtin::BitangentScreen => ("b_world", "frame.view_proj"),
                    Builtin::TangentScreenCenter => ("t_world", "frame.center_view_proj"),
                    _ => ("b_world", "frame.center_view_proj"),
                };
                let _ = writeln!(
                    w,
                    "    out.{field} = npr_project_dir({matrix}, world, {dir}, frame_size);"
                );
            }
        }
        if let PassKind::Render {
            depth: PassDepth::Test { bias_depth, span, .. },
            ..
        } = &pass.kind
        {
            if *bias_depth > 0.0 {
                // z/w is affine in screen space, so subtracting b·w from every
                // vertex's z lowers the window depth of every fragment by b.
                let _ = writeln!(
                    w,
                    "    // {}: {}: window depth lowered by the bias.\n    clip.z = clip.z - {} * clip.w;",
                    self.line_of(*span),
                    self.snippet(*span),
                    fmt_f32(*bias_depth)
                );
            }
        }
        w.push_str("    out.clip = clip;\n    // Screen position, interpolated linearly in screen space (exact for any triangle).\n    out.screen_uv = clip.xy / clip.w * vec2<f32>(0.5, -0.5) + vec2<f32>(0.5);\n    return out;\n}\n\n");
    }
}

/// The screen-space tangent-frame builtins: (builtin, varying location, varying name).
const SCREEN_FRAME_VARYINGS: &[(Builtin, u32, &str)] = &[
    (Builtin::TangentScreen, 8, "tangent_screen"),
    (Builtin::BitangentScreen, 9, "bitangent_screen"),
    (Builtin::TangentScreenCenter, 10, "tangent_screen_center"),
    (Builtin::BitangentScreenCenter, 11, "bitangent_screen_center"),
];

fn is_screen_frame(b: Builtin) -> bool {
    SCREEN_FRAME_VARYINGS.iter().any(|(s, _, _)| *s == b)
}

/// The size in px of a pass at `scale` of the output, as the runner allocates
/// it (`npr_runner::render::scaled_size`: rounded half up, at least 1).
pub(super) fn pass_size_wgsl(scale: f64) -> String {
    if scale == 1.0 {
        "frame.resolution".into()
    } else {
        format!(
            "max(floor(frame.resolution * {} + vec2<f32>(0.5)), vec2<f32>(1.0))",
            fmt_f32(scale)
        )
    }
}
