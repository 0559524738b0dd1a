//! An operator's GPU-against-reference cases, as data: per parameter the
//! argument each call gets (a constant, a list or random values, the call's
//! pixel, a synthetic texture), the tolerance, and the operator's f64
//! reference as a function of the resolved arguments. The generic GPU test
//! (`stdlib/tests/gpu_cases.rs`) builds each call from the operator's
//! signature and these cases, so a new operator needs no hand-written GPU
//! test; the completeness test requires at least one case per operator.

use crate::image_f64::ImageF64;
use crate::Operator;

/// One argument's value in one call: a number in `.0[0]` (an int, enum
/// index or bool as 0/1 too) or a vector's components.
pub type Value = [f64; 4];

/// What a parameter gets in the calls of a [`Case`].
#[derive(Debug, Clone, Copy)]
pub enum Arg {
    /// The same value in every call.
    Const(Value),
    /// Each value in turn: a factor of the case's calls (the calls are the
    /// cartesian product of every `Each` and `Random` argument).
    Each(&'static [Value]),
    /// `n` values drawn uniformly per component from `[lo, hi]` by a fixed
    /// generator (seeded by the operator, case and argument): a factor like `Each`.
    Random { lo: Value, hi: Value, n: u32 },
    /// A function of another (number) argument's value in the same call,
    /// e.g. a point on a sphere from its normal.
    From { arg: usize, f: fn(Value) -> Value },
    /// The call's pixel of the case's `pixels` grid, as a texel centre
    /// ((x + ½)/w, (y + ½)/h): "this pixel" for operators that read a texture there.
    Uv,
    /// A uv affine in the pixel: `origin + (x + ½)·dx + (y + ½)·dy`, so its
    /// screen derivatives are `dx` and `dy`. (An operator that takes
    /// derivatives needs an even grid when a case has several calls: the
    /// 2×2 quads derivatives are taken over must not straddle two calls.)
    ScreenUv {
        origin: [f64; 2],
        dx: [f64; 2],
        dy: [f64; 2],
    },
    /// A texture parameter's texture.
    Texture(Tex),
}

/// A synthetic texture a case creates.
#[derive(Debug, Clone, Copy)]
pub struct Tex {
    /// Its texels (the reference sees them rounded to `format`).
    pub image: fn() -> ImageF64,
    pub format: TexFormat,
    /// A sampled texture's sampler repeats (otherwise it clamps to the edge); both filter linearly.
    pub repeat: bool,
    /// A full mip chain: level k ≥ 1's texels (the sampler filters between levels linearly).
    pub levels: Option<fn(u32) -> ImageF64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexFormat {
    Rgba32Float,
    Rgba8Unorm,
}

/// How far the GPU may be from the reference, per compared channel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tol {
    /// |gpu − reference| ≤ t.
    Abs(f64),
    /// |gpu − reference| ≤ t · max(1, |reference|).
    Rel(f64),
}

/// A set of calls of one operator, compared with its reference.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// Why this case exists (printed with its error).
    pub what: &'static str,
    /// One per parameter, in the operator's order.
    pub args: &'static [Arg],
    /// The grid [`Arg::Uv`] and [`Arg::ScreenUv`] run over; every
    /// combination of the `Each`/`Random` values runs over all of it.
    pub pixels: (u32, u32),
    pub tol: Tol,
    /// The share of calls whose reference is NaN (undefined: within
    /// rounding of a discontinuity such as a threshold) that may be skipped.
    pub max_skipped: f64,
}

impl Case {
    /// A case over `args` with one pixel, an absolute tolerance and nothing skipped.
    pub const fn new(what: &'static str, args: &'static [Arg], tol: Tol) -> Case {
        Case {
            what,
            args,
            pixels: (1, 1),
            tol,
            max_skipped: 0.0,
        }
    }

