//! `sample`: a bilinear read of a texture or filterable target at level 0.
//! Tolerance 4e-3 on 8-bit data: bilinear weights are quantized by the
//! sampler (8 sub-texel bits on lavapipe).

mod demos;

use super::{p, tex8, Arg, Case, OpDef, Tol};
use crate::image_f64::ImageF64;
use crate::{Default, Footprint, Operator, Param, Ty, Unit};

/// Bilinear filtering with clamp-to-edge addressing at level 0.
pub fn sample(tex: &ImageF64, uv: [f64; 2]) -> [f64; 4] {
    let x = uv[0] * tex.width as f64 - 0.5;
    let y = uv[1] * tex.height as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let (a, b, c, d) = (
        tex.load(x0, y0),
        tex.load(x0 + 1, y0),
        tex.load(x0, y0 + 1),
        tex.load(x0 + 1, y0 + 1),
    );
    std::array::from_fn(|i| {
        let top = a[i] * (1.0 - fx) + b[i] * fx;
        let bottom = c[i] * (1.0 - fx) + d[i] * fx;
        top * (1.0 - fy) + bottom * fy
    })
}

/// A smooth pattern, so sub-texel weight quantization stays small.
fn smooth() -> ImageF64 {
    ImageF64::new(16, 12, |x, y| {
        let (x, y) = (f64::from(x), f64::from(y));
        [x / 16.0, y / 12.0, (x + y) / 28.0, 1.0]
    })
}

pub const SAMPLE: OpDef = OpDef::new(
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
        wgsl: include_str!("sample.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("tex", Footprint::Anywhere)],
    },
    |a| sample(a[0].tex(), a[1].v2()),
    &[Case::new(
        "a smooth 16×12 8-bit image, magnified to 37×29",
        &[tex8(smooth, false), Arg::Uv],
        Tol::Abs(4e-3),
    )
    .over(37, 29)],
)
// Bilinear weights are convex: the read stays in the hull of the texels.
.with_texel_hull("tex")
.with_demo(demos::SAMPLE);
