//! LSA contours (Zaidi et al., "Local Surface Approximation Contours for
//! Virtual Reality Stylisation"): the full monoscopic method `lsa` (eqs.
//! 1–8 and the e_max acceleration of §4.1), the variants a constant false
//! `plane` or `aa` compiles to, and the line-density filter (§4.1). The
//! shared WGSL is in the `lsa_core`, `lsa_plane` and `lsa_aa` snippets;
//! normals may be octahedral codes (the `oct` snippet of `ops/gbuffer`).
//!
//! Tolerance 1e-4: the remap from [η_min, η_max] multiplies f32 rounding
//! of the fitted spheres' errors by 1/(η_max − η_min) = 4 (5.5e-7 measured
//! on lavapipe on the wavy surface, where most errors fall inside the band).

pub mod reference;
pub use reference::*;

mod demos;

use super::{images, p, tex32, Arg, Case, OpDef, Tol, UV_SCREEN};
use crate::image_f64::ImageF64;
use crate::{Default, Footprint, Operator, Param, Radius, Specialization, Ty, Unit};

/// The G-buffers' size.
const N: u32 = 33;

/// A unit sphere's front 3 m ahead, background (alpha 0) around it; xyz
/// normals (`octahedral`: `oct_encode(n)` in rg).
fn sphere(octahedral: bool) -> (ImageF64, ImageF64) {
    let at = |x: u32, y: u32| {
        let u = (f64::from(x) - 16.0) / 14.0;
        let v = (f64::from(y) - 16.0) / 14.0;
        let w2 = 1.0 - u * u - v * v;
        if w2 <= 0.0 {
            return ([0.0; 4], [0.0; 4]);
        }
        let w = w2.sqrt();
        ([u, v, w - 3.0, 1.0], [u, v, w, 1.0])
    };
    gbuffer(at, octahedral)
}

/// Two parallel planes facing the eye, the right half 0.3 m nearer.
fn planes(octahedral: bool) -> (ImageF64, ImageF64) {
    let at = |x: u32, y: u32| {
        let (u, v) = (f64::from(x) / 16.0 - 1.0, f64::from(y) / 16.0 - 1.0);
        let z = if x > 16 { -2.7 } else { -3.0 };
        ([u * 0.1, v * 0.1, z, 1.0], [0.0, 0.0, 1.0, 1.0])
    };
    gbuffer(at, octahedral)
}

/// A wavy surface z = −3 + 0.04·sin(6u)·cos(4v) (u, v in texels / 8):
/// curvature that varies, so errors fall inside the remap's band as well
/// as at its ends.
fn waves(octahedral: bool) -> (ImageF64, ImageF64) {
    let at = |x: u32, y: u32| {
        let (u, v) = (f64::from(x) / 8.0 - 2.0, f64::from(y) / 8.0 - 2.0);
        let k = 0.125;
        let (s, c) = ((6.0 * u).sin(), (4.0 * v).cos());
        let z = -3.0 + 0.04 * s * c;
        // The surface (k·u, k·v, z): n ∝ (−∂z/∂x, −∂z/∂y, 1) with x = k·u, y = k·v.
        let (dzdu, dzdv) = (0.24 * (6.0 * u).cos() * c, -0.16 * s * (4.0 * v).sin());
        ([u * k, v * k, z, 1.0], [-dzdu / k, -dzdv / k, 1.0, 1.0])
    };
    gbuffer(at, octahedral)
}

fn gbuffer(at: impl Fn(u32, u32) -> ([f64; 4], [f64; 4]), octahedral: bool) -> (ImageF64, ImageF64) {
    let pos = ImageF64::new(N, N, |x, y| at(x, y).0);
    let normals = ImageF64::new(N, N, |x, y| {
        let n = at(x, y).1;
        if octahedral {
            let e = crate::ops::gbuffer::oct_encode([n[0], n[1], n[2]]);
            [e[0], e[1], 0.0, 1.0]
        } else {
            n
        }
    });
    (pos, normals)
}

/// An `lsa*` operator over a G-buffer with xyz or octahedral normals; the
/// flags it has, then η at the paper's [1/4, 1/2] and the encoding.
macro_rules! lsa_case {
    ($what:expr, $scene:ident, $octahedral:expr, [$($flag:expr),*]) => {
        Case::new(
            $what,
            &[
                tex32(|| $scene($octahedral).0),
                tex32(|| $scene($octahedral).1),
                Arg::Uv,
                $($flag,)*
                each![0.25],
                each![0.5],
                each![$octahedral as i32],
            ],
            // Remapped errors in [0, 1]: 5.5e-7 measured on lavapipe (the
            // wavy surface; the others are exact), so 1e-5 leaves 18× for
            // drivers' 2-ulp `inverseSqrt` and `length` and the ×4 of the
            // remap from [¼, ½].
            Tol::Abs(1e-5),
        )
        .over(N, N)
    };
}

