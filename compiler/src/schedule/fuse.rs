//! Pointwise fusion: an image pass whose targets only one image pass reads,
//! and only at its own pixel, is computed inside that reader. The target is
//! never stored, one pass and one full-image write and read are saved, and
//! nothing is computed twice (one reader, one read per pixel).
//!
//! The reader's reads of the fused targets become the producer's output
//! expressions, wrapped in `Conversion::Stored(format)` where the format
//! rounds (16-bit floats, 8-bit unorm), so the fused pass sees the values
//! the target would have held: the same image as the naive schedule.
//!
//! Not fused, with the reason in the report: a target that is the output,
//! blends, is sRGB, is read from the previous frame or the other eye, is
//! passed to an operator that reads around the pixel, is read by two
//! passes, by a pass of another kind, or at another scale; a pass whose
//! `schedule:` forces it (or its reader) to run as written or tiled; every
//! pass under `--schedule naive`.

use super::footprint::{pass_apron, texture_reads, Read};
use super::plan::Plan;
use super::unstored::{must_be_stored, reader_kind_and_scale, take_over_inputs};
use crate::ir::*;
use crate::mid::prune::Live;
use crate::report::Report;
use npr_abi::formats::Storage;
use std::collections::{BTreeMap, BTreeSet};

/// Fuses every image pass that `plan` lets be fused and can be, in
/// execution order (so a chain of pointwise passes becomes one), and
/// reports each image pass's schedule.
pub(super) fn fuse_pointwise(ir: &mut Ir, live: &mut Live, plan: &Plan, report: &mut Report) {
    let mut i = 0;
    while i < live.passes.len() {
        let pid = live.passes[i];
        if !matches!(ir.pass(pid).kind, PassKind::Image { .. }) {
            i += 1;
            continue;
        }
        let name = format!("pass `{}`", ir.pass(pid).name);
        if let Some(f) = plan.forced(pid) {
            let how = match f.schedule {
                Schedule::Tiled => ", which runs it as its own pass, over tiles",
                Schedule::Recompute => ", which computes it in its reader's tiles",
                _ => ", which runs it as written",
            };
            report.push("schedule", name, format!("separate pass: {}{how}", f.why()));
            i += 1;
            continue;
        }
        if plan.run == Schedule::Naive {
            report.push(
                "schedule",
                name,
                "separate pass: `--schedule naive` runs every pass as written".into(),
            );
            i += 1;
            continue;
        }
        match consumer(ir, live, plan, pid) {
            Ok((reader, why)) => {
                let into = ir.pass(reader).name.clone();
                fuse(ir, live, pid, reader);
                live.passes.remove(i);
                report.push("fused", name, format!("into `{into}`: {why}"));
            }
            Err(why) => {
                let apron = match pass_apron(ir, pid) {
                    Some(0) => "its target reads are at the pixel".to_string(),
                    Some(r) => format!("a tile of it needs a {r}-texel apron"),
                    None => "a target read at a computed coordinate bounds no tile".to_string(),
                };
                report.push("schedule", name, format!("separate pass: {why}; {apron}"));
                i += 1;
            }
        }
    }
}

