//! The operators, one folder per operator or family of variants: its
//! metadata (an [`OpDef`]: the [`crate::Operator`], its f64 reference as a
//! function of one call's arguments, its GPU cases), its f64 reference
//! functions (each under its operator's name) and its WGSL files. Each
//! operator is registered with one line below, in the order of
//! [`crate::all`] (the IR names operators by that index).
//!
//! Adding an operator (or a variant to a family's folder):
//! 1. `ops/<name>/<name>.wgsl` with the function `npr_<name>` (helpers
//!    `npr_<name>__*`; shared helpers are snippets, see [`crate::snippets`]);
//! 2. `ops/<name>/mod.rs` with a `//!` header citing the paper, the f64
//!    reference `pub fn <name>` (or in a `reference.rs` beside it,
//!    re-exported), and `pub const <NAME>: OpDef = OpDef::new(Operator { …
//!    }, |args| <reference of one call>, &[Case::new(…), …])`: at least one
//!    data case, with its tolerance and why, and `.with_demo(demos::<NAME>)`:
//!    its demo in `ops/<name>/demos.rs` (a style calling it and a scene of
//!    `examples/`, which `npr doc` renders, or `Demo::NoDemo("why")`);
//! 3. `pub mod <name>;` and `<name>::<NAME> => <name>,` at the end of the
//!    registry below (appending keeps every operator's index), and the
//!    reference's re-export in `crate::reference`.
//!
//! `tests/completeness.rs` says what is missing (naga, the signature, the
//! docs, the reference's name, the cases' fit to the signature);
//! `tests/gpu_cases.rs` runs the cases on the GPU, no test code needed.

pub mod case;
pub mod demo;
pub use case::*;
pub use demo::*;

/// `each![a, b, …]`: numbers in turn, an [`Arg::Each`] of scalars.
macro_rules! each {
    ($($x:expr),* $(,)?) => {
        $crate::ops::Arg::Each(&[$([$x as f64, 0.0, 0.0, 0.0]),*])
    };
}

pub mod artmaps;
pub mod breakup;
pub mod colour;
pub mod filters;
pub mod gbuffer;
pub mod images;
pub mod lsa;
pub mod metatexture;
pub mod patterns;
pub mod sample;
pub mod shading;
pub mod shadow;
pub mod stereo;

use crate::{Default, Param, Ty, Unit};

/// A required parameter with no unit or range.
pub(crate) const fn p(name: &'static str, ty: Ty, doc: &'static str) -> Param {
    Param {
        name,
        ty,
        unit: Unit::None,
        default: Default::Required,
        range: None,
        doc,
    }
}

/// `uv: vec2 = screen_uv`: where an image operator reads (this pixel by default).
pub(crate) const UV_SCREEN: Param = Param {
    name: "uv",
    ty: Ty::Vec2,
    unit: Unit::None,
    default: Default::Builtin("screen_uv"),
    range: None,
    doc: "where to read, in [0, 1]² (default: this pixel)",
};

/// `family::DEF => reference`: the registered operators in order, each
/// with the name of its f64 reference function, which must exist in its
/// family's module (this does not compile otherwise).
macro_rules! registry {
    ($($family:ident :: $def:ident => $reference:ident),* $(,)?) => {
        /// Every registered operator, in the order of [`crate::all`].
        pub static ALL: &[OpDef] = &[$(OpDef { reference_fn: stringify!($reference), ..$family::$def }),*];
        const _: () = {
            $(let _ = $family::$reference;)*
        };
    };
}

registry! {
    shading::LAMBERT => lambert,
    shading::HALF_LAMBERT => half_lambert,
    shading::TOON => toon,
    shading::THRESHOLD => threshold,
    filters::GAUSSIAN => gaussian,
    filters::DOWNSAMPLE => downsample,
    filters::SOBEL => sobel,
    filters::NORMAL_DEPTH_EDGES => normal_depth_edges,
    colour::OVER => over,
    colour::LUMINANCE => luminance,
    colour::SATURATION => saturation,
    colour::OVERLAY => overlay,
    sample::SAMPLE => sample,
    metatexture::METATEXTURE_GRAD => metatexture_grad,
    metatexture::METATEXTURE => metatexture,
    metatexture::METATEXTURE4_GRAD => metatexture4_grad,
    metatexture::METATEXTURE4 => metatexture4,
    shadow::SHADOW => shadow,
    stereo::CONTOUR_FADE => contour_fade,
    stereo::REPROJECTION_MASK => reprojection_mask,
    stereo::STEREO_CONSISTENCY => stereo_consistency,
    breakup::RADIAL_ALPHA => radial_alpha,
    breakup::UV_GRADIENTS => uv_gradients,
    metatexture::METATEXTURE_CONTOUR_GRAD => metatexture_contour_grad,
    metatexture::METATEXTURE_CONTOUR => metatexture_contour,
    breakup::LIVE_TEXTURE => live_texture,
    breakup::LINE_BOIL => line_boil,
    breakup::ROLL_COMPENSATE => roll_compensate,
    breakup::DISTANCE_ATTENUATE => distance_attenuate,
    breakup::WARP => warp,
    lsa::LSA => lsa,
    lsa::LSA_SUM => lsa_sum,
    lsa::LSA_CURV_AA => lsa_curv_aa,
    lsa::LSA_CURV => lsa_curv,
    lsa::LSA_DENSITY => lsa_density,
    patterns::ID_SHARE => id_share,
    patterns::COMPLEX_MUL => complex_mul,
    patterns::PATTERN_UV => pattern_uv,
    patterns::HALFTONE_SCREEN => halftone_screen,
    patterns::HALFTONE => halftone,
    artmaps::SAMPLE_BIASED => sample_biased,
    artmaps::SAMPLE_RIPMAP => sample_ripmap,
    gbuffer::OCT_ENCODE => oct_encode,
    gbuffer::OCT_DECODE => oct_decode,
}

/// The registered operator `name`.
pub fn find(name: &str) -> Option<&'static OpDef> {
    ALL.iter().find(|d| d.op.name == name)
}