/// LSA reads each direction's neighbours one step away (eqs. 1–7)...
const LSA_FOOTPRINT: &[(&str, Footprint)] = &[
    (
        "pos",
        Footprint::Around {
            uv: "uv",
            radius: Radius::Texels(1),
        },
    ),
    (
        "normals",
        Footprint::Around {
            uv: "uv",
            radius: Radius::Texels(1),
        },
    ),
];
/// ...and, with the anti-aliasing term (eq. 8), two steps away.
const LSA_FOOTPRINT_AA: &[(&str, Footprint)] = &[
    (
        "pos",
        Footprint::Around {
            uv: "uv",
            radius: Radius::Texels(2),
        },
    ),
    (
        "normals",
        Footprint::Around {
            uv: "uv",
            radius: Radius::Texels(2),
        },
    ),
];

const LSA_POS: Param = p(
    "pos",
    Ty::Texture,
    "G-buffer positions (world or view space) in rgb, alpha 1 on geometry and 0 on background",
);
const LSA_NORMALS: Param = p(
    "normals",
    Ty::Texture,
    "G-buffer unit normals (same space and size as `pos`): xyz in rgb, or octahedral codes in rg (see `normal_encoding`)",
);
/// How `normals` stores a normal. Last in every LSA parameter list, so the
/// specializations keep it, and positional calls written before it existed
/// keep their meaning. Only `npr_lsa_core__fetch` reads it.
const LSA_NORMAL_ENCODING: Param = Param {
    name: "normal_encoding",
    ty: Ty::Enum(&["xyz", "octahedral"]),
    unit: Unit::None,
    default: Default::Variant("xyz"),
    range: None,
    doc: "xyz: the normal in rgb; octahedral: `oct_encode(normal)` in rg (an `rg16float` target), for the packed G-buffer with view-space `rgba16float` positions",
};
const LSA_PLANE: Param = Param {
    name: "plane",
    ty: Ty::Bool,
    unit: Unit::None,
    default: Default::Number(1.0),
    range: None,
    doc: "add e_plane (eq. 6) to e_curv (eq. 7): lines between parallel planes",
};
const LSA_AA: Param = Param {
    name: "aa",
    ty: Ty::Bool,
    unit: Unit::None,
    default: Default::Number(1.0),
    range: None,
    doc: "eq. 8: test against the pixels two steps away to halve single-pixel noise",
};
const LSA_ETA_MIN: Param = Param {
    name: "eta_min",
    ty: Ty::Float,
    unit: Unit::None,
    default: Default::Number(0.25),
    range: Some((0.0, 8.0)),
    doc: "η_min of the remap (§3.2): errors at or below it give no line",
};
const LSA_ETA_MAX: Param = Param {
    name: "eta_max",
    ty: Ty::Float,
    unit: Unit::None,
    default: Default::Number(0.5),
    range: Some((0.0, 8.0)),
    doc: "η_max of the remap (§3.2): errors at or above it give a full line",
};
const LSA_FULL_PARAMS: &[Param] = &[
    LSA_POS,
    LSA_NORMALS,
    UV_SCREEN,
    LSA_PLANE,
    LSA_AA,
    LSA_ETA_MIN,
    LSA_ETA_MAX,
    LSA_NORMAL_ENCODING,
];
const LSA_SUM_PARAMS: &[Param] = &[
    LSA_POS,
    LSA_NORMALS,
    UV_SCREEN,
    LSA_PLANE,
    LSA_ETA_MIN,
    LSA_ETA_MAX,
    LSA_NORMAL_ENCODING,
];
const LSA_AA_PARAMS: &[Param] = &[
    LSA_POS,
    LSA_NORMALS,
    UV_SCREEN,
    LSA_AA,
    LSA_ETA_MIN,
    LSA_ETA_MAX,
    LSA_NORMAL_ENCODING,
];
const LSA_BASE_PARAMS: &[Param] = &[
    LSA_POS,
    LSA_NORMALS,
    UV_SCREEN,
    LSA_ETA_MIN,
    LSA_ETA_MAX,
    LSA_NORMAL_ENCODING,
];

pub const LSA: OpDef = OpDef::new(
    Operator {
        name: "lsa",
        doc: "LSA contour error, full monoscopic method: per direction (E, SE, S, SW) the remapped registration error of both neighbours against spheres fitted to p and the opposite neighbour; `plane` adds e_plane (eq. 7), `aa` applies eq. 8. A constant false flag compiles to a variant without that code.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–8 and the e_max acceleration of §4.1",
        params: LSA_FULL_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("lsa.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core", "lsa_plane", "lsa_aa"],
        specializations: &[
            Specialization { param: "plane", value: 0.0, use_operator: "lsa_curv_aa" },
            Specialization { param: "aa", value: 0.0, use_operator: "lsa_sum" },
        ],
        footprints: LSA_FOOTPRINT_AA,
    },
    |a| lsa(a[0].tex(), a[1].tex(), a[2].v2(), &LsaSettings { plane: a[3].b(), aa: a[4].b(), eta_min: a[5].f(), eta_max: a[6].f(), octahedral: a[7].i() == 1 }),
    &[lsa_case!("a sphere over background", sphere, false, [each![0, 1], each![0, 1]]), lsa_case!("a sphere, octahedral normals", sphere, true, [each![0, 1], each![0, 1]]), lsa_case!("a wavy surface", waves, false, [each![0, 1], each![0, 1]]), lsa_case!("a depth step between parallel planes", planes, false, [each![1], each![0, 1]])],
).with_demo(demos::LSA);

