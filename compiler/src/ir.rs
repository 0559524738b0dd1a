//! The compiler's intermediate representation: an arena graph with spans.
//!
//! Expressions live in one arena ([`Ir::exprs`]) and refer to each other by
//! [`ExprId`]. Sharing is allowed (a `let` used twice is one node referenced
//! twice), so the graph is a DAG, never a tree. A node is always created
//! after its operands, so iterating the arena in order visits operands first
//! (the typechecker relies on this).

use dsl::Span;
use serde::Serialize;
use stdlib::Unit;

mod lines;
pub use lines::{LineSettings, LinesKind};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct ExprId(pub u32);
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct ParamId(pub u32);
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct TextureId(pub u32);
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct PassId(pub u32);

/// A pass output: (pass, index into that pass's outputs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct TargetRef {
    pub pass: PassId,
    pub output: u32,
}

/// Value types. Colours are `Vec4`. Handles are textures passed to operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Ty {
    /// Not yet known (before typecheck) or the type of an erroneous node.
    Unknown,
    Float,
    Int,
    Bool,
    Vec2,
    Vec3,
    Vec4,
    /// A pass target used as a texture (passed to an operator, or read at `screen_uv`).
    Target(TargetRef),
    /// A declared texture (passed to an operator, or sampled at `uv`).
    Texture(TextureId),
}

impl Ty {
    pub fn components(self) -> Option<u32> {
        match self {
            Ty::Float | Ty::Int | Ty::Bool => Some(1),
            Ty::Vec2 => Some(2),
            Ty::Vec3 => Some(3),
            Ty::Vec4 => Some(4),
            _ => None,
        }
    }

    pub fn float_vec(n: u32) -> Ty {
        match n {
            1 => Ty::Float,
            2 => Ty::Vec2,
            3 => Ty::Vec3,
            _ => Ty::Vec4,
        }
    }

    pub fn is_numeric(self) -> bool {
        matches!(self, Ty::Float | Ty::Int | Ty::Vec2 | Ty::Vec3 | Ty::Vec4)
    }

    pub fn wgsl(self) -> &'static str {
        match self {
            Ty::Float => "f32",
            Ty::Int => "i32",
            Ty::Bool => "bool",
            Ty::Vec2 => "vec2<f32>",
            Ty::Vec3 => "vec3<f32>",
            Ty::Vec4 => "vec4<f32>",
            _ => "<handle>",
        }
    }

    pub fn describe(self) -> &'static str {
        match self {
            Ty::Unknown => "an unknown type",
            Ty::Float => "float",
            Ty::Int => "int",
            Ty::Bool => "bool",
            Ty::Vec2 => "vec2",
            Ty::Vec3 => "vec3",
            Ty::Vec4 => "vec4",
            Ty::Target(_) => "a pass target",
            Ty::Texture(_) => "a texture",
        }
    }
}

/// A compile-time constant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum Const {
    Float(f64),
    Int(i64),
    Bool(bool),
    /// vec2..vec4 (colours included).
    Vec(Vec<f64>),
}

impl Const {
    pub fn as_f64s(&self) -> Vec<f64> {
        match self {
            Const::Float(v) => vec![*v],
            Const::Int(v) => vec![*v as f64],
            Const::Bool(b) => vec![if *b { 1.0 } else { 0.0 }],
            Const::Vec(v) => v.clone(),
        }
    }

    pub fn scalar(&self) -> Option<f64> {
        match self {
            Const::Float(v) => Some(*v),
            Const::Int(v) => Some(*v as f64),
            Const::Bool(b) => Some(if *b { 1.0 } else { 0.0 }),
            Const::Vec(_) => None,
        }
    }
}

