//! Compute passes: the module of a `compute(objects)`, `compute(vertices)`
//! or `compute(pixels, ...)` pass — its own buffers (group 2), the vertex
//! attributes it reads as storage buffers (group 1 after the `Object`
//! block), and its entry points; the parts the two element domains share
//! (the reduction trees, the element's values, the object stage). The
//! element stage over pixels is in `compute_pixels.rs`.
//!
//! `compute(vertices)` reduces in two stages, correct on any adapter (no
//! float atomics, no subgroups), each one dispatch over every object the
//! pass runs over (its members): the element stage (`reduce_elements`,
//! ⌈vertices / 1024⌉ workgroups of 256 per member) accumulates 4 elements
//! per invocation and tree-reduces them in workgroup memory to one partial
//! per value; the object stage (`reduce_objects`, one workgroup of 64 per
//! member) tree-reduces the member's partials into its value slots.
//! Every sum is therefore a fixed-shape pairwise tree: deterministic, and
//! with an error that grows like log₂(n) ulps rather than n.
//!
//! `compute(objects)` (`update_objects`, workgroups of 64) runs once per
//! member: its states
//! read the previous frame's copy of the value buffer (or their first
//! value, until the object's "written" flag is set), and it writes every
//! value and the flag into this frame's copy.

use super::expr::{slot_swizzle, to_slot};
use super::helpers::UNIT_HELPER;
use super::{EmittedPass, Emitter, PassCtx};
use crate::ir::*;
use npr_abi::manifest::{
    Attribute, ReduceOp, ELEMENTS_PER_INVOCATION, ELEMENT_WORKGROUP, OBJECT_WORKGROUP, SAMPLE_WORDS,
};
use std::fmt::Write;

/// Entry points of compute passes (the manifest names them).
pub const ELEMENTS_ENTRY: &str = "reduce_elements";
pub const REDUCE_OBJECTS_ENTRY: &str = "reduce_objects";
pub const UPDATE_OBJECTS_ENTRY: &str = "update_objects";

/// The attributes the element stage of a pass over vertices reads, in
/// binding order (group 1, bindings 1..): the position always (it gives
/// the world position and every value made from it), the others when read.
pub(super) fn attributes(domain: ComputeDomain, builtins: &std::collections::BTreeSet<Builtin>) -> Vec<Attribute> {
    if !domain.on_meshes() {
        return Vec::new();
    }
    let mut a = vec![Attribute::Position];
    if builtins
        .iter()
        .any(|b| matches!(b, Builtin::NormalWorld | Builtin::NormalView))
    {
        a.push(Attribute::Normal);
    }
    if builtins.contains(&Builtin::Uv) {
        a.push(Attribute::Uv);
    }
    // An animated object's previous pose (docs/decisions/0053).
    if builtins.contains(&Builtin::PositionPrevious) {
        a.push(Attribute::PreviousPosition);
    }
    a
}

/// The identity of a reduction, as a `vec4<f32>` (min and max start at
/// ±f32::MAX, so an object with no element reads ±3.4e38). Not ±infinity:
/// WGSL has no literal for it and refuses a constant expression that makes
/// one. f32::MAX is spelled exactly (`expr::F32_MAX_WGSL`), since Tint
/// refuses the shortest decimal, `3.4028235e38`, as past the f32 range.
pub(super) fn identity(op: ReduceOp) -> String {
    match op {
        ReduceOp::Sum => "vec4<f32>(0.0)".to_string(),
        ReduceOp::Min => format!("vec4<f32>({})", super::expr::F32_MAX_WGSL),
        ReduceOp::Max => format!("vec4<f32>(-{})", super::expr::F32_MAX_WGSL),
    }
}

pub(super) fn combine(op: ReduceOp, a: &str, b: &str) -> String {
    match op {
        ReduceOp::Sum => format!("{a} + {b}"),
        ReduceOp::Min => format!("min({a}, {b})"),
        ReduceOp::Max => format!("max({a}, {b})"),
    }
}