/// The one image pass that `pid`'s targets can be fused into, with why, or
/// why not.
fn consumer(ir: &Ir, live: &Live, plan: &Plan, pid: PassId) -> Result<(PassId, String), String> {
    let pass = ir.pass(pid);
    let targets = live.targets_of(pid);
    for t in &targets {
        // A constant stays a stored target: inlined, the reader's expressions
        // over it would be constant too, and a shader compiler folds them,
        // where out-of-domain math (`sqrt(-0.8)`, indeterminate in WGSL)
        // may give another value than the same math at run time (naga
        // rejects some outright: the generated-style soak's case 48924).
        must_be_stored(ir, *t, "which would make its reader's expressions over it constant")?;
    }
    let mut readers = BTreeSet::new();
    for q in &live.passes {
        let reader = ir.pass(*q);
        let nodes = ir.reachable(&reader.roots().all());
        // Targets passed to an operator as textures: it reads them itself
        // (`textureLoad`), so there is no value to substitute, even where
        // its footprint is the pixel alone.
        let handles: BTreeMap<ExprId, (ExprId, Read)> = nodes
            .iter()
            .flat_map(|n| texture_reads(ir, *n).into_iter().map(move |(a, read)| (a, (*n, read))))
            .collect();
        for n in &nodes {
            let ExprKind::Target { target, copy } = ir.expr(*n).kind else {
                continue;
            };
            if target.pass != pid {
                continue;
            }
            let name = ir.target_name(target);
            match copy {
                TargetCopy::Previous => {
                    return Err(format!("`{}` reads `{name}` from the previous frame", reader.name));
                }
                TargetCopy::OtherEye => return Err(format!("`{}` reads the other eye's `{name}`", reader.name)),
                TargetCopy::This => {}
            }
            if let Some((call, read)) = handles.get(n) {
                let op = match &ir.expr(*call).kind {
                    ExprKind::Call {
                        callee: Callee::Operator(i),
                        ..
                    } => npr_stdlib::all()[*i as usize].name,
                    _ => "an operator",
                };
                return Err(format!("`{}` passes `{name}` to `{op}`, which {read}", reader.name));
            }
            readers.insert(*q);
        }
    }
    let reader = match readers.iter().collect::<Vec<_>>().as_slice() {
        [one] => **one,
        [] => return Err("no pass reads its targets".into()),
        many => {
            let names: Vec<String> = many.iter().map(|p| format!("`{}`", ir.pass(**p).name)).collect();
            return Err(format!(
                "read by {}: fusing would compute it once per reader",
                names.join(" and ")
            ));
        }
    };
    let r = ir.pass(reader);
    if let Some(f) = plan.forced(reader) {
        return Err(format!(
            "its reader `{}` is {}, so nothing is fused into it",
            r.name,
            f.why()
        ));
    }
    reader_kind_and_scale(ir, reader, pid)?;
    let stored: Vec<&str> = targets
        .iter()
        .map(|t| pass.outputs[t.output as usize].format)
        .filter(|f| f.storage() != Storage::Exact)
        .map(|f| f.name())
        .collect();
    let names: Vec<String> = targets.iter().map(|t| format!("`{}`", ir.target_name(*t))).collect();
    let rounding = if stored.is_empty() {
        String::new()
    } else {
        format!(" ({} rounding repeated)", stored.join(", "))
    };
    Ok((
        reader,
        format!("it reads {} only at its own pixel{rounding}", names.join(", ")),
    ))
}

/// Computes pass `producer` inside `reader`: the reader's reads of its
/// targets become the producer's (stored) values; its inputs and `let`
/// names move over; its targets leave `live`.
fn fuse(ir: &mut Ir, live: &mut Live, producer: PassId, reader: PassId) {
    let targets = live.targets_of(producer);
    let mut replacement: BTreeMap<TargetRef, ExprId> = BTreeMap::new();
    for t in &targets {
        let o = ir.pass(producer).outputs[t.output as usize].clone();
        let value = ir.expr(o.value).clone();
        let id = match o.format.storage() {
            Storage::Exact => o.value,
            _ => ir.add_typed(
                ExprKind::Convert {
                    conversion: Conversion::Stored(o.format),
                    operand: o.value,
                },
                Ty::float_vec(o.format.channels()),
                value.unit,
                value.span,
            ),
        };
        replacement.insert(*t, id);
    }
    let r = ir.pass(reader);
    let roots: Vec<ExprId> = r
        .roots()
        .all()
        .into_iter()
        .chain(r.lets.iter().map(|l| l.value))
        .collect();
    let mut map: BTreeMap<ExprId, ExprId> = BTreeMap::new();
    for n in ir.reachable(&roots) {
        let e = ir.expr(n).clone();
        if let ExprKind::Target {
            target,
            copy: TargetCopy::This,
        } = e.kind
        {
            if let Some(r) = replacement.get(&target) {
                map.insert(n, *r);
                continue;
            }
        }
        let operands = ir.operands(n);
        let new: Vec<ExprId> = operands.iter().map(|o| map.get(o).copied().unwrap_or(*o)).collect();
        if new != operands {
            let kind = ir.with_operands(n, &new);
            let id = ir.add_typed(kind, e.ty, e.unit, e.span);
            map.insert(n, id);
        }
    }
    let producer_name = ir.pass(producer).name.clone();
    let producer_lets = ir.pass(producer).lets.clone();
    let r = &mut ir.passes[reader.0 as usize];
    for o in &mut r.outputs {
        o.value = map.get(&o.value).copied().unwrap_or(o.value);
    }
    for l in &mut r.lets {
        l.value = map.get(&l.value).copied().unwrap_or(l.value);
    }
    // The producer's `let`s keep their names in the fused WGSL, prefixed
    // with its pass name (and made unique).
    for mut l in producer_lets {
        let mut name = format!("{producer_name}_{}", l.name);
        while r.lets.iter().any(|x| x.name == name) {
            name.push('_');
        }
        l.name = name;
        r.lets.push(l);
    }
    take_over_inputs(ir, reader, producer);
    for t in targets {
        live.targets.remove(&t);
    }
}
