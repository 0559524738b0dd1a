//! Tiled compute for neighbourhood reads (issue 14): an image pass whose
//! operators read a target within a bounded radius of the pixel runs as a
//! compute shader over `npr_abi::manifest::TILE_SIZE`² workgroups. Each
//! workgroup loads the tile plus an apron of that radius (the operators'
//! declared footprints, `footprint.rs`) into workgroup memory once, and the
//! operators' `textureLoad`s of that target read it from there
//! (`emit/tiled`).
//!
//! The footprint only sizes the apron: a read outside it (or outside the
//! image) makes the workgroup run again without its tiles (`emit/tiled`),
//! so the image never depends on the metadata being right, only the speed
//! does (`stdlib/tests/footprints.rs` checks the metadata is sound and
//! tight; `tests/gpu/schedule_equivalence.rs` narrows the tiles on purpose).
//!
//! Not tiled, with the reason in the report: a pass that reads no target
//! around the pixel, blends, writes a format compute cannot store, reads a
//! texture as a value or calls an operator that takes screen derivatives
//! (compute has none), or whose tiles would not fit in workgroup memory.
//! A pass whose `schedule: tiled` forces tiles gets them under every
//! `--schedule`, or E0311 at that setting with the reason above.
//!
//! A pass that computes a target in its tiles (`recompute.rs`) is tiled
//! under every schedule, that target's tile filled by its producer's
//! expression instead of a load.

use super::footprint::{texture_reads, Read};
use super::plan::Plan;
use crate::ir::*;
use crate::mid::prune::Live;
use crate::report::Report;
use npr_abi::manifest::{Blend, TargetCopy, TILE_SIZE};
use npr_diag::{codes, Diagnostic};
use std::collections::{BTreeMap, BTreeSet};

/// Workgroup memory a tiled pass may use: WebGPU's default limit
/// (`maxComputeWorkgroupStorageSize`), which every adapter offers.
pub const WORKGROUP_MEMORY: u32 = 16384;

/// Workgroup memory a tiled shader declares besides its tiles: the two
/// miss flags (`npr_tile_misses`, `npr_tile_any_missed`; `emit::tiled`),
/// 16 bytes each by WebGPU's rule (every workgroup variable's size is
/// rounded up to 16). Without them a 4-channel tile with an 8-texel apron
/// (exactly 16384 bytes) passed here and then needed 16416.
pub const TILE_FLAGS_BYTES: u32 = 32;

/// Each tile of `tiling` `deficit` texels narrower than the footprints
/// ask (the tests' `CompileOptions::tile_apron_deficit`; 0 changes
/// nothing).
fn narrowed(mut tiling: Tiling, deficit: u32) -> Tiling {
    for r in &mut tiling.reads {
        r.radius = r.radius.saturating_sub(deficit);
    }
    tiling
}

