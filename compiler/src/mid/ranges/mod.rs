//! Value ranges proved by the compiler (issue 49): a sound interval
//! analysis over the IR after overrides and before specialisation (so that
//! a param nobody fixed still ranges over its declared range), run in
//! every compile.
//!
//! It starts from the ranges of what a pass reads (`inputs.rs`: params
//! over their declared ranges or at their `--set` values, builtins,
//! textures), propagates
//! through every expression (`eval.rs`, with the interval arithmetic of
//! `interval.rs` and per-component vectors of `value.rs`), through each
//! target's format into the passes that read it, and across frames: a
//! `previous(...)` read starts at the target's clear value and is joined
//! with what the frame stores until nothing grows, or widened to the
//! format's whole range after [`MAX_FRAME_ROUNDS`] rounds; a per-object
//! `state` starts at its first value and is joined with its update the
//! same way, its growing bounds then widened to thresholds (`widen`).
//! An `if` argument that narrows another argument is split (`paths.rs`).
//! Each operation whose operands reach a value where WGSL's result is
//! undefined or not finite becomes a warning (`domains.rs`); each live
//! target's proved range is kept for `npr check --ranges` and
//! `npr compile --report` (`text.rs`).
//!
//! Sound means: every f32 value the shader can compute lies in the range
//! (under the runtime contract of `inputs.rs`); "finite" is never claimed
//! when it is not proved. `tests.rs` checks that with random expressions at
//! random points.

pub mod domains;
pub mod eval;
pub mod inputs;
pub mod interval;
mod paths;
pub mod text;
pub mod value;

#[cfg(test)]
mod tests;

use crate::ir::*;
use crate::mid::prune::Live;
use eval::{Eval, Finding, Reads};
use interval::Iv;
use npr_abi::manifest::{Blend, ReduceOp};
use npr_diag::Diagnostic;
use value::Val;

/// Rounds of frames before a history read is widened to its format's range.
pub const MAX_FRAME_ROUNDS: usize = 4;

/// One live target's proved range.
#[derive(Debug, Clone)]
pub struct TargetRange {
    pub target: TargetRef,
    pub name: String,
    pub format: npr_abi::Format,
    /// What the target holds: stored through its format, the clear value
    /// joined.
    pub range: Val,
    /// Whether the value written (before the format's store) is proved
    /// finite: a unorm store hides a NaN as some number in [0, 1].
    pub value_finite: bool,
    /// What stops the proof that the value is finite (empty when it is):
    /// each node's span and what it is.
    pub stops: Vec<(npr_diag::Span, String)>,
}

/// The analysis's result.
#[derive(Debug, Clone)]
pub struct Ranges {
    pub targets: Vec<TargetRange>,
    pub warnings: Vec<Diagnostic>,
    /// Operations the analysis cannot prove defined, whose operands come
    /// from values it knows nothing of (no warning: see `domains.rs`).
    pub unproved: Vec<Finding>,
    /// Frame rounds the history reads took (0 without history).
    pub frame_rounds: usize,
    pub history_widened: bool,
}

/// Analyse the live passes of `ir` (before specialisation, so that a
/// param not fixed still ranges over its declared range): `params` says
/// how each ranges (`inputs::param_range`).
pub fn analyse(ir: &Ir, live: &Live, params: &[inputs::ParamRange]) -> Ranges {
    let mut reads = Reads::default();
    for t in &live.history {
        let pass = ir.pass(t.pass);
        let n = pass.outputs[t.output as usize].format.channels() as usize;
        // The first frame's previous copy: the clear value, or zeros where
        // the runtime starts it empty.
        reads
            .history
            .insert(*t, clear_value(pass, n).join(&Val::splat(Iv::point(0.0), n)));
    }
    let mut rounds = 0;
    let mut widened = false;
    loop {
        rounds += 1;
        let (targets, findings, states) = frame(ir, live, params, &mut reads);
        // Grow each history read by what this frame stored, and each
        // state by its update (past the rounds, to anything).
        let mut grown = false;
        for (key, (old, update)) in states {
            let joined = old.join(&update);
            let new = if rounds >= MAX_STATE_ROUNDS {
                Val::top(update.comps.len())
            } else if rounds >= MAX_FRAME_ROUNDS {
                widen(&old, &joined)
            } else {
                joined
            };
            if reads.states.get(&key) != Some(&new) {
                grown = true;
                reads.states.insert(key, new);
            }
        }
        for t in &live.history {
            let stored = reads.targets.get(t).cloned().unwrap_or_else(|| Val::top(4));
            let old = reads.history[t].clone();
            let new = old.join(&stored);
            if new != old {
                grown = true;
                reads.history.insert(*t, new);
            }
        }
        if !grown {
            let (warnings, unproved) = domains::warnings(ir, findings);
            return Ranges {
                targets,
                warnings,
                unproved,
                frame_rounds: if live.history.is_empty() && reads.states.is_empty() {
                    0
                } else {
                    rounds
                },
                history_widened: widened,
            };
        }
        if widened {
            // The format's range holds every value a store leaves, so this
            // only grows a vector's length bound; give up on that too.
            for t in &live.history {
                let n = reads.history[t].comps.len();
                reads.history.insert(*t, Val::top(n));
            }
        }
        if rounds >= MAX_FRAME_ROUNDS && !widened {
            // Widen: a history read may hold anything its format can.
            for t in &live.history {
                let f = ir.pass(t.pass).outputs[t.output as usize].format;
                let n = f.channels() as usize;
                reads.history.insert(*t, Val::splat(inputs::format_range(f), n));
            }
            widened = true;
        }
    }
}

