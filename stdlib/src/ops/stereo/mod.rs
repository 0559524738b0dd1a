//! The stereo operators of LSA contours for VR (Zaidi et al., §4.2): the
//! contour fade-out, the reprojection mask (eqs. 9–11) and the consistency
//! bound between the two eyes' lines.

pub mod reference;
pub use reference::*;

mod demos;

use super::{p, random, scalar, tex32, Arg, Case, OpDef, Tol, UV_SCREEN};
use crate::image_f64::{unit, ImageF64};
use crate::{Default, Footprint, Operator, Param, Radius, Ty, Unit};

const LEFT: Arg = Arg::Const([-0.032, 0.01, 0.0, 0.0]);
const RIGHT: Arg = Arg::Const([0.032, 0.01, 0.0, 0.0]);
const FORWARD: Arg = Arg::Const([0.0, 0.0, -1.0, 0.0]);
/// The point of a sphere of radius 0.5 m, 2 m ahead, with normal `n` (argument 1).
const SPHERE_POINT: Arg = Arg::From {
    arg: 1,
    f: |n| {
        let u = unit([n[0], n[1], n[2]]);
        [0.5 * u[0], 0.5 * u[1], -2.0 + 0.5 * u[2], 0.0]
    },
};

const W: u32 = 30;
const H: u32 = 12;

/// Synthetic reprojections: a smooth fronto-parallel shift of 3.3 px, a
/// depth jump of 9 px in the right third, background in a corner.
fn reproj() -> ImageF64 {
    ImageF64::new(W, H, |x, y| {
        if x < 3 && y < 3 {
            return [0.0; 4];
        }
        let shift = if x >= 20 { 12.3 } else { 3.3 } + 0.05 * f64::from(y);
        [f64::from(x) + 0.5 + shift, f64::from(y) + 0.5, 0.0, 1.0]
    })
}

/// The other eye's inverse map, off by 0.4 px in every 7th column, uncovered in row 9.
fn reproj_other() -> ImageF64 {
    ImageF64::new(W, H, |x, y| {
        let back = if x % 7 == 3 { 2.9 } else { 3.3 };
        [
            f64::from(x) + 0.5 - back - 0.05 * f64::from(y),
            f64::from(y) + 0.5,
            0.0,
            if y == 9 { 0.0 } else { 1.0 },
        ]
    })
}

fn lines() -> ImageF64 {
    ImageF64::new(W, H, |x, y| {
        [
            if (x + y) % 5 == 0 { 1.0 } else { 0.1 * f64::from(x % 3) },
            0.0,
            0.0,
            1.0,
        ]
    })
}

fn lines_other() -> ImageF64 {
    ImageF64::new(W, H, |x, y| {
        [if (x + 2 * y) % 9 == 0 { 0.8 } else { 0.0 }, 0.0, 0.0, 1.0]
    })
}

pub const CONTOUR_FADE: OpDef = OpDef::new(
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
        wgsl: include_str!("contour_fade.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(contour_fade(a[0].v3(), a[1].v3(), a[2].v3(), a[3].v3(), a[4].v3(), a[5].f(), a[6].f())),
    &[
        Case::new(
            "points around a sphere 2 m ahead, eyes 6.4 cm apart",
            &[SPHERE_POINT, random([-1.0; 4], [1.0; 4], 300), LEFT, RIGHT, FORWARD, each![1.75], each![0.4375]],
            // acos near ±1 and the ramp's small width (≈ 1.3·ᾱ ≈ 0.04 rad)
            // amplify f32 rounding: 2e-3 of the fade's range.
            Tol::Abs(2e-3),
        ),
        Case::new(
            "a zero normal, a point at an eye",
            &[
                Arg::Each(&[[0.0, 0.0, -2.0, 0.0], [-0.032, 0.01, 0.0, 0.0]]),
                Arg::Each(&[[0.0; 4], [0.0, 0.0, 1.0, 0.0]]),
                LEFT,
                RIGHT,
                FORWARD,
                each![1.75],
                each![0.4375],
            ],
            Tol::Abs(2e-3),
        ),
    ],
).with_demo(demos::CONTOUR_FADE);

pub const REPROJECTION_MASK: OpDef = OpDef::new(
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
        wgsl: include_str!("reprojection_mask.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[
            ("reproj", Footprint::Around { uv: "uv", radius: Radius::Texels(1) }),
            ("reproj_other", Footprint::Anywhere),
        ],
    },
    |a| {
        let (r, o) = (a[0].tex(), a[1].tex());
        scalar(reprojection_mask(r, o, r.pixel_of(a[2].v2()), (a[3].f(), a[4].f()), (a[5].f(), a[6].f())))
    },
    &[Case::new(
        "a 3.3 px shift, a 9 px depth jump, background, the other eye's inverse",
        &[tex32(reproj), tex32(reproj_other), Arg::Uv, each![2.0], each![4.0], each![3.0], each![6.0]],
        Tol::Abs(1e-5),
    )
    .over(W, H)],
).with_demo(demos::REPROJECTION_MASK);

pub const STEREO_CONSISTENCY: OpDef = OpDef::new(
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
        wgsl: include_str!("stereo_consistency.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[
            ("e", Footprint::Around { uv: "uv", radius: Radius::Texels(0) }),
            ("e_other", Footprint::Anywhere),
            ("reproj", Footprint::Around { uv: "uv", radius: Radius::Texels(0) }),
        ],
    },
    |a| {
        let e = a[0].tex();
        scalar(stereo_consistency(e, a[1].tex(), a[2].tex(), a[3].f(), e.pixel_of(a[4].v2())))
    },
    &[Case::new(
        "lines in both eyes on the reprojection above, masks 0, 0.3 and 1",
        &[tex32(lines), tex32(lines_other), tex32(reproj), each![0.0, 0.3, 1.0], Arg::Uv],
        Tol::Abs(1e-6),
    )
    .over(W, H)],
).with_demo(demos::STEREO_CONSISTENCY);
