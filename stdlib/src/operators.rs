//! The operator table: metadata for every stdlib operator, and its WGSL.

use crate::ops::{p, UV_SCREEN};
use crate::{Default, Footprint, Operator, Param, Radius, Specialization, Stage, Ty, Unit};

pub static ALL: &[Operator] = &[
    // ---- LSA contours (Zaidi et al., "Local Surface Approximation Contours for
    // Virtual Reality Stylisation"). Kept at the end of the table.
    Operator {
        name: "lsa",
        doc: "LSA contour error, full monoscopic method: per direction (E, SE, S, SW) the remapped registration error of both neighbours against spheres fitted to p and the opposite neighbour; `plane` adds e_plane (eq. 7), `aa` applies eq. 8. A constant false flag compiles to a variant without that code.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–8 and the e_max acceleration of §4.1",
        params: LSA_FULL_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/lsa.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core", "lsa_plane", "lsa_aa"],
        specializations: &[
            Specialization { param: "plane", value: 0.0, use_operator: "lsa_curv_aa" },
            Specialization { param: "aa", value: 0.0, use_operator: "lsa_sum" },
        ],
        footprints: LSA_FOOTPRINT_AA,
    },
    Operator {
        name: "lsa_sum",
        doc: "LSA contour error with e_sum = e_curv + e_plane and no anti-aliasing term; what `lsa` compiles to when `aa` is false.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–7",
        params: LSA_SUM_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/lsa_sum.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core", "lsa_plane"],
        specializations: &[Specialization { param: "plane", value: 0.0, use_operator: "lsa_curv" }],
        footprints: LSA_FOOTPRINT,
    },
    Operator {
        name: "lsa_curv_aa",
        doc: "LSA contour error on e_curv with the anti-aliasing term of eq. 8; what `lsa` compiles to when `plane` is false.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–5 and 8",
        params: LSA_AA_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/lsa_curv_aa.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core", "lsa_aa"],
        specializations: &[Specialization { param: "aa", value: 0.0, use_operator: "lsa_curv" }],
        footprints: LSA_FOOTPRINT_AA,
    },
    Operator {
        name: "lsa_curv",
        doc: "LSA contour error, base method: sphere-fitting LSA (eqs. 2–3), e_curv (eq. 5), remapped from [eta_min, eta_max]; one channel per direction E, SE, S, SW, whose maximum is E(p) of eq. 1.",
        reference: "Zaidi et al., LSA Contours for VR, eqs. 1–5",
        params: LSA_BASE_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/lsa_curv.wgsl"),
        depends: &[],
        snippets: &["oct", "lsa_core"],
        specializations: &[],
        footprints: LSA_FOOTPRINT,
    },
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
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/lsa_density.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("src", Footprint::Around { uv: "uv", radius: Radius::Texels(2) })],
    },
];

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
