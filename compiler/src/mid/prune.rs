//! Prune: keep only what the output depends on.
//!
//! Walks back from the output target: live passes, live targets, and the
//! parameters, builtins, textures and operators their expressions use. A
//! live pass's `depth: test(other)` keeps `other` live, even when none of
//! its targets is read (it then runs for its depth alone).
//! Everything else is dropped and listed in the report with the reason.

use crate::ir::*;
use crate::mid::dag::PassGraph;
use crate::report::Report;
use std::collections::BTreeSet;

#[derive(Debug, Clone, Default)]
pub struct Live {
    pub passes: Vec<PassId>,
    pub targets: BTreeSet<TargetRef>,
    pub params: BTreeSet<ParamId>,
    pub textures: BTreeSet<TextureId>,
    /// Targets read with `previous(...)`: they outlive the frame.
    pub history: BTreeSet<TargetRef>,
    /// Per-object values of compute passes that a live pass reads: (pass, slot).
    pub values: BTreeSet<(PassId, u32)>,
    /// Passes whose kept depth a live pass tests against.
    pub depth: BTreeSet<PassId>,
}

impl Live {
    /// The live targets of pass `pass`, in output order.
    pub fn targets_of(&self, pass: PassId) -> Vec<TargetRef> {
        self.targets.iter().filter(|t| t.pass == pass).copied().collect()
    }

    /// The live slots of a compute pass, in slot order.
    pub fn value_slots(&self, pass: PassId) -> Vec<u32> {
        self.values
            .iter()
            .filter(|(p, _)| *p == pass)
            .map(|(_, s)| *s)
            .collect()
    }
}

pub fn prune(ir: &Ir, graph: &PassGraph, report: &mut Report) -> Live {
    let Some(output) = ir.output else {
        return Live::default();
    };
    // A `previous(...)` read keeps its target alive although it is no
    // dependency within the frame (its pass may run later, or be the reader
    // itself), so walk again from the output plus every history target found
    // until no new one appears. Each round only grows the seed set, which is
    // bounded by the number of targets.
    let mut seeds = BTreeSet::from([output]);
    let live = loop {
        let live = walk(ir, graph, &seeds);
        let grown: BTreeSet<TargetRef> = seeds.union(&live.history).copied().collect();
        if grown == seeds {
            break live;
        }
        seeds = grown;
    };
    report_removed(ir, graph, &live, report);
    live
}

/// One walk back from `seeds` in reverse execution order: every reader is
/// visited before what it reads within the frame.
fn walk(ir: &Ir, graph: &PassGraph, seeds: &BTreeSet<TargetRef>) -> Live {
    let mut live = Live {
        targets: seeds.clone(),
        ..Live::default()
    };
    for pid in graph.order.iter().rev() {
        let mut roots = live_roots(ir, *pid, &live);
        if roots.is_empty() && !live.depth.contains(pid) {
            continue;
        }
        live.passes.push(*pid);
        if let Some((tested, _)) = ir.pass(*pid).depth_test() {
            live.depth.insert(tested);
        }
        // The host's depth, drawn into this pass's depth buffer.
        if let Some((input, _)) = ir.pass(*pid).input_depth_test() {
            live.textures.insert(input);
        }
        // A state read inside its own pass (`StateOld`) makes that value
        // live too, which adds roots of this same pass: repeat until none.
        loop {
            let before = live.values.len();
            for id in ir.reachable(&roots) {
                match ir.expr(id).kind {
                    ExprKind::Target { target, copy } => {
                        live.targets.insert(target);
                        if copy == TargetCopy::Previous {
                            live.history.insert(target);
                        }
                    }
                    ExprKind::Param(p)
                    | ExprKind::Call {
                        callee: Callee::Intrinsic(Intrinsic::Ramp(p)),
                        ..
                    } => {
                        live.params.insert(p);
                    }
                    ExprKind::Texture(t) => {
                        live.textures.insert(t);
                    }
                    ExprKind::ObjectValue { pass, slot } => {
                        live.values.insert((pass, slot));
                    }
                    ExprKind::StateOld { slot } => {
                        live.values.insert((*pid, slot));
                    }
                    _ => {}
                }
            }
            if live.values.len() == before {
                break;
            }
            roots = live_roots(ir, *pid, &live);
        }
    }
    live.passes.reverse();
    live
}

/// The expressions a pass must evaluate for its live outputs and values
/// ([`Pass::roots`] of those alone): the live outputs' values, what the
/// pass evaluates whenever it runs (also when it runs for its depth
/// alone), the live values and, for any of those, what they need. Empty
/// when the pass is dead.
fn live_roots(ir: &Ir, pid: PassId, live: &Live) -> Vec<ExprId> {
    let all = ir.pass(pid).roots();
    let live_outputs: Vec<u32> = live.targets_of(pid).iter().map(|t| t.output).collect();
    let mut roots: Vec<ExprId> = live_outputs.iter().map(|i| all.outputs[*i as usize]).collect();
    if !roots.is_empty() || live.depth.contains(&pid) {
        roots.extend(&all.vertex);
        roots.extend(&all.settings);
    }
    let mut any_value = false;
    for (slot, v) in all.values.iter().enumerate() {
        if live.values.contains(&(pid, slot as u32)) {
            roots.extend(v);
            any_value = true;
        }
    }
    if any_value {
        // A pass over pixels reads its ID target for every live value.
        roots.extend(all.key);
    }
    roots
}

/// A warning for each compute pass that no live pass reads: it is removed,
/// which is rarely what its author meant.
pub fn unread_compute_passes(ir: &Ir, live: &Live) -> Vec<npr_diag::Diagnostic> {
    ir.passes
        .iter()
        .enumerate()
        .filter(|(i, p)| matches!(p.kind, PassKind::Compute { .. }) && !live.passes.contains(&PassId(*i as u32)))
        .map(|(_, p)| {
            npr_diag::Diagnostic::warning(
                npr_diag::codes::UNREAD_COMPUTE,
                format!("compute pass `{}` is never read, so it is removed", p.name),
            )
            .with_primary(p.name_span, "no live pass reads its values")
            .with_help(match p.kind.values().first() {
                Some(v) => format!(
                    "read its values per object in a render or compute pass, e.g. `{}.{}`",
                    p.name, v.name
                ),
                None => "give it a value with `reduce`, `out` or `state`, and read it".to_string(),
            })
        })
        .collect()
}

/// Everything the walk dropped, with the reason, in execution order.
fn report_removed(ir: &Ir, graph: &PassGraph, live: &Live, report: &mut Report) {
    for pid in graph.order.iter().rev() {
        let pass = ir.pass(*pid);
        if !live.passes.contains(pid) {
            report.removed(format!("pass `{}`", pass.name), "the output does not depend on it");
            continue;
        }
        for (slot, v) in pass.kind.values().iter().enumerate() {
            if !live.values.contains(&(*pid, slot as u32)) {
                report.removed(format!("value `{}.{}`", pass.name, v.name), "nothing reads it");
            }
        }
        let roots = live_roots(ir, *pid, live);
        for (i, o) in pass.outputs.iter().enumerate() {
            if !live.targets.contains(&TargetRef {
                pass: *pid,
                output: i as u32,
            }) {
                report.removed(format!("target `{}.{}`", pass.name, o.name), "nothing reads it");
            }
        }
        let reachable = ir.reachable(&roots);
        for l in &pass.lets {
            if !reachable.contains(&l.value) {
                report.removed(
                    format!("let `{}` in pass `{}`", l.name, pass.name),
                    "no live output uses it",
                );
            }
        }
    }
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
}
