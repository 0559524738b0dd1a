//! Operators of dynamic 2D patterns (Breslav et al. 2007): the fuzzy
//! visibility of a sample in an ID image (§3.1), complex multiplication for
//! the similarity update (§3.2–3.3) and the pattern coordinates of a pixel
//! (§3.3), and the halftone screen that such a frame carries, with its LOD
//! blend (§3.4) and tone correction (§3.5).

pub mod reference;
pub use reference::*;

mod demos;

use super::{p, pair, random, scalar, tex32, Arg, Case, OpDef, Tol, Value};
use crate::halftone_table::{table_from_image, table_image, HalftoneTable};
use crate::{Default, Footprint, Operator, Param, Radius, Ty, Unit};

/// An ID image with three objects at sizes down to 1×1, read on and off
/// it (uv from −0.5 to 1.5), every radius and ID.
macro_rules! id_case {
    ($what:expr, $w:expr, $h:expr) => {
        Case::new(
            $what,
            &[
                tex32(|| {
                    crate::image_f64::ImageF64::new($w, $h, |x, y| [f64::from((x / 3 + y / 2) % 3), 0.0, 0.0, 1.0])
                }),
                Arg::ScreenUv {
                    origin: [-0.5, -0.5],
                    dx: [2.0 / (2.0 * $w as f64 + 1.0), 0.0],
                    dy: [0.0, 2.0 / (2.0 * $h as f64 + 1.0)],
                },
                each![0, 1, 2, 5],
                each![0.0, 1.0, 2.4, 8.0],
            ],
            Tol::Abs(1e-6),
        )
        .over(2 * $w + 1, 2 * $h + 1)
    };
}

/// The pattern's axes: zero, and scales from 1e-3 to 1e3.
const FRAME_U: &[Value] = &[
    [0.0; 4],
    [1e-3, -2e-3, 0.0, 0.0],
    [0.7, 0.2, 0.0, 0.0],
    [800.0, -300.0, 0.0, 0.0],
];
const FRAME_V: &[Value] = &[[-2e-3, 1e-3, 0.0, 0.0], [-0.2, 0.9, 0.0, 0.0], [300.0, 800.0, 0.0, 0.0]];
/// Blends inside and outside [0, 1].
const BLENDS: Arg = each![0.0, 1.0, 0.37, -0.5, 2.0];
const CELL_POINTS: &[Value] = &[
    [0.0; 4],
    [0.5, 0.5, 0.0, 0.0],
    [0.25, 0.75, 0.0, 0.0],
    [-3.0, 7.5, 0.0, 0.0],
];

/// The halftone over a table built for `edge`, at random points, tones
/// (beyond [0, 1] too) and blends. smoothstep's slope is 1.5/(2·edge): the
/// screen's f32 error (2e-6) and the thresholds' f32 rounding, times that.
macro_rules! halftone_case {
    ($what:expr, $edge:expr, $corrected:expr) => {
        Case::new(
            $what,
            &[
                tex32(|| table_image(&HalftoneTable::build($edge as f32 as f64, $corrected))),
                random([-10.0; 4], [10.0; 4], 10),
                random([-0.1; 4], [1.1; 4], 8),
                BLENDS,
            ],
            Tol::Abs(1e-5 * 1.5 / (2.0 * $edge)),
        )
    };
}