/// A live value of the pass being emitted: (IR slot, packed slot, value).
pub(super) type LiveValue<'a> = (u32, u32, &'a ObjectValue);

/// `npr_vertex(i)`: vertex `i` of the members' pooled vertices, in world
/// space, now and in the previous frame. With `previous` (the pass reads
/// `position.previous`), the previous frame's is the vertex's previous
/// position (`Attribute::PreviousPosition`: an animated object's previous
/// pose) under the previous model; else the current vertex under it.
fn vertex_input(w: &mut String, normal: bool, uv: bool, previous: bool) {
    w.push_str(
        "// Vertex `i` of the members' vertices (of `object`), in world space, now and in the previous frame.\n\
         fn npr_vertex(i: u32) -> NprVertex {\n\
         \x20   let p = vec4<f32>(a_position[3u * i], a_position[3u * i + 1u], a_position[3u * i + 2u], 1.0);\n\
         \x20   var v: NprVertex;\n\
         \x20   v.position_world = (object.model * p).xyz;\n",
    );
    if previous {
        w.push_str("    // The previous positions follow every member's current ones in `a_position`.\n    let j = arrayLength(&a_position) / 6u + i;\n    let p_previous = vec4<f32>(a_position[3u * j], a_position[3u * j + 1u], a_position[3u * j + 2u], 1.0);\n    v.position_previous = (object.previous_model * p_previous).xyz;\n");
    } else {
        w.push_str("    v.position_previous = (object.previous_model * p).xyz;\n");
    }
    if normal {
        w.push_str("    let n = vec3<f32>(a_normal[3u * i], a_normal[3u * i + 1u], a_normal[3u * i + 2u]);\n    v.normal_world = (object.normal_matrix * vec4<f32>(n, 0.0)).xyz;\n");
    }
    if uv {
        w.push_str("    v.uv = vec2<f32>(a_uv[2u * i], a_uv[2u * i + 1u]);\n");
    }
    w.push_str("    return v;\n}\n\n");
}

/// `npr_vertex(i)` of a pass over samples: sample `i`, the point of its
/// triangle at its barycentric coordinates (Breslav et al. 2007 §3.1), so
/// it follows the surface when the object moves or its vertices do.
/// With `previous`, its previous position is the same point of the
/// triangle's previous vertices ([`vertex_input`]).
fn sample_input(w: &mut String, normal: bool, uv: bool, previous: bool) {
    let p_previous = if previous {
        "vec4<f32>(w.x * npr_mesh_position_previous(t.x) + w.y * npr_mesh_position_previous(t.y) + w.z * npr_mesh_position_previous(t.z), 1.0)"
    } else {
        "p"
    };
    if previous {
        w.push_str("// The previous positions follow every member's current ones in `a_position`.\nfn npr_mesh_position_previous(i: u32) -> vec3<f32> {\n    let j = arrayLength(&a_position) / 6u + i;\n    return vec3<f32>(a_position[3u * j], a_position[3u * j + 1u], a_position[3u * j + 2u]);\n}\n\n");
    }
    let _ = writeln!(
        w,
        "fn npr_mesh_position(i: u32) -> vec3<f32> {{
    return vec3<f32>(a_position[3u * i], a_position[3u * i + 1u], a_position[3u * i + 2u]);
}}

