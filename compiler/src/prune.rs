//! Prune: keep only what the output depends on.
//!
//! Walks back from the output target: live passes, live targets, and the
//! parameters, builtins, textures and operators their expressions use.
//! Everything else is dropped and listed in the report with the reason.

use crate::dag::{pass_roots, PassGraph};
use crate::ir::*;
use crate::report::Report;
use std::collections::BTreeSet;

#[derive(Debug, Clone, Default)]
pub struct Live {
    pub passes: Vec<PassId>,
    pub targets: BTreeSet<TargetRef>,
    pub params: BTreeSet<ParamId>,
    pub textures: BTreeSet<TextureId>,
}

pub fn prune(ir: &Ir, graph: &PassGraph, report: &mut Report) -> Live {
    let mut live = Live::default();
    let Some(output) = ir.output else {
        return live;
    };
    live.targets.insert(output);
    // Reverse execution order: every reader is visited before what it reads.
    for pid in graph.order.iter().rev() {
        let pass = ir.pass(*pid);
        let live_outputs: Vec<&PassOutput> = pass
            .outputs
            .iter()
            .enumerate()
            .filter(|(i, _)| {
                live.targets.contains(&TargetRef {
                    pass: *pid,
                    output: *i as u32,
                })
            })
            .map(|(_, o)| o)
            .collect();
        if live_outputs.is_empty() {
            report.removed(format!("pass `{}`", pass.name), "the output does not depend on it");
            continue;
        }
        for (i, o) in pass.outputs.iter().enumerate() {
            if !live.targets.contains(&TargetRef {
                pass: *pid,
                output: i as u32,
            }) {
                report.removed(format!("target `{}.{}`", pass.name, o.name), "nothing reads it");
            }
        }
        live.passes.push(*pid);
        let mut roots: Vec<ExprId> = live_outputs.iter().map(|o| o.value).collect();
        roots.extend(Ir::vertex_roots(pass));
        for id in ir.reachable(&roots) {
            match ir.expr(id).kind {
                ExprKind::Target(t) | ExprKind::OtherEyeTarget(t) => {
                    live.targets.insert(t);
                }
                ExprKind::Param(p) => {
                    live.params.insert(p);
                }
                ExprKind::Texture(t) => {
                    live.textures.insert(t);
                }
                _ => {}
            }
        }
        for l in &pass.lets {
            if !ir.reachable(&roots).contains(&l.value) {
                report.removed(
                    format!("let `{}` in pass `{}`", l.name, pass.name),
                    "no live output uses it",
                );
            }
        }
    }
    live.passes.reverse();
    for (i, p) in ir.params.iter().enumerate() {
        if !live.params.contains(&ParamId(i as u32)) {
            report.removed(format!("param `{}`", p.name), "no live expression reads it");
        }
    }
    for (i, t) in ir.textures.iter().enumerate() {
        if !live.textures.contains(&TextureId(i as u32)) {
            report.removed(format!("texture `{}`", t.name), "no live expression reads it");
        }
    }
    let _ = pass_roots;
    live
}