pub const ID_SHARE: OpDef = OpDef::new(
    Operator {
        name: "id_share",
        doc: "The share of the (2r+1)² ID-image texels around `uv` that hold `id` (0 off the image): a sample's fuzzy visibility.",
        reference: "Breslav et al. 2007 §3.1 (fuzzy visibility after Luft and Deussen 2006, on an ID image as in Kalnins et al. 2002)",
        params: &[
            p("ids", Ty::Texture, "an ID image (`out id: r32float = object.id`)"),
            p("uv", Ty::Vec2, "where, in [0, 1]² of the image"),
            p("id", Ty::Float, "the object's ID (`object.id`)"),
            Param {
                name: "radius",
                ty: Ty::Float,
                unit: Unit::Px,
                default: Default::Number(2.0),
                range: Some((0.0, 8.0)),
                doc: "half the window's side, in texels (rounded)",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("id_share.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("ids", Footprint::Around { uv: "uv", radius: Radius::Scaled { param: "radius", k: 1.0, max: 8 } })],
    },
    |a| scalar(id_share(a[0].tex(), a[1].v2(), a[2].f(), a[3].f())),
    &[
        id_case!("a 1×1 image", 1, 1),
        id_case!("a 3×7 image", 3, 7),
        id_case!("a 33×20 image", 33, 20),
    ],
).with_demo(demos::ID_SHARE);

pub const COMPLEX_MUL: OpDef = OpDef::new(
    Operator {
        name: "complex_mul",
        doc: "The complex product a·b of two 2D vectors: b rotated by a's angle and scaled by |a|.",
        reference: "Breslav et al. 2007 §3.2 (the similarity z as a complex number)",
        params: &[
            p("a", Ty::Vec2, "a complex number"),
            p("b", Ty::Vec2, "a complex number"),
        ],
        returns: Ty::Vec2,
        wgsl: include_str!("complex_mul.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| pair(complex_mul(a[0].v2(), a[1].v2())),
    &[
        Case::new(
            "unit scale",
            &[random([-1.0; 4], [1.0; 4], 20), random([-1.0; 4], [1.0; 4], 20)],
            Tol::Rel(1e-4),
        ),
        Case::new(
            "scales 1e3 and 1e-3",
            &[random([-1e3; 4], [1e3; 4], 20), random([-1e-3; 4], [1e-3; 4], 20)],
            Tol::Rel(1e-4),
        ),
    ],
)
.with_demo(demos::COMPLEX_MUL);

pub const PATTERN_UV: OpDef = OpDef::new(
    Operator {
        name: "pattern_uv",
        doc: "Pattern coordinates ((q−o)·u/|u|², (q−o)·v/|v|²) of the image point q in the pattern frame (o, u, v).",
        reference: "Breslav et al. 2007 §3.3",
        params: &[
            p("o", Ty::Vec2, "the pattern's origin in the image, px"),
            p("u", Ty::Vec2, "the image vector of the pattern's (1, 0), px"),
            p("v", Ty::Vec2, "the image vector of the pattern's (0, 1), px"),
            Param {
                name: "q",
                ty: Ty::Vec2,
                unit: Unit::Px,
                default: Default::Builtin("frag_coord"),
                range: None,
                doc: "the image point, in px (default: this pixel)",
            },
        ],
        returns: Ty::Vec2,
        wgsl: include_str!("pattern_uv.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| pair(pattern_uv(a[0].v2(), a[1].v2(), a[2].v2(), a[3].v2())),
    &[Case::new(
        "pattern frames from 1e-3 to 1e3 px, a zero u",
        &[
            random([-500.0; 4], [500.0; 4], 4),
            Arg::Each(FRAME_U),
            Arg::Each(FRAME_V),
            random([-500.0; 4], [500.0; 4], 4),
        ],
        Tol::Rel(1e-4),
    )],
)
.with_demo(demos::PATTERN_UV);

pub const HALFTONE_SCREEN: OpDef = OpDef::new(
    Operator {
        name: "halftone_screen",
        doc: "The procedural dot screen's height in [0.1, 0.9] at pattern coordinates `uv`: the mean over both axes of 0.5 + 0.4·cos(2πx), mixed by `blend` with the screen of half the period so that dots morph over an LOD transition.",
        reference: "Breslav et al. 2007 §3.4 (jot-lib nprdata/glsl/haftone_tx.fp, procedural dots)",
        params: &[
            p("uv", Ty::Vec2, "pattern coordinates (`pattern_uv(...)`), one cell per unit"),
            Param {
                name: "blend",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.0),
                range: Some((0.0, 1.0)),
                doc: "0: this screen; 1: the screen of half the period (§3.4)",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("halftone_screen.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
    |a| scalar(halftone_screen(a[0].v2(), a[1].f())),
    &[
        Case::new("near the origin", &[random([-1.0; 4], [1.0; 4], 20), BLENDS], Tol::Abs(2e-6)),
        Case::new("10 cells out", &[random([-10.0; 4], [10.0; 4], 20), BLENDS], Tol::Abs(2e-6)),
        Case::new("1000 cells out (coarse f32 coordinates)", &[random([-1e3; 4], [1e3; 4], 20), BLENDS], Tol::Abs(2e-6)),
        Case::new("cell corners and centres", &[Arg::Each(CELL_POINTS), BLENDS], Tol::Abs(2e-6)),
    ],
).with_demo(demos::HALFTONE_SCREEN)
// The result's bounds (issue 49): checked by tests/op_ranges.rs.
.with_range(0.0, 1.0);

pub const HALFTONE: OpDef = OpDef::new(
    Operator {
        name: "halftone",
        doc: "A tone-corrected halftone: the paper's share (1 = paper, 0 = ink) at `uv` for the wanted `tone`, on `halftone_screen(uv, blend)`, with the threshold looked up in a `halftone_table(...)` texture so that the mean over a cell is `tone` at every blend.",
        reference: "Breslav et al. 2007 §3.5 (tone correction; jot-lib src/gtex/haftone_tx.cpp, Halftone_TX::compute_inverse_R)",
        params: &[
            p("table", Ty::Texture, "a `texture t = halftone_table(edge: 0.1)` (its thresholds and its edge)"),
            p("uv", Ty::Vec2, "pattern coordinates (`pattern_uv(...)`), one cell per unit"),
            Param {
                name: "tone",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.5),
                range: Some((0.0, 1.0)),
                doc: "the wanted mean tone, 1 = white paper",
            },
            Param {
                name: "blend",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.0),
                range: Some((0.0, 1.0)),
                doc: "the LOD blend towards the half-period screen (§3.4)",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("halftone.wgsl"),
        depends: &["halftone_screen"],
        snippets: &[],
        specializations: &[],
        footprints: &[("table", Footprint::Anywhere)],
    },
    |a| scalar(halftone(&table_from_image(a[0].tex()), a[1].v2(), a[2].f(), a[3].f())),
    &[
        halftone_case!("soft edges, corrected", 0.1, true),
        halftone_case!("softer edges, corrected", 0.2, true),
        halftone_case!("sharp edges, corrected", 0.02, true),
        halftone_case!("soft edges, uncorrected", 0.1, false),
    ],
).with_demo(demos::HALFTONE);