/// Decides, for every live image pass, whether it runs tiled: under
/// `--schedule tiled` and `recompute` every pass the tiler accepts, and
/// under every schedule the passes whose `schedule: tiled` forces it and
/// those that compute a target in their tiles. The tilings go in
/// `ir.tiled`, every decision in the report; under `auto` only the passes
/// `tiled` would tile are reported, with why `auto` does not (measured
/// slower on lavapipe). A forced pass the tiler refuses is E0311.
pub(super) fn tile_neighbourhoods(ir: &mut Ir, live: &Live, plan: &Plan, report: &mut Report) -> Vec<Diagnostic> {
    let mut errors = Vec::new();
    for pid in &live.passes {
        if !matches!(ir.pass(*pid).kind, PassKind::Image { .. }) {
            continue;
        }
        let name = format!("pass `{}`", ir.pass(*pid).name);
        let forced = plan.forced(*pid);
        let computes = ir.recomputed.values().any(|r| r.reader == *pid);
        if forced.is_some_and(|f| f.schedule == Schedule::Recompute) {
            // Still live, so not computed in its reader: E0312 says why.
            continue;
        }
        // A pass that computes a target in its tiles runs tiled.
        let schedule = if computes {
            Schedule::Tiled
        } else {
            forced.map_or(plan.run, |f| f.schedule)
        };
        match (tiling(ir, live, *pid), schedule) {
            (Ok(t), s) if s.tiles() => {
                let what: Vec<String> = t
                    .reads
                    .iter()
                    .map(|r| {
                        let from = match r.source {
                            TileSource::Load => String::new(),
                            TileSource::Recompute => format!(" (computed from pass `{}`)", ir.pass(r.target.pass).name),
                        };
                        format!("`{}` with a {}-texel apron{from}", ir.target_name(r.target), r.radius)
                    })
                    .collect();
                let by = match forced {
                    Some(f) => format!("{}: ", f.why()),
                    None if computes => "it computes a target in its tiles: ".to_string(),
                    None => String::new(),
                };
                report.push(
                    "tiled",
                    name,
                    format!(
                        "{by}compute over {TILE_SIZE}×{TILE_SIZE} tiles, keeping {} in workgroup memory ({} bytes)",
                        what.join(", "),
                        t.bytes()
                    ),
                );
                ir.tiled.insert(*pid, narrowed(t, plan.apron_deficit));
            }
            (Err(why), s) if s.tiles() => match forced {
                Some(f) => errors.push(
                    Diagnostic::error(codes::CANNOT_TILE, format!("pass `{}` cannot run tiled", ir.pass(*pid).name))
                        .with_primary(f.span, "`schedule: tiled` asked for here")
                        .with_secondary(ir.pass(*pid).name_span, "this pass")
                        .with_help(format!(
                            "the tiler refuses it: {why}; write `schedule: auto` (or no `schedule:`) to let the compiler choose, or `schedule: naive`"
                        )),
                ),
                None => report.push("not tiled", name, why),
            },
            // A pass forced `naive` under `--schedule tiled`: say why the
            // run's schedule did not tile it.
            (_, Schedule::Naive) if plan.run.tiles() => {
                let why = forced.map_or(String::new(), |f| f.why());
                report.push("not tiled", name, why);
            }
            (Ok(t), Schedule::Auto) => report.push(
                "not tiled",
                name,
                format!(
                    "`--schedule tiled` would keep {} bytes in workgroup memory; auto does not, as tiles measured 1.0-2.2x slower than the fragment pass on lavapipe (docs/PERFORMANCE.md)",
                    t.bytes()
                ),
            ),
            _ => {}
        }
    }
    errors
}

/// The tiling of image pass `pid`, or why it is not tiled: the targets its
/// operators load around the pixel, and those it computes in its tiles
/// (`ir.recomputed`).
pub(super) fn tiling(ir: &Ir, live: &Live, pid: PassId) -> Result<Tiling, String> {
    let pass = ir.pass(pid);
    let live_outputs: Vec<&PassOutput> = live
        .targets_of(pid)
        .iter()
        .map(|t| &pass.outputs[t.output as usize])
        .collect();
    for o in &live_outputs {
        if o.blend != Blend::Replace {
            return Err(format!("`{}` blends into its target (compute has no blending)", o.name));
        }
        if !o.format.storage_capable() {
            return Err(format!(
                "`{}` is {}, which a compute shader cannot store",
                o.name,
                o.format.name()
            ));
        }
    }
    if live_outputs.is_empty() {
        return Err("it writes no live target".into());
    }
    let roots = pass.roots().all();
    let nodes = ir.reachable(&roots);
    if samples_a_texture(ir, &roots, &nodes) {
        return Err("it samples a texture as a value, which takes screen derivatives".into());
    }
    let mut radii: BTreeMap<TargetRef, u32> = BTreeMap::new();
    for n in &nodes {
        let e = ir.expr(*n);
        if let ExprKind::Call {
            callee: Callee::Operator(i),
            ..
        } = &e.kind
        {
            if let Some(op) = uses_derivatives(*i as usize) {
                return Err(format!("`{op}` takes screen derivatives, which compute has none of"));
            }
        }
        for (arg, read) in texture_reads(ir, *n) {
            let ExprKind::Target {
                target,
                copy: TargetCopy::This,
            } = ir.expr(arg).kind
            else {
                continue;
            };
            // A tile is in the pass's own pixel grid: only a target of the
            // same scale lines up texel for pixel.
            if ir.pass(target.pass).scale != pass.scale {
                continue;
            }
            if let Read::AroundPixel { radius } = read {
                if radius > 0 && is_loaded(ir, *n, arg) {
                    let r = radii.entry(target).or_default();
                    *r = (*r).max(radius);
                }
            }
        }
    }
    let mut recomputed = BTreeSet::new();
    for (target, r) in &ir.recomputed {
        if r.reader == pid {
            let radius = radii.entry(*target).or_default();
            *radius = (*radius).max(r.radius);
            recomputed.insert(*target);
        }
    }
    if radii.is_empty() {
        return Err("no operator reads a target around the pixel".into());
    }
    let tiling = Tiling {
        reads: radii
            .into_iter()
            .map(|(target, radius)| TileRead {
                target,
                radius,
                channels: ir.pass(target.pass).outputs[target.output as usize].format.channels(),
                source: if recomputed.contains(&target) {
                    TileSource::Recompute
                } else {
                    TileSource::Load
                },
            })
            .collect(),
    };
    let bytes = tiling.bytes() + TILE_FLAGS_BYTES;
    if bytes > WORKGROUP_MEMORY {
        return Err(format!(
            "its tiles need {bytes} bytes of workgroup memory (widest apron: {} texel(s)), over the {WORKGROUP_MEMORY} every adapter has",
            tiling.reads.iter().map(|r| r.radius).max().unwrap_or(0)
        ));
    }
    Ok(tiling)
}

