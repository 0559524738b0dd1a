//! Emit one readable WGSL module per live pass.
//!
//! Layout of a module: a header naming the pass and its `.npr` line; the
//! bindings it uses (group 0: frame, style params, targets, textures; group 1:
//! the per-object block of render passes); the stdlib operators it calls; the
//! vertex shader; the fragment shader with one `let` per user `let` and per
//! shared subexpression, each commented with the `.npr` line it came from.

use crate::allocate::Allocation;
use crate::ir::*;
use abi::manifest::{Attribute, Binding, ParamBinding, Resource};
use dsl::SourceMap;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// What one emitted pass needs from the runner.
pub struct EmittedPass {
    pub wgsl: String,
    pub bindings: Vec<Binding>,
    /// Group 1 bindings after the `Object` block (binding 0): per-object textures.
    pub object_bindings: Vec<Binding>,
    pub attributes: Vec<Attribute>,
}

/// `struct Frame`, generated from `abi::FrameBlock` (one definition of the block).
const FRAME_STRUCT: &str = abi::FRAME_WGSL;

const PROJECT_HELPER: &str = "// World point -> (screen u, screen v, NDC depth) under `view_proj`; w <= 0
// (behind the eye) maps far outside the screen.
fn npr_project(view_proj: mat4x4<f32>, p: vec3<f32>) -> vec3<f32> {
    let c = view_proj * vec4<f32>(p, 1.0);
    if (c.w <= 1e-8) {
        return vec3<f32>(-1e9, -1e9, 1.0);
    }
    let ndc = c.xyz / c.w;
    return vec3<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5, ndc.z);
}
";

const LOAD_HELPER: &str = "// Nearest texel of `t` at `uv`, so targets of different scales line up.
fn npr_load(t: texture_2d<f32>, uv: vec2<f32>) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(t));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    return textureLoad(t, p, 0);
}
";

pub struct Emitter<'a> {
    pub ir: &'a Ir,
    pub alloc: &'a Allocation,
    pub bindings: &'a [ParamBinding],
    pub sources: &'a SourceMap,
}

struct PassCtx {
    is_render: bool,
    /// Names given to shared or user-named nodes, in emission order.
    named: BTreeMap<ExprId, String>,
    target_names: BTreeMap<TargetRef, String>,
    /// Bindings of targets read with `other_eye(...)`.
    other_target_names: BTreeMap<TargetRef, String>,
    uses_linear_sampler: bool,
}

