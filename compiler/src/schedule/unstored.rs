//! What pointwise fusion (`fuse.rs`) and recomputed tiles (`recompute.rs`)
//! share: a producer whose target is not stored, because its one image
//! reader computes it. Both refuse the same targets and the same readers,
//! and both hand the producer's inputs to the reader.

use crate::ir::*;
use npr_abi::formats::Storage;
use npr_abi::manifest::Blend;

/// Why target `t` must stay stored, if it must: it is the output, blends,
/// is a constant (`constant_why` says why that matters to the caller), or
/// is sRGB, whose encoding no shader repeats.
pub(super) fn must_be_stored(ir: &Ir, t: TargetRef, constant_why: &str) -> Result<(), String> {
    let o = &ir.pass(t.pass).outputs[t.output as usize];
    let name = ir.target_name(t);
    if ir.output == Some(t) {
        return Err(format!("`{name}` is the style's output"));
    }
    if o.blend != Blend::Replace {
        return Err(format!("`{name}` blends into its target"));
    }
    if matches!(ir.expr(o.value).kind, ExprKind::Const(_)) {
        return Err(format!("`{name}` is a constant, {constant_why}"));
    }
    if o.format.storage() == Storage::Srgb8 {
        return Err(format!(
            "`{name}` is {}, whose encoding is not repeated",
            o.format.name()
        ));
    }
    Ok(())
}

/// Why `reader` cannot compute pass `producer`'s target, if it cannot: it
/// is not an image pass, or runs at another scale (its pixels are not the
/// producer's).
pub(super) fn reader_kind_and_scale(ir: &Ir, reader: PassId, producer: PassId) -> Result<(), String> {
    let r = ir.pass(reader);
    if !matches!(r.kind, PassKind::Image { .. }) {
        return Err(format!("read by `{}`, a {} pass", r.name, r.kind.name()));
    }
    let scale = ir.pass(producer).scale;
    if r.scale != scale {
        return Err(format!("`{}` runs at scale {}, this pass at {scale}", r.name, r.scale));
    }
    Ok(())
}

/// The reader computes `producer` now: it reads what the producer read
/// (its `inputs`, for the pass order), and no longer the producer.
pub(super) fn take_over_inputs(ir: &mut Ir, reader: PassId, producer: PassId) {
    let moved = match &ir.pass(producer).kind {
        PassKind::Image { inputs, .. } => inputs.clone(),
        _ => Vec::new(),
    };
    if let PassKind::Image { inputs, .. } = &mut ir.passes[reader.0 as usize].kind {
        inputs.retain(|p| *p != producer);
        for p in moved {
            if !inputs.contains(&p) {
                inputs.push(p);
            }
        }
    }
}
