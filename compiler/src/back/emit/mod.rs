//! Emit: one readable WGSL module per live pass, and the manifest.
//!
//! Layout of a module: a header naming the pass and its `.npr` line; the
//! bindings it uses (`bindings.rs`); the helpers and stdlib operators it
//! calls (`helpers.rs`); the vertex shader of its kind (`render.rs`,
//! `image.rs`, `lines.rs`); the fragment shader with one `let` per user `let`, per
//! shared subexpression and per target read more than once, each commented
//! with the `.npr` line it came from. Expressions are emitted by one
//! kind-independent emitter (`expr.rs`), which asks its `KindCtx` what
//! differs by kind; `emit_pass` matches on the kind for the module's parts,
//! and each kind's file (`render.rs`, `image.rs`, `lines.rs`, `compute.rs`,
//! `tiled/`) writes its own entry points.

mod bindings;
pub mod compute;
mod compute_pixels;
mod expr;
mod helpers;
mod image;
mod lines;
pub mod manifest;
mod render;
mod tiled;
mod uses;

pub use expr::fmt_f32;

use crate::back::allocate::Allocation;
use crate::ir::*;
use expr::KindCtx;
use helpers::{LOAD_HELPER, PROJECT_HELPER};
use npr_abi::manifest::{Attribute, Binding, ParamBinding};
use npr_diag::SourceMap;
use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// What one emitted pass needs from the runner.
pub struct EmittedPass {
    pub wgsl: String,
    pub bindings: Vec<Binding>,
    /// Group 1 bindings after the `Object` block (binding 0): per-object textures.
    pub object_bindings: Vec<Binding>,
    pub attributes: Vec<Attribute>,
    /// The shader declares `npr_abi::formats::HALF_ROUNDING_OVERRIDE`.
    pub device_half_rounding: bool,
}

pub struct Emitter<'a> {
    pub ir: &'a Ir,
    pub alloc: &'a Allocation,
    pub bindings: &'a [ParamBinding],
    pub sources: &'a SourceMap,
}

/// An expression nested deeper than this (in naga's count: parentheses and
/// call arguments) gets a `let` of its own, so that no emitted expression
/// comes near naga's parser recursion limit (200, statements included),
/// however deep the `.npr` expression is, and the emitter's own recursion
/// stays this shallow.
const SPLIT_DEPTH: usize = 32;
/// An expression whose inline WGSL would be longer than this many bytes gets
/// a `let` too: `normalize(a)` repeats `a`, so nested `normalize`s grew the
/// text threefold per level.
const SPLIT_LEN: usize = 16 * 1024;

/// What [`Emitter::shape`] estimates of a node's inline WGSL.
#[derive(Debug, Clone, Copy)]
struct Shape {
    depth: usize,
    len: usize,
}

impl Shape {
    /// A node emitted as the name of its `let`.
    const NAME: Shape = Shape { depth: 1, len: 12 };
    /// A node without operands (a builtin may be three calls deep itself).
    const LEAF: Shape = Shape { depth: 3, len: 80 };
}

/// The state of the expression emitter within one pass.
struct PassCtx {
    kind: KindCtx,
    /// Names given to shared or user-named nodes, in emission order.
    named: BTreeMap<ExprId, String>,
    /// The binding name of each target read, per copy.
    target_names: BTreeMap<(TargetCopy, TargetRef), String>,
    uses_linear_sampler: bool,
    /// `select`s whose condition goes through `npr_runtime_bool`
    /// (`Uses::runtime_conditions`).
    runtime_conditions: BTreeSet<ExprId>,
    /// In a tiled module, the copies of handle-taking functions that its
    /// calls name, as (function, bindings), collected as the calls are
    /// written (`tiled/library.rs`); `None` in any other module, whose
    /// calls pass the handles.
    per_binding: Option<RefCell<tiled::CopyCalls>>,
}

/// The name of the copy of `function` whose handle parameters are bound,
/// in order, to `bindings`: what a tiled module's calls name (`expr.rs`)
/// and the copy `tiled/library.rs` makes.
fn copy_name(function: &str, bindings: &[String]) -> String {
    format!("{function}__{}", bindings.join("__"))
}

impl PassCtx {
    /// The context of a pass of kind `kind` whose bindings are named
    /// `target_names`, before any `let` is named.
    fn new(kind: &PassKind, target_names: BTreeMap<(TargetCopy, TargetRef), String>, uses: &uses::Uses) -> PassCtx {
        PassCtx {
            kind: KindCtx::of(kind),
            named: BTreeMap::new(),
            target_names,
            uses_linear_sampler: uses.linear_sampler,
            runtime_conditions: uses.runtime_conditions.clone(),
            per_binding: None,
        }
    }
}