/// Values the runtime provides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum Builtin {
    /// In a pass over samples: the distance between neighbouring samples
    /// on the surface, in world units (the diameter of the tangent disc
    /// each sample stands for, Breslav et al. 2007 §3.1).
    SampleSpacing,
    Uv,
    NormalWorld,
    NormalView,
    PositionWorld,
    PositionView,
    /// Light-space NDC of the surface point: x, y in [−1, 1] (unwarped), z in [0, 1].
    PositionLight,
    Tangent,
    ViewDir,
    Depth,
    FragCoord,
    ScreenUv,
    Resolution,
    Time,
    Frame,
    Eye,
    LightDir,
    LightColor,
    LightIntensity,
    /// `light2.dir` … `light4.dir`: the scene's extra lights (index 0..3 is
    /// light2..light4, `Frame::more_light_dir`).
    MoreLightDir(u8),
    MoreLightColor(u8),
    MoreLightIntensity(u8),
    CameraPosition,
    CameraNear,
    CameraFar,
    /// (P₀₀, P₁₁) of the projection matrix: the focal lengths in NDC units
    /// that Age of Sail eq. 12 divides the screen position by.
    CameraFocal,
    /// The left and right eye positions of a stereo camera (both the camera
    /// position in mono), and the unit view direction.
    CameraLeftEye,
    CameraRightEye,
    CameraForward,
    /// Screen-space projection T_s of the unit world tangent (direction of
    /// increasing u), in px per metre, computed in the vertex shader from the
    /// analytic Jacobian of the projection and interpolated (Age of Sail §3.2).
    TangentScreen,
    /// B_s: the same for the unit bitangent (direction of increasing v).
    BitangentScreen,
    /// T_s projected with the stereo camera's centre (the same for both eyes;
    /// equal to `tangent.screen` in mono), against stereo "shimmer" (§3.2).
    TangentScreenCenter,
    /// B_s projected with the stereo camera's centre.
    BitangentScreenCenter,
    /// The object's position in the scene's object list (0, 1, ...).
    ObjectIndex,
    /// The object's id for ID images: its index + 1, so that 0 (a cleared
    /// target) means "no object".
    ObjectId,
    /// The world position of this surface point in the previous frame (the
    /// object's previous transform; equal to `position` on the first frame).
    PositionPrevious,
    /// In a `lines` pass: the screen-space arc length along the strip's
    /// chain, in px (the s of Klein et al. 2000 §5's sin(2π·s/λ + φ)).
    LineArc,
    /// In a `lines` pass: −1 on one edge of the strip, +1 on the other,
    /// interpolated across it (for soft edges or a brush profile).
    LineAcross,
    /// In a render pass: the blending weight of the patch being drawn at
    /// this point (Breslav et al. 2007 §3.6), interpolated from its
    /// vertices; 1 on objects without patches. A pass that reads it draws
    /// each patch over its n-ring too (`abi::Attribute::PatchWeight`).
    PatchWeight,
}

