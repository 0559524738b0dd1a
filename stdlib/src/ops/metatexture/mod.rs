//! MetaTexture (Harvill et al., Age of Sail, journal 2019, §3): a
//! tileable example texture blended at quantized scales so it keeps its
//! screen-space size on any surface (eqs. 1–8, eqs. 4–5 swapped: see the
//! erratum in `meta.wgsl`), with skew (eqs. 14–23) and contrast (eqs.
//! 24–25) compensation, the 4-tap variants that `skew: 0` compiles to, the
//! contour orientation of §3.5, and each with explicit gradients (`_grad`)
//! or fragment derivatives. The shared WGSL is the `meta` snippet.
//!
//! Tolerances: 8-bit bilinear weights (lavapipe) on a texture whose
//! neighbours differ by ≤ 0.06, and f32 coordinates at scale ≤ 4096:
//! ≤ 0.06/32 + 1/255 < 6e-3; variance-preserving contrast divides by √c ≥
//! 1/2, doubling it: 1.2e-2; the contour blend's 1/√k(w) ≤ √2 on top: 1.7e-2.

pub mod reference;
pub use reference::*;

mod demos;

use super::{p, random, Arg, Case, OpDef, Tol, Value};
use crate::image_f64::ImageF64;
use crate::{Default, Footprint, Operator, Param, Specialization, Ty, Unit};

/// The MetaTexture settings shared by both variants, after the texture/uv/gradients.
macro_rules! metatexture_settings {
    () => {
        [
            Param {
                name: "width",
                ty: Ty::Float,
                unit: Unit::Px,
                default: Default::Number(256.0),
                range: Some((1.0, 4096.0)),
                doc: "target screen-space width of the example texture (w of eq. 1)",
            },
            Param {
                name: "beta",
                ty: Ty::Enum(&["linear", "cubic", "quintic"]),
                unit: Unit::None,
                default: Default::Variant("cubic"),
                range: None,
                doc: "blend function β of eq. 7",
            },
            Param {
                name: "base",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(2.0),
                range: Some((1.01, 16.0)),
                doc: "quantization base: 2 as in the paper; 3, √2 or φ also work",
            },
            Param {
                name: "skew",
                ty: Ty::Int,
                unit: Unit::None,
                default: Default::Number(0.0),
                range: Some((0.0, 8.0)),
                doc: "skew levels n (eq. 16); 0 = 4 taps, ≥ 1 = 8 taps",
            },
            Param {
                name: "contrast",
                ty: Ty::Enum(&["none", "printed", "variance"]),
                unit: Unit::None,
                default: Default::Variant("none"),
                range: None,
                doc: "contrast compensation: none, × c as printed (eq. 24), or ÷ √c (variance-preserving)",
            },
            Param {
                name: "mean",
                ty: Ty::Color,
                unit: Unit::None,
                default: Default::Number(0.5),
                range: None,
                doc: "mean of the example texture, the pivot of contrast compensation",
            },
        ]
    };
}

const METATEXTURE_SAMPLED: Param = p("tex", Ty::SampledTexture, "the tileable example texture (wrap: repeat)");
const METATEXTURE_UV: Param = Param {
    name: "uv",
    ty: Ty::Vec2,
    unit: Unit::None,
    default: Default::Builtin("uv"),
    range: None,
    doc: "surface texture coordinates",
};

const METATEXTURE_GRAD_PARAMS: &[Param] = &{
    let s = metatexture_settings!();
    [
        METATEXTURE_SAMPLED,
        METATEXTURE_UV,
        p("grad_u", Ty::Vec2, "screen-space gradient of u, in UV per px"),
        p("grad_v", Ty::Vec2, "screen-space gradient of v, in UV per px"),
        s[0],
        s[1],
        s[2],
        s[3],
        s[4],
        s[5],
    ]
};

const METATEXTURE_PARAMS: &[Param] = &{
    let s = metatexture_settings!();
    [METATEXTURE_SAMPLED, METATEXTURE_UV, s[0], s[1], s[2], s[3], s[4], s[5]]
};

const METATEXTURE4_GRAD_PARAMS: &[Param] = &{
    let s = metatexture_settings!();
    [
        METATEXTURE_SAMPLED,
        METATEXTURE_UV,
        p("grad_u", Ty::Vec2, "screen-space gradient of u, in UV per px"),
        p("grad_v", Ty::Vec2, "screen-space gradient of v, in UV per px"),
        s[0],
        s[1],
        s[2],
        s[4],
        s[5],
    ]
};