/// Rounds of frames before a state is unknown: past [`MAX_FRAME_ROUNDS`]
/// its growing bounds jump to the next threshold each round (`widen`).
pub const MAX_STATE_ROUNDS: usize = MAX_FRAME_ROUNDS + STATE_THRESHOLDS.len() + 1;

/// Where a state's growing bound is widened to: a state that decays
/// towards 0 or 1 (a fade, a smoothing) reaches its fixed point there in
/// one step instead of never.
const STATE_THRESHOLDS: [f64; 9] = [
    -interval::F32_MAX,
    -1e6,
    -1e3,
    -1.0,
    0.0,
    1.0,
    1e3,
    1e6,
    interval::F32_MAX,
];

/// `new` (which holds `old`) with each bound that moved out past `old`'s
/// moved further, to the next threshold (interval widening with
/// thresholds): sound, since it only grows the range.
fn widen(old: &Val, new: &Val) -> Val {
    let comps = new
        .comps
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let o = old.at(i);
            let lo = if c.lo < o.lo {
                STATE_THRESHOLDS
                    .iter()
                    .rev()
                    .copied()
                    .find(|t| *t <= c.lo)
                    .unwrap_or(f64::NEG_INFINITY)
            } else {
                c.lo
            };
            let hi = if c.hi > o.hi {
                STATE_THRESHOLDS
                    .iter()
                    .copied()
                    .find(|t| *t >= c.hi)
                    .unwrap_or(f64::INFINITY)
            } else {
                c.hi
            };
            Iv { lo, hi, nan: c.nan }
        })
        .collect();
    Val { comps, norm: None }
}

/// A pass's clear value, as `n` components.
fn clear_value(pass: &Pass, n: usize) -> Val {
    Val {
        comps: pass.clear.iter().take(n).map(|c| Iv::point(*c)).collect(),
        norm: None,
    }
}

/// Per compute pass and slot: a state's old value this frame and its update.
type StateUpdates = Vec<((PassId, u32), (Val, Val))>;