impl Builtin {
    /// (spelling, builtin) for every name a style can write.
    pub const SPELLINGS: &'static [(&'static str, Builtin)] = &[
        ("uv", Builtin::Uv),
        ("normal", Builtin::NormalWorld),
        ("normal.world", Builtin::NormalWorld),
        ("normal.view", Builtin::NormalView),
        ("position", Builtin::PositionWorld),
        ("position.world", Builtin::PositionWorld),
        ("position.view", Builtin::PositionView),
        ("position.light", Builtin::PositionLight),
        ("tangent", Builtin::Tangent),
        ("view_dir", Builtin::ViewDir),
        ("depth", Builtin::Depth),
        ("frag_coord", Builtin::FragCoord),
        ("screen_uv", Builtin::ScreenUv),
        ("resolution", Builtin::Resolution),
        ("time", Builtin::Time),
        ("frame", Builtin::Frame),
        ("eye", Builtin::Eye),
        ("light.dir", Builtin::LightDir),
        ("light.color", Builtin::LightColor),
        ("light.intensity", Builtin::LightIntensity),
        ("light2.dir", Builtin::MoreLightDir(0)),
        ("light2.color", Builtin::MoreLightColor(0)),
        ("light2.intensity", Builtin::MoreLightIntensity(0)),
        ("light3.dir", Builtin::MoreLightDir(1)),
        ("light3.color", Builtin::MoreLightColor(1)),
        ("light3.intensity", Builtin::MoreLightIntensity(1)),
        ("light4.dir", Builtin::MoreLightDir(2)),
        ("light4.color", Builtin::MoreLightColor(2)),
        ("light4.intensity", Builtin::MoreLightIntensity(2)),
        ("camera.position", Builtin::CameraPosition),
        ("camera.near", Builtin::CameraNear),
        ("camera.far", Builtin::CameraFar),
        ("camera.focal", Builtin::CameraFocal),
        ("camera.left_eye", Builtin::CameraLeftEye),
        ("camera.right_eye", Builtin::CameraRightEye),
        ("camera.forward", Builtin::CameraForward),
        ("tangent.screen", Builtin::TangentScreen),
        ("bitangent.screen", Builtin::BitangentScreen),
        ("tangent.screen_center", Builtin::TangentScreenCenter),
        ("bitangent.screen_center", Builtin::BitangentScreenCenter),
        ("object.index", Builtin::ObjectIndex),
        ("object.id", Builtin::ObjectId),
        ("position.previous", Builtin::PositionPrevious),
        ("sample.spacing", Builtin::SampleSpacing),
        ("line.s", Builtin::LineArc),
        ("line.across", Builtin::LineAcross),
        ("patch.weight", Builtin::PatchWeight),
    ];

    pub fn name(self) -> &'static str {
        Self::SPELLINGS
            .iter()
            .rev()
            .find(|(_, b)| *b == self)
            .map(|(s, _)| *s)
            .unwrap_or("?")
    }

    pub fn ty_unit(self) -> (Ty, Unit) {
        use Builtin::*;
        match self {
            Uv | ScreenUv => (Ty::Vec2, Unit::None),
            NormalWorld | NormalView | Tangent | ViewDir | LightDir | PositionLight => (Ty::Vec3, Unit::None),
            PositionWorld | PositionView | CameraPosition | PositionPrevious => (Ty::Vec3, Unit::Meters),
            ObjectIndex | ObjectId => (Ty::Int, Unit::None),
            Depth | CameraNear | CameraFar | SampleSpacing => (Ty::Float, Unit::Meters),
            CameraLeftEye | CameraRightEye => (Ty::Vec3, Unit::Meters),
            CameraForward => (Ty::Vec3, Unit::None),
            FragCoord | Resolution => (Ty::Vec2, Unit::Px),
            Time => (Ty::Float, Unit::Seconds),
            LineArc => (Ty::Float, Unit::Px),
            LineAcross | PatchWeight => (Ty::Float, Unit::None),
            Frame | Eye => (Ty::Int, Unit::None),
            LightColor | MoreLightColor(_) | MoreLightDir(_) => (Ty::Vec3, Unit::None),
            LightIntensity | MoreLightIntensity(_) => (Ty::Float, Unit::None),
            // px per metre has no unit of its own; NDC focal lengths are ratios.
            CameraFocal | TangentScreen | BitangentScreen | TangentScreenCenter | BitangentScreenCenter => {
                (Ty::Vec2, Unit::None)
            }
        }
    }

    /// Interpolated per fragment (the fragment shader's varyings or its pixel
    /// position), so a `vertex { ... }` modifier cannot read it.
    pub fn is_per_fragment(self) -> bool {
        use Builtin::*;
        self.needs_geometry()
            || self.is_line_value()
            || matches!(
                self,
                FragCoord | ScreenUv | TangentScreen | BitangentScreen | TangentScreenCenter | BitangentScreenCenter
            )
    }

    /// Exists only in the fragments of a `lines` pass's strips.
    pub fn is_line_value(self) -> bool {
        matches!(self, Builtin::LineArc | Builtin::LineAcross)
    }

    /// Only meaningful on scene geometry (needs vertex data).
    pub fn needs_geometry(self) -> bool {
        use Builtin::*;
        matches!(
            self,
            Uv | NormalWorld
                | NormalView
                | PositionWorld
                | PositionView
                | Tangent
                | ViewDir
                | PositionLight
                | Depth
                | TangentScreen
                | BitangentScreen
                | TangentScreenCenter
                | BitangentScreenCenter
                | PositionPrevious
                | SampleSpacing
                | PatchWeight
        )
    }

    /// Needs an object (the `Object` block): render and compute passes.
    pub fn needs_object(self) -> bool {
        matches!(self, Builtin::ObjectIndex | Builtin::ObjectId)
    }

    /// Whether a compute pass over the pixels of an ID target has it: the
    /// pixel's position (not the interpolated screen-space frames, which
    /// exist only for fragments of geometry).
    pub fn in_pixel_elements(self) -> bool {
        matches!(self, Builtin::FragCoord | Builtin::ScreenUv)
    }

    /// Whether a compute pass over the vertices of objects has it: the
    /// vertex's own attributes and what follows from them, not what exists
    /// only per fragment (the pixel, interpolated screen-space frames) or
    /// what needs the light camera.
    pub fn in_vertex_elements(self) -> bool {
        use Builtin::*;
        !self.is_per_fragment()
            || matches!(
                self,
                Uv | NormalWorld | NormalView | PositionWorld | PositionView | ViewDir | Depth | PositionPrevious
            )
    }
}