/// Whether the pass whose expressions are `nodes` (from `roots`) reads a
/// texture as a value, which the emitter samples with `textureSample`
/// (implicit derivatives, a fragment-stage builtin): a texture that is a
/// root, or an operand of anything but an operator's texture parameter.
/// The typechecker leaves such a read typed as the texture, so the type
/// alone does not tell it from an operator's argument.
pub(super) fn samples_a_texture(ir: &Ir, roots: &[ExprId], nodes: &[ExprId]) -> bool {
    let is_texture = |e: ExprId| matches!(ir.expr(e).kind, ExprKind::Texture(_));
    if roots.iter().any(|r| is_texture(*r)) {
        return true;
    }
    nodes.iter().any(|n| match &ir.expr(*n).kind {
        ExprKind::Call {
            callee: Callee::Operator(i),
            args,
        } => {
            npr_stdlib::all()[*i as usize].params.iter().zip(args).any(|(p, a)| {
                is_texture(*a) && !matches!(p.ty, npr_stdlib::Ty::Texture | npr_stdlib::Ty::SampledTexture)
            })
        }
        _ => ir.operands(*n).into_iter().any(is_texture),
    })
}

/// Whether `call` passes `arg` as a plain texture (read by `textureLoad`),
/// not a sampled one (filtered reads stay on the texture unit).
fn is_loaded(ir: &Ir, call: ExprId, arg: ExprId) -> bool {
    let ExprKind::Call {
        callee: Callee::Operator(i),
        args,
    } = &ir.expr(call).kind
    else {
        return false;
    };
    let op = &npr_stdlib::all()[*i as usize];
    op.params
        .iter()
        .zip(args)
        .any(|(p, a)| *a == arg && p.ty == npr_stdlib::Ty::Texture)
}

/// The name of operator `i` or of one it depends on when its WGSL takes
/// screen derivatives (explicitly, or through an implicit-LOD sample).
pub(super) fn uses_derivatives(i: usize) -> Option<&'static str> {
    let op = &npr_stdlib::all()[i];
    let takes = |wgsl: &str| {
        ["dpdx", "dpdy", "fwidth", "textureSample("]
            .iter()
            .any(|d| wgsl.contains(d))
    };
    let own = takes(op.wgsl)
        || op
            .snippets
            .iter()
            .any(|s| npr_stdlib::snippets::find(s).is_some_and(takes));
    if own {
        return Some(op.name);
    }
    op.depends.iter().find_map(|d| {
        let j = npr_stdlib::all().iter().position(|o| o.name == *d)?;
        uses_derivatives(j)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn index(name: &str) -> usize {
        npr_stdlib::all().iter().position(|o| o.name == name).expect("operator")
    }

    #[test]
    fn derivative_takers_are_found_through_their_dependencies() {
        assert_eq!(uses_derivatives(index("metatexture")), Some("metatexture"));
        assert_eq!(uses_derivatives(index("sample_biased")), Some("sample_biased"));
        assert_eq!(uses_derivatives(index("sobel")), None);
        assert_eq!(uses_derivatives(index("lsa")), None);
    }
}
