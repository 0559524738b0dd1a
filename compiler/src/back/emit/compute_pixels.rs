//! The element stage of `compute(pixels, ids.id)`: every pixel of an ID
//! target, reduced per object by the ID at the pixel.
//!
//! A pixel's object is not known before the pass reads it, so a workgroup
//! cannot own one object as in a pass over vertices. Each element workgroup
//! (at most `MAX_PIXEL_WORKGROUPS`, `npr_dispatch.y` of them) loops over
//! every `npr_dispatch.y`-th 32 × 32 tile, 2 × 2 pixels per invocation. Per
//! tile it takes rounds, one per distinct object in the tile, smallest
//! index first: a workgroup tree finds the two smallest object indices
//! still pending (so a tile of one object, the common case, needs one such
//! tree, not two), the value trees reduce that object's pixels, and
//! invocation 0 folds the result into the workgroup's own partial of that
//! object. Partials are laid out `[workgroup][object][value]`; each
//! workgroup starts its own at the identity, so nothing needs clearing
//! between frames, and no two workgroups write one partial: no atomics, and
//! every sum has the same order in every run (deterministic). The object
//! stage then reduces each member's `npr_dispatch.y` partials.
//!
//! Rounds stay in uniform control flow: the pair of indices is read with
//! `workgroupUniformLoad`, so every branch and loop exit on it is uniform
//! and every barrier of the trees is reached by the whole workgroup.

use super::compute::{combine, identity, object_stage, reduce_ops, reduction_trees, LiveValue, ELEMENTS_ENTRY};
use super::{Emitter, PassCtx};
use crate::ir::*;
use npr_abi::manifest::{ParamBinding, ELEMENT_WORKGROUP, PIXEL_TILE};
use std::fmt::Write;

/// Pixels per invocation (2 × 2, 16 apart, in a 32 × 32 tile).
const PER_INVOCATION: u32 = 4;