/// WGSL built-in functions and constructors the language exposes directly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Intrinsic {
    /// `vec2(..)`, `vec3(..)`, `vec4(..)`: components flattened, or one scalar splatted.
    Construct(u32),
    /// Component-wise, same type in and out: abs, floor, sin, ...
    Map(&'static str),
    /// Same-typed operands, same type out: min, max, pow, step, atan2.
    Map2(&'static str),
    /// clamp(x, lo, hi), smoothstep(lo, hi, x), mix(a, b, t).
    Map3(&'static str),
    /// Vector to scalar: length.
    Length,
    Dot,
    Distance,
    Normalize,
    Cross,
    /// `project(p)`: world point → (screen u, screen v, NDC depth) in this eye.
    Project,
    /// `project_other_eye(p)`: the same in the other eye of a stereo frame.
    ProjectOtherEye,
    /// `project_previous(p)`: the same with the previous frame's camera.
    ProjectPrevious,
}

impl Intrinsic {
    /// Every intrinsic a style can call, by spelling: the single source of
    /// both [`Intrinsic::lookup`] and [`Intrinsic::name`]'s spellings (a unit
    /// test checks that each entry's `name()` is its spelling).
    pub const TABLE: &'static [(&'static str, Intrinsic)] = &[
        ("vec2", Intrinsic::Construct(2)),
        ("vec3", Intrinsic::Construct(3)),
        ("vec4", Intrinsic::Construct(4)),
        ("abs", Intrinsic::Map("abs")),
        ("floor", Intrinsic::Map("floor")),
        ("ceil", Intrinsic::Map("ceil")),
        ("fract", Intrinsic::Map("fract")),
        ("round", Intrinsic::Map("round")),
        ("sqrt", Intrinsic::Map("sqrt")),
        ("exp", Intrinsic::Map("exp")),
        ("exp2", Intrinsic::Map("exp2")),
        ("log", Intrinsic::Map("log")),
        ("log2", Intrinsic::Map("log2")),
        ("sin", Intrinsic::Map("sin")),
        ("cos", Intrinsic::Map("cos")),
        ("tan", Intrinsic::Map("tan")),
        ("asin", Intrinsic::Map("asin")),
        ("acos", Intrinsic::Map("acos")),
        ("atan", Intrinsic::Map("atan")),
        ("sign", Intrinsic::Map("sign")),
        ("saturate", Intrinsic::Map("saturate")),
        ("min", Intrinsic::Map2("min")),
        ("max", Intrinsic::Map2("max")),
        ("pow", Intrinsic::Map2("pow")),
        ("step", Intrinsic::Map2("step")),
        ("atan2", Intrinsic::Map2("atan2")),
        ("clamp", Intrinsic::Map3("clamp")),
        ("smoothstep", Intrinsic::Map3("smoothstep")),
        ("mix", Intrinsic::Map3("mix")),
        ("length", Intrinsic::Length),
        ("dot", Intrinsic::Dot),
        ("distance", Intrinsic::Distance),
        ("normalize", Intrinsic::Normalize),
        ("cross", Intrinsic::Cross),
        ("project", Intrinsic::Project),
        ("project_other_eye", Intrinsic::ProjectOtherEye),
        ("project_previous", Intrinsic::ProjectPrevious),
    ];

    pub fn lookup(name: &str) -> Option<Intrinsic> {
        Self::TABLE.iter().find(|(n, _)| *n == name).map(|(_, i)| *i)
    }

    /// Every spelling, in table order (for "did you mean").
    pub fn names() -> impl Iterator<Item = &'static str> {
        Self::TABLE.iter().map(|(n, _)| *n)
    }

    pub fn name(self) -> &'static str {
        match self {
            Intrinsic::Construct(2) => "vec2",
            Intrinsic::Construct(3) => "vec3",
            Intrinsic::Construct(_) => "vec4",
            Intrinsic::Map(n) | Intrinsic::Map2(n) | Intrinsic::Map3(n) => n,
            Intrinsic::Length => "length",
            Intrinsic::Dot => "dot",
            Intrinsic::Distance => "distance",
            Intrinsic::Normalize => "normalize",
            Intrinsic::Cross => "cross",
            Intrinsic::Project => "project",
            Intrinsic::ProjectOtherEye => "project_other_eye",
            Intrinsic::ProjectPrevious => "project_previous",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Callee {
    Intrinsic(Intrinsic),
    /// A stdlib operator, by index into `stdlib::all()`.
    Operator(u32),
}

/// Implicit conversions inserted by the typechecker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Conversion {
    IntToFloat,
    /// Scalar to vecN.
    Splat(u32),
    /// vec3 colour to vec4 with alpha 1.
    Rgb1,
    /// vec4 to vec3 (drop alpha) where a vec3 is expected.
    Rgb,
    /// The value a target of this format would hold after storing it: what a
    /// fused pass reads where the separate pass read the target
    /// (`schedule::fuse`). Never for a 32-bit float or sRGB format.
    Stored(abi::Format),
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum ExprKind {
    Const(Const),
    /// `50%`: a fraction of the output image height, in px.
    PercentOfHeight(f64),
    Param(ParamId),
    Builtin(Builtin),
    /// A pass target: a handle (when passed to an operator) or a value read
    /// at `screen_uv`, from this frame and eye, the other eye, or the
    /// previous frame.
    Target {
        target: TargetRef,
        copy: TargetCopy,
    },
    /// A texture: a handle, or a value sampled at `uv` (render) / `screen_uv` (image).
    Texture(TextureId),
    /// A per-object value of a compute pass (`sums.area`) for the object
    /// being drawn or computed, as this frame's run of that pass left it.
    ObjectValue {
        pass: PassId,
        slot: u32,
    },
    /// Inside the compute pass that owns `state` slot `slot`: its value from
    /// the previous frame, or its first value on the first frame.
    StateOld {
        slot: u32,
    },
    /// `.xyz`, `.rg`: component indices.
    Swizzle {
        base: ExprId,
        components: Vec<u8>,
    },
    Unary {
        op: dsl::ast::UnOp,
        operand: ExprId,
    },
    Binary {
        op: dsl::ast::BinOp,
        lhs: ExprId,
        rhs: ExprId,
    },
    /// Arguments in the callee's parameter order, defaults filled in.
    Call {
        callee: Callee,
        args: Vec<ExprId>,
    },
    Select {
        cond: ExprId,
        then: ExprId,
        otherwise: ExprId,
    },
    Convert {
        conversion: Conversion,
        operand: ExprId,
    },
    /// Placeholder for an expression that failed to resolve (diagnostic already reported).
    Error,
}

/// Which copy of a target a read sees: the manifest's definition, shared.
pub use abi::manifest::TargetCopy;

impl ExprKind {
    /// The target this node reads within this frame, for either eye:
    /// dependencies and lifetimes are the same for both, since every pass
    /// runs for both eyes before the next pass starts. A `previous(...)`
    /// read is not one (see [`ExprKind::history_read`]).
    pub fn target_read(&self) -> Option<TargetRef> {
        match self {
            ExprKind::Target { target, copy } if *copy != TargetCopy::Previous => Some(*target),
            _ => None,
        }
    }

    /// The target this node reads as the previous frame left it.
    pub fn history_read(&self) -> Option<TargetRef> {
        match self {
            ExprKind::Target {
                target,
                copy: TargetCopy::Previous,
            } => Some(*target),
            _ => None,
        }
    }

    /// The compute pass whose per-object value this node reads.
    pub fn value_read(&self) -> Option<(PassId, u32)> {
        match self {
            ExprKind::ObjectValue { pass, slot } => Some((*pass, *slot)),
            _ => None,
        }
    }

    /// Any read of a target, whichever copy.
    pub fn any_target_read(&self) -> Option<(TargetRef, TargetCopy)> {
        match self {
            ExprKind::Target { target, copy } => Some((*target, *copy)),
            _ => None,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Expr {
    pub kind: ExprKind,
    pub ty: Ty,
    pub unit: Unit,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum ParamTy {
    Value(Ty),
    Enum(Vec<String>),
    Range(Ty),
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Keyframe {
    pub time_s: f64,
    pub value: Vec<f64>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Param {
    pub name: String,
    pub doc: String,
    pub ty: ParamTy,
    pub value_ty: Ty,
    pub unit: Unit,
    pub per_object: bool,
    pub default: ExprId,
    pub range: Option<(f64, f64)>,
    pub keys: Vec<Keyframe>,
    pub interpolation: String,
    pub span: Span,
    pub name_span: Span,
}

/// One argument of `filter("…", name: value)`: a constant in canonical
/// units (degrees as radians), with the unit it was written in, or a bare
/// name that is none of the host's (`mode: soft`), the choice of an enum
/// param of the filter, resolved against the filter's variants when it is
/// compiled (`filter_args`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FilterArg {
    pub name: String,
    /// Empty for a choice.
    pub value: Vec<f64>,
    pub unit: Unit,
    pub choice: Option<String>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum TextureSource {
    Image {
        path: String,
        resolved: String,
        srgb: bool,
    },
    Noise(abi::NoiseSpec),
    HalftoneTable(abi::HalftoneTableSpec),
    /// `artmap(image("…"), filter: "…", levels: …)` (Klein et al. 2000
    /// §4.2): `filter` is the filter's key in `Loaded::filters`, and
    /// `filter_name` the path as written.
    Artmap {
        path: String,
        resolved: String,
        srgb: bool,
        /// The compiled filter's key: `filter_file`, plus its arguments when
        /// it has any (one compiled filter per path and argument list).
        filter: String,
        /// The filter file's key in `Loaded::filters` (its resolved path).
        filter_file: String,
        filter_name: String,
        /// `filter: filter("hatching.npr", spacing: 8)`: new defaults for
        /// the filter's params, checked against them when it is compiled.
        filter_args: Vec<FilterArg>,
        levels: Option<u32>,
        /// `ripmap(...)`: every 2^-i × 2^-j level in one atlas.
        rip: bool,
    },
    /// `filter_input()`, in a filter style: the level being filtered.
    FilterInput,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Texture {
    pub name: String,
    pub doc: String,
    pub source: TextureSource,
    pub wrap_repeat: bool,
    pub filter_linear: bool,
    pub mips: bool,
    /// Declared `object param name: texture = ...`: bound in group 1, and the
    /// scene may give each object its own image (the default otherwise).
    pub per_object: bool,
    pub span: Span,
}

/// What a pass is, with the data only that kind has. Everything every kind
/// has (name, scale, clear, lets, outputs, spans) is on [`Pass`]; a stage
/// that behaves differently per kind matches on this, one arm per kind.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum PassKind {
    /// Draws scene objects.
    Render {
        /// `render(tag)`: the objects drawn; `None` (`render(scene)`) draws all.
        tag: Option<String>,
        /// Whose eye the pass sees the scene through: `view(light)`.
        view: PassView,
        /// `vertex { ... }`: expressions the vertex shader evaluates.
        vertex: VertexModifiers,
        /// `depth: keep` / `depth: test(pass, bias: ...)`.
        depth: PassDepth,
    },
    /// A fullscreen pass over its inputs.
    Image { inputs: Vec<PassId> },
    /// A compute pass over a domain, producing per-object values.
    Compute {
        domain: ComputeDomain,
        /// `compute(vertices, tag)`: only objects with the tag; `None` runs over all.
        tag: Option<String>,
        /// `compute(pixels, ids.id)`: the read of the ID target whose pixels
        /// the pass runs over. `Some` exactly for `Pixels` (after a
        /// resolve error, `None` there too; such an IR is never emitted).
        key: Option<ExprId>,
        /// `compute(samples)`: the samples per object and their seed (the
        /// pass's `count:` and `seed:` settings). `Some` exactly for `Samples`.
        samples: Option<abi::manifest::SampleSpec>,
        /// Its per-object values, one slot each, in slot order.
        values: Vec<ObjectValue>,
    },
    /// Wavy strips along the silhouettes and creases of scene objects
    /// (Klein et al. 2000, §5); see [`lines`].
    Lines(LinesKind),
}

/// What a compute pass runs over: the manifest's definition, shared.
pub use abi::manifest::ComputeDomain;

/// How a per-object value of a compute pass is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ValueRule {
    /// `reduce n: t = sum(v)` (and `min`, `max`) over the elements of each object.
    Reduce(abi::manifest::ReduceOp),
    /// `out n: t = v`: computed once per object.
    Out,
    /// `state n: t = first` with its update `n = v`: kept across frames.
    State,
}

/// One per-object value of a compute pass.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ObjectValue {
    pub name: String,
    /// Float, Vec2, Vec3 or Vec4 (stored as a `vec4<f32>` slot).
    pub ty: Ty,
    pub rule: ValueRule,
    /// The reduced element value, the `out` value, or the state's update.
    pub value: ExprId,
    /// A state's first value.
    pub first: Option<ExprId>,
    pub span: Span,
    pub name_span: Span,
}

impl ObjectValue {
    /// The expressions this value evaluates.
    pub fn roots(&self) -> Vec<ExprId> {
        std::iter::once(self.value).chain(self.first).collect()
    }
}

impl PassKind {
    /// The kind's name as a style writes it (`render`, `image`).
    pub fn name(&self) -> &'static str {
        match self {
            PassKind::Render { .. } => "render",
            PassKind::Image { .. } => "image",
            PassKind::Compute { .. } => "compute",
            PassKind::Lines(_) => "lines",
        }
    }

    /// Whether the pass runs per object, so that it has the `Object` block
    /// (per-object params, `object.id`, compute passes' per-object values).
    pub fn has_object(&self) -> bool {
        match self {
            PassKind::Render { .. } | PassKind::Compute { .. } => true,
            // Strips of every object are drawn at once: no object per fragment.
            PassKind::Image { .. } | PassKind::Lines(_) => false,
        }
    }

    /// The expressions the kind evaluates outside its fragments: the ID
    /// target read of a pass over pixels, a lines pass's shape settings
    /// (evaluated on the CPU by the runner; none for other kinds).
    pub fn domain_roots(&self) -> Vec<ExprId> {
        match self {
            PassKind::Compute { key, .. } => key.iter().copied().collect(),
            PassKind::Lines(lines) => lines.shape.roots().to_vec(),
            PassKind::Render { .. } | PassKind::Image { .. } => Vec::new(),
        }
    }

    /// The per-object values of a compute pass (none for other kinds).
    pub fn values(&self) -> &[ObjectValue] {
        match self {
            PassKind::Compute { values, .. } => values,
            PassKind::Render { .. } | PassKind::Image { .. } | PassKind::Lines(_) => &[],
        }
    }

    /// Whether the pass draws scene objects, so that it has geometry
    /// (`needs_geometry` builtins) and per-object data (the group-1 block,
    /// per-object params and textures).
    pub fn draws_objects(&self) -> bool {
        match self {
            PassKind::Render { .. } => true,
            PassKind::Image { .. } | PassKind::Compute { .. } | PassKind::Lines(_) => false,
        }
    }
}

/// `vertex { ... }` of a render pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct VertexModifiers {
    /// `inflate: width`, in px: push each vertex along its screen-space normal.
    pub inflate: Option<ExprId>,
    /// `shadow_warp: k`: the sigmoid warp of light-space x, y (Age of Sail §5,
    /// depth pass); only in `view(light)` passes.
    pub shadow_warp: Option<ExprId>,
}

impl VertexModifiers {
    /// The expressions, in the order the vertex shader evaluates them.
    pub fn roots(&self) -> Vec<ExprId> {
        self.inflate.into_iter().chain(self.shadow_warp).collect()
    }
}

/// What a render pass does with its depth buffer (`depth: ...`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub enum PassDepth {
    /// Its own, cleared, discarded after the pass (the default).
    #[default]
    Own,
    /// `depth: keep`: stored for later passes' depth tests.
    Keep,
    /// `depth: test(pass, bias: b)`: test against the depth `pass` kept,
    /// without writing it. One of the biases is non-zero at most.
    Test {
        pass: PassId,
        /// `bias: N px`: slope-scaled, by the runner (`DepthBiasState`).
        bias_px: f64,
        /// `bias: b`: in window depth (0 near, 1 far), by the vertex shader.
        bias_depth: f64,
        /// The `depth: test(...)` setting.
        span: Span,
    },
}

impl Pass {
    /// The pass whose kept depth this pass tests against, if any, with the
    /// span of the setting.
    pub fn depth_test(&self) -> Option<(PassId, Span)> {
        match self.kind {
            PassKind::Render {
                depth: PassDepth::Test { pass, span, .. },
                ..
            }
            | PassKind::Lines(LinesKind {
                depth: PassDepth::Test { pass, span, .. },
                ..
            }) => Some((pass, span)),
            _ => None,
        }
    }

    /// Whether the pass keeps its depth buffer (`depth: keep`).
    pub fn keeps_depth(&self) -> bool {
        matches!(
            self.kind,
            PassKind::Render {
                depth: PassDepth::Keep,
                ..
            }
        )
    }
}

/// The camera a render pass projects with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum PassView {
    /// The scene camera (the eye being rendered, in stereo).
    #[default]
    Camera,
    /// An orthographic camera looking along the light, fitted to the scene
    /// bounds (`Frame::light_view_proj`): for shadow-caster depth maps.
    Light,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassOutput {
    pub name: String,
    pub format: abi::Format,
    pub value: ExprId,
    /// `{ blend: ... }`: how the value combines with the target.
    pub blend: abi::manifest::Blend,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Let {
    pub name: String,
    pub value: ExprId,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pass {
    pub name: String,
    pub doc: String,
    pub kind: PassKind,
    pub scale: f64,
    pub clear: [f64; 4],
    pub lets: Vec<Let>,
    pub outputs: Vec<PassOutput>,
    pub span: Span,
    pub name_span: Span,
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct Ir {
    pub style_name: String,
    pub params: Vec<Param>,
    pub textures: Vec<Texture>,
    pub passes: Vec<Pass>,
    pub exprs: Vec<Expr>,
    pub output: Option<TargetRef>,
    pub output_span: Span,
    /// `scene_has(tag)` calls folded against a known scene: (tag, answer).
    pub scene_queries: Vec<(String, bool)>,
}

impl Ir {
    pub fn add(&mut self, kind: ExprKind, span: Span) -> ExprId {
        self.exprs.push(Expr {
            kind,
            ty: Ty::Unknown,
            unit: Unit::None,
            span,
        });
        ExprId(self.exprs.len() as u32 - 1)
    }

    pub fn add_typed(&mut self, kind: ExprKind, ty: Ty, unit: Unit, span: Span) -> ExprId {
        self.exprs.push(Expr { kind, ty, unit, span });
        ExprId(self.exprs.len() as u32 - 1)
    }

    pub fn expr(&self, id: ExprId) -> &Expr {
        &self.exprs[id.0 as usize]
    }

    pub fn expr_mut(&mut self, id: ExprId) -> &mut Expr {
        &mut self.exprs[id.0 as usize]
    }

    /// The expressions a pass's vertex shader evaluates (`vertex { ... }`).
    pub fn vertex_roots(pass: &Pass) -> Vec<ExprId> {
        match &pass.kind {
            PassKind::Render { vertex, .. } => vertex.roots(),
            PassKind::Image { .. } | PassKind::Compute { .. } | PassKind::Lines(_) => Vec::new(),
        }
    }

    pub fn pass(&self, id: PassId) -> &Pass {
        &self.passes[id.0 as usize]
    }

    pub fn target_name(&self, t: TargetRef) -> String {
        let pass = self.pass(t.pass);
        let out = pass
            .outputs
            .get(t.output as usize)
            .map(|o| o.name.as_str())
            .unwrap_or("?");
        format!("{}.{}", pass.name, out)
    }

    /// The operands of a node, in order.
    pub fn operands(&self, id: ExprId) -> Vec<ExprId> {
        match &self.expr(id).kind {
            ExprKind::Swizzle { base, .. } => vec![*base],
            ExprKind::Unary { operand, .. } | ExprKind::Convert { operand, .. } => vec![*operand],
            ExprKind::Binary { lhs, rhs, .. } => vec![*lhs, *rhs],
            ExprKind::Call { args, .. } => args.clone(),
            ExprKind::Select { cond, then, otherwise } => vec![*cond, *then, *otherwise],
            _ => Vec::new(),
        }
    }

    /// The node `id` with its operands replaced, in [`Ir::operands`] order.
    pub fn with_operands(&self, id: ExprId, new: &[ExprId]) -> ExprKind {
        let mut kind = self.expr(id).kind.clone();
        match &mut kind {
            ExprKind::Swizzle { base, .. } => *base = new[0],
            ExprKind::Unary { operand, .. } | ExprKind::Convert { operand, .. } => *operand = new[0],
            ExprKind::Binary { lhs, rhs, .. } => (*lhs, *rhs) = (new[0], new[1]),
            ExprKind::Call { args, .. } => args.copy_from_slice(new),
            ExprKind::Select { cond, then, otherwise } => (*cond, *then, *otherwise) = (new[0], new[1], new[2]),
            _ => {}
        }
        kind
    }

    /// Every node reachable from `roots` (each once), operands before users.
    pub fn reachable(&self, roots: &[ExprId]) -> Vec<ExprId> {
        let mut seen = vec![false; self.exprs.len()];
        let mut order = Vec::new();
        let mut stack: Vec<(ExprId, bool)> = roots.iter().rev().map(|r| (*r, false)).collect();
        while let Some((id, expanded)) = stack.pop() {
            let i = id.0 as usize;
            if expanded {
                order.push(id);
                continue;
            }
            if seen[i] {
                continue;
            }
            seen[i] = true;
            stack.push((id, true));
            for op in self.operands(id).into_iter().rev() {
                if !seen[op.0 as usize] {
                    stack.push((op, false));
                }
            }
        }
        order
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_intrinsic_spelling_round_trips() {
        for (spelling, i) in Intrinsic::TABLE {
            assert_eq!(Intrinsic::lookup(spelling), Some(*i));
            assert_eq!(i.name(), *spelling, "{i:?} is spelled `{spelling}` in the table");
        }
        assert_eq!(Intrinsic::lookup("no_such_function"), None);
    }
}
