//! Operators of dynamic 2D patterns (Breslav et al. 2007): the fuzzy
//! visibility of a sample in an ID image (§3.1), complex multiplication for
//! the similarity update (§3.2–3.3) and the pattern coordinates of a pixel
//! (§3.3), and the halftone screen that such a frame carries, with its LOD
//! blend (§3.4) and tone correction (§3.5).

use crate::ops::p;
use crate::{Default, Footprint, Operator, Param, Radius, Stage, Ty, Unit};

pub static ALL: &[Operator] = &[
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/id_share.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("ids", Footprint::Around { uv: "uv", radius: Radius::Scaled { param: "radius", k: 1.0, max: 8 } })],
    },
    Operator {
        name: "complex_mul",
        doc: "The complex product a·b of two 2D vectors: b rotated by a's angle and scaled by |a|.",
        reference: "Breslav et al. 2007 §3.2 (the similarity z as a complex number)",
        params: &[p("a", Ty::Vec2, "a complex number"), p("b", Ty::Vec2, "a complex number")],
        returns: Ty::Vec2,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/complex_mul.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/pattern_uv.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/halftone_screen.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[],
    },
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
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/halftone.wgsl"),
        depends: &["halftone_screen"],
        snippets: &[],
        specializations: &[],
        footprints: &[("table", Footprint::Anywhere)],
    },
];