    /// The same case over a grid of pixels.
    pub const fn over(self, w: u32, h: u32) -> Case {
        Case { pixels: (w, h), ..self }
    }

    /// The same case, allowing a share of undefined (NaN) references.
    pub const fn skipping(self, share: f64) -> Case {
        Case {
            max_skipped: share,
            ..self
        }
    }
}

/// One argument of one call, resolved, as the reference sees it.
#[derive(Debug, Clone, Copy)]
pub enum Val<'a> {
    Num(Value),
    /// A uv ([`Arg::Uv`] or [`Arg::ScreenUv`]) with its screen derivatives.
    Uv {
        uv: [f64; 2],
        dx: [f64; 2],
        dy: [f64; 2],
    },
    Tex(&'a ImageF64),
}

impl Val<'_> {
    pub fn v4(&self) -> [f64; 4] {
        match self {
            Val::Num(v) => *v,
            Val::Uv { uv, .. } => [uv[0], uv[1], 0.0, 0.0],
            Val::Tex(_) => panic!("a texture is not a number"),
        }
    }
    pub fn f(&self) -> f64 {
        self.v4()[0]
    }
    pub fn i(&self) -> i64 {
        self.f() as i64
    }
    pub fn b(&self) -> bool {
        self.f() != 0.0
    }
    pub fn v2(&self) -> [f64; 2] {
        let v = self.v4();
        [v[0], v[1]]
    }
    pub fn v3(&self) -> [f64; 3] {
        let v = self.v4();
        [v[0], v[1], v[2]]
    }
    pub fn tex(&self) -> &ImageF64 {
        match self {
            Val::Tex(t) => t,
            _ => panic!("not a texture"),
        }
    }
    /// The screen derivatives (∂uv/∂x, ∂uv/∂y) of a uv argument.
    pub fn derivatives(&self) -> ([f64; 2], [f64; 2]) {
        match self {
            Val::Uv { dx, dy, .. } => (*dx, *dy),
            _ => panic!("not a uv"),
        }
    }
}

/// A float result as the first channel of four.
pub fn scalar(x: f64) -> [f64; 4] {
    [x, 0.0, 0.0, 0.0]
}

/// A vec2 result in the first two channels.
pub fn pair(v: [f64; 2]) -> [f64; 4] {
    [v[0], v[1], 0.0, 0.0]
}

/// A vec3 result in the first three channels.
pub fn triple(v: [f64; 3]) -> [f64; 4] {
    [v[0], v[1], v[2], 0.0]
}

/// An operator as registered: its metadata, its f64 reference for one call
/// and its GPU cases.
#[derive(Debug, Clone, Copy)]
pub struct OpDef {
    pub op: Operator,
    /// The name of the f64 reference function in the operator's module
    /// (the registration checks that it exists; the completeness test that
    /// it is the operator's own name).
    pub reference_fn: &'static str,
    /// The reference for one call, arguments in parameter order; NaN where
    /// the reference is undefined (see [`Case::max_skipped`]).
    pub eval: fn(&[Val]) -> [f64; 4],
    pub cases: &'static [Case],
    /// What `npr doc` renders to show the operator (see [`super::Demo`]).
    pub demo: super::Demo,
    /// Bounds every component of the result stays in for finite
    /// arguments within their parameters' declared ranges (issue 49: the compiler's range analysis starts from
    /// them); `None` where nothing is promised. `tests/op_ranges.rs` checks
    /// the reference at the argument ends.
    pub range: Option<(f64, f64)>,
    /// The texture parameter whose texels bound the result: each
    /// component is a convex combination (weights ≥ 0 summing to 1) of
    /// that component of the texture's texels, for finite texels and
    /// finite other arguments (issue 49: the range analysis bounds a
    /// filter's result by what its input target or image holds).
    /// `tests/op_ranges.rs` checks the reference on random textures.
    pub texel_hull: Option<&'static str>,
}

