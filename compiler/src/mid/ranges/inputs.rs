//! Where ranges start: each builtin's range (what the runtime provides),
//! each parameter's (its declared range, `--set` applied), each texture's
//! (its format's) and what a target holds after a store in its format.
//!
//! The builtin ranges are the runtime's contract as `ir/builtins.rs`
//! documents it: unit directions (normals, light and view directions,
//! tangents) have length 1 up to f32 rounding, `screen_uv` is in [0, 1],
//! `time`, `frame`, depths and distances are ≥ 0. A mesh with a degenerate
//! normal breaks the first; the analysis assumes meshes that `npr` loads
//! (which recompute zero normals) do not.

use super::interval::{Iv, F32_MAX};
use super::value::Val;
use crate::ir::{Builtin, Ir, ParamTy, TextureSource, Ty};
use npr_abi::Format;

/// Every finite value ≥ 0.
const NON_NEGATIVE: Iv = Iv {
    lo: 0.0,
    hi: F32_MAX,
    nan: false,
};

fn finite(n: usize) -> Val {
    Val::splat(Iv::FINITE, n)
}

/// The range the runtime gives builtin `b`.
pub fn builtin(b: Builtin) -> Val {
    use Builtin::*;
    let n = b.ty_unit().0.components().unwrap_or(1) as usize;
    match b {
        NormalWorld | NormalView | Tangent | ViewDir | LightDir | MoreLightDir(_) | CameraForward | CameraRight
        | CameraUp => Val::unit(n),
        ScreenUv | PatchWeight | Eye | CameraOrthographic => Val::splat(Iv::UNIT, n),
        LineAcross => Val::splat(Iv::SIGNED_UNIT, n),
        // Light-space NDC: x, y in [−1, 1], z in [0, 1] (builtins.rs).
        PositionLight => Val {
            comps: vec![Iv::SIGNED_UNIT, Iv::SIGNED_UNIT, Iv::UNIT],
            norm: None,
        },
        Time
        | Frame
        | Depth
        | CameraFar
        | SampleSpacing
        | FragCoord
        | LightColor
        | LightIntensity
        | MoreLightColor(_)
        | MoreLightIntensity(_)
        | ObjectIndex
        | ObjectId
        | LineArc
        | LineSet => Val::splat(NON_NEGATIVE, n),
        // A perspective camera's near plane is past the eye, and its
        // focal lengths (P₀₀, P₁₁ = cot(fov/2) over the aspect and 1) are
        // positive: its fov is in (0°, 180°). An orthographic camera's
        // (2 / width, 2 / height) are positive: its height is. Scenes check
        // these (E0405), and so does the embedding API for every frame's
        // camera (E0616).
        CameraNear | CameraFocal => Val::splat(Iv::new(f32::MIN_POSITIVE as f64, F32_MAX), n),
        Resolution => Val::splat(Iv::new(1.0, F32_MAX), n),
        Uv
        | PositionWorld
        | PositionView
        | CameraPosition
        | PositionPrevious
        | CameraLeftEye
        | CameraRightEye
        | TangentScreen
        | BitangentScreen
        | TangentScreenCenter
        | BitangentScreenCenter => finite(n),
    }
}

/// How a parameter ranges in this compile.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamRange {
    /// Over its declared range (`in a..b`), or every value of a bool or
    /// enum: a param nobody fixed, which the sweep, the studio or a
    /// test's `set` may move.
    Declared,
    /// Its value here: a `--set` value, or the default of a param that
    /// declares no range (kept live or not: the proof is over declared
    /// ranges, as the sweep's is).
    Value,
}

/// How `p` ranges: fixed by `--set` (`set`), or not. A param kept live
/// (`--keep-params`) ranges as one that is not: over its declared range.
pub fn param_range(p: &crate::ir::Param, set: bool, keep: bool) -> ParamRange {
    let declared = p.range.is_some() || matches!(p.ty, ParamTy::Enum(_) | ParamTy::Value(Ty::Bool));
    if (set && !keep) || !declared {
        ParamRange::Value
    } else {
        ParamRange::Declared
    }
}

