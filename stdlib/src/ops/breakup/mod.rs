//! The MetaTexture extensions and Edge Breakup operators of Age of Sail
//! (Harvill et al., journal 2019): radial-angle compensation (§3.3, eqs.
//! 11–13), smooth UV gradients (§3.2, eqs. 9–10), the live texture (§6.1,
//! eqs. 27–30), line boil (§4.2), camera-roll compensation (§4.3),
//! distance attenuation (§4.4, eq. 26) and the warp itself (§4).

pub mod reference;
pub use reference::*;

mod demos;

use super::{images, p, pair, random, scalar, tex32, Arg, Case, OpDef, Tol, Value, UV_SCREEN};
use crate::{Default, Footprint, Operator, Param, Ty, Unit};

/// Screen positions at the centre and corners; focal lengths incl. 0 and huge.
const CORNERS: &[Value] = &[
    [0.0; 4],
    [1.0, 1.0, 0.0, 0.0],
    [0.5, 0.5, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
];
const FOCALS: &[Value] = &[
    [1.0, 1.0, 0.0, 0.0],
    [2.747, 2.747, 0.0, 0.0],
    [0.8, 1.4, 0.0, 0.0],
    [0.0; 4],
    [1e-8, 3.0, 0.0, 0.0],
    [1e8, 1e8, 0.0, 0.0],
];
/// T_s and B_s: ordinary, zero, tiny, huge, equal.
const TANGENTS: &[Value] = &[
    [120.0, 3.0, 0.0, 0.0],
    [0.0; 4],
    [1e-12, 0.0, 0.0, 0.0],
    [1e12, -1e12, 0.0, 0.0],
    [40.0, 40.0, 0.0, 0.0],
];
const BITANGENTS: &[Value] = &[
    [-5.0, 80.0, 0.0, 0.0],
    [0.0; 4],
    [0.0, 1e-12, 0.0, 0.0],
    [3e11, 1e12, 0.0, 0.0],
    [40.0, 40.0, 0.0, 0.0],
];
const DENSITIES: &[Value] = &[
    [1.0, 1.0, 0.0, 0.0],
    [0.0; 4],
    [1e6, 1e6, 0.0, 0.0],
    [0.25, 4.0, 0.0, 0.0],
];
/// ∇u: ordinary, zero, tiny, huge.
const GRAD_U: &[Value] = &[
    [0.01, 0.0, 0.0, 0.0],
    [0.0, -3.0, 0.0, 0.0],
    [1e-35, 0.0, 0.0, 0.0],
    [0.0; 4],
    [1e35, 1e35, 0.0, 0.0],
    [-0.2, 0.7, 0.0, 0.0],
];

/// Displacements of a whole number of texels plus or minus a quarter (a
/// nearest read is exact there), near and far off the image, at texel centres.
macro_rules! warp_case {
    ($what:expr, $strength:expr) => {
        Case::new(
            $what,
            &[
                tex32(|| images::noise(24, 16, 61)),
                Arg::Each(&[
                    [10.25 / $strength, -3.25 / $strength, 0.0, 0.0],
                    [-37.25 / $strength, 20.75 / $strength, 0.0, 0.0],
                    [0.25 / $strength, -0.25 / $strength, 0.0, 0.0],
                    [2.75 / $strength, 1.25 / $strength, 0.0, 0.0],
                    [-5.25 / $strength, -39.75 / $strength, 0.0, 0.0],
                ]),
                each![$strength],
                Arg::Uv,
            ],
            Tol::Abs(0.0),
        )
        .over(24, 16)
    };
}

pub const RADIAL_ALPHA: OpDef = OpDef::new(
    Operator {
        name: "radial_alpha",
        doc: "Radial-angle compensation α = |Q|² + 1, Q = (s_x/P₀₀, s_y/P₁₁) with s the NDC position (= 1/cos² of the angle off the optical axis); `width: texel_width * radial_alpha()` is eq. 11.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.3, eqs. 11–13",
        params: &[
            Param {
                name: "screen_uv",
                ty: Ty::Vec2,
                unit: Unit::None,
                default: Default::Builtin("screen_uv"),
                range: None,
                doc: "position on screen in [0, 1]² (default: this pixel)",
            },
            Param {
                name: "focal",
                ty: Ty::Vec2,
                unit: Unit::None,
                default: Default::Builtin("camera.focal"),
                range: None,
                doc: "(P₀₀, P₁₁) of the projection matrix (default: this camera's)",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("radial_alpha.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(radial_alpha(a[0].v2(), a[1].v2())),
    &[
        Case::new("the centre and corners", &[Arg::Each(CORNERS), Arg::Each(FOCALS)], Tol::Rel(1e-5)),
        Case::new("random pixels", &[random([0.0; 4], [1.0, 1.0, 0.0, 0.0], 8), Arg::Each(FOCALS)], Tol::Rel(1e-5)),
    ],
).with_demo(demos::RADIAL_ALPHA);

pub const UV_GRADIENTS: OpDef = OpDef::new(
    Operator {
        name: "uv_gradients",
        doc: "Smooth screen-space UV gradients from the per-vertex screen-space tangent frame: (∇u, ∇v) packed as vec4 (xy = ∇u, zw = ∇v, UV per px) for `metatexture_grad`; continuous across triangles, unlike derivatives. Default: the exact inverse of the tangent frame; `mode: paper` is eqs. 9–10 as printed.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.2, eqs. 9–10",
        params: &[
            Param {
                name: "tangent",
                ty: Ty::Vec2,
                unit: Unit::None,
                default: Default::Builtin("tangent.screen"),
                range: None,
                doc: "T_s, screen-space projection of the unit tangent in px per metre (`tangent.screen_center` in stereo projects with one camera for both eyes)",
            },
            Param {
                name: "bitangent",
                ty: Ty::Vec2,
                unit: Unit::None,
                default: Default::Builtin("bitangent.screen"),
                range: None,
                doc: "B_s, screen-space projection of the unit bitangent (direction of +v) in px per metre",
            },
            Param {
                name: "density",
                ty: Ty::Vec2,
                unit: Unit::None,
                default: Default::Number(1.0),
                range: Some((0.0, 1e6)),
                doc: "world-space UV density (|∇_w u|, |∇_w v|) in UV per metre, constant per mesh (e.g. an `object param`)",
            },
            Param {
                name: "mode",
                ty: Ty::Enum(&["inverse", "paper"]),
                unit: Unit::None,
                default: Default::Variant("inverse"),
                range: None,
                doc: "inverse: rows of [T_s B_s]⁻¹ (true gradients, right for skew compensation); paper: eqs. 9–10 as printed (∇u ∥ T_s)",
            },
        ],
        returns: Ty::Vec4,
        wgsl: include_str!("uv_gradients.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| uv_gradients(a[0].v2(), a[1].v2(), a[2].v2(), a[3].i()),
    &[
        Case::new(
            "ordinary, zero, tiny, huge and equal projections; densities at the range ends",
            &[Arg::Each(TANGENTS), Arg::Each(BITANGENTS), Arg::Each(DENSITIES), each![0, 1]],
            Tol::Rel(1e-5),
        ),
        Case::new(
            "random projections and densities",
            &[
                random([-200.0; 4], [200.0; 4], 6),
                random([-200.0; 4], [200.0; 4], 6),
                random([0.0; 4], [10.0; 4], 2),
                each![0, 1],
            ],
            Tol::Rel(1e-5),
        ),
    ],
).with_demo(demos::UV_GRADIENTS);

pub const LIVE_TEXTURE: OpDef = OpDef::new(
    Operator {
        name: "live_texture",
        doc: "Live texture: cycles smoothly through a mix of T's red, green and blue channels, T' = ½ + (T·L₁) cos 2πft + (T·L₂) sin 2πft (the three equal components of eq. 27, returned as one float); offset `time` by world position for a travelling effect.",
        reference: "Harvill et al., Age of Sail (journal 2019) §6.1, eqs. 27–30 (ft read as 2π·f·t, f in cycles per second)",
        params: &[
            p("t", Ty::Color, "the texture value T (rgb used)"),
            Param {
                name: "freq",
                ty: Ty::Float,
                unit: Unit::Hertz,
                default: Default::Number(0.75),
                range: Some((0.0, 30.0)),
                doc: "f, cycles per second (the paper uses 0.5–1 Hz)",
            },
            Param {
                name: "time",
                ty: Ty::Float,
                unit: Unit::Seconds,
                default: Default::Builtin("time"),
                range: None,
                doc: "t (default: the frame time; e.g. `time + dot(position.world, …)` for a world-space offset)",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("live_texture.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(live_texture(a[0].v4(), a[1].f(), a[2].f())),
    &[Case::new(
        "random colours and times, frequencies at the range ends",
        &[
            random([0.0, 0.0, 0.0, 1.0], [1.0; 4], 12),
            each![0.0, 0.5, 1.0, 30.0],
            random([-100.0; 4], [100.0; 4], 12),
        ],
        // f32 phase: f·t ≤ 3000 keeps fract(f·t) within 2.5e-4 of f64.
        Tol::Abs(3e-3),
    )],
).with_demo(demos::LIVE_TEXTURE);

pub const LINE_BOIL: OpDef = OpDef::new(
    Operator {
        name: "line_boil",
        doc: "Animated line boil: uv plus a stepped, periodic offset that changes `rate` times per second (12 Hz = on twos at 24 fps) and repeats every `cycle` steps.",
        reference: "Harvill et al., Age of Sail (journal 2019) §4.2 (Fig. 12)",
        params: &[
            Param {
                name: "uv",
                ty: Ty::Vec2,
                unit: Unit::None,
                default: Default::Builtin("uv"),
                range: None,
                doc: "texture coordinates to offset",
            },
            Param {
                name: "amount",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(1.0),
                range: Some((0.0, 1.0)),
                doc: "largest offset in UV (1 = anywhere in a tileable texture)",
            },
            Param {
                name: "rate",
                ty: Ty::Float,
                unit: Unit::Hertz,
                default: Default::Number(12.0),
                range: Some((0.0, 120.0)),
                doc: "drawings per second (0 = still)",
            },
            Param {
                name: "cycle",
                ty: Ty::Int,
                unit: Unit::None,
                default: Default::Number(4.0),
                range: Some((1.0, 1024.0)),
                doc: "number of distinct drawings before the boil repeats",
            },
            Param {
                name: "time",
                ty: Ty::Float,
                unit: Unit::Seconds,
                default: Default::Builtin("time"),
                range: None,
                doc: "the clock (default: the frame time)",
            },
        ],
        returns: Ty::Vec2,
        wgsl: include_str!("line_boil.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| {
        let (rate, time) = (a[2].f(), a[4].f());
        // A step function of time: undefined within 1% of a step's edge.
        let s = (time * rate.max(0.0) + 1e-3).fract();
        if rate > 0.0 && !(0.01..=0.99).contains(&s) {
            return [f64::NAN; 4];
        }
        pair(line_boil(a[0].v2(), a[1].f(), rate, a[3].i(), time))
    },
    &[Case::new(
        "amounts, rates and cycles at the range ends, times from −4 s to 40 s",
        &[
            random([0.0; 4], [1.0; 4], 3),
            each![1.0, 0.0, 0.3],
            each![12.0, 0.0, 120.0, 6.0],
            each![4, 1024, 1],
            random([-4.0; 4], [40.0; 4], 16),
        ],
        // k·(1/φ₂) for k < 1024 in f32: ≤ 6e-5 before fract.
        Tol::Abs(2e-4),
    )
    .skipping(0.05)],
).with_demo(demos::LINE_BOIL);

pub const ROLL_COMPENSATE: OpDef = OpDef::new(
    Operator {
        name: "roll_compensate",
        doc: "Camera-roll compensation: a warp vector expressed in the frame of the screen-space ∇u (x along ∇u, y 90° from it), so the warp field rolls with the camera.",
        reference: "Harvill et al., Age of Sail (journal 2019) §4.3 (Fig. 13)",
        params: &[
            p("offset", Ty::Vec2, "the warp vector, e.g. a noise texture's rg remapped to [−1, 1]"),
            p("grad_u", Ty::Vec2, "screen-space gradient of u (e.g. `uv_gradients(...).xy`)"),
        ],
        returns: Ty::Vec2,
        wgsl: include_str!("roll_compensate.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| pair(roll_compensate(a[0].v2(), a[1].v2())),
    &[Case::new(
        "ordinary, zero, tiny and huge ∇u",
        &[random([-1.0; 4], [1.0; 4], 6), Arg::Each(GRAD_U)],
        Tol::Abs(1e-6),
    )],
).with_demo(demos::ROLL_COMPENSATE);

pub const DISTANCE_ATTENUATE: OpDef = OpDef::new(
    Operator {
        name: "distance_attenuate",
        doc: "Distance compensation of the warp intensity: ρ' = ρ / (1 + (d/falloff)²).",
        reference: "Harvill et al., Age of Sail (journal 2019) §4.4, eq. 26",
        params: &[
            p("rho", Ty::Float, "warp intensity ρ"),
            Param {
                name: "d",
                ty: Ty::Float,
                unit: Unit::Meters,
                default: Default::Required,
                range: None,
                doc: "distance from the camera, e.g. `distance(position.world, camera.position)`",
            },
            Param {
                name: "falloff",
                ty: Ty::Float,
                unit: Unit::Meters,
                default: Default::Number(1.0),
                range: Some((0.001, 1e5)),
                doc: "distance unit of eq. 26 (1 m as printed): ρ halves at d = falloff",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("distance_attenuate.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(distance_attenuate(a[0].f(), a[1].f(), a[2].f())),
    &[Case::new(
        "d → 0, d → 1e5 and beyond, falloff at both ends of its range",
        &[
            each![0.0, 1.0, 2.0],
            each![0.0, 1e-3, 1.0, 7.5, 1e5, 1e20, -3.0],
            each![0.001, 1.0, 1e5],
        ],
        Tol::Rel(1e-6),
    )],
)
.with_demo(demos::DISTANCE_ATTENUATE);

pub const WARP: OpDef = OpDef::new(
    Operator {
        name: "warp",
        doc: "Edge-breakup warp: `src` read at this pixel displaced by offset · strength px (nearest texel, clamped at the border); use on the clean colour pass with the warp pass's vector field.",
        reference: "Harvill et al., Age of Sail (journal 2019) §4 (Fig. 10)",
        params: &[
            p("src", Ty::Texture, "the target to warp (e.g. the colour pass)"),
            p("offset", Ty::Vec2, "the warp vector at this pixel (e.g. a warp pass's rg target)"),
            Param {
                name: "strength",
                ty: Ty::Float,
                unit: Unit::Px,
                default: Default::Number(4.0),
                range: Some((0.0, 256.0)),
                doc: "displacement in px of `src` for a unit offset",
            },
            UV_SCREEN,
        ],
        returns: Ty::Vec4,
        wgsl: include_str!("warp.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("src", Footprint::Anywhere)],
    },
    |a| warp(a[0].tex(), a[1].v2(), a[2].f(), a[3].v2()),
    &[
        warp_case!("strength 4", 4.0),
        warp_case!("strength 256", 256.0),
        Case::new(
            "strength 0",
            &[tex32(|| images::noise(24, 16, 61)), Arg::Each(&[[3.0, -7.0, 0.0, 0.0]]), each![0.0], Arg::Uv],
            Tol::Abs(0.0),
        )
        .over(24, 16),
    ],
).with_demo(demos::WARP);