// Sample `i` of the members' samples (of `object`), in world space, now and in the previous frame.
fn npr_vertex(i: u32) -> NprVertex {{
    let s = {SAMPLE_WORDS}u * i;
    let t = vec3<u32>(npr_samples[s], npr_samples[s + 1u], npr_samples[s + 2u]);
    let b = vec3<f32>(1.0, bitcast<f32>(npr_samples[s + 3u]), bitcast<f32>(npr_samples[s + 4u]));
    let w = vec3<f32>(1.0 - b.y - b.z, b.y, b.z);
    let p = vec4<f32>(w.x * npr_mesh_position(t.x) + w.y * npr_mesh_position(t.y) + w.z * npr_mesh_position(t.z), 1.0);
    var v: NprVertex;
    v.position_world = (object.model * p).xyz;
    v.position_previous = (object.previous_model * {p_previous}).xyz;
    // The object-space spacing scaled by the model's mean linear scale.
    let m = mat3x3<f32>(object.model[0].xyz, object.model[1].xyz, object.model[2].xyz);
    v.spacing = bitcast<f32>(npr_samples[s + 5u]) * pow(abs(determinant(m)), 1.0 / 3.0);"
    );
    if normal {
        w.push_str(
            "    let n = w.x * npr_mesh_normal(t.x) + w.y * npr_mesh_normal(t.y) + w.z * npr_mesh_normal(t.z);\n    v.normal_world = (object.normal_matrix * vec4<f32>(n, 0.0)).xyz;\n",
        );
    }
    if uv {
        w.push_str("    v.uv = w.x * npr_mesh_uv(t.x) + w.y * npr_mesh_uv(t.y) + w.z * npr_mesh_uv(t.z);\n");
    }
    w.push_str("    return v;\n}\n\n");
    if normal {
        w.push_str("fn npr_mesh_normal(i: u32) -> vec3<f32> {\n    return vec3<f32>(a_normal[3u * i], a_normal[3u * i + 1u], a_normal[3u * i + 2u]);\n}\n\n");
    }
    if uv {
        w.push_str(
            "fn npr_mesh_uv(i: u32) -> vec2<f32> {\n    return vec2<f32>(a_uv[2u * i], a_uv[2u * i + 1u]);\n}\n\n",
        );
    }
}

/// The reduction of each live value of a pass over elements.
pub(super) fn reduce_ops(live: &[LiveValue]) -> Vec<ReduceOp> {
    live.iter()
        .map(|(_, _, v)| match v.rule {
            ValueRule::Reduce(op) => op,
            // Resolve gives a pass over elements only reductions.
            ValueRule::Out | ValueRule::State => ReduceOp::Sum,
        })
        .collect()
}

/// The constants of the two stages and `npr_tree_<op>`, the workgroup tree
/// of each reduction the pass uses.
pub(super) fn reduction_trees(w: &mut String, ops: &[ReduceOp]) {
    let _ = writeln!(
        w,
        "const NPR_REDUCED: u32 = {}u; // partials per workgroup\n\
         const NPR_ELEMENT_WG: u32 = {ELEMENT_WORKGROUP}u;\n\
         const NPR_OBJECT_WG: u32 = {OBJECT_WORKGROUP}u;\n\n\
         var<workgroup> npr_tree: array<vec4<f32>, {ELEMENT_WORKGROUP}>;\n",
        ops.len()
    );
    let mut used_ops: Vec<ReduceOp> = ops.to_vec();
    used_ops.sort_by_key(|o| o.name());
    used_ops.dedup();
    for op in used_ops {
        let name = op.name();
        let step = combine(op, "npr_tree[lid]", "npr_tree[lid + s]");
        let _ = writeln!(
            w,
            "// Pairwise {name} of `v` over the first `n` invocations (a power of two), in
// workgroup memory; every invocation gets the result. Called in uniform control flow.
fn npr_tree_{name}(lid: u32, n: u32, v: vec4<f32>) -> vec4<f32> {{
    npr_tree[lid] = v;
    workgroupBarrier();
    for (var s = n / 2u; s > 0u; s = s / 2u) {{
        if (lid < s) {{
            npr_tree[lid] = {step};
        }}
        workgroupBarrier();
    }}
    let r = npr_tree[0];
    workgroupBarrier();
    return r;
}}
"
        );
    }
}

