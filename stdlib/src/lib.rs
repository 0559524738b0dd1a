//! The npr operator standard library.
//!
//! Each operator lives in a folder of [`ops`] (one per operator or family
//! of variants): a WGSL function (`<name>.wgsl`) plus metadata (its
//! signature, parameter types, units, defaults, ranges, docs, and the paper
//! and equation numbers it implements), a CPU f64 reference under its own
//! name, and the GPU-against-reference cases the generic test runs. Every
//! reference is re-exported by [`reference`](mod@reference); [`all`] is the registry of
//! [`ops`], in order.
//!
//! WGSL conventions (the compiler relies on them):
//! - operator `foo` is the WGSL function `npr_foo`; private helpers in the same
//!   file are prefixed `npr_foo__`;
//! - parameters appear in the WGSL signature in the order of [`Operator::params`];
//! - a [`Ty::Texture`] parameter is one `texture_2d<f32>` argument, read with
//!   `textureLoad` (so unfilterable float targets work); a [`Ty::SampledTexture`]
//!   parameter is two arguments, `texture_2d<f32>` then `sampler`;
//! - an [`Ty::Enum`] parameter is an `i32` holding the variant's index;
//! - a [`Ty::Color`] is a `vec4<f32>` with straight (not premultiplied) alpha;
//! - quantities with a [`Unit`] arrive in the canonical unit: px, metres,
//!   seconds, hertz, radians.

pub mod halftone_table;
pub mod image_f64;
pub mod metrics;
pub mod ops;
pub mod reference;
/// The f64 references of the G-buffer packing operators.
pub use ops::gbuffer::reference as reference_gbuffer;
/// The f64 references of the LSA contour operators.
pub use ops::lsa::reference as reference_lsa;
/// The f64 references of `shadow` (the Age of Sail pipeline, §5).
pub use ops::shadow::reference as reference_pipeline;
/// The f64 references of the stereo operators (LSA contours §4.2).
pub use ops::stereo::reference as reference_stereo;

use serde::Serialize;

/// A value type in the operator signatures (and in the compiler's type system).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Ty {
    Float,
    Int,
    Bool,
    Vec2,
    Vec3,
    Vec4,
    /// An RGBA colour, `vec4<f32>`.
    Color,
    /// A texture read with `textureLoad`: `texture_2d<f32>`.
    Texture,
    /// A texture read with a sampler: `texture_2d<f32>, sampler`.
    SampledTexture,
    /// A compile-time choice among named variants, passed as `i32`.
    Enum(&'static [&'static str]),
}

impl Ty {
    /// The WGSL type of a value of this type (textures: the texture part).
    pub fn wgsl(self) -> &'static str {
        match self {
            Ty::Float => "f32",
            Ty::Int | Ty::Enum(_) => "i32",
            Ty::Bool => "bool",
            Ty::Vec2 => "vec2<f32>",
            Ty::Vec3 => "vec3<f32>",
            Ty::Vec4 | Ty::Color => "vec4<f32>",
            Ty::Texture | Ty::SampledTexture => "texture_2d<f32>",
        }
    }
}

/// The physical dimension of a quantity: defined in the ABI, where the
/// typing of parameter values (`npr_abi::param_value`) needs it.
pub use npr_abi::Unit;

/// What a parameter gets when the call omits it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Default {
    /// The argument must be given.
    Required,
    Number(f64),
    /// A builtin value such as `screen_uv`.
    Builtin(&'static str),
    /// An enum variant by name.
    Variant(&'static str),
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Param {
    pub name: &'static str,
    pub ty: Ty,
    pub unit: Unit,
    pub default: Default,
    /// Inclusive bounds a constant argument must lie in.
    pub range: Option<(f64, f64)>,
    pub doc: &'static str,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Operator {
    pub name: &'static str,
    pub doc: &'static str,
    /// Source: paper and equation numbers, or a textbook reference.
    pub reference: &'static str,
    pub params: &'static [Param],
    pub returns: Ty,
    /// The WGSL source defining `npr_<name>` (and its private helpers).
    pub wgsl: &'static str,
    /// Other operators whose WGSL functions this one calls.
    pub depends: &'static [&'static str],
    /// Shared WGSL helper files (from [`snippets`]) this one calls.
    pub snippets: &'static [&'static str],
    /// Cheaper operators to call instead when an argument is a known constant.
    pub specializations: &'static [Specialization],
    /// What it reads of each texture parameter, by parameter name (one
    /// entry per [`Ty::Texture`] / [`Ty::SampledTexture`] parameter; the
    /// completeness test checks it, `tests/footprints.rs` measures it).
    pub footprints: &'static [(&'static str, Footprint)],
}

