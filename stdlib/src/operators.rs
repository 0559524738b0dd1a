//! The operator table: metadata for every stdlib operator, and its WGSL.

use crate::{Default, Operator, Param, Specialization, Stage, Ty, Unit};

const fn p(name: &'static str, ty: Ty, doc: &'static str) -> Param {
    Param {
        name,
        ty,
        unit: Unit::None,
        default: Default::Required,
        range: None,
        doc,
    }
}

const UV_SCREEN: Param = Param {
    name: "uv",
    ty: Ty::Vec2,
    unit: Unit::None,
    default: Default::Builtin("screen_uv"),
    range: None,
    doc: "where to read, in [0, 1]² (default: this pixel)",
};

pub static ALL: &[Operator] = &[
    Operator {
        name: "lambert",
        doc: "Lambert diffuse term max(n·l, 0); zero vectors give 0.",
        reference: "Lambert 1760; any graphics text",
        params: &[
            p("n", Ty::Vec3, "surface normal"),
            p("l", Ty::Vec3, "direction towards the light"),
        ],
        returns: Ty::Float,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/lambert.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "half_lambert",
        doc: "Half-Lambert (0.5·n·l + 0.5)²: soft falloff that keeps form on the shadow side.",
        reference: "Mitchell et al., Shading in Valve's Source Engine, SIGGRAPH 2006 course",
        params: &[
            p("n", Ty::Vec3, "surface normal"),
            p("l", Ty::Vec3, "direction towards the light"),
        ],
        returns: Ty::Float,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/half_lambert.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/toon.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/threshold.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "gaussian",
        doc: "One pass of a separable Gaussian blur along x or y (radius ⌈3σ⌉ ≤ 48 texels, clamp to edge).",
        reference: "separable Gaussian convolution; Age of Sail §5 blur chain",
        params: &[
            p("src", Ty::Texture, "the target or texture to blur"),
            UV_SCREEN,
            Param {
                name: "sigma",
                ty: Ty::Float,
                unit: Unit::Px,
                default: Default::Number(2.0),
                range: Some((0.3, 16.0)),
                doc: "standard deviation in texels of `src`",
            },
            Param {
                name: "axis",
                ty: Ty::Enum(&["x", "y"]),
                unit: Unit::None,
                default: Default::Variant("x"),
                range: None,
                doc: "blur direction",
            },
        ],
        returns: Ty::Vec4,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/gaussian.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "downsample",
        doc: "2×2 box filter: the mean of the four source texels under a half-resolution pixel.",
        reference: "box-filter mip reduction",
        params: &[p("src", Ty::Texture, "the full-resolution target"), UV_SCREEN],
        returns: Ty::Vec4,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/downsample.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "sobel",
        doc: "Sobel gradient magnitude of channel r (e.g. depth), each axis scaled by 1/8.",
        reference: "Sobel & Feldman 1968; the Sobel baseline of the LSA contours paper",
        params: &[
            p("src", Ty::Texture, "the target to differentiate (channel r)"),
            UV_SCREEN,
        ],
        returns: Ty::Float,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/sobel.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "normal_depth_edges",
        doc: "Roberts-cross edges on encoded normals (rgb = n·0.5+0.5) and linear depth (r): 1 on an edge, else 0.",
        reference: "Roberts 1963; the normal+depth outline baseline of the LSA contours paper",
        params: &[
            p("normals", Ty::Texture, "view-space normals encoded as n·0.5 + 0.5"),
            p("depth", Ty::Texture, "linear depth in metres (channel r)"),
            UV_SCREEN,
            Param {
                name: "depth_threshold",
                ty: Ty::Float,
                unit: Unit::Meters,
                default: Default::Number(0.1),
                range: Some((0.0, 100.0)),
                doc: "depth difference that counts as an edge",
            },
            Param {
                name: "normal_threshold",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.4),
                range: Some((0.0, 2.0)),
                doc: "normal difference that counts as an edge",
            },
        ],
        returns: Ty::Float,
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/normal_depth_edges.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "over",
        doc: "Porter-Duff `fg over bg` with straight alpha.",
        reference: "Porter & Duff, Compositing Digital Images, SIGGRAPH 1984",
        params: &[p("fg", Ty::Color, "foreground"), p("bg", Ty::Color, "background")],
        returns: Ty::Color,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/over.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "luminance",
        doc: "Rec. 709 luma of a colour.",
        reference: "ITU-R BT.709",
        params: &[p("c", Ty::Color, "colour")],
        returns: Ty::Float,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/luminance.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/saturation.wgsl"),
        depends: &["luminance"],
        snippets: &[],
        specializations: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/overlay.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "sample",
        doc: "Filtered read of a texture or float16/unorm target at `uv` (mip level 0).",
        reference: "bilinear texture filtering",
        params: &[
            p("tex", Ty::SampledTexture, "texture or target to read"),
            Param {
                name: "uv",
                ty: Ty::Vec2,
                unit: Unit::None,
                default: Default::Builtin("screen_uv"),
                range: None,
                doc: "where to read, in [0, 1]²",
            },
        ],
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/sample.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
    },
    Operator {
        name: "metatexture_grad",
        doc: "MetaTexture: a tileable example texture blended at quantized scales so it keeps its screen-space size on any surface; UV gradients given explicitly.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3, eqs. 1–8 (eqs. 4–5 swapped, see erratum), skew eqs. 14–23, contrast eqs. 24–25",
        params: METATEXTURE_GRAD_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/metatexture_grad.wgsl"),
        depends: &[],
        snippets: &["meta"],
        specializations: &[Specialization { param: "skew", value: 0.0, use_operator: "metatexture4_grad" }],
    },
    Operator {
        name: "metatexture",
        doc: "MetaTexture with UV gradients from fragment derivatives (eq. 1 with ∇u = (∂u/∂x, ∂u/∂y)).",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.1, eqs. 1–8",
        params: METATEXTURE_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/metatexture.wgsl"),
        depends: &["metatexture_grad"],
        snippets: &["meta"],
        specializations: &[Specialization { param: "skew", value: 0.0, use_operator: "metatexture4" }],
    },
    Operator {
        name: "metatexture4_grad",
        doc: "4-tap MetaTexture (no skew compensation) with explicit UV gradients; what `metatexture_grad` compiles to when `skew` is 0.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.1, eqs. 1–8 (eqs. 4–5 swapped, see erratum), contrast eqs. 24–25",
        params: METATEXTURE4_GRAD_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/metatexture4_grad.wgsl"),
        depends: &[],
        snippets: &["meta"],
        specializations: &[],
    },
    Operator {
        name: "metatexture4",
        doc: "4-tap MetaTexture with UV gradients from fragment derivatives; what `metatexture` compiles to when `skew` is 0.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.1, eqs. 1–8",
        params: METATEXTURE4_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/metatexture4.wgsl"),
        depends: &["metatexture4_grad"],
        snippets: &["meta"],
        specializations: &[],
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
        snippets: &["lsa_core", "lsa_plane", "lsa_aa"],
        specializations: &[
            Specialization { param: "plane", value: 0.0, use_operator: "lsa_curv_aa" },
            Specialization { param: "aa", value: 0.0, use_operator: "lsa_sum" },
        ],
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
        snippets: &["lsa_core", "lsa_plane"],
        specializations: &[Specialization { param: "plane", value: 0.0, use_operator: "lsa_curv" }],
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
        snippets: &["lsa_core", "lsa_aa"],
        specializations: &[Specialization { param: "aa", value: 0.0, use_operator: "lsa_curv" }],
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
        snippets: &["lsa_core"],
        specializations: &[],
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
    },
];

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

const METATEXTURE4_PARAMS: &[Param] = &{
    let s = metatexture_settings!();
    [METATEXTURE_SAMPLED, METATEXTURE_UV, s[0], s[1], s[2], s[4], s[5]]
};

const LSA_POS: Param = p(
    "pos",
    Ty::Texture,
    "G-buffer positions (world or view space) in rgb, alpha 1 on geometry and 0 on background",
);
const LSA_NORMALS: Param = p(
    "normals",
    Ty::Texture,
    "G-buffer unit normals in rgb (same space and size as `pos`)",
);
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
];
const LSA_SUM_PARAMS: &[Param] = &[LSA_POS, LSA_NORMALS, UV_SCREEN, LSA_PLANE, LSA_ETA_MIN, LSA_ETA_MAX];
const LSA_AA_PARAMS: &[Param] = &[LSA_POS, LSA_NORMALS, UV_SCREEN, LSA_AA, LSA_ETA_MIN, LSA_ETA_MAX];
const LSA_BASE_PARAMS: &[Param] = &[LSA_POS, LSA_NORMALS, UV_SCREEN, LSA_ETA_MIN, LSA_ETA_MAX];