pub const LSA_SUM: OpDef = OpDef::new(
    Operator {
        name: "lsa_sum",
        doc: "LSA contour error with e_sum = e_curv + e_plane and no anti-aliasing term; what `lsa` compiles to when `aa` is false.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–7",
        params: LSA_SUM_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("lsa_sum.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core", "lsa_plane"],
        specializations: &[Specialization { param: "plane", value: 0.0, use_operator: "lsa_curv" }],
        footprints: LSA_FOOTPRINT,
    },
    |a| lsa(a[0].tex(), a[1].tex(), a[2].v2(), &LsaSettings { plane: a[3].b(), aa: false, eta_min: a[4].f(), eta_max: a[5].f(), octahedral: a[6].i() == 1 }),
    &[lsa_case!("a sphere over background", sphere, false, [each![0, 1]]), lsa_case!("a depth step between parallel planes", planes, false, [each![1]]), lsa_case!("a wavy surface", waves, false, [each![0, 1]])],
).with_demo(demos::LSA_SUM);

pub const LSA_CURV_AA: OpDef = OpDef::new(
    Operator {
        name: "lsa_curv_aa",
        doc: "LSA contour error on e_curv with the anti-aliasing term of eq. 8; what `lsa` compiles to when `plane` is false.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–5 and 8",
        params: LSA_AA_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("lsa_curv_aa.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core", "lsa_aa"],
        specializations: &[Specialization { param: "aa", value: 0.0, use_operator: "lsa_curv" }],
        footprints: LSA_FOOTPRINT_AA,
    },
    |a| lsa(a[0].tex(), a[1].tex(), a[2].v2(), &LsaSettings { plane: false, aa: a[3].b(), eta_min: a[4].f(), eta_max: a[5].f(), octahedral: a[6].i() == 1 }),
    &[lsa_case!("a sphere over background", sphere, false, [each![0, 1]]), lsa_case!("a depth step between parallel planes", planes, false, [each![1]]), lsa_case!("a wavy surface", waves, false, [each![0, 1]])],
).with_demo(demos::LSA_CURV_AA);

pub const LSA_CURV: OpDef = OpDef::new(
    Operator {
        name: "lsa_curv",
        doc: "LSA contour error, base method: sphere-fitting LSA (eqs. 2–3), e_curv (eq. 5), remapped from [eta_min, eta_max]; one channel per direction E, SE, S, SW, whose maximum is E(p) of eq. 1.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–5",
        params: LSA_BASE_PARAMS,
        returns: Ty::Vec4,
        wgsl: include_str!("lsa_curv.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core"],
        specializations: &[],
        footprints: LSA_FOOTPRINT,
    },
    |a| lsa(a[0].tex(), a[1].tex(), a[2].v2(), &LsaSettings { plane: false, aa: false, eta_min: a[3].f(), eta_max: a[4].f(), octahedral: a[5].i() == 1 }),
    &[lsa_case!("a sphere over background", sphere, false, []), lsa_case!("a depth step between parallel planes", planes, false, []), lsa_case!("a wavy surface", waves, false, [])],
).with_demo(demos::LSA_CURV);

pub const LSA_DENSITY: OpDef = OpDef::new(
    Operator {
        name: "lsa_density",
        doc: "LSA line-density filter: per direction channel, e − 2·strength·(smallest e on the 5-pixel line through p in that direction), clamped to [0, 1]; strength 1 in the full method, 0.5 in the base method.",
        reference: "Zaidi et al., LSA Contours for VR, §4.1 line density and Fig. 4; strengths from §5.1",
        params: &[
            p("src", Ty::Texture, "per-direction errors from an `lsa*` operator"),
            UV_SCREEN,
            Param {
                name: "strength",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(1.0),
                range: Some((0.0, 1.0)),
                doc: "1 in the full method, 0.5 in the base method, 0 = off",
            },
        ],
        returns: Ty::Vec4,
        wgsl: include_str!("lsa_density.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("src", Footprint::Around { uv: "uv", radius: Radius::Texels(2) })],
    },
    |a| lsa_density(a[0].tex(), a[1].v2(), a[2].f()),
    &[Case::new(
        "random per-direction errors, strengths at the range ends",
        &[tex32(|| images::noise(N, N, 5)), Arg::Uv, each![1.0, 0.5, 0.0]],
        Tol::Abs(1e-6),
    )
    .over(N, N)],
).with_demo(demos::LSA_DENSITY);
