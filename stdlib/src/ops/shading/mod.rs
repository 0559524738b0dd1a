//! Shading terms and ramps: Lambert and half-Lambert diffuse, the N-step
//! toon ramp and the smooth threshold (Age of Sail §5.1 shadow shapes).

mod demos;

use super::{nums, p, random, scalar, Arg, Case, OpDef, Tol, Value};
use crate::image_f64::{dot3, unit};
use crate::{Default, Operator, Param, Ty, Unit};

pub fn lambert(n: [f64; 3], l: [f64; 3]) -> f64 {
    dot3(unit(n), unit(l)).max(0.0)
}

pub fn half_lambert(n: [f64; 3], l: [f64; 3]) -> f64 {
    let h = 0.5 * dot3(unit(n), unit(l)) + 0.5;
    h * h
}

pub fn toon(x: f64, steps: i64) -> f64 {
    let n = steps.max(1) as f64;
    let band = (x.clamp(0.0, 1.0) * n).floor().min(n - 1.0);
    if n > 1.0 {
        band / (n - 1.0)
    } else {
        0.0
    }
}

pub fn threshold(x: f64, lo: f64, hi: f64) -> f64 {
    if hi <= lo {
        return if x >= lo { 1.0 } else { 0.0 };
    }
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Random directions, and the hard ones: zero, tiny, huge, exact opposites.
const UNIT_BOX: (Value, Value) = ([-1.0, -1.0, -1.0, 0.0], [1.0, 1.0, 1.0, 1.0]);
const HARD_VECTORS: &[Value] = &[
    [0.0; 4],
    [1e-20, 0.0, 0.0, 0.0],
    [1e18, -1e18, 0.0, 1.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0, 0.0],
];
/// Both vectors normalized: f32 rounding of a few operations on values ≤ 1.
const DIFFUSE_CASES: &[Case] = &[
    Case::new(
        "random directions",
        &[random(UNIT_BOX.0, UNIT_BOX.1, 20), random(UNIT_BOX.0, UNIT_BOX.1, 20)],
        Tol::Abs(1e-5),
    ),
    Case::new(
        "zero, tiny, huge and opposite vectors",
        &[nums(HARD_VECTORS), nums(HARD_VECTORS)],
        Tol::Abs(1e-5),
    ),
];
const NL: &[Param] = &[
    p("n", Ty::Vec3, "surface normal"),
    p("l", Ty::Vec3, "direction towards the light"),
];

pub const LAMBERT: OpDef = OpDef::new(
    Operator {
        name: "lambert",
        doc: "Lambert diffuse term max(n·l, 0); zero vectors give 0.",
        reference: "Lambert 1760; any graphics text",
        params: NL,
        returns: Ty::Float,
        wgsl: include_str!("lambert.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(lambert(a[0].v3(), a[1].v3())),
    DIFFUSE_CASES,
)
.with_demo(demos::LAMBERT)
// The result's bounds (issue 49): checked by tests/op_ranges.rs.
.with_range(0.0, 1.0);

pub const HALF_LAMBERT: OpDef = OpDef::new(
    Operator {
        name: "half_lambert",
        doc: "Half-Lambert (0.5·n·l + 0.5)²: soft falloff that keeps form on the shadow side.",
        reference: "Mitchell et al., Shading in Valve's Source Engine, SIGGRAPH 2006 course",
        params: NL,
        returns: Ty::Float,
        wgsl: include_str!("half_lambert.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(half_lambert(a[0].v3(), a[1].v3())),
    DIFFUSE_CASES,
)
.with_demo(demos::HALF_LAMBERT)
// The result's bounds (issue 49): checked by tests/op_ranges.rs.
.with_range(0.0, 1.0);

/// Steps at both ends of the range; x outside [0, 1], on band edges, and random.
const STEPS: Arg = each![1, 2, 3, 5, 16];

pub const TOON: OpDef = OpDef::new(
    Operator {
        name: "toon",
        doc: "N-step toon ramp: x in [0, 1] quantized to `steps` bands, band k → k/(steps−1).",
        reference: "Lake et al., Stylized Rendering Techniques for Scalable Real-Time 3D Animation, NPAR 2000",
        params: &[
            p("x", Ty::Float, "the value to quantize, clamped to [0, 1]"),
            Param {
                name: "steps",
                ty: Ty::Int,
                unit: Unit::None,
                default: Default::Number(3.0),
                range: Some((1.0, 16.0)),
                doc: "number of bands",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("toon.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(toon(a[0].f(), a[1].i())),
    &[
        Case::new(
            "outside [0, 1] and on band edges",
            &[each![-0.5, 0.0, 1.0, 1.5, 0.5, 1.0 / 3.0], STEPS],
            Tol::Abs(1e-6),
        ),
        Case::new("random x", &[random([0.0; 4], [1.0; 4], 20), STEPS], Tol::Abs(1e-6)),
    ],
)
.with_demo(demos::TOON)
// The result's bounds (issue 49): checked by tests/op_ranges.rs.
.with_range(0.0, 1.0);

/// Bands including lo == hi and lo > hi (a step).
const LOS: Arg = each![0.45, 0.5, 0.6, 0.0];
const HIS: Arg = each![0.55, 0.5, 0.4, 1.0];

pub const THRESHOLD: OpDef = OpDef::new(
    Operator {
        name: "threshold",
        doc: "Smooth threshold: 0 below lo, 1 above hi, smoothstep between (a step when lo ≥ hi).",
        reference: "Age of Sail (Harvill et al. 2019), §5.1 thresholded shadow shapes",
        params: &[
            p("x", Ty::Float, "the value to threshold"),
            Param {
                name: "lo",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.45),
                range: None,
                doc: "lower edge of the band",
            },
            Param {
                name: "hi",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.55),
                range: None,
                doc: "upper edge of the band",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("threshold.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(threshold(a[0].f(), a[1].f(), a[2].f())),
    &[
        Case::new(
            "on and around the band edges",
            &[each![-1.0, 0.0, 0.45, 0.5, 0.55, 0.9, 2.0], LOS, HIS],
            Tol::Abs(1e-5),
        ),
        Case::new("random x", &[random([-0.2; 4], [1.2; 4], 20), LOS, HIS], Tol::Abs(1e-5)),
    ],
)
.with_demo(demos::THRESHOLD)
// The result's bounds (issue 49): checked by tests/op_ranges.rs.
.with_range(0.0, 1.0);