/// Stage 2 (`reduce_objects`): workgroup `m` tree-reduces member m's
/// `count` partials (after `setup`), the `c`-th at `partial(c)`, into its
/// object's value slots.
pub(super) fn object_stage(
    w: &mut String,
    live: &[LiveValue],
    ops: &[ReduceOp],
    doc: &str,
    setup: &str,
    count: &str,
    partial: &str,
) {
    let identities: Vec<String> = ops.iter().map(|o| identity(*o)).collect();
    let _ = writeln!(
        w,
        "{doc}
@compute @workgroup_size({OBJECT_WORKGROUP})
fn {REDUCE_OBJECTS_ENTRY}(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {{
    let member = npr_members[wg.x];
    object = npr_objects[member.x].o;
{setup}
    var acc = array<vec4<f32>, {}>({});
    for (var c = lid; c < {count}; c = c + NPR_OBJECT_WG) {{
        let p = {partial};",
        ops.len(),
        identities.join(", ")
    );
    for (k, op) in ops.iter().enumerate() {
        let _ = writeln!(
            w,
            "        acc[{k}] = {};",
            combine(*op, &format!("acc[{k}]"), &format!("npr_partials[p + {k}u]"))
        );
    }
    w.push_str("    }\n");
    for (k, ((_, packed, _), op)) in live.iter().zip(ops).enumerate() {
        let _ = writeln!(
            w,
            "    let r{k} = npr_tree_{}(lid, NPR_OBJECT_WG, acc[{k}]);\n    if (lid == 0u) {{\n        npr_values[member.x * NPR_SLOTS + {packed}u] = r{k};\n    }}",
            op.name()
        );
    }
    w.push_str("}\n");
}

impl Emitter<'_> {
    /// The WGSL and bindings of compute pass `pid`.
    pub(super) fn emit_compute(&self, pid: PassId, domain: ComputeDomain) -> EmittedPass {
        let pass = self.ir.pass(pid);
        let live: Vec<LiveValue> = pass
            .kind
            .values()
            .iter()
            .enumerate()
            .filter_map(|(i, v)| {
                self.alloc
                    .value_slots
                    .get(&(pid, i as u32))
                    .map(|packed| (i as u32, *packed, v))
            })
            .collect();
        let value_roots: Vec<ExprId> = live.iter().flat_map(|(_, _, v)| v.roots()).collect();
        let nodes = self.ir.reachable(&value_roots);
        // The ID target of a pass over pixels is bound too.
        let mut roots = value_roots.clone();
        roots.extend(pass.roots().key);
        let uses = self.uses(&self.ir.reachable(&roots), &roots, &[]);
        let attributes = attributes(domain, &uses.builtins);
        let per_object = self.alloc.slots_per_object.get(&pid).copied().unwrap_or(0);
        let state = self.alloc.keeps_state(self.ir, pid);

        let mut w = String::new();
        let _ = writeln!(
            w,
            "// npr: pass `{}` ({}), compute over {}, style \"{}\"",
            pass.name,
            self.line_of(pass.name_span),
            domain.name(),
            self.ir.style_name
        );
        w.push_str("// Generated by the npr compiler; edit the .npr file, not this one.\n\n");
        let declared = self.declare(&pass.kind, &uses, uses.expressions_read_frame());
        w.push_str(&declared.text);
        let bound: Vec<&Attribute> = attributes.iter().filter(|a| a.has_compute_binding()).collect();
        for (i, a) in bound.iter().enumerate() {
            let _ = writeln!(
                w,
                "@group(1) @binding({}) var<storage, read> a_{}: array<f32>; // every member's vertices",
                i + 2,
                a.name()
            );
        }
        w.push_str(
            "@group(2) @binding(0) var<storage, read_write> npr_values: array<vec4<f32>>; // this frame's values\n",
        );
        if domain == ComputeDomain::Samples {
            let _ = writeln!(
                w,
                "@group(1) @binding({}) var<storage, read> npr_samples: array<u32>; // {SAMPLE_WORDS} words per sample: triangle, b1, b2, spacing",
                bound.len() + 2
            );
        }
        match domain {
            ComputeDomain::Vertices | ComputeDomain::Samples => w.push_str(
                "@group(2) @binding(1) var<storage, read_write> npr_partials: array<vec4<f32>>; // per element workgroup\n\
                 @group(2) @binding(2) var<uniform> npr_dispatch: vec4<u32>; // x: element workgroups of all members\n",
            ),
            ComputeDomain::Pixels => w.push_str(
                "@group(2) @binding(1) var<storage, read_write> npr_partials: array<vec4<f32>>; // per element workgroup per object\n\
                 @group(2) @binding(2) var<uniform> npr_dispatch: vec4<u32>; // x: the scene's objects, y: element workgroups\n",
            ),
            ComputeDomain::Objects if state => w.push_str(
                "@group(2) @binding(1) var<storage, read> npr_values_previous: array<vec4<f32>>; // the previous frame's\n",
            ),
            ComputeDomain::Objects => {}
        }
        w.push('\n');
        if domain.on_meshes() {
            w.push_str(UNIT_HELPER);
        }
        self.emit_helpers(&mut w, &uses);
        let _ = writeln!(
            w,
            "// vec4 slots per object in `npr_values`.\nconst NPR_SLOTS: u32 = {per_object}u;\n"
        );
        let mut ctx = PassCtx {
            kind: super::expr::KindCtx::of(&pass.kind),
            named: Default::default(),
            target_names: declared.target_names,
            uses_linear_sampler: uses.linear_sampler,
            runtime_conditions: uses.runtime_conditions.clone(),
            per_binding: None,
        };
        match domain {
            ComputeDomain::Vertices | ComputeDomain::Samples => self.vertex_stages(
                &mut w,
                pass,
                (&live, &attributes, domain == ComputeDomain::Samples),
                &nodes,
                &uses.value_uses,
                &mut ctx,
            ),
            ComputeDomain::Pixels => self.pixel_stages(&mut w, pass, &live, &nodes, &uses.value_uses, &mut ctx),
            ComputeDomain::Objects => self.object_update(
                &mut w,
                pass,
                &live,
                state,
                per_object,
                &nodes,
                &uses.value_uses,
                &mut ctx,
            ),
        }
        EmittedPass {
            wgsl: w,
            bindings: declared.bindings,
            object_bindings: declared.object_bindings,
            attributes,
            device_half_rounding: uses.repeats_half_stores(),
        }
    }

    /// `npr_vertex`, `npr_element` and the two reduction stages of a pass
    /// over vertices or (`over_samples`) over surface samples, whose element
    /// `i` is a point of a triangle of the members' pooled vertices.
    fn vertex_stages(
        &self,
        w: &mut String,
        pass: &Pass,
        (live, attributes, over_samples): (&[LiveValue], &[Attribute], bool),
        nodes: &[ExprId],
        value_uses: &std::collections::BTreeMap<ExprId, usize>,
        ctx: &mut PassCtx,
    ) {
        let ops = reduce_ops(live);
        let _ = writeln!(w, "const NPR_PER_INVOCATION: u32 = {ELEMENTS_PER_INVOCATION}u;");
        reduction_trees(w, &ops);
        // The element's inputs.
        let has = |a: Attribute| attributes.contains(&a);
        w.push_str("struct NprVertex {\n    position_world: vec3<f32>,\n    position_previous: vec3<f32>,\n");
        if has(Attribute::Normal) {
            w.push_str("    normal_world: vec3<f32>,\n");
        }
        if has(Attribute::Uv) {
            w.push_str("    uv: vec2<f32>,\n");
        }
        if over_samples {
            w.push_str("    spacing: f32,\n");
        }
        w.push_str("}\n\n");
        let previous = has(Attribute::PreviousPosition);
        if over_samples {
            sample_input(w, has(Attribute::Normal), has(Attribute::Uv), previous);
        } else {
            vertex_input(w, has(Attribute::Normal), has(Attribute::Uv), previous);
        }
        self.element_values(
            w,
            pass,
            live,
            nodes,
            value_uses,
            ctx,
            "// The reduced values of vertex `i` (of the members' vertices), one slot each.\nfn npr_element(i: u32)",
            "    let in = npr_vertex(i);",
        );
        let identities: Vec<String> = ops.iter().map(|o| identity(*o)).collect();
        // Element stage.
        let _ = writeln!(
            w,
            "// The member whose element workgroups include `w` (members are in order of
// their first workgroup; one with no vertices owns none).
fn npr_member_of(w: u32) -> u32 {{
    var lo = 0u;
    var hi = arrayLength(&npr_members);
    while (hi - lo > 1u) {{
        let mid = (lo + hi) / 2u;
        if (npr_members[mid].w <= w) {{
            lo = mid;
        }} else {{
            hi = mid;
        }}
    }}
    return lo;
}}

// Stage 1: element workgroup `w` (over all members) reduces NPR_ELEMENT_WG × NPR_PER_INVOCATION
// vertices of its member to one partial per value. No invocation returns early, so the
// trees' barriers stay in uniform control flow.
@compute @workgroup_size({ELEMENT_WORKGROUP})
fn {}(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lid: u32) {{
    let w = wg.x + wg.y * 65535u;
    let in_range = w < npr_dispatch.x;
    let member = npr_members[npr_member_of(min(w, npr_dispatch.x - 1u))];
    object = npr_objects[member.x].o;
    let chunk = w - member.w;
    var acc = array<vec4<f32>, {}>({});
    for (var k = 0u; k < NPR_PER_INVOCATION; k = k + 1u) {{
        let i = (chunk * NPR_PER_INVOCATION + k) * NPR_ELEMENT_WG + lid;
        if (in_range && i < member.z) {{
            let e = npr_element(member.y + i);",
            ELEMENTS_ENTRY,
            ops.len(),
            identities.join(", ")
        );
        for (k, op) in ops.iter().enumerate() {
            let _ = writeln!(
                w,
                "            acc[{k}] = {};",
                combine(*op, &format!("acc[{k}]"), &format!("e[{k}]"))
            );
        }
        w.push_str("        }\n    }\n");
        for (k, op) in ops.iter().enumerate() {
            let _ = writeln!(
                w,
                "    let r{k} = npr_tree_{}(lid, NPR_ELEMENT_WG, acc[{k}]);\n    if (lid == 0u && in_range) {{\n        npr_partials[w * NPR_REDUCED + {k}u] = r{k};\n    }}",
                op.name()
            );
        }
        w.push_str("}\n\n");
        object_stage(
            w,
            live,
            &ops,
            "// Stage 2: workgroup `m` reduces member m's partials (its element workgroups) into its object's slots.",
            "    let per_workgroup = NPR_ELEMENT_WG * NPR_PER_INVOCATION;\n    let chunks = (member.z + per_workgroup - 1u) / per_workgroup;",
            "chunks",
            "(member.w + c) * NPR_REDUCED",
        );
    }

    /// `npr_element`: the reduced values of one element, one slot each,
    /// after the pass's lets. `signature` declares it up to its return type;
    /// `prologue` makes `in`, the element's inputs.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn element_values(
        &self,
        w: &mut String,
        pass: &Pass,
        live: &[LiveValue],
        nodes: &[ExprId],
        value_uses: &std::collections::BTreeMap<ExprId, usize>,
        ctx: &mut PassCtx,
        signature: &str,
        prologue: &str,
    ) {
        let n = live.len();
        let _ = writeln!(w, "{signature} -> array<vec4<f32>, {n}> {{");
        if !prologue.is_empty() {
            let _ = writeln!(w, "{prologue}");
        }
        self.emit_lets(w, pass, nodes, value_uses, ctx);
        let mut slots = Vec::new();
        for (_, _, v) in live {
            let _ = writeln!(
                w,
                "    // {}: reduce {}: {}",
                self.line_of(v.span),
                v.name,
                self.snippet(v.span).split_once('=').map_or("", |(_, r)| r.trim())
            );
            slots.push(to_slot(&self.expr(v.value, ctx), v.ty));
        }
        let _ = writeln!(
            w,
            "    return array<vec4<f32>, {n}>(\n        {},\n    );\n}}\n",
            slots.join(",\n        ")
        );
    }

    /// `update_objects`: states from the previous copy, then every value.
    #[allow(clippy::too_many_arguments)]
    fn object_update(
        &self,
        w: &mut String,
        pass: &Pass,
        live: &[LiveValue],
        state: bool,
        per_object: u32,
        nodes: &[ExprId],
        value_uses: &std::collections::BTreeMap<ExprId, usize>,
        ctx: &mut PassCtx,
    ) {
        let _ = writeln!(
            w,
            "// Once per member object.\n@compute @workgroup_size({OBJECT_WORKGROUP})\nfn {UPDATE_OBJECTS_ENTRY}(@builtin(global_invocation_id) id: vec3<u32>) {{\n    if (id.x >= arrayLength(&npr_members)) {{\n        return;\n    }}\n    object = npr_objects[npr_members[id.x].x].o;\n    let npr_base = object.ids.x * NPR_SLOTS;"
        );
        let flag = per_object.saturating_sub(1);
        // The first values read no state (the typechecker makes sure), so
        // their lets come first, with the same sharing and splitting of deep
        // expressions as every other let (a first value deep through lets
        // would otherwise reach naga's nesting limit inline).
        let first_roots: Vec<ExprId> = live.iter().filter_map(|(_, _, v)| v.first).collect();
        let first_nodes = self.ir.reachable(&first_roots);
        self.emit_lets(w, pass, &first_nodes, value_uses, ctx);
        if state {
            let _ = writeln!(
                w,
                "    // The object's state was written in an earlier frame (slot {flag}, x = 1).\n    let npr_kept = npr_values_previous[npr_base + {flag}u].x > 0.5;"
            );
        }
        for (ir_slot, packed, v) in live {
            if v.rule != ValueRule::State {
                continue;
            }
            let Some(first) = v.first else { continue };
            let _ = writeln!(
                w,
                "    // {}: state {}: {} = {}",
                self.line_of(v.span),
                v.name,
                v.ty.describe(),
                self.snippet(self.ir.expr(first).span)
            );
            let first = self.expr(first, ctx);
            let _ = writeln!(
                w,
                "    let npr_old_{ir_slot} = select({first}, npr_values_previous[npr_base + {packed}u]{}, npr_kept);",
                slot_swizzle(v.ty)
            );
        }
        // The rest, without what the first values' lets named already.
        let rest: Vec<ExprId> = nodes.iter().copied().filter(|n| !ctx.named.contains_key(n)).collect();
        self.emit_lets(w, pass, &rest, value_uses, ctx);
        for (_, packed, v) in live {
            let what = match v.rule {
                ValueRule::State => format!("{} = ", v.name),
                _ => format!("out {}: {} = ", v.name, v.ty.describe()),
            };
            let _ = writeln!(
                w,
                "    // {}: {what}{}",
                self.line_of(v.span),
                self.snippet(self.ir.expr(v.value).span)
            );
            let value = to_slot(&self.expr(v.value, ctx), v.ty);
            let _ = writeln!(w, "    npr_values[npr_base + {packed}u] = {value};");
        }
        if state {
            let _ = writeln!(w, "    npr_values[npr_base + {flag}u] = vec4<f32>(1.0, 0.0, 0.0, 0.0);");
        }
        w.push_str("}\n");
    }
}
