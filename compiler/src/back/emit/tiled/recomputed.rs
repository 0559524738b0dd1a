//! The targets a tiled pass computes in its tiles (`schedule/recompute.rs`):
//! what their producers read, which the module declares too, and each
//! producer's function, `npr_compute_<t>(q)`, the texel a store would have
//! left at q.

use super::library::Function;
use super::tiles::stored_texel;
use crate::back::emit::expr::KindCtx;
use crate::back::emit::uses::Uses;
use crate::back::emit::{Emitter, PassCtx};
use crate::ir::*;
use npr_abi::manifest::TargetCopy;
use std::collections::BTreeMap;
use std::fmt::Write;

/// A target computed in a tiled pass's tiles: what its function evaluates.
pub(super) struct Producer {
    pub target: TargetRef,
    /// The producer's expressions for the target, operands first.
    nodes: Vec<ExprId>,
    /// How often each is read as a value there (names its `let`s).
    value_uses: BTreeMap<ExprId, usize>,
}

impl Emitter<'_> {
    /// The producers of the targets computed in `tiling`'s tiles, with what
    /// they read added to `uses` (the module declares it) and their formats'
    /// rounding helpers.
    pub(super) fn recomputed_uses(&self, tiling: &Tiling, uses: &mut Uses) -> Vec<Producer> {
        let mut producers = Vec::new();
        for r in tiling.reads.iter().filter(|r| r.source == TileSource::Recompute) {
            let o = &self.ir.pass(r.target.pass).outputs[r.target.output as usize];
            let nodes = self.ir.reachable(&[o.value]);
            let mut own = self.uses(&nodes, &[o.value], &[]);
            let value_uses = std::mem::take(&mut own.value_uses);
            uses.absorb(own);
            uses.store(o.format);
            producers.push(Producer {
                target: r.target,
                nodes,
                value_uses,
            });
        }
        producers
    }

    /// `npr_compute_<t>(q)`: the texel producer `p`'s target would hold at
    /// q, as `textureLoad` would return it. Its pixel is set up as the tiled
    /// entry sets up the pass's own (`in.clip` at the texel centre, the
    /// prologue's `screen_uv`), which is how the producer's fragment saw it.
    /// The copies its calls name join `ctx`'s.
    pub(super) fn recompute_function(&self, p: &Producer, ctx: &PassCtx) -> Function {
        let pass = self.ir.pass(p.target.pass);
        let o = &pass.outputs[p.target.output as usize];
        let name = &ctx.target_names[&(TargetCopy::This, p.target)];
        let mut body = String::new();
        let _ = writeln!(
            body,
            " -> vec4<f32> {{
    var in: Varyings;
    in.clip = vec4<f32>(vec2<f32>(q) + vec2<f32>(0.5), 0.0, 1.0);
    in.screen_uv = in.clip.xy / {};",
            crate::back::emit::render::pass_size_wgsl(pass.scale)
        );
        let mut own = PassCtx {
            kind: KindCtx::of(&pass.kind),
            named: BTreeMap::new(),
            target_names: ctx.target_names.clone(),
            uses_linear_sampler: ctx.uses_linear_sampler,
            runtime_conditions: ctx.runtime_conditions.clone(),
            per_binding: Some(Default::default()),
        };
        self.emit_lets(&mut body, pass, &p.nodes, &p.value_uses, &mut own);
        self.output_comment(&mut body, o);
        let v = self.expr(o.value, &own);
        let _ = write!(body, "    return {};\n}}", stored_texel(o.format, &v));
        if let (Some(mine), Some(theirs)) = (&ctx.per_binding, own.per_binding) {
            mine.borrow_mut().extend(theirs.into_inner());
        }
        Function {
            doc: format!(
                "// `{}` of pass `{}` ({}), computed at texel q instead of stored.\n",
                self.ir.target_name(p.target),
                pass.name,
                self.line_of(pass.name_span),
            ),
            name: format!("npr_compute_{name}"),
            params: vec![("q".into(), "vec2<i32>".into())],
            rest: body,
        }
    }
}