/// Which texels of a texture argument an operator reads (issue 14: a
/// compiler that runs a neighbourhood operator in workgroup tiles sizes the
/// tile's apron from this; fusion refuses any read but the pixel's own).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Footprint {
    /// Texels within `radius` (Chebyshev distance, in the texture's own
    /// texels) of the texel under the parameter named `uv`; when that
    /// argument is the pixel's `screen_uv`, a neighbourhood of the pixel.
    Around { uv: &'static str, radius: Radius },
    /// Anywhere: at a coordinate computed from data (a warp, a
    /// reprojection, a light-space lookup, a sampled uv, a table lookup).
    Anywhere,
}

/// The radius of a [`Footprint::Around`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Radius {
    Texels(u32),
    /// min(⌈k · value⌉, max) of the named parameter (e.g. a Gaussian's 3σ),
    /// known when the argument is a constant.
    Scaled {
        param: &'static str,
        k: f64,
        max: u32,
    },
}

impl Radius {
    /// The radius in texels, given the constant value of the parameter a
    /// scaled radius depends on (`None`: not a constant, so only `max` bounds it).
    pub fn texels(self, value: Option<f64>) -> u32 {
        match self {
            Radius::Texels(r) => r,
            Radius::Scaled { k, max, .. } => match value {
                Some(v) if v.is_finite() => ((k * v).ceil().max(0.0) as u32).min(max),
                _ => max,
            },
        }
    }
}

/// "When `param` is the constant `value`, call `use_operator` instead": the
/// replacement takes the same parameters minus `param`. This is how a style
/// without skew compensation emits no 8-tap MetaTexture code.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Specialization {
    pub param: &'static str,
    pub value: f64,
    pub use_operator: &'static str,
}

/// Shared WGSL helpers, by name: (name, source). Their functions are prefixed
/// `npr_<name>__` and are emitted once per module that needs them.
pub mod snippets {
    pub const ALL: &[(&str, &str)] = &[
        ("meta", include_str!("ops/metatexture/meta.wgsl")),
        ("lsa_core", include_str!("ops/lsa/lsa_core.wgsl")),
        ("lsa_plane", include_str!("ops/lsa/lsa_plane.wgsl")),
        ("lsa_aa", include_str!("ops/lsa/lsa_aa.wgsl")),
        ("oct", include_str!("ops/gbuffer/oct.wgsl")),
    ];

    pub fn find(name: &str) -> Option<&'static str> {
        ALL.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
    }
}

impl Operator {
    pub fn wgsl_fn(&self) -> String {
        format!("npr_{}", self.name)
    }

    pub fn param(&self, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.name == name)
    }

    /// What it reads of its texture parameter `name` (`None`: not one).
    pub fn footprint(&self, name: &str) -> Option<Footprint> {
        self.footprints.iter().find(|(n, _)| *n == name).map(|(_, f)| *f)
    }
}

/// Every operator in the standard library, in a fixed order (the IR names
/// operators by their index here): the operator table, then the dynamic
/// 2D patterns' operators, the art-map operators and the G-buffer packing
/// operators.
pub fn all() -> &'static [Operator] {
    static ALL: std::sync::LazyLock<Vec<Operator>> =
        std::sync::LazyLock::new(|| ops::ALL.iter().map(|d| d.op).collect());
    &ALL
}

/// Look an operator up by its `.npr` name.
pub fn find(name: &str) -> Option<&'static Operator> {
    all().iter().find(|o| o.name == name)
}
