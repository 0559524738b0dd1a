//! Image filters over a target's neighbourhood: the separable Gaussian
//! blur, the 2×2 box downsample, the Sobel gradient and Roberts-cross
//! normal + depth edges (the outline baselines of the LSA contours paper).
//!
//! Tolerances: blurs 1e-5 (sums of ≤ 97 weights, renormalized); the edge
//! detector is exact except within 1e-4 of a threshold (skipped).

mod demos;

use super::{images, p, scalar, tex32, Arg, Case, OpDef, Tol, UV_SCREEN};
use crate::image_f64::{dot3, ImageF64};
use crate::{Default, Footprint, Operator, Param, Radius, Ty, Unit};

/// Largest blur radius in texels (as in gaussian.wgsl).
pub const GAUSSIAN_MAX_RADIUS: i64 = 48;

pub fn gaussian(src: &ImageF64, uv: [f64; 2], sigma: f64, axis: i64) -> [f64; 4] {
    let (px, py) = src.pixel_of(uv);
    let s = sigma.max(1e-3);
    let radius = ((3.0 * s).ceil() as i64).min(GAUSSIAN_MAX_RADIUS);
    let (dx, dy) = if axis == 0 { (1, 0) } else { (0, 1) };
    let mut acc = [0.0; 4];
    let mut total = 0.0;
    for i in -radius..=radius {
        let w = (-((i * i) as f64) / (2.0 * s * s)).exp();
        let t = src.load(px + dx * i, py + dy * i);
        for c in 0..4 {
            acc[c] += w * t[c];
        }
        total += w;
    }
    acc.map(|a| a / total)
}

pub fn downsample(src: &ImageF64, uv: [f64; 2]) -> [f64; 4] {
    let bx = (uv[0] * src.width as f64 - 0.5).floor() as i64;
    let by = (uv[1] * src.height as f64 - 0.5).floor() as i64;
    let mut acc = [0.0; 4];
    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let t = src.load(bx + dx, by + dy);
        for c in 0..4 {
            acc[c] += 0.25 * t[c];
        }
    }
    acc
}

pub fn sobel(src: &ImageF64, uv: [f64; 2]) -> f64 {
    let (px, py) = src.pixel_of(uv);
    let v = |i: i64, j: i64| src.load(px + i, py + j)[0];
    let gx = (v(1, -1) + 2.0 * v(1, 0) + v(1, 1)) - (v(-1, -1) + 2.0 * v(-1, 0) + v(-1, 1));
    let gy = (v(-1, 1) + 2.0 * v(0, 1) + v(1, 1)) - (v(-1, -1) + 2.0 * v(0, -1) + v(1, -1));
    (gx * gx + gy * gy).sqrt() / 8.0
}

pub fn normal_depth_edges(
    normals: &ImageF64,
    depth: &ImageF64,
    uv: [f64; 2],
    depth_threshold: f64,
    normal_threshold: f64,
) -> f64 {
    let (nx, ny) = normals.pixel_of(uv);
    let (dx, dy) = depth.pixel_of(uv);
    let n = |i: i64, j: i64| {
        let t = normals.load(nx + i, ny + j);
        [t[0] * 2.0 - 1.0, t[1] * 2.0 - 1.0, t[2] * 2.0 - 1.0]
    };
    let d = |i: i64, j: i64| depth.load(dx + i, dy + j)[0];
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let (a, b) = (sub(n(1, 1), n(0, 0)), sub(n(0, 1), n(1, 0)));
    let dn = (dot3(a, a) + dot3(b, b)).sqrt();
    let dd = ((d(1, 1) - d(0, 0)).powi(2) + (d(0, 1) - d(1, 0)).powi(2)).sqrt();
    if dn > normal_threshold || dd > depth_threshold {
        1.0
    } else {
        0.0
    }
}

/// Depth: a plane with a step (an occluding edge) and background 0.
fn depth_step(w: u32, h: u32) -> ImageF64 {
    ImageF64::new(w, h, |x, y| {
        let d = if x < w / 2 {
            2.0 + 0.01 * f64::from(y)
        } else if y % 11 == 5 {
            0.0
        } else {
            5.0
        };
        [d, 0.0, 0.0, 1.0]
    })
}

/// A blur of a w × h `image` at every σ (the range's ends) and axis, one output pixel per texel.
macro_rules! gaussian_case {
    ($what:expr, $w:expr, $h:expr, $image:expr) => {
        Case::new(
            $what,
            &[tex32(|| $image), Arg::Uv, each![0.3, 1.0, 2.5, 16.0], each![0, 1]],
            Tol::Abs(1e-5),
        )
        .over($w, $h)
    };
}

/// Edges of random normals and a depth step, thresholds in the range and at its ends.
macro_rules! edges_case {
    ($what:expr, $w:expr, $h:expr) => {
        Case::new(
            $what,
            &[
                tex32(|| images::noise($w, $h, 77)),
                tex32(|| depth_step($w, $h)),
                Arg::Uv,
                each![0.1, 1e-3, 100.0],
                each![0.4, 1e-3, 2.0],
            ],
            Tol::Abs(0.0),
        )
        .over($w, $h)
        .skipping(0.1)
    };
}

