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