impl Emitter<'_> {
    fn line_of(&self, span: dsl::Span) -> String {
        let (line, _) = self.sources.line_col(span.file, span.start);
        let name = self.sources.get(span.file).map(|f| f.name.as_str()).unwrap_or("?");
        let file = std::path::Path::new(name)
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        format!("{file}:{line}")
    }

    fn snippet(&self, span: dsl::Span) -> String {
        let s = self.sources.snippet(span);
        let one_line: String = s.split_whitespace().collect::<Vec<_>>().join(" ");
        if one_line.len() > 80 {
            format!(
                "{}...",
                &one_line[..one_line.char_indices().nth(77).map_or(one_line.len(), |(i, _)| i)]
            )
        } else {
            one_line
        }
    }

    pub fn emit_pass(&self, pid: PassId) -> EmittedPass {
        let pass = self.ir.pass(pid);
        let is_render = matches!(pass.kind, PassKind::Render { .. });
        let live_outputs: Vec<(usize, &PassOutput)> = pass
            .outputs
            .iter()
            .enumerate()
            .filter(|(i, _)| {
                self.alloc
                    .target_index(TargetRef {
                        pass: pid,
                        output: *i as u32,
                    })
                    .is_some()
            })
            .collect();
        let frag_roots: Vec<ExprId> = live_outputs.iter().map(|(_, o)| o.value).collect();
        let frag_nodes = self.ir.reachable(&frag_roots);
        let vert_nodes = self.ir.reachable(&Ir::vertex_roots(pass));
        let all_nodes: Vec<ExprId> = frag_nodes.iter().chain(vert_nodes.iter()).copied().collect();

        // What the pass uses.
        let mut builtins = BTreeSet::new();
        let mut targets_read = BTreeSet::new();
        let mut other_targets_read = BTreeSet::new();
        let mut uses_project = false;
        let mut textures_read = BTreeSet::new();
        let mut uses_style = false;
        let mut uses_object = false;
        let mut uses_percent = false;
        let mut operators = BTreeSet::new();
        let mut uses_linear_sampler = false;
        let mut texture_as_value = false;
        for id in &all_nodes {
            match &self.ir.expr(*id).kind {
                ExprKind::Builtin(b) => {
                    builtins.insert(*b);
                }
                ExprKind::Target(t) => {
                    targets_read.insert(*t);
                }
                ExprKind::OtherEyeTarget(t) => {
                    other_targets_read.insert(*t);
                }
                ExprKind::Texture(t) => {
                    textures_read.insert(*t);
                }
                ExprKind::Call {
                    callee: Callee::Intrinsic(Intrinsic::Project | Intrinsic::ProjectOtherEye),
                    ..
                } => uses_project = true,
                ExprKind::Param(p) => match self.bindings[p.0 as usize] {
                    ParamBinding::Uniform => uses_style = true,
                    ParamBinding::PerObject => uses_object = true,
                    _ => {}
                },
                ExprKind::PercentOfHeight(_) => uses_percent = true,
                ExprKind::Call {
                    callee: Callee::Operator(i),
                    args,
                } => {
                    operators.insert(*i as usize);
                    let op = &stdlib::all()[*i as usize];
                    for (p, a) in op.params.iter().zip(args) {
                        if p.ty == stdlib::Ty::SampledTexture && self.ir.expr(*a).kind.target_read().is_some() {
                            uses_linear_sampler = true;
                        }
                    }
                }
                _ => {}
            }
        }
        // A texture read as a value samples at `uv` in render passes.
        for id in &frag_nodes {
            if matches!(self.ir.expr(*id).kind, ExprKind::Texture(_)) && self.used_as_value(*id, &frag_nodes) {
                texture_as_value = true;
            }
        }
        let frame_builtin = builtins.iter().any(|b| {
            !matches!(
                b,
                Builtin::Uv
                    | Builtin::NormalWorld
                    | Builtin::PositionWorld
                    | Builtin::Tangent
                    | Builtin::FragCoord
                    | Builtin::ScreenUv
            )
        });
        let uses_frame = is_render || frame_builtin || uses_percent || uses_project;

        // Screen-space tangent frames (Age of Sail §3.2) need the tangent attribute.
        let uses_screen_frame = builtins.iter().any(|b| is_screen_frame(*b));
        let mut attributes = Vec::new();
        if is_render {
            attributes.push(Attribute::Position);
            let needs_normal = pass.inflate.is_some()
                || builtins.iter().any(|b| {
                    matches!(
                        b,
                        Builtin::NormalWorld
                            | Builtin::NormalView
                            | Builtin::BitangentScreen
                            | Builtin::BitangentScreenCenter
                    )
                });
            if needs_normal {
                attributes.push(Attribute::Normal);
            }
            if builtins.contains(&Builtin::Uv) || texture_as_value {
                attributes.push(Attribute::Uv);
            }
            if builtins.contains(&Builtin::Tangent) || uses_screen_frame {
                attributes.push(Attribute::Tangent);
            }
        }

        let mut w = String::new();
        let _ = writeln!(
            w,
            "// npr: pass `{}` ({}), style \"{}\"",
            pass.name,
            self.line_of(pass.name_span),
            self.ir.style_name
        );
        let _ = writeln!(
            w,
            "// Generated by the npr compiler; edit the .npr file, not this one.\n"
        );
        // Bindings.
        let mut binds = Vec::new();
        let mut object_binds = Vec::new();
        let mut decls = String::new();
        let mut next = 0u32;
        if uses_frame {
            decls.push_str(FRAME_STRUCT);
            let _ = writeln!(decls, "@group(0) @binding({next}) var<uniform> frame: Frame;");
            binds.push(Binding {
                binding: next,
                resource: Resource::FrameUniforms,
            });
            next += 1;
        }
        if uses_style {
            decls.push_str("struct Params {\n");
            for (i, b) in self.bindings.iter().enumerate() {
                if *b == ParamBinding::Uniform {
                    let _ = writeln!(decls, "    p_{}: vec4<f32>,", self.ir.params[i].name);
                }
            }
            decls.push_str("}\n");
            let _ = writeln!(decls, "@group(0) @binding({next}) var<uniform> params: Params;");
            binds.push(Binding {
                binding: next,
                resource: Resource::StyleUniforms,
            });
            next += 1;
        }
        // This eye's targets, then (stereo styles) the other eye's copies.
        let mut target_names = BTreeMap::new();
        let mut other_target_names = BTreeMap::new();
        let reads = targets_read.iter().map(|t| (t, false));
        for (t, other_eye) in reads.chain(other_targets_read.iter().map(|t| (t, true))) {
            let Some(index) = self.alloc.target_index(*t) else {
                continue;
            };
            let (prefix, note) = if other_eye {
                ("t_other_", ", the other eye's")
            } else {
                ("t_", "")
            };
            let name = format!("{prefix}{}", self.ir.target_name(*t).replace('.', "_"));
            let fmt = self.ir.pass(t.pass).outputs[t.output as usize].format;
            let _ = writeln!(
                decls,
                "@group(0) @binding({next}) var {name}: texture_2d<f32>; // {}{note}",
                fmt.name()
            );
            binds.push(Binding {
                binding: next,
                resource: Resource::Target {
                    target: index,
                    filterable: fmt.is_filterable(),
                    other_eye,
                },
            });
            if other_eye {
                &mut other_target_names
            } else {
                &mut target_names
            }
            .insert(*t, name);
            next += 1;
        }
        for t in textures_read
            .iter()
            .filter(|t| !self.ir.textures[t.0 as usize].per_object)
        {
            let tex = &self.ir.textures[t.0 as usize];
            let _ = writeln!(
                decls,
                "@group(0) @binding({next}) var tex_{}: texture_2d<f32>;",
                tex.name
            );
            binds.push(Binding {
                binding: next,
                resource: Resource::Texture { texture: t.0 as usize },
            });
            next += 1;
            let _ = writeln!(decls, "@group(0) @binding({next}) var samp_{}: sampler;", tex.name);
            binds.push(Binding {
                binding: next,
                resource: Resource::TextureSampler { texture: t.0 as usize },
            });
            next += 1;
        }
        if uses_linear_sampler {
            let _ = writeln!(decls, "@group(0) @binding({next}) var samp_linear_clamp: sampler;");
            binds.push(Binding {
                binding: next,
                resource: Resource::LinearClampSampler,
            });
        }
        if is_render {
            decls.push_str("struct Object {\n    model: mat4x4<f32>,\n    normal_matrix: mat4x4<f32>,\n");
            for (i, b) in self.bindings.iter().enumerate() {
                if *b == ParamBinding::PerObject {
                    let _ = writeln!(decls, "    p_{}: vec4<f32>,", self.ir.params[i].name);
                }
            }
            decls.push_str("}\n@group(1) @binding(0) var<uniform> object: Object;\n");
            // Per-object textures follow the Object block in group 1, so one
            // bind group per object carries its uniforms and its images.
            let mut next1 = 1u32;
            for t in textures_read
                .iter()
                .filter(|t| self.ir.textures[t.0 as usize].per_object)
            {
                let tex = &self.ir.textures[t.0 as usize];
                let _ = writeln!(
                    decls,
                    "@group(1) @binding({next1}) var tex_{}: texture_2d<f32>; // per object",
                    tex.name
                );
                object_binds.push(Binding {
                    binding: next1,
                    resource: Resource::Texture { texture: t.0 as usize },
                });
                let _ = writeln!(
                    decls,
                    "@group(1) @binding({}) var samp_{}: sampler;",
                    next1 + 1,
                    tex.name
                );
                object_binds.push(Binding {
                    binding: next1 + 1,
                    resource: Resource::TextureSampler { texture: t.0 as usize },
                });
                next1 += 2;
            }
        }
        let _ = uses_object;
        w.push_str(&decls);
        w.push('\n');
        if !targets_read.is_empty() || !other_targets_read.is_empty() {
            w.push_str(LOAD_HELPER);
            w.push('\n');
        }
        if uses_project {
            w.push_str(PROJECT_HELPER);
            w.push('\n');
        }
        // Operators, dependencies first, after the shared helper snippets they use.
        let closure = self.operator_closure(&operators);
        let mut snippets: Vec<&str> = Vec::new();
        for op in &closure {
            for s in stdlib::all()[*op].snippets {
                if !snippets.contains(s) {
                    snippets.push(s);
                }
            }
        }
        for s in snippets {
            if let Some(src) = stdlib::snippets::find(s) {
                let _ = writeln!(w, "// ---- stdlib helpers `{s}`");
                w.push_str(src.trim_end());
                w.push_str("\n\n");
            }
        }
        for op in closure {
            let o = &stdlib::all()[op];
            let _ = writeln!(w, "// ---- stdlib operator `{}` ({})", o.name, o.reference);
            w.push_str(o.wgsl.trim_end());
            w.push_str("\n\n");
        }

        let mut ctx = PassCtx {
            is_render,
            named: BTreeMap::new(),
            target_names,
            other_target_names,
            uses_linear_sampler,
        };
        if is_render {
            self.render_vertex(&mut w, pass, &attributes, &builtins, &vert_nodes, &mut ctx);
        } else {
            w.push_str(IMAGE_VERTEX);
        }
        // Fragment shader.
        w.push_str("struct FragOut {\n");
        for (loc, (_, o)) in live_outputs.iter().enumerate() {
            let ty = crate::ir::Ty::float_vec(o.format.channels()).wgsl();
            let _ = writeln!(w, "    @location({loc}) o_{}: {ty}, // {}", o.name, o.format.name());
        }
        if is_render {
            // The screen position from the fragment's pixel centre rather than the
            // interpolated clip.xy / clip.w: exact, and defined on triangles the
            // rasterizer clipped at the eye plane, where the varying is not.
            let _ = writeln!(
                w,
                "}}\n\n@fragment\nfn fs_main(in_raw: Varyings) -> FragOut {{\n    var in = in_raw;\n    in.screen_uv = in_raw.clip.xy / {};",
                pass_size_wgsl(pass.scale)
            );
        } else {
            w.push_str("}\n\n@fragment\nfn fs_main(in: Varyings) -> FragOut {\n");
        }
        ctx.named.clear();
        self.emit_lets(&mut w, pass, &frag_nodes, &mut ctx);
        w.push_str("    var out: FragOut;\n");
        for (_, o) in &live_outputs {
            let _ = writeln!(
                w,
                "    // {}: out {}: {} = {}",
                self.line_of(o.span),
                o.name,
                o.format.name(),
                self.snippet(self.ir.expr(o.value).span)
            );
            let v = self.expr(o.value, &ctx);
            let _ = writeln!(w, "    out.o_{} = {v};", o.name);
        }
        w.push_str("    return out;\n}\n");
        EmittedPass {
            wgsl: w,
            bindings: binds,
            object_bindings: object_binds,
            attributes,
        }
    }

    fn used_as_value(&self, id: ExprId, nodes: &[ExprId]) -> bool {
        // A handle is "used as a value" unless every use is a texture parameter of an operator.
        let mut used = false;
        for n in nodes {
            let e = self.ir.expr(*n);
            match &e.kind {
                ExprKind::Call {
                    callee: Callee::Operator(i),
                    args,
                } => {
                    let op = &stdlib::all()[*i as usize];
                    for (p, a) in op.params.iter().zip(args) {
                        if *a == id && !matches!(p.ty, stdlib::Ty::Texture | stdlib::Ty::SampledTexture) {
                            used = true;
                        }
                    }
                }
                _ => {
                    if self.ir.operands(*n).contains(&id) {
                        used = true;
                    }
                }
            }
        }
        // An output written straight from a texture also reads it as a value.
        used || !nodes.iter().any(|n| self.ir.operands(*n).contains(&id))
    }

    fn operator_closure(&self, roots: &BTreeSet<usize>) -> Vec<usize> {
        let mut order = Vec::new();
        fn visit(i: usize, order: &mut Vec<usize>, depth: usize) {
            if order.contains(&i) || depth > 16 {
                return;
            }
            for d in stdlib::all()[i].depends {
                if let Some(j) = stdlib::all().iter().position(|o| o.name == *d) {
                    visit(j, order, depth + 1);
                }
            }
            order.push(i);
        }
        for r in roots {
            visit(*r, &mut order, 0);
        }
        order
    }

    /// Name user `let`s and shared subexpressions so each is computed once.
    fn emit_lets(&self, w: &mut String, pass: &Pass, nodes: &[ExprId], ctx: &mut PassCtx) {
        let mut uses: BTreeMap<ExprId, usize> = BTreeMap::new();
        for n in nodes {
            for o in self.ir.operands(*n) {
                *uses.entry(o).or_default() += 1;
            }
        }
        let user_lets: BTreeMap<ExprId, &Let> = pass.lets.iter().map(|l| (l.value, l)).collect();
        for n in nodes {
            let e = self.ir.expr(*n);
            let trivial = matches!(
                e.kind,
                ExprKind::Const(_)
                    | ExprKind::Param(_)
                    | ExprKind::Builtin(_)
                    | ExprKind::Target(_)
                    | ExprKind::OtherEyeTarget(_)
                    | ExprKind::Texture(_)
                    | ExprKind::PercentOfHeight(_)
            );
            let handle = matches!(e.ty, Ty::Target(_) | Ty::Texture(_));
            if handle {
                continue;
            }
            if let Some(l) = user_lets.get(n) {
                if trivial && uses.get(n).copied().unwrap_or(0) <= 1 {
                    continue;
                }
                let v = self.expr(*n, ctx);
                let _ = writeln!(
                    w,
                    "    // {}: let {} = {}",
                    self.line_of(l.span),
                    l.name,
                    self.snippet(self.ir.expr(l.value).span)
                );
                let name = format!("l_{}", l.name);
                let _ = writeln!(w, "    let {name} = {v};");
                ctx.named.insert(*n, name);
            } else if !trivial && uses.get(n).copied().unwrap_or(0) > 1 {
                let v = self.expr(*n, ctx);
                let name = format!("e{}", n.0);
                let _ = writeln!(w, "    let {name} = {v}; // shared: {}", self.snippet(e.span));
                ctx.named.insert(*n, name);
            }
        }
    }

    fn render_vertex(
        &self,
        w: &mut String,
        pass: &Pass,
        attributes: &[Attribute],
        builtins: &BTreeSet<Builtin>,
        vert_nodes: &[ExprId],
        ctx: &mut PassCtx,
    ) {
        w.push_str("struct VertexIn {\n");
        for (loc, a) in attributes.iter().enumerate() {
            let ty = match a {
                Attribute::Position | Attribute::Normal => "vec3<f32>",
                Attribute::Uv => "vec2<f32>",
                Attribute::Tangent => "vec4<f32>",
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
        for (b, loc, field) in SCREEN_FRAME_VARYINGS {
            if builtins.contains(b) {
                let _ = writeln!(w, "    @location({loc}) {field}: vec2<f32>,");
            }
        }
        w.push_str("}\n\n// Unit vector, or zero for a zero input (never NaN).\nfn npr_unit(v: vec3<f32>) -> vec3<f32> {\n    return v * inverseSqrt(max(dot(v, v), 1e-30));\n}\n\n");
        let screen_frame: Vec<&(Builtin, u32, &str)> = SCREEN_FRAME_VARYINGS
            .iter()
            .filter(|(b, _, _)| builtins.contains(b))
            .collect();
        if !screen_frame.is_empty() {
            w.push_str(PROJECT_DIR_HELPER);
        }
        w.push_str("@vertex\nfn vs_main(v: VertexIn) -> Varyings {\n    var out: Varyings;\n");
        let view_proj = match pass.view {
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
        if let Some(inflate) = pass.inflate {
            ctx.named.clear();
            self.emit_lets(w, pass, vert_nodes, ctx);
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
        if let Some(k) = pass.shadow_warp {
            if pass.inflate.is_none() {
                ctx.named.clear();
                self.emit_lets(w, pass, vert_nodes, ctx);
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
        w.push_str("    out.clip = clip;\n    // Screen position, interpolated linearly in screen space (exact for any triangle).\n    out.screen_uv = clip.xy / clip.w * vec2<f32>(0.5, -0.5) + vec2<f32>(0.5);\n    return out;\n}\n\n");
    }

    /// WGSL for a node in value context.
    fn expr(&self, id: ExprId, ctx: &PassCtx) -> String {
        if let Some(n) = ctx.named.get(&id) {
            return n.clone();
        }
        let e = self.ir.expr(id);
        match &e.kind {
            ExprKind::Const(c) => const_wgsl(c, e.ty),
            ExprKind::PercentOfHeight(f) => format!("({} * frame.resolution.y)", fmt_f32(*f)),
            ExprKind::Param(p) => {
                let param = &self.ir.params[p.0 as usize];
                let block = if self.bindings[p.0 as usize] == ParamBinding::PerObject {
                    "object"
                } else {
                    "params"
                };
                let slot = format!("{block}.p_{}", param.name);
                match e.ty {
                    Ty::Int => format!("i32({slot}.x)"),
                    Ty::Bool => format!("({slot}.x > 0.5)"),
                    Ty::Float => format!("{slot}.x"),
                    Ty::Vec2 => format!("{slot}.xy"),
                    Ty::Vec3 => format!("{slot}.xyz"),
                    _ => slot,
                }
            }
            ExprKind::Builtin(b) => builtin_wgsl(*b, ctx.is_render),
            ExprKind::Target(t) | ExprKind::OtherEyeTarget(t) => {
                let names = if matches!(e.kind, ExprKind::Target(_)) {
                    &ctx.target_names
                } else {
                    &ctx.other_target_names
                };
                let name = names.get(t).cloned().unwrap_or_else(|| "t_missing".into());
                let n = crate::typecheck::value_ty(self.ir, id).components().unwrap_or(4);
                let sw = match n {
                    1 => ".x",
                    2 => ".xy",
                    3 => ".xyz",
                    _ => "",
                };
                format!("npr_load({name}, in.screen_uv){sw}")
            }
            ExprKind::Texture(t) => {
                let name = &self.ir.textures[t.0 as usize].name;
                let uv = if ctx.is_render { "in.uv" } else { "in.screen_uv" };
                format!("textureSample(tex_{name}, samp_{name}, {uv})")
            }
            ExprKind::Swizzle { base, components } => {
                let letters: String = components
                    .iter()
                    .map(|c| ['x', 'y', 'z', 'w'][*c as usize & 3])
                    .collect();
                format!("{}.{letters}", self.expr(*base, ctx))
            }
            ExprKind::Unary { op, operand } => {
                let o = self.expr(*operand, ctx);
                match op {
                    dsl::ast::UnOp::Neg => format!("(-{o})"),
                    dsl::ast::UnOp::Not => format!("(!{o})"),
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                format!("({} {} {})", self.expr(*lhs, ctx), op.as_str(), self.expr(*rhs, ctx))
            }
            ExprKind::Select { cond, then, otherwise } => format!(
                "select({}, {}, {})",
                self.expr(*otherwise, ctx),
                self.expr(*then, ctx),
                self.expr(*cond, ctx)
            ),
            ExprKind::Convert { conversion, operand } => {
                let o = self.expr(*operand, ctx);
                match conversion {
                    Conversion::IntToFloat => format!("f32({o})"),
                    Conversion::Splat(n) => format!("vec{n}<f32>({o})"),
                    Conversion::Rgb1 => format!("vec4<f32>({o}, 1.0)"),
                    Conversion::Rgb => format!("({o}).xyz"),
                }
            }
            ExprKind::Call { callee, args } => match callee {
                Callee::Intrinsic(i) => {
                    let a: Vec<String> = args.iter().map(|x| self.expr(*x, ctx)).collect();
                    match i {
                        Intrinsic::Construct(n) => format!("vec{n}<f32>({})", a.join(", ")),
                        // A zero vector normalizes to zero instead of NaN.
                        Intrinsic::Normalize => format!("({0} * inverseSqrt(max(dot({0}, {0}), 1e-30)))", a[0]),
                        Intrinsic::Project => format!("npr_project(frame.view_proj, {})", a[0]),
                        Intrinsic::ProjectOtherEye => format!("npr_project(frame.other_view_proj, {})", a[0]),
                        other => format!("{}({})", other.name(), a.join(", ")),
                    }
                }
                Callee::Operator(i) => {
                    let op = &stdlib::all()[*i as usize];
                    let mut a = Vec::new();
                    for (p, x) in op.params.iter().zip(args) {
                        match p.ty {
                            stdlib::Ty::Texture => a.push(self.handle(*x, ctx)),
                            stdlib::Ty::SampledTexture => {
                                a.push(self.handle(*x, ctx));
                                a.push(self.sampler(*x, ctx));
                            }
                            _ => a.push(self.expr(*x, ctx)),
                        }
                    }
                    format!("npr_{}({})", op.name, a.join(", "))
                }
            },
            ExprKind::Error => "0.0 /* error */".into(),
        }
    }

    fn handle(&self, id: ExprId, ctx: &PassCtx) -> String {
        match self.ir.expr(id).kind {
            ExprKind::Target(t) => ctx.target_names.get(&t).cloned().unwrap_or_default(),
            ExprKind::OtherEyeTarget(t) => ctx.other_target_names.get(&t).cloned().unwrap_or_default(),
            ExprKind::Texture(t) => format!("tex_{}", self.ir.textures[t.0 as usize].name),
            _ => String::from("/* not a handle */"),
        }
    }

    fn sampler(&self, id: ExprId, ctx: &PassCtx) -> String {
        match self.ir.expr(id).kind {
            ExprKind::Texture(t) => format!("samp_{}", self.ir.textures[t.0 as usize].name),
            _ => {
                debug_assert!(
                    ctx.uses_linear_sampler,
                    "a target passed as a sampled texture needs the clamp sampler"
                );
                "samp_linear_clamp".into()
            }
        }
    }
}

const IMAGE_VERTEX: &str = "struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(linear) screen_uv: vec2<f32>,
}

// One triangle that covers the viewport; screen_uv is (0,0) at the top-left corner.
@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> Varyings {
    let p = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    var out: Varyings;
    out.clip = vec4<f32>(p * 2.0 - vec2<f32>(1.0), 0.0, 1.0);
    out.screen_uv = vec2<f32>(p.x, 1.0 - p.y);
    return out;
}

";

fn builtin_wgsl(b: Builtin, is_render: bool) -> String {
    let _ = is_render;
    match b {
        Builtin::Uv => "in.uv".into(),
        Builtin::NormalWorld => "npr_unit(in.normal_world)".into(),
        Builtin::NormalView => "npr_unit((frame.view * vec4<f32>(in.normal_world, 0.0)).xyz)".into(),
        Builtin::PositionWorld => "in.position_world".into(),
        Builtin::PositionView => "(frame.view * vec4<f32>(in.position_world, 1.0)).xyz".into(),
        // The light camera is orthographic (w = 1), so this is already NDC.
        Builtin::PositionLight => "(frame.light_view_proj * vec4<f32>(in.position_world, 1.0)).xyz".into(),
        Builtin::Tangent => "npr_unit(in.tangent.xyz)".into(),
        Builtin::ViewDir => "npr_unit(frame.camera_pos.xyz - in.position_world)".into(),
        Builtin::Depth => "(-(frame.view * vec4<f32>(in.position_world, 1.0)).z)".into(),
        Builtin::FragCoord => "in.clip.xy".into(),
        Builtin::ScreenUv => "in.screen_uv".into(),
        Builtin::Resolution => "frame.resolution".into(),
        Builtin::Time => "frame.time".into(),
        Builtin::Frame => "i32(frame.frame_index)".into(),
        Builtin::Eye => "i32(frame.eye)".into(),
        Builtin::LightDir => "frame.light_dir.xyz".into(),
        Builtin::LightColor => "frame.light_color.xyz".into(),
        Builtin::LightIntensity => "frame.light_dir.w".into(),
        Builtin::CameraPosition => "frame.camera_pos.xyz".into(),
        Builtin::CameraNear => "frame.near".into(),
        Builtin::CameraFar => "frame.far".into(),
        Builtin::CameraFocal => "frame.focal.xy".into(),
        Builtin::CameraLeftEye => "frame.eye_left.xyz".into(),
        Builtin::CameraRightEye => "frame.eye_right.xyz".into(),
        Builtin::CameraForward => "frame.camera_forward.xyz".into(),
        Builtin::TangentScreen => "in.tangent_screen".into(),
        Builtin::BitangentScreen => "in.bitangent_screen".into(),
        Builtin::TangentScreenCenter => "in.tangent_screen_center".into(),
        Builtin::BitangentScreenCenter => "in.bitangent_screen_center".into(),
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

/// The analytic Jacobian of projection + viewport applied to a world direction.
const PROJECT_DIR_HELPER: &str = "// Pixels moved per metre along world direction `dir` at `world`: the derivative of
// pixel = (ndc.x, -ndc.y) * size / 2 + size / 2 with ndc = clip.xy / clip.w (quotient rule).
// Screen y points down, like frag_coord and dpdy.
fn npr_project_dir(vp: mat4x4<f32>, world: vec4<f32>, dir: vec3<f32>, size: vec2<f32>) -> vec2<f32> {
    let c = vp * world;
    let d = vp * vec4<f32>(dir, 0.0);
    // Behind or on the eye plane the triangle is clipped; stay finite.
    let w = max(c.w, 1e-6);
    let dndc = (d.xy * w - c.xy * d.w) / (w * w);
    return vec2<f32>(dndc.x, -dndc.y) * 0.5 * size;
}

";

/// The size in px of a pass at `scale` of the output, as the runner allocates
/// it (`runner::render::scaled_size`: rounded half up, at least 1).
fn pass_size_wgsl(scale: f64) -> String {
    if scale == 1.0 {
        "frame.resolution".into()
    } else {
        format!(
            "max(floor(frame.resolution * {} + vec2<f32>(0.5)), vec2<f32>(1.0))",
            fmt_f32(scale)
        )
    }
}

/// An f32 literal WGSL accepts, e.g. `0.5f`, `1e-5f`.
pub fn fmt_f32(v: f64) -> String {
    let f = v as f32;
    let f = if f.is_finite() {
        f
    } else if f.is_nan() {
        0.0
    } else {
        f32::MAX.copysign(f)
    };
    let s = format!("{f:?}");
    format!("{s}f")
}

fn const_wgsl(c: &Const, ty: Ty) -> String {
    match (c, ty) {
        (Const::Int(i), Ty::Float) => fmt_f32(*i as f64),
        (Const::Int(i), _) => format!("{}i", (*i).clamp(i32::MIN as i64, i32::MAX as i64)),
        (Const::Float(f), Ty::Int) => format!("{}i", *f as i32),
        (Const::Float(f), _) => fmt_f32(*f),
        (Const::Bool(b), _) => b.to_string(),
        (Const::Vec(v), _) => {
            let n = v.len();
            let parts: Vec<String> = v.iter().map(|x| fmt_f32(*x)).collect();
            format!("vec{n}<f32>({})", parts.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn per_fragment_builtins_are_exactly_those_read_from_the_fragment_inputs() {
        // The typechecker rejects `Builtin::is_per_fragment` values in vertex
        // modifiers; the vertex shader has no `in`, so the two must agree.
        for (spelling, b) in Builtin::SPELLINGS {
            let wgsl = builtin_wgsl(*b, true);
            assert_eq!(wgsl.contains("in."), b.is_per_fragment(), "`{spelling}` emits `{wgsl}`");
        }
    }
}
