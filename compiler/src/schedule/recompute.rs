//! Recomputed tiles (issue 14's fused neighbourhood stages; Halide's
//! `compute_at`): an image pass whose one target its one reader reads
//! around the pixel is not stored. The reader runs tiled (`tile.rs`), and
//! each workgroup fills its tile of that target, apron included, by
//! evaluating the producer's expression at every tile texel, rounded to
//! the target's format as a store would round it (`emit/tiled`). After a
//! read outside the tile, the workgroup runs again evaluating the producer
//! where each read falls, so a footprint that is too small costs speed,
//! never a different image.
//!
//! What it trades: the target's write and read (its bytes per pixel, twice)
//! and one pass, against computing the producer on the apron as well,
//! `(TILE_SIZE + 2r)² / TILE_SIZE²` times its pixels (1.56× at r = 2).
//! Halide's lesson is that this pays for cheap producers and memory-bound
//! devices; on lavapipe it does not (docs/PERFORMANCE.md, "Recomputed
//! tiles"), so `auto` reports where `--schedule recompute` would do it and
//! does not. `schedule: recompute` on the producer asks for it under every
//! `--schedule`; where it cannot be done, that is E0312 at the setting.
//!
//! Not recomputed, with the reason: what pointwise fusion refuses of a
//! target (`fuse.rs`: the output, blending, sRGB, a constant, the previous
//! frame's or the other eye's copy, two readers, another kind or scale), a
//! pass with more than one live target, a producer that takes screen
//! derivatives or samples a texture (it runs in compute), one that itself
//! computes a target in its tiles (one level), a reader that samples the
//! target or reads it at a computed coordinate, a reader whose own
//! schedule is forced, or one the tiler refuses with the target in its tile.

use super::footprint::{texture_reads, Read};
use super::plan::Plan;
use super::tile::{self, samples_a_texture, uses_derivatives};
use super::unstored::{must_be_stored, reader_kind_and_scale, take_over_inputs};
use crate::ir::*;
use crate::mid::prune::Live;
use crate::report::Report;
use npr_abi::manifest::TILE_SIZE;
use npr_diag::{codes, Diagnostic};
use std::collections::BTreeSet;

/// Decides, in execution order, which image passes are computed in their
/// reader's tiles: under `--schedule recompute` every one that can be, and
/// under every schedule those whose `schedule: recompute` asks for it (the
/// others, E0312). Each is recorded in `ir.recomputed` and leaves `live`
/// with its target; the reader takes over its inputs. Under `auto` the
/// passes `recompute` would take are reported with why it does not.
pub(super) fn recompute_neighbourhoods(
    ir: &mut Ir,
    live: &mut Live,
    plan: &Plan,
    report: &mut Report,
) -> Vec<Diagnostic> {
    let mut errors = Vec::new();
    let mut i = 0;
    while i < live.passes.len() {
        let pid = live.passes[i];
        i += 1;
        if !matches!(ir.pass(pid).kind, PassKind::Image { .. }) {
            continue;
        }
        let forced = plan.forced(pid);
        let schedule = forced.map_or(plan.run, |f| f.schedule);
        if !matches!(schedule, Schedule::Auto | Schedule::Recompute) {
            continue;
        }
        let name = format!("pass `{}`", ir.pass(pid).name);
        match reader_tile(ir, live, plan, pid) {
            Ok((target, reader, radius)) if schedule == Schedule::Recompute => {
                let why = explain(ir, target, reader, radius);
                let by = forced.map_or(String::new(), |f| format!("{}: ", f.why()));
                report.push("recomputed", name, format!("{by}{why}"));
                commit(ir, live, target, reader, radius);
                i -= 1;
                live.passes.remove(i);
            }
            Ok((target, reader, radius)) => report.push(
                "not recomputed",
                name,
                format!(
                    "`--schedule recompute` would compute it in `{}`'s tiles ({:.2}x its pixels) instead of storing `{}`; auto does not, as recomputed tiles measured slower than storing it on lavapipe (docs/PERFORMANCE.md)",
                    ir.pass(reader).name,
                    apron_work(radius),
                    ir.target_name(target)
                ),
            ),
            Err(why) => {
                if let Some(f) = forced.filter(|f| f.schedule == Schedule::Recompute) {
                    errors.push(
                        Diagnostic::error(
                            codes::CANNOT_RECOMPUTE,
                            format!("pass `{}` cannot be computed in its reader's tiles", ir.pass(pid).name),
                        )
                        .with_primary(f.span, "`schedule: recompute` asked for here")
                        .with_secondary(ir.pass(pid).name_span, "this pass")
                        .with_help(format!(
                            "{why}; write `schedule: auto` (or no `schedule:`) to let the compiler choose, or `schedule: naive`"
                        )),
                    );
                } else if plan.run == Schedule::Recompute {
                    report.push("not recomputed", name, why);
                }
            }
        }
    }
    errors
}

/// The tile's pixels over the block's: how many times its pixels the
/// producer is evaluated with an `radius`-texel apron.
fn apron_work(radius: u32) -> f64 {
    let side = f64::from(TILE_SIZE + 2 * radius);
    side * side / f64::from(TILE_SIZE * TILE_SIZE)
}

/// The report's reason for a recomputed pass.
fn explain(ir: &Ir, target: TargetRef, reader: PassId, radius: u32) -> String {
    let reader = &ir.pass(reader).name;
    let format = ir.pass(target.pass).outputs[target.output as usize].format;
    format!(
        "in `{reader}`'s tiles: `{reader}` reads `{}` within {radius} texel(s) of the pixel, so each {TILE_SIZE}×{TILE_SIZE} workgroup computes it on its tile and apron ({:.2}x its pixels) and the {} target ({} bytes a pixel, written and read) is not stored",
        ir.target_name(target),
        apron_work(radius),
        format.name(),
        format.bytes_per_pixel()
    )
}

