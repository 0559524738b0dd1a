//! Operators of art-maps (Klein et al. 2000 §4.2): reading an art-map with
//! a per-surface level-of-detail bias, and reading a rip-map with a level
//! per axis.

use crate::ops::p;
use crate::{Default, Footprint, Operator, Param, Stage, Ty, Unit};

pub static ALL: &[Operator] = &[
    Operator {
    name: "sample_biased",
    doc: "Trilinear read of a mip-mapped texture at `uv` with its level of detail moved by `bias` levels (+1: strokes twice as large on screen).",
    reference: "Klein et al. 2000 §4.2 (LOD bias for stroke size per surface), by textureSampleGrad with the derivatives × 2^bias",
    params: &[
        p("tex", Ty::SampledTexture, "a mip-mapped texture, e.g. an `artmap(...)`"),
        p("uv", Ty::Vec2, "where to read (repeats with `wrap: repeat`)"),
        Param {
            name: "bias",
            ty: Ty::Float,
            unit: Unit::None,
            default: Default::Number(0.0),
            range: Some((-8.0, 8.0)),
            doc: "levels added to the hardware's level of detail",
        },
    ],
    returns: Ty::Vec4,
    stage: Stage::Any,
    wgsl: include_str!("../wgsl/sample_biased.wgsl"),
    depends: &[],
    snippets: &[],
    specializations: &[],
    footprints: &[("tex", Footprint::Anywhere)],
},
    Operator {
        name: "sample_ripmap",
        doc: "Read of a `ripmap(...)` at `uv`: the level of each axis from that axis's screen derivatives, the four levels around blended bilinearly; uv repeats.",
        reference: "Klein et al. 2000 §4.2, Fig. 7–8 (rip-maps with art-maps keep strokes' aspect on oblique surfaces)",
        params: &[
            p("tex", Ty::SampledTexture, "a `ripmap(...)` texture"),
            p("uv", Ty::Vec2, "where to read (repeats)"),
        ],
        returns: Ty::Vec4,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/sample_ripmap.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("tex", Footprint::Anywhere)],
    },
];
