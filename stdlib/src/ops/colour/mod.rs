//! Colour operators: Porter-Duff `over` with straight alpha, Rec. 709
//! luma, luma-preserving saturation and the overlay blend mode (Age of
//! Sail §5.2 colour controls). Tolerances 1e-5 (1e-6 for luma): f32
//! rounding of a few operations on values ≤ 1.

mod demos;

use super::{p, random, scalar, Arg, Case, OpDef, Tol, Value};
use crate::{Default, Operator, Param, Ty, Unit};

pub fn over(fg: [f64; 4], bg: [f64; 4]) -> [f64; 4] {
    let a = fg[3] + bg[3] * (1.0 - fg[3]);
    if a <= 0.0 {
        return [0.0; 4];
    }
    let c = |i: usize| (fg[i] * fg[3] + bg[i] * bg[3] * (1.0 - fg[3])) / a.max(1e-8);
    [c(0), c(1), c(2), a]
}

pub fn luminance(c: [f64; 4]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

pub fn saturation(c: [f64; 4], amount: f64) -> [f64; 4] {
    let g = luminance(c);
    [
        g + (c[0] - g) * amount,
        g + (c[1] - g) * amount,
        g + (c[2] - g) * amount,
        c[3],
    ]
}

pub fn overlay(base: [f64; 4], blend: [f64; 4], opacity: f64) -> [f64; 4] {
    let ch = |i: usize| {
        let (b, s) = (base[i], blend[i]);
        let o = if b < 0.5 {
            2.0 * b * s
        } else {
            1.0 - 2.0 * (1.0 - b) * (1.0 - s)
        };
        b + (o - b) * opacity
    };
    [ch(0), ch(1), ch(2), base[3]]
}

const RANDOM_COLOUR: Arg = random([0.0; 4], [1.0; 4], 12);
/// Both transparent, opaque over anything, the mid-grey overlay pivot.
const HARD_FG: &[Value] = &[[0.0; 4], [1.0, 0.0, 0.0, 1.0], [0.5, 0.5, 0.5, 0.5]];
const HARD_BG: &[Value] = &[[0.0; 4], [0.0, 1.0, 0.0, 0.0], [0.5, 0.5, 0.5, 1.0]];
const AMOUNTS: Arg = each![0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0];

pub const OVER: OpDef = OpDef::new(
    Operator {
        name: "over",
        doc: "Porter-Duff `fg over bg` with straight alpha.",
        reference: "Porter & Duff, Compositing Digital Images, SIGGRAPH 1984",
        params: &[p("fg", Ty::Color, "foreground"), p("bg", Ty::Color, "background")],
        returns: Ty::Color,
        wgsl: include_str!("over.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| over(a[0].v4(), a[1].v4()),
    &[
        Case::new("random colours", &[RANDOM_COLOUR, RANDOM_COLOUR], Tol::Abs(1e-5)),
        Case::new(
            "transparent, opaque and half colours",
            &[Arg::Each(HARD_FG), Arg::Each(HARD_BG)],
            Tol::Abs(1e-5),
        ),
    ],
)
.with_demo(demos::OVER);

pub const LUMINANCE: OpDef = OpDef::new(
    Operator {
        name: "luminance",
        doc: "Rec. 709 luma of a colour.",
        reference: "ITU-R BT.709",
        params: &[p("c", Ty::Color, "colour")],
        returns: Ty::Float,
        wgsl: include_str!("luminance.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(luminance(a[0].v4())),
    &[
        Case::new("random colours", &[random([0.0; 4], [1.0; 4], 50)], Tol::Abs(1e-6)),
        Case::new(
            "transparent, opaque and half colours",
            &[Arg::Each(HARD_FG)],
            Tol::Abs(1e-6),
        ),
    ],
)
.with_demo(demos::LUMINANCE);

pub const SATURATION: OpDef = OpDef::new(
    Operator {
        name: "saturation",
        doc: "Scale saturation: 0 = grey, 1 = unchanged, > 1 = more saturated; alpha kept.",
        reference: "luma-preserving saturation (Haeberli 1993)",
        params: &[
            p("c", Ty::Color, "colour"),
            Param {
                name: "amount",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(1.0),
                range: Some((0.0, 4.0)),
                doc: "saturation factor",
            },
        ],
        returns: Ty::Color,
        wgsl: include_str!("saturation.wgsl"),
        depends: &["luminance"],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| saturation(a[0].v4(), a[1].f()),
    &[
        Case::new(
            "random colours over the range of amounts",
            &[RANDOM_COLOUR, AMOUNTS],
            Tol::Abs(1e-5),
        ),
        Case::new(
            "transparent, opaque and half colours",
            &[Arg::Each(HARD_FG), AMOUNTS],
            Tol::Abs(1e-5),
        ),
    ],
)
.with_demo(demos::SATURATION);

pub const OVERLAY: OpDef = OpDef::new(
    Operator {
        name: "overlay",
        doc: "Overlay blend mode of `blend` onto `base`, mixed by `opacity`; base alpha kept.",
        reference: "the overlay blend mode (Adobe PDF blend modes); Age of Sail §5.2 colour controls",
        params: &[
            p("base", Ty::Color, "the underlying colour"),
            p("blend", Ty::Color, "the colour overlaid"),
            Param {
                name: "opacity",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(1.0),
                range: Some((0.0, 1.0)),
                doc: "how much of the overlay result to use",
            },
        ],
        returns: Ty::Color,
        wgsl: include_str!("overlay.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| overlay(a[0].v4(), a[1].v4(), a[2].f()),
    &[
        Case::new(
            "random colours",
            &[RANDOM_COLOUR, RANDOM_COLOUR, each![0.0, 0.125, 0.5, 1.0]],
            Tol::Abs(1e-5),
        ),
        Case::new(
            "transparent, opaque and the mid-grey pivot",
            &[Arg::Each(HARD_FG), Arg::Each(HARD_BG), each![0.0, 0.5, 1.0]],
            Tol::Abs(1e-5),
        ),
    ],
)
.with_demo(demos::OVERLAY);