/// Records `target` as computed in `reader`'s tiles: it leaves `live` (its
/// pass is removed by the caller) and the reader takes over its producer's
/// inputs, as a fused pass does.
fn commit(ir: &mut Ir, live: &mut Live, target: TargetRef, reader: PassId, radius: u32) {
    ir.recomputed.insert(target, Recomputed { reader, radius });
    live.targets.remove(&target);
    take_over_inputs(ir, reader, target.pass);
}

/// The target of `pid` that its reader could compute in its tiles, that
/// reader and the apron, or why not.
fn reader_tile(ir: &mut Ir, live: &Live, plan: &Plan, pid: PassId) -> Result<(TargetRef, PassId, u32), String> {
    let pass = ir.pass(pid);
    let target = match live.targets_of(pid).as_slice() {
        [one] => *one,
        [] => return Err("it writes no live target".into()),
        many => {
            return Err(format!(
                "it writes {} live targets, and a recomputed tile holds one",
                many.len()
            ))
        }
    };
    must_be_stored(ir, target, "which is cheaper stored")?;
    let roots = pass.roots().all();
    let nodes = ir.reachable(&roots);
    if samples_a_texture(ir, &roots, &nodes) {
        return Err("it samples a texture as a value, which takes screen derivatives".into());
    }
    for n in &nodes {
        match &ir.expr(*n).kind {
            ExprKind::Call {
                callee: Callee::Operator(i),
                ..
            } => {
                if let Some(op) = uses_derivatives(*i as usize) {
                    return Err(format!("`{op}` takes screen derivatives, which compute has none of"));
                }
            }
            ExprKind::Target { target: t, .. } if ir.recomputed.contains_key(t) => {
                return Err(format!(
                    "it computes `{}` in its own tiles, and recomputation is one level deep",
                    ir.target_name(*t)
                ));
            }
            _ => {}
        }
    }
    let (reader, radius) = sole_reader(ir, live, target)?;
    let r = ir.pass(reader);
    if let Some(f) = plan.forced(reader) {
        return Err(format!("its reader `{}` is {}", r.name, f.why()));
    }
    reader_kind_and_scale(ir, reader, pid)?;
    // The reader's tiling with this target in it: tentatively recorded, so
    // the tiler sizes its apron and counts its bytes.
    ir.recomputed.insert(target, Recomputed { reader, radius });
    let tiling = tile::tiling(ir, live, reader);
    ir.recomputed.remove(&target);
    tiling.map_err(|why| format!("its reader `{}` cannot be tiled with it: {why}", ir.pass(reader).name))?;
    Ok((target, reader, radius))
}

/// The one live pass that reads `target`, and how far around its pixel,
/// when every read is this frame's copy, passed to an operator that loads
/// it around the pixel or read as a value (at the pixel); else why not.
fn sole_reader(ir: &Ir, live: &Live, target: TargetRef) -> Result<(PassId, u32), String> {
    let name = ir.target_name(target);
    let mut readers = BTreeSet::new();
    let mut radius = 0;
    for q in &live.passes {
        let reader = ir.pass(*q);
        let nodes = ir.reachable(&reader.roots().all());
        for n in &nodes {
            for (arg, read) in texture_reads(ir, *n) {
                if !matches!(ir.expr(arg).kind, ExprKind::Target { target: t, .. } if t == target) {
                    continue;
                }
                let ExprKind::Call {
                    callee: Callee::Operator(i),
                    args,
                } = &ir.expr(*n).kind
                else {
                    continue;
                };
                let op = &npr_stdlib::all()[*i as usize];
                let loaded = op
                    .params
                    .iter()
                    .zip(args)
                    .any(|(p, a)| *a == arg && p.ty == npr_stdlib::Ty::Texture);
                match read {
                    Read::AroundPixel { radius: r } if loaded => radius = radius.max(r),
                    Read::AroundPixel { .. } => {
                        return Err(format!(
                            "`{}` passes `{name}` to `{}`, which samples it (filtered reads stay on the texture unit)",
                            reader.name, op.name
                        ))
                    }
                    Read::Anywhere => {
                        return Err(format!(
                            "`{}` passes `{name}` to `{}`, which {read}",
                            reader.name, op.name
                        ))
                    }
                }
            }
            let ExprKind::Target { target: t, copy } = ir.expr(*n).kind else {
                continue;
            };
            if t != target {
                continue;
            }
            match copy {
                TargetCopy::Previous => {
                    return Err(format!("`{}` reads `{name}` from the previous frame", reader.name))
                }
                TargetCopy::OtherEye => return Err(format!("`{}` reads the other eye's `{name}`", reader.name)),
                TargetCopy::This => {}
            }
            readers.insert(*q);
        }
    }
    match readers.iter().collect::<Vec<_>>().as_slice() {
        [one] => Ok((**one, radius)),
        [] => Err("no pass reads its target".into()),
        many => {
            let names: Vec<String> = many.iter().map(|p| format!("`{}`", ir.pass(**p).name)).collect();
            Err(format!(
                "read by {}: each would compute it in its own tiles",
                names.join(" and ")
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_apron_work_is_the_tile_over_the_block() {
        assert_eq!(apron_work(0), 1.0);
        assert_eq!(apron_work(2), 400.0 / 256.0);
    }
}