/// How far past its declared bounds an operator's result may round (a
/// share of each bound's magnitude: a few f32 ulps, as `n·l` of unit
/// vectors comes out 1 + 2⁻²³). The range analysis widens by it, the
/// test of the ranges allows it.
pub const RANGE_SLACK: f64 = 4.0 * f32::EPSILON as f64;

impl OpDef {
    /// [`OpDef::range`] widened by [`RANGE_SLACK`].
    pub fn range_with_slack(&self) -> Option<(f64, f64)> {
        self.range
            .map(|(lo, hi)| (lo - RANGE_SLACK * lo.abs(), hi + RANGE_SLACK * hi.abs()))
    }
}

/// Uniform random values in a box (shorthand for [`Arg::Random`]).
pub const fn random(lo: Value, hi: Value, n: u32) -> Arg {
    Arg::Random { lo, hi, n }
}

/// A number in every call.
pub const fn num(x: f64) -> Arg {
    Arg::Const([x, 0.0, 0.0, 0.0])
}

/// Several numbers in turn.
pub const fn nums(xs: &'static [Value]) -> Arg {
    Arg::Each(xs)
}

/// A 32-bit float texture made by `image`, clamped.
pub const fn tex32(image: fn() -> ImageF64) -> Arg {
    Arg::Texture(Tex {
        image,
        format: TexFormat::Rgba32Float,
        repeat: false,
        levels: None,
    })
}

/// An 8-bit unorm texture made by `image`, with a clamping or repeating sampler.
pub const fn tex8(image: fn() -> ImageF64, repeat: bool) -> Arg {
    Arg::Texture(Tex {
        image,
        format: TexFormat::Rgba8Unorm,
        repeat,
        levels: None,
    })
}

/// An 8-bit unorm texture with a full mip chain: level 0 is `image`, level k is `level(k)`.
pub const fn tex8_mipmapped(image: fn() -> ImageF64, level: fn(u32) -> ImageF64, repeat: bool) -> Arg {
    Arg::Texture(Tex {
        image,
        format: TexFormat::Rgba8Unorm,
        repeat,
        levels: Some(level),
    })
}

impl OpDef {
    /// An operator with its reference and cases (the registration line names its reference function).
    pub const fn new(op: Operator, eval: fn(&[Val]) -> [f64; 4], cases: &'static [Case]) -> OpDef {
        OpDef {
            op,
            reference_fn: "",
            eval,
            cases,
            demo: super::Demo::Missing,
            range: None,
            texel_hull: None,
        }
    }

    /// The same operator with the bounds of its result.
    pub const fn with_range(self, lo: f64, hi: f64) -> OpDef {
        OpDef {
            range: Some((lo, hi)),
            ..self
        }
    }

    /// The same operator with its result in the hull of texture parameter
    /// `param`'s texels (a filter whose weights are convex).
    pub const fn with_texel_hull(self, param: &'static str) -> OpDef {
        OpDef {
            texel_hull: Some(param),
            ..self
        }
    }

    /// How far past its texels' hull a [`OpDef::texel_hull`] operator's
    /// f32 result may round: a share of the hull's largest magnitude, for
    /// up to 97 taps (the Gaussian's 48-texel radius) summed and divided
    /// by their weights' sum. Not past 0 from a hull on one side of it:
    /// non-negative terms never round below 0.
    pub fn hull_with_slack(lo: f64, hi: f64) -> (f64, f64) {
        let slack = 256.0 * f32::EPSILON as f64;
        let m = lo.abs().max(hi.abs());
        let lo = if lo >= 0.0 { lo * (1.0 - slack) } else { lo - slack * m };
        let hi = if hi <= 0.0 { hi * (1.0 - slack) } else { hi + slack * m };
        (lo, hi)
    }

    /// The same operator with its demo (every operator needs one).
    pub const fn with_demo(self, demo: super::Demo) -> OpDef {
        OpDef { demo, ..self }
    }
}