pub const GAUSSIAN: OpDef = OpDef::new(
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
        wgsl: include_str!("gaussian.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[(
            "src",
            Footprint::Around {
                uv: "uv",
                radius: Radius::Scaled {
                    param: "sigma",
                    k: 3.0,
                    max: 48,
                },
            },
        )],
    },
    |a| gaussian(a[0].tex(), a[1].v2(), a[2].f(), a[3].i()),
    &[
        gaussian_case!("a 1×1 image", 1, 1, images::noise(1, 1, 10)),
        gaussian_case!("a 3×7 checker", 3, 7, images::checker(3, 7)),
        gaussian_case!("a 32×24 ramp", 32, 24, images::ramp(32, 24)),
        gaussian_case!("a 32×24 checker", 32, 24, images::checker(32, 24)),
        gaussian_case!("32×24 noise", 32, 24, images::noise(32, 24, 12)),
    ],
)
// Weights exp(−d²/2σ²) > 0, divided by their sum: convex, and so
// within the hull of the source's texels.
.with_texel_hull("src")
.with_demo(demos::GAUSSIAN);

pub const DOWNSAMPLE: OpDef = OpDef::new(
    Operator {
        name: "downsample",
        doc: "2×2 box filter: the mean of the four source texels under a half-resolution pixel.",
        reference: "box-filter mip reduction",
        params: &[p("src", Ty::Texture, "the full-resolution target"), UV_SCREEN],
        returns: Ty::Vec4,
        wgsl: include_str!("downsample.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[(
            "src",
            Footprint::Around {
                uv: "uv",
                radius: Radius::Texels(1),
            },
        )],
    },
    |a| downsample(a[0].tex(), a[1].v2()),
    &[
        Case::new(
            "a 1×1 image",
            &[tex32(|| images::noise(1, 1, 10)), Arg::Uv],
            Tol::Abs(1e-6),
        ),
        Case::new(
            "a 3×7 checker to 1×3",
            &[tex32(|| images::checker(3, 7)), Arg::Uv],
            Tol::Abs(1e-6),
        )
        .over(1, 3),
        Case::new(
            "a 32×24 ramp",
            &[tex32(|| images::ramp(32, 24)), Arg::Uv],
            Tol::Abs(1e-6),
        )
        .over(16, 12),
        Case::new(
            "32×24 noise",
            &[tex32(|| images::noise(32, 24, 12)), Arg::Uv],
            Tol::Abs(1e-6),
        )
        .over(16, 12),
    ],
)
// Four texels at 0.25 each: convex.
.with_texel_hull("src")
.with_demo(demos::DOWNSAMPLE);

pub const SOBEL: OpDef = OpDef::new(
    Operator {
        name: "sobel",
        doc: "Sobel gradient magnitude of channel r (e.g. depth), each axis scaled by 1/8.",
        reference: "Sobel & Feldman 1968; the Sobel baseline of the LSA contours paper",
        params: &[
            p("src", Ty::Texture, "the target to differentiate (channel r)"),
            UV_SCREEN,
        ],
        returns: Ty::Float,
        wgsl: include_str!("sobel.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[(
            "src",
            Footprint::Around {
                uv: "uv",
                radius: Radius::Texels(1),
            },
        )],
    },
    |a| scalar(sobel(a[0].tex(), a[1].v2())),
    &[
        Case::new("a 1×1 image", &[tex32(|| depth_step(1, 1)), Arg::Uv], Tol::Abs(1e-5)),
        Case::new(
            "a 3×7 depth step",
            &[tex32(|| depth_step(3, 7)), Arg::Uv],
            Tol::Abs(1e-5),
        )
        .over(3, 7),
        Case::new(
            "a 40×30 depth step",
            &[tex32(|| depth_step(40, 30)), Arg::Uv],
            Tol::Abs(1e-5),
        )
        .over(40, 30),
    ],
)
.with_demo(demos::SOBEL);

pub const NORMAL_DEPTH_EDGES: OpDef = OpDef::new(
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
        wgsl: include_str!("normal_depth_edges.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[
            (
                "normals",
                Footprint::Around {
                    uv: "uv",
                    radius: Radius::Texels(1),
                },
            ),
            (
                "depth",
                Footprint::Around {
                    uv: "uv",
                    radius: Radius::Texels(1),
                },
            ),
        ],
    },
    |a| {
        let (n, d, uv, dt, nt) = (a[0].tex(), a[1].tex(), a[2].v2(), a[3].f(), a[4].f());
        // Binary: undefined within 1e-4 of a threshold, where f32 and f64 may differ.
        let near = |t: f64| normal_depth_edges(n, d, uv, dt + t, nt + t);
        let (lo, hi) = (near(-1e-4), near(1e-4));
        scalar(if lo == hi { lo } else { f64::NAN })
    },
    &[
        edges_case!("a 1×1 image", 1, 1),
        edges_case!("a 3×7 depth step", 3, 7),
        edges_case!("a 40×30 depth step", 40, 30),
    ],
)
.with_demo(demos::NORMAL_DEPTH_EDGES);