impl Emitter<'_> {
    /// Whether the pass's values read the pixel's object (its block, its
    /// params, other passes' values for it): only then is the object's
    /// block copied per pixel.
    fn reads_object(&self, nodes: &[ExprId]) -> bool {
        nodes.iter().any(|n| match &self.ir.expr(*n).kind {
            ExprKind::Builtin(b) => b.needs_object(),
            ExprKind::ObjectValue { .. } => true,
            ExprKind::Param(p) => self.bindings[p.0 as usize] == ParamBinding::PerObject,
            _ => false,
        })
    }

    /// `npr_id`, `npr_element`, the element stage over pixels and the object stage.
    pub(super) fn pixel_stages(
        &self,
        w: &mut String,
        pass: &Pass,
        live: &[LiveValue],
        nodes: &[ExprId],
        value_uses: &std::collections::BTreeMap<ExprId, usize>,
        ctx: &mut PassCtx,
    ) {
        let PassKind::Compute { key: Some(key), .. } = &pass.kind else {
            // Resolve gives every pass over pixels its ID target; without
            // one, the manifest refuses the pass as an internal error.
            w.push_str("// internal error: a pass over pixels without its ID target\n");
            return;
        };
        let ops = reduce_ops(live);
        reduction_trees(w, &ops);
        let _ = writeln!(
            w,
            "const NPR_TILE: u32 = {PIXEL_TILE}u; // pixels per side of a tile
// No object (background, or a value that is not an ID of this scene).
const NPR_NONE: u32 = 0xffffffffu;

var<workgroup> npr_index_tree: array<vec2<u32>, {ELEMENT_WORKGROUP}>;
var<workgroup> npr_indices: vec2<u32>;

// A pixel: its centre in the ID target's pixels and in [0, 1]².
struct NprPixel {{
    clip: vec4<f32>,
    screen_uv: vec2<f32>,
}}

// Pixel `p` of an ID target of `size` (clamped inside it: a pixel outside is no object's).
fn npr_pixel(p: vec2<u32>, size: vec2<u32>) -> NprPixel {{
    let centre = vec2<f32>(min(p, size - vec2<u32>(1u))) + 0.5;
    return NprPixel(vec4<f32>(centre, 0.0, 1.0), centre / vec2<f32>(size));
}}

// The ID target at the pixel: `object.id`, the object's index + 1.
fn npr_id(in: NprPixel) -> f32 {{
    return {};
}}
",
            self.expr(*key, ctx)
        );
        let id_texture = self.handle(*key, ctx);
        self.element_values(
            w,
            pass,
            live,
            nodes,
            value_uses,
            ctx,
            "// The reduced values of a pixel (of `object`, its object), one slot each.\nfn npr_element(in: NprPixel)",
            "",
        );
        let identities: Vec<String> = ops.iter().map(|o| identity(*o)).collect();
        // The two smallest distinct indices, and a round. The four pixels of
        // an invocation are written out, not looped over: constant indices
        // keep them in registers (a software rasterizer's compute shaders
        // spill dynamically indexed arrays to memory).
        let _ = writeln!(
            w,
            "// The two smallest distinct indices of `a` and `b` (each a pair, smaller first, NPR_NONE for none).
fn npr_two_smallest(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {{
    let first = min(a.x, b.x);
    let above = select(vec4<u32>(NPR_NONE), vec4<u32>(a, b), vec4<u32>(a, b) > vec4<u32>(first));
    return vec2<u32>(first, min(min(above.x, above.y), min(above.z, above.w)));
}}

// The two smallest distinct pending indices of the workgroup, the same in every invocation (uniform).
fn npr_smallest(lid: u32, pending: vec4<u32>) -> vec2<u32> {{
    let low = npr_two_smallest(vec2<u32>(pending.x, NPR_NONE), vec2<u32>(pending.y, NPR_NONE));
    let high = npr_two_smallest(vec2<u32>(pending.z, NPR_NONE), vec2<u32>(pending.w, NPR_NONE));
    npr_index_tree[lid] = npr_two_smallest(low, high);
    workgroupBarrier();
    for (var s = NPR_ELEMENT_WG / 2u; s > 0u; s = s / 2u) {{
        if (lid < s) {{
            npr_index_tree[lid] = npr_two_smallest(npr_index_tree[lid], npr_index_tree[lid + s]);
        }}
        workgroupBarrier();
    }}
    if (lid == 0u) {{
        npr_indices = npr_index_tree[0];
    }}
    return workgroupUniformLoad(&npr_indices);
}}
"
        );
        // The element stage.
        let _ = writeln!(
            w,
            "// Stage 1: element workgroup `g` reduces the pixels of every npr_dispatch.y-th tile into its
// own partial of each object (partials[g][object][value]). No invocation returns early.
@compute @workgroup_size({ELEMENT_WORKGROUP})
fn {ELEMENTS_ENTRY}(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {{
    let objects = npr_dispatch.x;
    let workgroups = npr_dispatch.y;
    let g = wg.x;
    let base = g * objects * NPR_REDUCED;
    // This workgroup's partials start at the identity.
    for (var o = lid; o < objects; o = o + NPR_ELEMENT_WG) {{
        let p = base + o * NPR_REDUCED;"
        );
        for (k, id) in identities.iter().enumerate() {
            let _ = writeln!(w, "        npr_partials[p + {k}u] = {id};");
        }
        let _ = writeln!(
            w,
            "    }}
    storageBarrier();
    let size = textureDimensions({id_texture});
    let tiles_x = (size.x + NPR_TILE - 1u) / NPR_TILE;
    let tiles = tiles_x * ((size.y + NPR_TILE - 1u) / NPR_TILE);
    let local = vec2<u32>(lid % 16u, lid / 16u);
    for (var t = g; t < tiles; t = t + workgroups) {{
        let corner = vec2<u32>(t % tiles_x, t / tiles_x) * NPR_TILE + local;
        // This invocation's four pixels (2 × 2, 16 apart): their object index until a round has
        // reduced them, then NPR_NONE; and their values."
        );
        let mut pending = Vec::new();
        for k in 0..PER_INVOCATION {
            let (dx, dy) = (16 * (k % 2), 16 * (k / 2));
            let _ = writeln!(
                w,
                "        let pixel{k} = corner + vec2<u32>({dx}u, {dy}u);
        let in{k} = npr_pixel(pixel{k}, size);
        let id{k} = npr_id(in{k});
        let valid{k} = pixel{k}.x < size.x && pixel{k}.y < size.y && id{k} >= 0.5 && id{k} < f32(objects) + 0.5;
        let index{k} = select(NPR_NONE, u32(id{k} + 0.5) - 1u, valid{k});"
            );
            if self.reads_object(nodes) {
                let _ = writeln!(w, "        object = npr_objects[select(0u, index{k}, valid{k})].o;");
            }
            let _ = writeln!(w, "        let e{k} = npr_element(in{k});");
            pending.push(format!("index{k}"));
        }
        let _ = writeln!(
            w,
            "        var pending = vec4<u32>({});
        var indices = npr_smallest(lid, pending);
        loop {{
            if (indices.x == NPR_NONE) {{
                break;
            }}
{}            if (indices.y == NPR_NONE) {{
                break;
            }}
{}            indices = npr_smallest(lid, pending);
        }}
    }}
}}
",
            pending.join(", "),
            round(&ops, &identities, "indices.x"),
            round(&ops, &identities, "indices.y"),
        );
        object_stage(
            w,
            live,
            &ops,
            "// Stage 2: workgroup `m` reduces member m's partial of every element workgroup into its object's slots.",
            "",
            "npr_dispatch.y",
            "(c * npr_dispatch.x + member.x) * NPR_REDUCED",
        );
    }
}

/// One round over object `index` (a uniform expression): its pixels among
/// the invocation's four reduced over the workgroup, folded into workgroup
/// g's partial of it by invocation 0, and no longer pending.
fn round(ops: &[npr_abi::manifest::ReduceOp], identities: &[String], index: &str) -> String {
    let mut r = format!("            {{\n                let mine = pending == vec4<u32>({index});\n");
    for (k, op) in ops.iter().enumerate() {
        let pick = |px: u32| {
            format!(
                "select({}, e{px}[{k}], mine.{})",
                identities[k],
                ["x", "y", "z", "w"][px as usize]
            )
        };
        // Pairwise, as the trees: (p0 ∘ p1) ∘ (p2 ∘ p3).
        let pair = |a: u32, b: u32| format!("({})", combine(*op, &pick(a), &pick(b)));
        let four = combine(*op, &pair(0, 1), &pair(2, 3));
        let _ = writeln!(
            r,
            "                let r{k} = npr_tree_{}(lid, NPR_ELEMENT_WG, {four});",
            op.name()
        );
    }
    let _ = writeln!(
        r,
        "                if (lid == 0u) {{\n                    let p = base + {index} * NPR_REDUCED;"
    );
    for (k, op) in ops.iter().enumerate() {
        let _ = writeln!(
            r,
            "                    npr_partials[p + {k}u] = {};",
            combine(*op, &format!("npr_partials[p + {k}u]"), &format!("r{k}"))
        );
    }
    r.push_str(
        "                }\n                pending = select(pending, vec4<u32>(NPR_NONE), mine);\n            }\n",
    );
    r
}