impl Emitter<'_> {
    fn line_of(&self, span: npr_diag::Span) -> String {
        let (line, _) = self.sources.line_col(span.file, span.start);
        let name = self.sources.get(span.file).map(|f| f.name.as_str()).unwrap_or("?");
        let file = std::path::Path::new(name)
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        format!("{file}:{line}")
    }

    fn snippet(&self, span: npr_diag::Span) -> String {
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
        // A compute pass has no fragments: its own layout (`compute.rs`).
        if let PassKind::Compute { domain, .. } = &pass.kind {
            return self.emit_compute(pid, *domain);
        }
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
        // A tiled image pass is a compute module (`tiled/`).
        if let Some(tiling) = self.ir.tiled.get(&pid) {
            return self.emit_tiled(pid, tiling, &live_outputs);
        }
        let frag_roots: Vec<ExprId> = live_outputs.iter().map(|(_, o)| o.value).collect();
        let frag_nodes = self.ir.reachable(&frag_roots);
        let vert_nodes = self.ir.reachable(&pass.roots().vertex);
        let uses = self.uses(&frag_nodes, &frag_roots, &vert_nodes);
        // Per kind: whether the frame block is bound, and the vertex attributes.
        let (uses_frame, attributes) = match &pass.kind {
            // The vertex shader projects with the frame's matrices.
            PassKind::Render { vertex, .. } => (true, render::attributes(vertex, &uses)),
            // The prologue's `screen_uv` divides by the pass size.
            PassKind::Image { .. } => (true, Vec::new()),
            PassKind::Compute { .. } => (uses.expressions_read_frame(), Vec::new()),
            // The fragment prologue reads the frame's resolution; the strip
            // vertex is not a mesh attribute.
            PassKind::Lines(_) => (true, Vec::new()),
        };

        let mut w = self.module_header(pass);
        let declared = self.declare(&pass.kind, &uses, uses_frame);
        w.push_str(&declared.text);
        w.push('\n');
        self.emit_helpers(&mut w, &uses);

        let mut ctx = PassCtx::new(&pass.kind, declared.target_names, &uses);
        match &pass.kind {
            PassKind::Render { view, vertex, .. } => {
                self.render_vertex(&mut w, pass, (*view, vertex), &attributes, &uses.builtins, &mut ctx)
            }
            PassKind::Image { .. } | PassKind::Compute { .. } => {
                w.push_str(image::IMAGE_VARYINGS);
                w.push_str(image::IMAGE_VERTEX);
            }
            PassKind::Lines(lines) => self.lines_vertex(&mut w, lines),
        }
        let emitted = |wgsl| EmittedPass {
            wgsl,
            bindings: declared.bindings,
            object_bindings: declared.object_bindings,
            attributes,
            device_half_rounding: uses.repeats_half_stores(),
        };
        if live_outputs.is_empty() {
            // Kept for its depth alone (a later pass tests against it): the
            // fragment stage writes no colour.
            let _ = writeln!(
                w,
                "// No target of this pass is read; it runs for the depth a later pass tests against.\n@fragment\nfn fs_main(in: Varyings) {{\n}}"
            );
            return emitted(w);
        }
        // Fragment shader.
        let outputs: Vec<&PassOutput> = live_outputs.iter().map(|(_, o)| *o).collect();
        w.push_str(&fragment_outputs(&outputs));
        match &pass.kind {
            PassKind::Render { .. } => render::fragment_prologue(&mut w, pass.scale),
            PassKind::Lines(_) => {
                render::fragment_prologue(&mut w, pass.scale);
                w.push_str(lines::FRAGMENT_VISIBILITY);
            }
            PassKind::Image { .. } | PassKind::Compute { .. } => {
                w.push_str(image::FRAGMENT_SIGNATURE);
                w.push_str(&image::pixel_prologue(pass.scale));
            }
        }
        w.push_str(&self.pixel_body(pass, &frag_nodes, &uses, &outputs, &mut ctx));
        w.push_str("}\n");
        emitted(w)
    }

    /// The module's first lines: the pass, its `.npr` line and the style.
    fn module_header(&self, pass: &Pass) -> String {
        format!(
            "// npr: pass `{}` ({}), style \"{}\"\n// Generated by the npr compiler; edit the .npr file, not this one.\n\n",
            pass.name,
            self.line_of(pass.name_span),
            self.ir.style_name
        )
    }

    /// The body of the function that computes one pixel, after its
    /// prologue: the `let`s, then `outputs` (the live ones, in order) into
    /// a `FragOut`, returned; the caller closes the function.
    fn pixel_body(
        &self,
        pass: &Pass,
        frag_nodes: &[ExprId],
        uses: &uses::Uses,
        outputs: &[&PassOutput],
        ctx: &mut PassCtx,
    ) -> String {
        let mut w = String::new();
        ctx.named.clear();
        self.emit_lets(&mut w, pass, frag_nodes, &uses.value_uses, ctx);
        w.push_str("    var out: FragOut;\n");
        for o in outputs {
            self.output_comment(&mut w, o);
            let v = self.expr(o.value, ctx);
            let _ = writeln!(w, "    out.o_{} = {v};", o.name);
        }
        w.push_str("    return out;\n");
        w
    }

    /// The helpers the expressions call (`npr_load`, `npr_project`), then
    /// the stdlib operators: the WGSL a module includes as written.
    fn emit_helpers(&self, w: &mut String, uses: &uses::Uses) {
        if uses.reads_targets() {
            w.push_str(LOAD_HELPER);
            w.push('\n');
        }
        if uses.project {
            w.push_str(PROJECT_HELPER);
            w.push('\n');
        }
        for g in &uses.ramps {
            w.push_str(&helpers::ramp_helper(&self.ir.params[g.0 as usize].name));
            w.push('\n');
        }
        if !uses.runtime_conditions.is_empty() {
            w.push_str(helpers::RUNTIME_BOOL_HELPER);
            w.push('\n');
        }
        if uses.repeats_half_stores() {
            w.push_str(&helpers::round_f16_helper());
            w.push('\n');
        }
        for f in &uses.stored {
            w.push_str(&helpers::stored_helper(*f));
            w.push('\n');
        }
        self.emit_operators(w, &uses.operators);
    }

    /// The stdlib operators called (dependencies first), after the shared
    /// helper snippets they use.
    fn emit_operators(&self, w: &mut String, operators: &BTreeSet<usize>) {
        let closure = operator_closure(operators);
        let mut snippets: Vec<&str> = Vec::new();
        for op in &closure {
            for s in npr_stdlib::all()[*op].snippets {
                if !snippets.contains(s) {
                    snippets.push(s);
                }
            }
        }
        for s in snippets {
            if let Some(src) = npr_stdlib::snippets::find(s) {
                let _ = writeln!(w, "// ---- stdlib helpers `{s}`");
                w.push_str(src.trim_end());
                w.push_str("\n\n");
            }
        }
        for op in closure {
            let o = &npr_stdlib::all()[op];
            let _ = writeln!(w, "// ---- stdlib operator `{}` ({})", o.name, o.reference);
            w.push_str(o.wgsl.trim_end());
            w.push_str("\n\n");
        }
    }

    /// Name user `let`s, shared subexpressions and targets read as values
    /// more than once, so each is computed (each target loaded) once.
    ///
    /// A target read is keyed by (copy, target), not by node: `thin.e.x` and
    /// `thin.e.y` are two `Target` nodes reading the same texel, so they
    /// share one `npr_load`, named at the first of them (operands come
    /// before users in `nodes`, so every user follows it).
    fn emit_lets(
        &self,
        w: &mut String,
        pass: &Pass,
        nodes: &[ExprId],
        value_uses: &BTreeMap<ExprId, usize>,
        ctx: &mut PassCtx,
    ) {
        let mut uses: BTreeMap<ExprId, usize> = BTreeMap::new();
        for n in nodes {
            for o in self.ir.operands(*n) {
                *uses.entry(o).or_default() += 1;
            }
        }
        let user_lets: BTreeMap<ExprId, &Let> = pass.lets.iter().map(|l| (l.value, l)).collect();
        let read_key = |id: ExprId| match self.ir.expr(id).kind {
            ExprKind::Target { target, copy } => Some((copy, target)),
            _ => None,
        };
        let mut reads: BTreeMap<(TargetCopy, TargetRef), Vec<ExprId>> = BTreeMap::new();
        for n in nodes {
            if let Some(key) = read_key(*n) {
                reads.entry(key).or_default().push(*n);
            }
        }
        let mut shapes: BTreeMap<ExprId, Shape> = BTreeMap::new();
        for n in nodes {
            let e = self.ir.expr(*n);
            if let Some(key) = read_key(*n) {
                self.name_target_read(w, &reads[&key], value_uses, &user_lets, ctx);
                continue;
            }
            let shape = self.shape(*n, &shapes, ctx);
            shapes.insert(*n, shape);
            let trivial = matches!(
                e.kind,
                ExprKind::Const(_)
                    | ExprKind::Param(_)
                    | ExprKind::Builtin(_)
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
                self.user_let_comment(w, l);
                let name = format!("l_{}", l.name);
                let _ = writeln!(w, "    let {name} = {v};");
                ctx.named.insert(*n, name);
            } else if !trivial && uses.get(n).copied().unwrap_or(0) > 1 {
                let v = self.expr(*n, ctx);
                let name = format!("e{}", n.0);
                let _ = writeln!(w, "    let {name} = {v}; // shared: {}", self.snippet(e.span));
                ctx.named.insert(*n, name);
            } else if !trivial && (shape.depth > SPLIT_DEPTH || shape.len > SPLIT_LEN) {
                let v = self.expr(*n, ctx);
                let name = format!("e{}", n.0);
                let _ = writeln!(w, "    let {name} = {v}; // split: {}", self.snippet(e.span));
                ctx.named.insert(*n, name);
            }
            if ctx.named.contains_key(n) {
                shapes.insert(*n, Shape::NAME);
            }
        }
    }

    /// How deeply naga will nest (parentheses and call arguments) and how
    /// long the WGSL of node `id` will be if it is emitted inline, from its
    /// operands' shapes (operands come first in emission order).
    fn shape(&self, id: ExprId, shapes: &BTreeMap<ExprId, Shape>, ctx: &PassCtx) -> Shape {
        if ctx.named.contains_key(&id) {
            return Shape::NAME;
        }
        let operands = self.ir.operands(id);
        if operands.is_empty() {
            return Shape::LEAF;
        }
        // `normalize(a)` writes `a` three times, three calls deep.
        let (levels, copies) = match self.ir.expr(id).kind {
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Normalize),
                ..
            } => (4, 3),
            _ => (1, 1),
        };
        let of = |o: &ExprId| shapes.get(o).copied().unwrap_or(Shape::LEAF);
        Shape {
            depth: levels + operands.iter().map(|o| of(o).depth).max().unwrap_or(0),
            len: 24 + copies * operands.iter().map(|o| of(o).len).sum::<usize>(),
        }
    }

    /// At the first node of `group` (all reads of one target for one eye):
    /// when the group is read as a value more than once, one `let` loads
    /// it, named after the user `let` that binds it if any, and every node
    /// of the group refers to that name.
    fn name_target_read(
        &self,
        w: &mut String,
        group: &[ExprId],
        value_uses: &BTreeMap<ExprId, usize>,
        user_lets: &BTreeMap<ExprId, &Let>,
        ctx: &mut PassCtx,
    ) {
        let first = group[0];
        if ctx.named.contains_key(&first) {
            return;
        }
        let reads: usize = group.iter().map(|n| value_uses.get(n).copied().unwrap_or(0)).sum();
        if reads <= 1 {
            return;
        }
        let v = self.expr(first, ctx);
        let name = match group.iter().find_map(|n| user_lets.get(n)) {
            Some(l) => {
                self.user_let_comment(w, l);
                let name = format!("l_{}", l.name);
                let _ = writeln!(w, "    let {name} = {v};");
                name
            }
            None => {
                let name = format!("e{}", first.0);
                let span = self.ir.expr(first).span;
                let _ = writeln!(w, "    let {name} = {v}; // shared: {}", self.snippet(span));
                name
            }
        };
        for n in group {
            ctx.named.insert(*n, name.clone());
        }
    }

    /// `// file:line: out name: format = expression`, above the line that
    /// computes an output.
    fn output_comment(&self, w: &mut String, o: &PassOutput) {
        let _ = writeln!(
            w,
            "    // {}: out {}: {} = {}",
            self.line_of(o.span),
            o.name,
            o.format.name(),
            self.snippet(self.ir.expr(o.value).span)
        );
    }

    fn user_let_comment(&self, w: &mut String, l: &Let) {
        let _ = writeln!(
            w,
            "    // {}: let {} = {}",
            self.line_of(l.span),
            l.name,
            self.snippet(self.ir.expr(l.value).span)
        );
    }
}

/// `FragOut`: one location per live output, in order.
fn fragment_outputs(outputs: &[&PassOutput]) -> String {
    let mut w = String::from("struct FragOut {\n");
    for (loc, o) in outputs.iter().enumerate() {
        let ty = crate::ir::Ty::float_vec(o.format.channels()).wgsl();
        let _ = writeln!(w, "    @location({loc}) o_{}: {ty}, // {}", o.name, o.format.name());
    }
    w.push_str("}\n\n");
    w
}

/// `roots` and the operators they depend on, dependencies first.
fn operator_closure(roots: &BTreeSet<usize>) -> Vec<usize> {
    let mut order = Vec::new();
    fn visit(i: usize, order: &mut Vec<usize>, depth: usize) {
        if order.contains(&i) || depth > 16 {
            return;
        }
        for d in npr_stdlib::all()[i].depends {
            if let Some(j) = npr_stdlib::all().iter().position(|o| o.name == *d) {
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