/// One frame: every live pass in order (operands before readers), the
/// targets' ranges, the domain findings and the states' updates.
fn frame(
    ir: &Ir,
    live: &Live,
    params: &[inputs::ParamRange],
    reads: &mut Reads,
) -> (Vec<TargetRange>, Vec<Finding>, StateUpdates) {
    reads.targets.clear();
    reads.values.clear();
    let mut targets = Vec::new();
    let mut findings = Vec::new();
    let mut states = Vec::new();
    for pid in &live.passes {
        let pass = ir.pass(*pid);
        let mut ev = Eval::new(ir, reads, params);
        ev.pass = Some(*pid);
        ev.run(&pass.roots().all());
        let mut stores = Vec::new();
        for t in live.targets_of(*pid) {
            let out = &pass.outputs[t.output as usize];
            let v = ev.val(out.value);
            let n = out.format.channels() as usize;
            if inputs::is_f16(out.format)
                && v.comps
                    .iter()
                    .any(|c| c.lo < -inputs::F16_MAX || c.hi > inputs::F16_MAX)
            {
                ev.findings.push(Finding {
                    domain: eval::Domain::F16Overflow,
                    at: out.value,
                    operands: vec![(out.value, v.clone())],
                });
            }
            let stored = match out.blend {
                Blend::Replace => inputs::stored(out.format, &v).join(&clear_value(pass, n)),
                // Blending combines with what earlier draws left: any
                // value the format holds.
                _ => Val::splat(inputs::format_range(out.format), n),
            };
            let stops = if v.is_finite() {
                Vec::new()
            } else {
                stops(ir, &ev, out.value)
            };
            stores.push((t, out, v.is_finite(), stored, stops));
        }
        let mut values = Vec::new();
        for (slot, value) in pass.kind.values().iter().enumerate() {
            let v = ev.val(value.value);
            let n = value.ty.components().unwrap_or(4) as usize;
            let r = match value.rule {
                ValueRule::Reduce(ReduceOp::Min | ReduceOp::Max) | ValueRule::Out => v,
                // A sum over any number of elements: its sign at most.
                ValueRule::Reduce(ReduceOp::Sum) => Val {
                    comps: v
                        .comps
                        .iter()
                        .map(|c| {
                            let lo = if c.lo >= 0.0 { 0.0 } else { f64::NEG_INFINITY };
                            let hi = if c.hi <= 0.0 { 0.0 } else { f64::INFINITY };
                            Iv { lo, hi, nan: true }
                        })
                        .collect(),
                    norm: None,
                },
                // What other passes read: the state after this frame's
                // update (or kept, where the pass did not run for an object).
                ValueRule::State => {
                    let old = ev.val_of_state(slot as u32, n);
                    states.push(((*pid, slot as u32), (old.clone(), v.clone())));
                    v.join(&old)
                }
            };
            values.push(((*pid, slot as u32), r));
        }
        findings.append(&mut ev.findings);
        for (t, out, finite, stored, stops) in stores {
            targets.push(TargetRange {
                target: t,
                name: format!("{}.{}", pass.name, out.name),
                format: out.format,
                range: stored.clone(),
                value_finite: finite,
                stops,
            });
            reads.targets.insert(t, stored);
        }
        for (k, v) in values {
            reads.values.insert(k, v);
        }
    }
    (targets, findings, states)
}

/// Where the proof that `root` is finite stops: the domain findings under
/// it, and the nodes whose range is unknown although their operands' are
/// finite (an operator with no declared range, a read of a target or
/// per-object value not proved finite, a projection). Five at most.
fn stops(ir: &Ir, ev: &Eval, root: ExprId) -> Vec<(npr_diag::Span, String)> {
    let mut out: Vec<(npr_diag::Span, String)> = Vec::new();
    for id in ir.reachable(&[root]) {
        let e = ir.expr(id);
        if let Some(f) = ev.findings.iter().find(|f| f.at == id) {
            let what = if f.domain == eval::Domain::F16Overflow {
                format!(
                    "stored in an f16 target, which it may overflow ({})",
                    domains::code_of(f.domain)
                )
            } else {
                format!(
                    "`{}`, whose undefined case is not ruled out ({})",
                    domains::what(ir, id),
                    domains::code_of(f.domain)
                )
            };
            out.push((e.span, what));
            continue;
        }
        if ev.val(id).is_finite() || !ir.operands(id).iter().all(|o| ev.val(*o).is_finite()) {
            continue;
        }
        let what = match &e.kind {
            ExprKind::Call {
                callee: Callee::Operator(i),
                ..
            } => match npr_stdlib::ops::ALL.get(*i as usize) {
                Some(d) if d.range.is_some() => {
                    format!("operator `{}` with arguments outside its parameters' ranges", d.op.name)
                }
                Some(d) => format!("operator `{}`, which declares no result range", d.op.name),
                None => "an operator".into(),
            },
            ExprKind::Target { target, .. } => format!("target `{}`, not proved finite", ir.target_name(*target)),
            ExprKind::ObjectValue { .. } | ExprKind::StateOld { .. } => {
                "a per-object value with no bound (a sum, or a state that grows without one)".into()
            }
            ExprKind::Texture(t) => format!(
                "texture `{}` (an HDR image or a filter's input)",
                ir.textures[t.0 as usize].name
            ),
            ExprKind::Call {
                callee: Callee::Intrinsic(i),
                ..
            } => format!("`{}` (may overflow or is unbounded here)", i.name()),
            ExprKind::Binary { op, .. } => format!("`{}` (may overflow here)", op.as_str()),
            _ => "an unbounded value".into(),
        };
        out.push((e.span, what));
    }
    out.truncate(5);
    out
}
