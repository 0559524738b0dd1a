//! Allocate: give each live target a physical texture, aliasing targets whose
//! lifetimes do not overlap, and lay out the uniform blocks.
//!
//! Lifetime of a target: from the pass that writes it to the last pass that
//! reads it (the output lives to the end). Two targets share a physical
//! texture only when format and scale match and the first is dead before the
//! second is written, so no pass ever reads and writes the same texture.
//!
//! A history target (read with `previous(...)`) is never aliased: its
//! physical texture is its own, marked `history`, and the runner keeps a
//! second copy of it for the previous frame's value.

use crate::ir::*;
use crate::mid::prune::Live;
use crate::report::Report;
use crate::InternalError;
use npr_abi::manifest::{ParamBinding, PhysicalTexture, OBJECT_PARAMS_OFFSET};
use std::collections::BTreeMap;

#[derive(Debug, Clone, Default)]
pub struct Allocation {
    /// Live targets in creation order, with their physical index.
    pub targets: Vec<(TargetRef, usize)>,
    pub physical: Vec<PhysicalTexture>,
    /// Byte offsets of uniform and per-object parameter slots.
    pub param_offsets: BTreeMap<ParamId, u64>,
    pub style_uniform_size: u64,
    pub object_uniform_size: u64,
    /// Live passes in execution order (a pass's index in the manifest).
    pub passes: Vec<PassId>,
    /// Each live per-object value of a compute pass: its slot in the pass's
    /// value buffer (live values are packed in declaration order).
    pub value_slots: BTreeMap<(PassId, u32), u32>,
    /// Slots per object of each live compute pass: its live values, plus
    /// one for the "state written" flag when it keeps state.
    pub slots_per_object: BTreeMap<PassId, u32>,
}

impl Allocation {
    /// The manifest index of a live pass.
    pub fn pass_index(&self, p: PassId) -> Option<usize> {
        self.passes.iter().position(|x| *x == p)
    }

    /// Whether a live compute pass keeps state (two copies of its values).
    pub fn keeps_state(&self, ir: &Ir, p: PassId) -> bool {
        ir.pass(p)
            .kind
            .values()
            .iter()
            .enumerate()
            .any(|(i, v)| v.rule == ValueRule::State && self.value_slots.contains_key(&(p, i as u32)))
    }

    pub fn target_index(&self, t: TargetRef) -> Option<usize> {
        self.targets.iter().position(|(x, _)| *x == t)
    }
}