/// A parameter's declared range (or its type's, for a colour or
/// gradient), its keyframes joined.
pub fn param(p: &crate::ir::Param) -> Val {
    let n = p.value_ty.components().unwrap_or(1) as usize;
    let mut v = match &p.ty {
        ParamTy::Enum(options) => Val::splat(Iv::new(0.0, options.len().saturating_sub(1) as f64), 1),
        ParamTy::Value(Ty::Bool) => Val::splat(Iv::UNIT, 1),
        ParamTy::Color | ParamTy::Gradient => Val::splat(Iv::UNIT, n),
        _ => match p.range {
            Some((lo, hi)) => Val::splat(Iv::new(lo, hi), n),
            None => finite(n),
        },
    };
    // An animated param takes its keyframes' values (the range check lets
    // only values in range through; joined anyway, never narrower).
    for k in &p.keys {
        let kv = Val {
            comps: k.value.iter().map(|x| Iv::point(*x)).collect(),
            norm: None,
        };
        v = v.join(&kv);
    }
    v
}

/// What sampling a texture gives: 8- and 16-bit images, noise, tables and
/// art-maps are unorm ([0, 1]); an HDR image may hold anything.
pub fn texture(ir: &Ir, t: crate::ir::TextureId, n: usize) -> Val {
    let tex = &ir.textures[t.0 as usize];
    let hdr = |p: &str| {
        let p = p.to_ascii_lowercase();
        p.ends_with(".exr") || p.ends_with(".hdr")
    };
    match &tex.source {
        TextureSource::Image { path, .. } | TextureSource::Artmap { path, .. } if hdr(path) => Val::top(n),
        // A filter's input level is the filter's own target: any float.
        TextureSource::FilterInput => Val::top(n),
        _ => Val::splat(Iv::UNIT, n),
    }
}

/// The range a format's store leaves of `v`: unorm clamps to [0, 1] (NaN
/// stores as 0 in Vulkan and D3D, but WebGPU does not say: kept as a
/// possibility), f16 overflows past 65504 to ±∞.
pub fn stored(format: Format, v: &Val) -> Val {
    let comps = v
        .comps
        .iter()
        .map(|c| {
            if format.is_unorm() {
                // A unorm texel holds a number; NaN converts to one (0 in
                // Vulkan; some number in [0, 1] wherever).
                let k = c.clamp(Iv::point(0.0), Iv::point(1.0));
                let k = if c.nan { Iv::UNIT } else { k };
                Iv { nan: false, ..k }
            } else if is_f16(format) {
                f16(*c)
            } else {
                *c
            }
        })
        .collect();
    Val { comps, norm: None }
}

pub fn is_f16(format: Format) -> bool {
    matches!(format, Format::R16float | Format::Rg16float | Format::Rgba16float)
}

/// The largest finite f16.
pub const F16_MAX: f64 = 65504.0;

fn f16(c: Iv) -> Iv {
    // Round to nearest: values up to 65520 still round to 65504.
    // An f16 has 11 significant bits: a value moves by 2⁻¹¹ of itself at most.
    let lim = 65520.0;
    let r = 1.0 + 2f64.powi(-11);
    let end = |x: f64, inf: f64| if x.abs() >= lim { inf } else { x * r };
    if c.is_empty() {
        return c;
    }
    Iv {
        lo: if c.lo < 0.0 {
            end(c.lo, f64::NEG_INFINITY)
        } else {
            c.lo / r
        },
        hi: if c.hi > 0.0 { end(c.hi, f64::INFINITY) } else { c.hi / r },
        nan: c.nan,
    }
}

/// The range of a format itself: what a target of it can hold at all.
pub fn format_range(format: Format) -> Iv {
    if format.is_unorm() {
        Iv::UNIT
    } else {
        Iv::TOP
    }
}
