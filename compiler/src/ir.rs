//! The compiler's intermediate representation: an arena graph with spans.
//!
//! Expressions live in one arena ([`Ir::exprs`]) and refer to each other by
//! [`ExprId`]. Sharing is allowed (a `let` used twice is one node referenced
//! twice), so the graph is a DAG, never a tree. A node is always created
//! after its operands, so iterating the arena in order visits operands first
//! (the typechecker relies on this).

use npr_diag::Span;
use npr_stdlib::Unit;
use serde::Serialize;

mod builtins;
mod intrinsics;
mod lines;
mod passes;
mod roots;
mod schedule;
mod settings;
pub use builtins::Builtin;
pub use intrinsics::Intrinsic;
pub use lines::{LineSet, LineSettings, LinesKind};
pub use passes::*;
pub use roots::PassRoots;
pub use schedule::{Recomputed, Schedule, TileRead, TileSource, Tiling};
pub use settings::{Literal, ParamSetting, SettingOrigin};

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

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Callee {
    Intrinsic(Intrinsic),
    /// A stdlib operator, by index into `npr_stdlib::all()`.
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
    Stored(npr_abi::Format),
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
        op: npr_dsl::ast::UnOp,
        operand: ExprId,
    },
    Binary {
        op: npr_dsl::ast::BinOp,
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
pub use npr_abi::manifest::TargetCopy;

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
    /// `color`: a `vec4` that `--set`, the studio and the manifest know as
    /// a colour (`#rrggbb`, a colour picker).
    Color,
    Enum(Vec<String>),
    Range(Ty),
    /// A `gradient` kept live (`--keep-params`): its default is the
    /// [`npr_abi::gradient`] slots' components (a `Const::Vec` of 84), read
    /// only by `Intrinsic::Ramp`. A folded gradient is no IR param
    /// (`front/resolve/gradient.rs`).
    Gradient,
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

impl Param {
    /// The type as declared, as the manifest writes it: `float`, `int`,
    /// `bool`, `vec2`..`vec4`, `color`, `enum(a|b)`, `range`, or the unit
    /// of a unit type (`px`, `m`, `s`, `Hz`, `deg`).
    pub fn declared_type(&self) -> String {
        match &self.ty {
            ParamTy::Enum(v) => format!("enum({})", v.join("|")),
            ParamTy::Range(_) => "range".into(),
            ParamTy::Color => "color".into(),
            ParamTy::Gradient => npr_abi::gradient::GRADIENT_TYPE.into(),
            ParamTy::Value(t) => match self.unit {
                Unit::None => t.describe().into(),
                u => u.name().into(),
            },
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum TextureSource {
    Image {
        path: String,
        resolved: String,
        srgb: bool,
    },
    Noise(npr_abi::NoiseSpec),
    HalftoneTable(npr_abi::HalftoneTableSpec),
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
        /// the filter's params, typed against them in its compile.
        filter_args: Vec<ParamSetting>,
        levels: Option<u32>,
        /// `ripmap(...)`: every 2^-i × 2^-j level in one atlas.
        rip: bool,
    },
    /// `filter_input()`, in a filter style: the level being filtered.
    FilterInput,
    /// `input(kind, ...)`: an image the host gives (`npr_abi::input`).
    Input(npr_abi::InputKind),
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
    /// Image passes the schedule runs as compute over workgroup tiles.
    pub tiled: std::collections::BTreeMap<PassId, Tiling>,
    /// Targets the schedule does not store: their reader computes them in
    /// its tiles (`schedule/recompute.rs`).
    pub recomputed: std::collections::BTreeMap<TargetRef, Recomputed>,
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