pub fn allocate(
    ir: &Ir,
    live: &Live,
    bindings: &[ParamBinding],
    report: &mut Report,
) -> Result<Allocation, InternalError> {
    let mut alloc = Allocation {
        passes: live.passes.clone(),
        ..Allocation::default()
    };
    value_buffers(ir, live, &mut alloc, report);
    // Last use of each target, by execution position.
    let mut last_use: BTreeMap<TargetRef, usize> = BTreeMap::new();
    for (pos, pid) in live.passes.iter().enumerate() {
        let roots: Vec<ExprId> = ir.scheduled_roots(*pid);
        for id in ir.reachable(&roots) {
            if let Some(t) = ir.expr(id).kind.target_read() {
                let e = last_use.entry(t).or_insert(pos);
                *e = (*e).max(pos);
            }
        }
    }
    if let Some(out) = ir.output {
        last_use.insert(out, usize::MAX);
    }
    // The next frame reads a history target, so it is busy to the end, and
    // nothing written earlier in the frame may be reused for it either.
    for t in &live.history {
        last_use.insert(*t, usize::MAX);
    }
    // Each physical texture: (format, scale, last position it is busy).
    let mut busy_until: Vec<usize> = Vec::new();
    for (pos, pid) in live.passes.iter().enumerate() {
        let pass = ir.pass(*pid);
        for (i, o) in pass.outputs.iter().enumerate() {
            let t = TargetRef {
                pass: *pid,
                output: i as u32,
            };
            if !live.targets.contains(&t) {
                continue;
            }
            // Prune keeps a target only for a live reader or as the output.
            let Some(end) = last_use.get(&t).copied() else {
                return Err(InternalError {
                    message: format!("live target `{}` has no reader", ir.target_name(t)),
                    detail: "prune kept a target that no live pass reads and that is not the output".into(),
                    span: Some(o.span),
                    wgsl: None,
                });
            };
            let history = live.history.contains(&t);
            let reuse = alloc.physical.iter().enumerate().position(|(pi, ph)| {
                !history && !ph.history && ph.format == o.format && ph.scale == pass.scale && busy_until[pi] < pos
            });
            let phys = match reuse {
                Some(pi) => {
                    report.push(
                        "aliased",
                        format!("target `{}.{}`", pass.name, o.name),
                        format!("shares physical texture #{pi} with a target that is dead by then"),
                    );
                    busy_until[pi] = end;
                    pi
                }
                None => {
                    if history {
                        report.push(
                            "history",
                            format!("target `{}.{}`", pass.name, o.name),
                            "read with `previous(...)`: a texture of its own, kept across frames (two copies)".into(),
                        );
                    }
                    alloc.physical.push(PhysicalTexture {
                        format: o.format,
                        scale: pass.scale,
                        history,
                    });
                    busy_until.push(end);
                    alloc.physical.len() - 1
                }
            };
            alloc.targets.push((t, phys));
        }
    }
    // Kept depths are the runner's (one texture per keeping pass and eye
    // slot, never aliased), but the report says which pass keeps one for whom.
    for pid in &live.passes {
        let pass = ir.pass(*pid);
        if !pass.keeps_depth() {
            continue;
        }
        let testers: Vec<String> = live
            .passes
            .iter()
            .filter(|t| ir.pass(**t).depth_test().is_some_and(|(p, _)| p == *pid))
            .map(|t| format!("`{}`", ir.pass(*t).name))
            .collect();
        let why = if testers.is_empty() {
            "not kept: no live pass tests against it".to_string()
        } else {
            format!("kept for {}: a depth texture of its own (per eye)", testers.join(", "))
        };
        report.push("depth", format!("pass `{}`", pass.name), why);
    }
    let keeps_state = live.passes.iter().any(|p| alloc.keeps_state(ir, *p));
    if !live.history.is_empty() || keeps_state {
        report.push(
            "history",
            "frames depend on earlier frames".into(),
            "`npr render --time t` replays frames 0..=round(t × fps) at --fps; `--frames a..b` replays 0..a first"
                .into(),
        );
    }
    let mut style_slots = 0u64;
    let mut object_slots = 0u64;
    for (i, b) in bindings.iter().enumerate() {
        let id = ParamId(i as u32);
        match b {
            ParamBinding::Uniform => {
                alloc.param_offsets.insert(id, style_slots * 16);
                // A gradient's slots are contiguous (`npr_abi::gradient`).
                style_slots += npr_abi::gradient::slots_of(&ir.params[i].declared_type()) as u64;
            }
            ParamBinding::PerObject => {
                alloc.param_offsets.insert(id, OBJECT_PARAMS_OFFSET + object_slots * 16);
                object_slots += 1;
            }
            _ => {}
        }
    }
    alloc.style_uniform_size = style_slots * 16;
    let draws_objects = live.passes.iter().any(|p| ir.pass(*p).kind.has_object());
    alloc.object_uniform_size = if draws_objects {
        OBJECT_PARAMS_OFFSET + object_slots * 16
    } else {
        0
    };
    Ok(alloc)
}

/// Pack the live values of each compute pass into slots, and report the
/// buffers: one `vec4<f32>` per value per object, two copies when the pass
/// keeps state.
fn value_buffers(ir: &Ir, live: &Live, alloc: &mut Allocation, report: &mut Report) {
    for pid in &live.passes {
        let pass = ir.pass(*pid);
        let PassKind::Compute { domain, .. } = &pass.kind else {
            continue;
        };
        let slots = live.value_slots(*pid);
        for (packed, slot) in slots.iter().enumerate() {
            alloc.value_slots.insert((*pid, *slot), packed as u32);
        }
        let state = alloc.keeps_state(ir, *pid);
        let per_object = slots.len() as u32 + u32::from(state);
        alloc.slots_per_object.insert(*pid, per_object);
        let names: Vec<&str> = slots
            .iter()
            .map(|s| pass.kind.values()[*s as usize].name.as_str())
            .collect();
        report.push(
            "buffer",
            format!("compute pass `{}`", pass.name),
            format!(
                "over {}: {} per object ({}){}",
                domain.name(),
                names.join(", "),
                if per_object == 1 {
                    "1 vec4".to_string()
                } else {
                    format!("{per_object} vec4s")
                },
                if state {
                    "; keeps state: two copies, reset with the scene, the size or the style"
                } else {
                    ""
                }
            ),
        );
    }
}