const METATEXTURE_CONTOUR_GRAD_PARAMS: &[Param] = &{
    let g = METATEXTURE_GRAD_PARAMS;
    [
        g[0],
        g[1],
        g[2],
        g[3],
        g[4],
        g[5],
        g[6],
        g[7],
        g[8],
        g[9],
        Param {
            name: "orient",
            ty: Ty::Enum(&["off", "contour"]),
            unit: Unit::None,
            default: Default::Variant("contour"),
            range: None,
            doc: "off: plain MetaTexture (compiles to `metatexture_grad`); contour: re-orient (§3.5)",
        },
        Param {
            name: "band",
            ty: Ty::Float,
            unit: Unit::None,
            default: Default::Number(1.0),
            range: Some((0.01, 8.0)),
            doc: "width in octaves of |∇u|/|∇v| over which the two orientations blend",
        },
    ]
};

const METATEXTURE_CONTOUR_PARAMS: &[Param] = &{
    let g = METATEXTURE_CONTOUR_GRAD_PARAMS;
    [g[0], g[1], g[4], g[5], g[6], g[7], g[8], g[9], g[10], g[11]]
};

const METATEXTURE4_PARAMS: &[Param] = &{
    let s = metatexture_settings!();
    [METATEXTURE_SAMPLED, METATEXTURE_UV, s[0], s[1], s[2], s[4], s[5]]
};

/// A smooth tileable texture (8-bit, repeating).
fn tileable() -> ImageF64 {
    let tau = std::f64::consts::TAU;
    ImageF64::new(32, 32, |x, y| {
        let (u, v) = (f64::from(x) / 32.0, f64::from(y) / 32.0);
        [
            0.5 + 0.3 * (tau * u).sin(),
            0.5 + 0.3 * (tau * v).cos(),
            0.5 + 0.2 * (tau * (u + v)).sin(),
            1.0,
        ]
    })
}

const TEX: Arg = super::tex8(tileable, true);
const UVS: Arg = random([0.0; 4], [1.0, 1.0, 0.0, 0.0], 4);
/// The texture's screen width w of eq. 1, in px.
const W: f64 = 32.0;
/// ∇u and ∇v: ordinary, → 0, → ∞, parallel, zero, mixed.
const GRADS_U: &[Value] = &[
    [0.2 / W, 0.01 / W, 0.0, 0.0],
    [1e-12, 0.0, 0.0, 0.0],
    [1e6, 0.0, 0.0, 0.0],
    [0.1 / W, 0.1 / W, 0.0, 0.0],
    [0.0; 4],
    [3.0 / W, 0.5 / W, 0.0, 0.0],
];
const GRADS_V: &[Value] = &[
    [-0.02 / W, 0.3 / W, 0.0, 0.0],
    [0.0, 1e-12, 0.0, 0.0],
    [0.0, 1e6, 0.0, 0.0],
    [0.2 / W, 0.2 / W, 0.0, 0.0],
    [0.0; 4],
    [0.01 / W, 0.07 / W, 0.0, 0.0],
];
const WIDTH: Arg = each![W];
const BETA: Arg = each![1, 2, 0];
const BASE: Arg = each![2.0, 3.0, 1.618];
const SKEW: Arg = each![0, 1, 3];
const CONTRAST: Arg = each![0, 2, 1];
const MEAN: Arg = Arg::Const([0.5; 4]);
const BANDS: Arg = each![0.01, 1.0, 8.0];
/// uv affine in the pixel, so that its derivatives are (∇u, ∇v) as above.
const ORDINARY: Arg = Arg::ScreenUv {
    origin: [0.31, 0.17],
    dx: [0.2 / W, -0.02 / W],
    dy: [0.01 / W, 0.3 / W],
};
const ANISOTROPIC: Arg = Arg::ScreenUv {
    origin: [0.7, 0.4],
    dx: [3.0 / W, 0.01 / W],
    dy: [0.5 / W, 0.07 / W],
};
const PARALLEL: Arg = Arg::ScreenUv {
    origin: [0.2, 0.9],
    dx: [0.1 / W, 0.2 / W],
    dy: [0.1 / W, 0.2 / W],
};

/// A derivative variant over an 8 × 8 grid of its screen uv.
macro_rules! screen_case {
    ($what:expr, $uv:expr, [$($arg:expr),*], $tol:expr) => {
        Case::new($what, &[$($arg),*], Tol::Abs($tol)).over(8, 8)
    };
}

