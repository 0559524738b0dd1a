//! Operators of art-maps (Klein et al. 2000 §4.2): reading an art-map with
//! a per-surface level-of-detail bias, and reading a rip-map with a level
//! per axis. Both take screen derivatives. Their references give the level
//! a read selects, so the cases read textures whose level i holds i·STEP:
//! the value read is the level (`tests/gpu/artmaps.rs` checks the same through
//! the runner).

pub mod reference;
pub use reference::*;

mod demos;

use super::{p, tex8_mipmapped, Arg, Case, OpDef, Tol};
use crate::image_f64::ImageF64;
use crate::{Default, Footprint, Operator, Param, Ty, Unit};

/// The value per level (exact in 8 bits: 17/255).
const STEP: f64 = 1.0 / 15.0;

/// Level k of a 256² art-map whose level k is the constant k·STEP.
fn level(k: u32) -> ImageF64 {
    let s = (256u32 >> k).max(1);
    let v = f64::from(k) * STEP;
    ImageF64::new(s, s, |_, _| [v, v, v, 1.0])
}

/// A 64² rip-map atlas (128² texels, `npr_abi::RipmapAtlas`'s layout): level
/// (i, j) holds (i·STEP, j·STEP).
fn ripmap_atlas() -> ImageF64 {
    let offset = |k: u32| (0..k).map(|l| (64u32 >> l).max(1)).sum::<u32>();
    let level_of = |x: u32| (0..7).find(|i| offset(*i) <= x && x < offset(i + 1));
    ImageF64::new(128, 128, |x, y| match (level_of(x), level_of(y)) {
        (Some(i), Some(j)) => [f64::from(i) * STEP, f64::from(j) * STEP, 0.0, 1.0],
        _ => [0.0; 4],
    })
}

/// A biased read at `k` texels of level 0 per pixel, biases from −2 to 3.3.
/// llvmpipe's level is a fast log2 (0.04 level off seen at k = 10) with a
/// quantized trilinear weight: a tenth of a level.
macro_rules! biased_case {
    ($what:expr, $k:expr) => {
        Case::new(
            $what,
            &[
                tex8_mipmapped(|| level(0), level, true),
                Arg::ScreenUv {
                    origin: [0.1, 0.2],
                    dx: [$k / 256.0, 0.0],
                    dy: [0.0, $k / 256.0],
                },
                each![0.0, -1.0, 0.5, 2.0, 3.3, -2.0],
            ],
            Tol::Abs(0.1 * STEP),
        )
        .over(8, 8)
    };
}

/// A rip-map read at `ku`, `kv` texels of level 0 per pixel along u and v:
/// the levels are f32 shader arithmetic and the taps constant, so 1e-4.
macro_rules! ripmap_case {
    ($what:expr, $ku:expr, $kv:expr) => {
        Case::new(
            $what,
            &[
                Arg::Texture(super::Tex {
                    image: ripmap_atlas,
                    format: super::TexFormat::Rgba8Unorm,
                    repeat: true,
                    levels: None,
                }),
                Arg::ScreenUv {
                    origin: [0.3, 0.6],
                    dx: [$ku / 64.0, 0.0],
                    dy: [0.0, $kv / 64.0],
                },
            ],
            Tol::Abs(1e-4),
        )
        .over(8, 8)
    };
}

pub const SAMPLE_BIASED: OpDef = OpDef::new(
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
    wgsl: include_str!("sample_biased.wgsl"),
    depends: &[],
    snippets: &[],
    specializations: &[],
    footprints: &[("tex", Footprint::Anywhere)],
},
    |a| {
        let t = a[0].tex();
        let (dx, dy) = a[1].derivatives();
        let lod = sample_biased_lod(dx, dy, t.width, t.height, a[2].f());
        let v = sample_biased(lod, 32 - t.width.max(t.height).leading_zeros(), STEP);
        [v, v, v, 1.0]
    },
    &[
        biased_case!("1 texel per pixel", 1.0),
        biased_case!("10 texels per pixel", 10.0),
        biased_case!("4 texels per pixel", 4.0),
        biased_case!("0.3 texels per pixel (magnified)", 0.3),
    ],
).with_demo(demos::SAMPLE_BIASED);

pub const SAMPLE_RIPMAP: OpDef = OpDef::new(
    Operator {
        name: "sample_ripmap",
        doc: "Read of a `ripmap(...)` at `uv`: the level of each axis from that axis's screen derivatives, the four levels around blended bilinearly; uv repeats.",
        reference: "Klein et al. 2000 §4.2, Fig. 7–8 (rip-maps with art-maps keep strokes' aspect on oblique surfaces)",
        params: &[
            p("tex", Ty::SampledTexture, "a `ripmap(...)` texture"),
            p("uv", Ty::Vec2, "where to read (repeats)"),
        ],
        returns: Ty::Vec4,
        wgsl: include_str!("sample_ripmap.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| {
        let t = a[0].tex();
        let (dx, dy) = a[1].derivatives();
        let base = (t.width / 2, t.height / 2);
        let lods = sample_ripmap_lods(dx, dy, base.0, base.1);
        let levels = |s: u32| 32 - s.leading_zeros();
        let v = sample_ripmap(lods, [levels(base.0), levels(base.1)], STEP);
        [v[0], v[1], 0.0, 1.0]
    },
    &[
        ripmap_case!("isotropic", 1.0, 1.0),
        ripmap_case!("squashed along u", 4.0, 1.0),
        ripmap_case!("squashed along v", 1.0, 8.0),
        ripmap_case!("both, unequally", 16.0, 2.5),
        ripmap_case!("magnified along u, beyond the last level along v", 0.5, 100.0),
    ],
).with_demo(demos::SAMPLE_RIPMAP);
