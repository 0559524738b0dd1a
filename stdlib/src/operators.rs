//! The operator table: metadata for every stdlib operator, and its WGSL.

use crate::ops::{p, UV_SCREEN};
use crate::{Default, Footprint, Operator, Param, Radius, Specialization, Stage, Ty, Unit};

pub static ALL: &[Operator] = &[
    // ---- MetaTexture extensions (§3.2, §3.3, §3.5) and live texture (§6.1)
    Operator {
        name: "shadow",
        doc: "Cast-shadow visibility (lit fraction in [0, 1]) of a surface point, from a light-view depth map written by a `view(light)` pass; outside the map is lit.",
        reference: "Williams 1978 shadow maps with percentage-closer filtering; Harvill et al., Age of Sail (journal 2019) §5, depth pass with sigmoid-warped coordinates",
        params: &[
            p("depth_map", Ty::Texture, "light-space depth (channel r) from a `view(light)` pass, cleared to 1"),
            Param {
                name: "p_light",
                ty: Ty::Vec3,
                unit: Unit::None,
                default: Default::Builtin("position.light"),
                range: None,
                doc: "the point in light NDC (default: this fragment's `position.light`)",
            },
            Param {
                name: "bias",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.005),
                range: Some((0.0, 0.5)),
                doc: "depth bias against self-shadowing, in light-NDC depth (1 = the light frustum's depth)",
            },
            Param {
                name: "warp",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.0),
                range: Some((0.0, 16.0)),
                doc: "sigmoid strength k of the depth pass's `shadow_warp` (must match it)",
            },
            Param {
                name: "radius",
                ty: Ty::Int,
                unit: Unit::None,
                default: Default::Number(1.0),
                range: Some((0.0, 3.0)),
                doc: "percentage-closer filter radius in texels ((2r+1)² taps)",
            },
        ],
        returns: Ty::Float,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/shadow.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("depth_map", Footprint::Anywhere)],
    },
    Operator {
        name: "contour_fade",
        doc: "Stereo contour fade-out: a soft dark band on the near side of occluding contours, as wide as the two eyes' contours disagree; fuse with the line strength by `max`.",
        reference: "LSA contours for VR §4.2 (contour fade-out, Figs. 5–6: c_start = 7/4·ᾱ, c_end = 7/16·ᾱ)",
        params: &[
            Param { name: "p", ty: Ty::Vec3, unit: Unit::Meters, default: Default::Builtin("position.world"), range: None, doc: "the surface point (world space)" },
            Param { name: "n", ty: Ty::Vec3, unit: Unit::None, default: Default::Builtin("normal.world"), range: None, doc: "its normal (world space)" },
            Param { name: "eye_left", ty: Ty::Vec3, unit: Unit::Meters, default: Default::Builtin("camera.left_eye"), range: None, doc: "left eye position V_L" },
            Param { name: "eye_right", ty: Ty::Vec3, unit: Unit::Meters, default: Default::Builtin("camera.right_eye"), range: None, doc: "right eye position V_R" },
            Param { name: "forward", ty: Ty::Vec3, unit: Unit::None, default: Default::Builtin("camera.forward"), range: None, doc: "view direction F, the normal of the eye disc A" },
            Param { name: "start", ty: Ty::Float, unit: Unit::None, default: Default::Number(1.75), range: Some((0.0, 8.0)), doc: "c_start / ᾱ, where the fade begins (paper: 7/4)" },
            Param { name: "end", ty: Ty::Float, unit: Unit::None, default: Default::Number(0.4375), range: Some((0.0, 8.0)), doc: "c_end / ᾱ, where it reaches full strength (paper: 7/16)" },
        ],
        returns: Ty::Float,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/contour_fade.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    Operator {
        name: "reprojection_mask",
        doc: "Stereo reprojection mask M (1 where the two eyes' views cannot be matched: occlusion, round-trip error or parallax jumps; 0 where they agree), from per-pixel reprojections into the other eye.",
        reference: "LSA contours for VR §4.2, eqs. 9–11 (m over [2, 4] px, n over [3, 6] px)",
        params: &[
            p("reproj", Ty::Texture, "R_{i,j}: per pixel, its surface point's position in the other eye in px (xy), coverage in w"),
            p("reproj_other", Ty::Texture, "the other eye's R_{j,i}: `other_eye(...)` of the same target"),
            UV_SCREEN,
            Param { name: "m_lo", ty: Ty::Float, unit: Unit::Px, default: Default::Number(2.0), range: Some((0.0, 64.0)), doc: "round-trip error |D| (eq. 9) that starts to mask" },
            Param { name: "m_hi", ty: Ty::Float, unit: Unit::Px, default: Default::Number(4.0), range: Some((0.0, 64.0)), doc: "round-trip error that masks fully" },
            Param { name: "n_lo", ty: Ty::Float, unit: Unit::Px, default: Default::Number(3.0), range: Some((0.0, 64.0)), doc: "neighbour jump |J| (eq. 10) that starts to mask" },
            Param { name: "n_hi", ty: Ty::Float, unit: Unit::Px, default: Default::Number(6.0), range: Some((0.0, 64.0)), doc: "neighbour jump that masks fully" },
        ],
        returns: Ty::Float,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/reprojection_mask.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[
            ("reproj", Footprint::Around { uv: "uv", radius: Radius::Texels(1) }),
            ("reproj_other", Footprint::Anywhere),
        ],
    },
    Operator {
        name: "stereo_consistency",
        doc: "Bounds this eye's line strength E by M + (1 − M)·max of the other eye's E in a 5×5 window where this pixel lands, so lines survive only where both eyes draw them (or where reprojection is unreliable).",
        reference: "LSA contours for VR §4.2 (consistency pass)",
        params: &[
            p("e", Ty::Texture, "this eye's line strength E (channel r)"),
            p("e_other", Ty::Texture, "the other eye's E: `other_eye(...)` of the same target"),
            p("reproj", Ty::Texture, "R_{i,j} as for `reprojection_mask`"),
            p("mask", Ty::Float, "M_{i,j} at this pixel (`reprojection_mask`)"),
            UV_SCREEN,
        ],
        returns: Ty::Float,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/stereo_consistency.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[
            ("e", Footprint::Around { uv: "uv", radius: Radius::Texels(0) }),
            ("e_other", Footprint::Anywhere),
            ("reproj", Footprint::Around { uv: "uv", radius: Radius::Texels(0) }),
        ],
    },
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