pub const METATEXTURE_GRAD: OpDef = OpDef::new(
    Operator {
        name: "metatexture_grad",
        doc: "MetaTexture: a tileable example texture blended at quantized scales so it keeps its screen-space size on any surface; UV gradients given explicitly.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3, eqs. 1–8 (eqs. 4–5 swapped, see erratum), skew eqs. 14–23 (σ of eq. 14 negated, see reference::SKEW_SIGN), contrast eqs. 24–25",
        params: METATEXTURE_GRAD_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("metatexture_grad.wgsl"),
        depends: &[],
        snippets: &["meta"],
        specializations: &[Specialization { param: "skew", value: 0.0, use_operator: "metatexture4_grad" }],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| metatexture_grad(a[0].tex(), a[1].v2(), a[2].v2(), a[3].v2(), &MetaSettings { width: a[4].f(), beta: a[5].i(), base: a[6].f(), skew: a[7].i(), contrast: a[8].i(), mean: a[9].v4() }),
    &[Case::new(
        "ordinary and hard gradients (→ 0, → ∞, parallel, zero) at every setting",
        &[TEX, UVS, Arg::Each(GRADS_U), Arg::Each(GRADS_V), WIDTH, BETA, BASE, SKEW, CONTRAST, MEAN],
        Tol::Abs(1.2e-2),
    )],
).with_demo(demos::METATEXTURE_GRAD);

pub const METATEXTURE: OpDef = OpDef::new(
    Operator {
        name: "metatexture",
        doc: "MetaTexture with UV gradients from fragment derivatives (eq. 1 with ∇u = (∂u/∂x, ∂u/∂y)).",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.1, eqs. 1–8",
        params: METATEXTURE_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("metatexture.wgsl"),
        depends: &["metatexture_grad"],
        snippets: &["meta"],
        specializations: &[Specialization {
            param: "skew",
            value: 0.0,
            use_operator: "metatexture4",
        }],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| {
        let (dx, dy) = a[1].derivatives();
        metatexture(
            a[0].tex(),
            a[1].v2(),
            dx,
            dy,
            &MetaSettings {
                width: a[2].f(),
                beta: a[3].i(),
                base: a[4].f(),
                skew: a[5].i(),
                contrast: a[6].i(),
                mean: a[7].v4(),
            },
        )
    },
    &[
        screen_case!(
            "ordinary derivatives",
            ORDINARY,
            [TEX, ORDINARY, WIDTH, BETA, BASE, SKEW, CONTRAST, MEAN],
            1.2e-2
        ),
        screen_case!(
            "anisotropic derivatives",
            ANISOTROPIC,
            [TEX, ANISOTROPIC, WIDTH, BETA, BASE, SKEW, CONTRAST, MEAN],
            1.2e-2
        ),
        // ∇u ∥ ∇v, where skew's σ changes fastest with the derivatives' f32
        // rounding (1.19e-2 measured on lavapipe): a quarter more.
        screen_case!(
            "parallel ∇u and ∇v",
            PARALLEL,
            [TEX, PARALLEL, WIDTH, BETA, BASE, SKEW, CONTRAST, MEAN],
            1.5e-2
        ),
    ],
)
.with_demo(demos::METATEXTURE);

pub const METATEXTURE4_GRAD: OpDef = OpDef::new(
    Operator {
        name: "metatexture4_grad",
        doc: "4-tap MetaTexture (no skew compensation) with explicit UV gradients; what `metatexture_grad` compiles to when `skew` is 0.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.1, eqs. 1–8 (eqs. 4–5 swapped, see erratum), contrast eqs. 24–25",
        params: METATEXTURE4_GRAD_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("metatexture4_grad.wgsl"),
        depends: &[],
        snippets: &["meta"],
        specializations: &[],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| metatexture4_grad(a[0].tex(), a[1].v2(), a[2].v2(), a[3].v2(), &MetaSettings { width: a[4].f(), beta: a[5].i(), base: a[6].f(), skew: 0, contrast: a[7].i(), mean: a[8].v4() }),
    &[Case::new(
        "ordinary and hard gradients (→ 0, → ∞, parallel, zero) at every setting",
        &[TEX, UVS, Arg::Each(GRADS_U), Arg::Each(GRADS_V), WIDTH, BETA, BASE, CONTRAST, MEAN],
        Tol::Abs(1.2e-2),
    )],
).with_demo(demos::METATEXTURE4_GRAD);

pub const METATEXTURE4: OpDef = OpDef::new(
    Operator {
        name: "metatexture4",
        doc: "4-tap MetaTexture with UV gradients from fragment derivatives; what `metatexture` compiles to when `skew` is 0.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.1, eqs. 1–8",
        params: METATEXTURE4_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("metatexture4.wgsl"),
        depends: &["metatexture4_grad"],
        snippets: &["meta"],
        specializations: &[],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| {
        let (dx, dy) = a[1].derivatives();
        metatexture4(a[0].tex(), a[1].v2(), dx, dy, &MetaSettings { width: a[2].f(), beta: a[3].i(), base: a[4].f(), skew: 0, contrast: a[5].i(), mean: a[6].v4() })
    },
    &[
        screen_case!("ordinary derivatives", ORDINARY, [TEX, ORDINARY, WIDTH, BETA, BASE, CONTRAST, MEAN], 1.2e-2),
        screen_case!("anisotropic derivatives", ANISOTROPIC, [TEX, ANISOTROPIC, WIDTH, BETA, BASE, CONTRAST, MEAN], 1.2e-2),
    ],
).with_demo(demos::METATEXTURE4);

pub const METATEXTURE_CONTOUR_GRAD: OpDef = OpDef::new(
    Operator {
        name: "metatexture_contour_grad",
        doc: "MetaTexture of a directional texture re-oriented to indicate contour: its x axis follows the less foreshortened of u and v, blended by β across `band` octaves of |∇u|/|∇v| (no seam); `orient: off` compiles to `metatexture_grad`.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.5 (Fig. 8), on eqs. 1–8, 14–25",
        params: METATEXTURE_CONTOUR_GRAD_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("metatexture_contour_grad.wgsl"),
        depends: &["metatexture_grad"],
        snippets: &["meta"],
        specializations: &[Specialization { param: "orient", value: 0.0, use_operator: "metatexture_grad" }],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| metatexture_contour_grad(a[0].tex(), a[1].v2(), a[2].v2(), a[3].v2(), &MetaSettings { width: a[4].f(), beta: a[5].i(), base: a[6].f(), skew: a[7].i(), contrast: a[8].i(), mean: a[9].v4() }, a[10].i(), a[11].f()),
    &[Case::new(
        "ordinary and hard gradients, orientation off and on, narrow and wide bands",
        &[TEX, UVS, Arg::Each(GRADS_U), Arg::Each(GRADS_V), WIDTH, each![1], each![2.0], each![0, 2], CONTRAST, MEAN, each![0, 1], BANDS],
        Tol::Abs(1.7e-2),
    )],
).with_demo(demos::METATEXTURE_CONTOUR_GRAD);

pub const METATEXTURE_CONTOUR: OpDef = OpDef::new(
    Operator {
        name: "metatexture_contour",
        doc: "Contour-oriented MetaTexture (see `metatexture_contour_grad`) with UV gradients from fragment derivatives; `orient: off` compiles to `metatexture`.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.5 (Fig. 8), on eqs. 1–8, 14–25",
        params: METATEXTURE_CONTOUR_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("metatexture_contour.wgsl"),
        depends: &["metatexture_contour_grad"],
        snippets: &["meta"],
        specializations: &[Specialization { param: "orient", value: 0.0, use_operator: "metatexture" }],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| {
        let (dx, dy) = a[1].derivatives();
        metatexture_contour(a[0].tex(), a[1].v2(), dx, dy, &MetaSettings { width: a[2].f(), beta: a[3].i(), base: a[4].f(), skew: a[5].i(), contrast: a[6].i(), mean: a[7].v4() }, a[8].i(), a[9].f())
    },
    &[
        screen_case!(
            "ordinary derivatives",
            ORDINARY,
            [TEX, ORDINARY, WIDTH, each![1], each![2.0], each![0, 2], CONTRAST, MEAN, each![0, 1], BANDS],
            1.7e-2
        ),
        screen_case!(
            "anisotropic derivatives",
            ANISOTROPIC,
            [TEX, ANISOTROPIC, WIDTH, each![1], each![2.0], each![0, 2], CONTRAST, MEAN, each![0, 1], BANDS],
            1.7e-2
        ),
    ],
).with_demo(demos::METATEXTURE_CONTOUR);
