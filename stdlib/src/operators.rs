//! The operator table: metadata for every stdlib operator, and its WGSL.

use crate::ops::{p, UV_SCREEN};
use crate::{Default, Footprint, Operator, Param, Radius, Specialization, Stage, Ty, Unit};

pub static ALL: &[Operator] = &[
    Operator {
        name: "metatexture_grad",
        doc: "MetaTexture: a tileable example texture blended at quantized scales so it keeps its screen-space size on any surface; UV gradients given explicitly.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3, eqs. 1–8 (eqs. 4–5 swapped, see erratum), skew eqs. 14–23 (σ of eq. 14 negated, see reference::SKEW_SIGN), contrast eqs. 24–25",
        params: METATEXTURE_GRAD_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/metatexture_grad.wgsl"),
        depends: &[],
        snippets: &["meta"],
        specializations: &[Specialization { param: "skew", value: 0.0, use_operator: "metatexture4_grad" }],
        footprints: &[("tex", Footprint::Anywhere)],
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
        footprints: &[("tex", Footprint::Anywhere)],
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
        footprints: &[("tex", Footprint::Anywhere)],
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
        footprints: &[("tex", Footprint::Anywhere)],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/radial_alpha.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/uv_gradients.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    Operator {
        name: "metatexture_contour_grad",
        doc: "MetaTexture of a directional texture re-oriented to indicate contour: its x axis follows the less foreshortened of u and v, blended by β across `band` octaves of |∇u|/|∇v| (no seam); `orient: off` compiles to `metatexture_grad`.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.5 (Fig. 8), on eqs. 1–8, 14–25",
        params: METATEXTURE_CONTOUR_GRAD_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/metatexture_contour_grad.wgsl"),
        depends: &["metatexture_grad"],
        snippets: &["meta"],
        specializations: &[Specialization { param: "orient", value: 0.0, use_operator: "metatexture_grad" }],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    Operator {
        name: "metatexture_contour",
        doc: "Contour-oriented MetaTexture (see `metatexture_contour_grad`) with UV gradients from fragment derivatives; `orient: off` compiles to `metatexture`.",
        reference: "Harvill et al., Age of Sail (journal 2019) §3.5 (Fig. 8), on eqs. 1–8, 14–25",
        params: METATEXTURE_CONTOUR_PARAMS,
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/metatexture_contour.wgsl"),
        depends: &["metatexture_contour_grad"],
        snippets: &["meta"],
        specializations: &[Specialization { param: "orient", value: 0.0, use_operator: "metatexture" }],
        footprints: &[("tex", Footprint::Anywhere)],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/live_texture.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    // ---- Edge Breakup (§4)
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/line_boil.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    Operator {
        name: "roll_compensate",
        doc: "Camera-roll compensation: a warp vector expressed in the frame of the screen-space ∇u (x along ∇u, y 90° from it), so the warp field rolls with the camera.",
        reference: "Harvill et al., Age of Sail (journal 2019) §4.3 (Fig. 13)",
        params: &[
            p("offset", Ty::Vec2, "the warp vector, e.g. a noise texture's rg remapped to [−1, 1]"),
            p("grad_u", Ty::Vec2, "screen-space gradient of u (e.g. `uv_gradients(...).xy`)"),
        ],
        returns: Ty::Vec2,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/roll_compensate.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/distance_attenuate.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
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
        stage: Stage::Image,
        wgsl: include_str!("../wgsl/warp.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("src", Footprint::Anywhere)],
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
