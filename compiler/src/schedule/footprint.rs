//! What a pass reads of a target it passes to an operator, from the
//! operator's declared footprint (`npr_stdlib::Footprint`): only its own pixel,
//! a neighbourhood of a known radius, or anywhere. Fusion needs the first;
//! a tiled schedule (issue 14) sizes its apron from the second; the third
//! bounds nothing.
//!
//! A footprint is "around the pixel" only when the operator's `uv` argument
//! is the pixel's own `screen_uv`, and a scaled radius (a Gaussian's 3σ) is
//! known only when its argument is a constant after specialization;
//! otherwise the declared maximum bounds it.

use crate::ir::*;
use std::fmt;

/// How a call reads one of its texture arguments.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Read {
    /// Within `radius` texels (Chebyshev) of the pixel's own texel; 0 is
    /// the pixel alone.
    AroundPixel { radius: u32 },
    /// At coordinates computed from data, or around a `uv` that is not the
    /// pixel's.
    Anywhere,
}

impl fmt::Display for Read {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Read::AroundPixel { radius: 0 } => write!(f, "reads it only at the pixel"),
            Read::AroundPixel { radius } => write!(f, "reads it within {radius} texel(s) of the pixel"),
            Read::Anywhere => write!(f, "reads it anywhere (at a computed coordinate)"),
        }
    }
}

/// The texture arguments of `call` (an operator call), each with how the
/// call reads it; empty for anything else.
pub fn texture_reads(ir: &Ir, call: ExprId) -> Vec<(ExprId, Read)> {
    let ExprKind::Call {
        callee: Callee::Operator(i),
        args,
    } = &ir.expr(call).kind
    else {
        return Vec::new();
    };
    let op = &npr_stdlib::all()[*i as usize];
    let arg_of = |name: &str| {
        op.params
            .iter()
            .position(|p| p.name == name)
            .and_then(|k| args.get(k).copied())
    };
    op.params
        .iter()
        .zip(args)
        .filter(|(p, _)| matches!(p.ty, npr_stdlib::Ty::Texture | npr_stdlib::Ty::SampledTexture))
        .map(|(p, a)| {
            let read = match op.footprint(p.name) {
                Some(npr_stdlib::Footprint::Around { uv, radius }) => {
                    let at_pixel =
                        arg_of(uv).is_some_and(|u| matches!(ir.expr(u).kind, ExprKind::Builtin(Builtin::ScreenUv)));
                    if at_pixel {
                        let value = match radius {
                            npr_stdlib::Radius::Scaled { param, .. } => {
                                arg_of(param).and_then(|v| match &ir.expr(v).kind {
                                    ExprKind::Const(c) => c.scalar(),
                                    _ => None,
                                })
                            }
                            npr_stdlib::Radius::Texels(_) => None,
                        };
                        Read::AroundPixel {
                            radius: radius.texels(value),
                        }
                    } else {
                        Read::Anywhere
                    }
                }
                // The completeness test guarantees a footprint per texture
                // parameter; a missing one is treated as the widest read.
                Some(npr_stdlib::Footprint::Anywhere) | None => Read::Anywhere,
            };
            (*a, read)
        })
        .collect()
}

/// The widest neighbourhood pass `pid` reads of any target (through its
/// operators' footprints): `Some(0)` when every target read is at the
/// pixel, `Some(r)` for an r-texel apron, `None` when some read is unbounded.
pub fn pass_apron(ir: &Ir, pid: PassId) -> Option<u32> {
    let pass = ir.pass(pid);
    let mut widest = 0;
    for n in ir.reachable(&pass.roots().all()) {
        for (arg, read) in texture_reads(ir, n) {
            if !matches!(ir.expr(arg).kind, ExprKind::Target { .. }) {
                continue;
            }
            match read {
                Read::AroundPixel { radius } => widest = widest.max(radius),
                Read::Anywhere => return None,
            }
        }
    }
    Some(widest)
}
