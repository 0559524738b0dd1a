//! The abstract syntax tree of a `.npr` style file.
//!
//! Every node carries a [`Span`] into the source it came from, so that later
//! stages (the compiler, the runner) can point diagnostics at the user's text.
//! Nothing here depends on pest: the parser converts pest pairs into these
//! types, and the rest of the workspace only ever sees these.

use npr_diag::span::Span;
use serde::Serialize;

/// A name with the span where it was written.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ident {
    pub name: String,
    pub span: Span,
}

/// A whole `.npr` file.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Ast {
    /// `style "Name"`; `None` only when the header is missing (a diagnostic is reported).
    pub style: Option<StyleHeader>,
    pub items: Vec<Item>,
    /// Names of declarations that did not parse (a syntax error was
    /// reported in each): errors saying such a name is unknown follow from
    /// that one and are not reported.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub broken: Vec<String>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StyleHeader {
    pub name: String,
    pub span: Span,
}

/// A top-level declaration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum Item {
    Use(UseDecl),
    Param(ParamDecl),
    Texture(TextureDecl),
    Pass(PassDecl),
    Output(OutputDecl),
}

/// `use "other.npr"` or `use std::name` — pulls another style's declarations in.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UseDecl {
    pub target: UseTarget,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum UseTarget {
    /// A path relative to the using file.
    File(String),
    /// A stdlib module path such as `std::toon`.
    Module(Vec<Ident>),
}

/// `[object] param name: type = default [in lo..hi] [animate { t: v, ... }]`
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamDecl {
    /// Joined `///` doc comment lines, without the slashes; empty if none.
    pub doc: String,
    /// `object param`: bound per object by the scene.
    pub per_object: bool,
    pub name: Ident,
    pub ty: TypeExpr,
    pub default: Expr,
    pub range: Option<RangeExpr>,
    pub animate: Option<Animation>,
    /// `{ wrap: repeat, ... }` after the default: sampler options of an
    /// `object param t: texture = image(...)` (empty for every other type).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub options: Vec<Setting>,
    pub span: Span,
}

/// A type as written: `float`, `int`, `bool`, `vec2`, `vec3`, `vec4`, `color`,
/// `texture`, a unit name used as a type (`px`, `m`, `s`, `deg`, ...),
/// `range` (a pair `a..b`), `blend`, or an inline enum `enum(a, b, c)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum TypeExpr {
    Named(Ident),
    Enum { variants: Vec<Ident>, span: Span },
}

impl TypeExpr {
    pub fn span(&self) -> Span {
        match self {
            TypeExpr::Named(id) => id.span,
            TypeExpr::Enum { span, .. } => *span,
        }
    }
}

/// `lo..hi`, where both ends are constant expressions (usually literals with units).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RangeExpr {
    pub lo: Box<Expr>,
    pub hi: Box<Expr>,
    pub span: Span,
}

/// `animate { 0s: 0.1, 8s: 0.3 }`, optionally `animate(linear|step|smooth) { ... }`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Animation {
    pub interpolation: Option<Ident>,
    pub keys: Vec<Keyframe>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Keyframe {
    /// The key time (a literal in `s`).
    pub time: Expr,
    pub value: Expr,
    pub span: Span,
}

/// `texture name = source { key: value, ... }`
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TextureDecl {
    pub doc: String,
    pub name: Ident,
    /// The source is a call: `image("path.png", srgb)`, `noise(size: 256, octaves: 4)`,
    /// and, later, `artmap(...)`. The compiler decides which calls are texture sources.
    pub source: Call,
    /// Sampler and storage options: `wrap`, `filter`, `mips`.
    pub options: Vec<Setting>,
    pub span: Span,
}

/// `key: value` inside a `{ ... }` option block.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Setting {
    pub key: Ident,
    pub value: Expr,
    pub span: Span,
}

/// `pass name: kind(inputs) [scale s] { body }`
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassDecl {
    pub doc: String,
    pub name: Ident,
    pub kind: PassKind,
    /// `scale 1/2`: resolution relative to the output size. `None` means 1.
    pub scale: Option<Expr>,
    /// `per_eye` / `other_eye` style modifiers written after the kind, e.g.
    /// `pass x: image(a) stereo(other_eye) { ... }`. Reserved for stereo work.
    pub modifiers: Vec<Setting>,
    pub body: PassBody,
    pub span: Span,
}

/// The kind of pass and what it reads.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassKind {
    /// `render`, `image`, and reserved for later issues: `compute`, `reduce`, `lines`.
    pub kind: Ident,
    /// For `render`: `scene` or a tag name. For `image`: the passes it
    /// reads. For `compute`: the domain, then a tag, or the ID target of
    /// `compute(pixels, ids.id)`.
    pub args: Vec<KindArg>,
    pub span: Span,
}

/// An argument of a pass kind: a name, or a pass's target (`ids.id`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KindArg {
    pub name: Ident,
    /// `.id` of `ids.id`.
    pub field: Option<Ident>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct PassBody {
    /// `vertex { inflate: expr, ... }` — vertex modifiers of a render pass.
    pub vertex: Vec<Setting>,
    /// `let name = expr` bindings shared by the outputs, in order.
    pub lets: Vec<LetBinding>,
    /// `out name: format = expr`.
    pub outputs: Vec<OutputTarget>,
    /// Any other `key: value` settings (`clear: #000000`, `depth: keep`).
    pub settings: Vec<Setting>,
    /// `state name: type = first` (compute passes over objects).
    pub states: Vec<StateDecl>,
    /// `reduce name: type = sum(value)` (compute passes over elements).
    pub reductions: Vec<Reduction>,
    /// `name = value`: a state's new value.
    pub updates: Vec<StateUpdate>,
    /// `set name { ... }`: the line sets of a lines pass (decision 0056).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub line_sets: Vec<LineSetDecl>,
}

/// `set name { edges: silhouette | crease(35deg), width: 3px, ... }`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LineSetDecl {
    pub name: Ident,
    /// Each `edges: a | b` written (more than one is an error).
    pub edges: Vec<EdgeUnion>,
    /// The other `key: value` settings.
    pub settings: Vec<Setting>,
    pub span: Span,
}

/// `edges: a | b(arg)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EdgeUnion {
    pub terms: Vec<EdgeTerm>,
    pub span: Span,
}

/// One edge type in a union: a name and an optional argument.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EdgeTerm {
    pub name: Ident,
    pub arg: Option<Expr>,
    pub span: Span,
}

/// `state name: type = first`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StateDecl {
    pub name: Ident,
    pub ty: Ident,
    /// The value on the first frame (and after a reset).
    pub first: Expr,
    pub span: Span,
}

/// `reduce name: type = op(value)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reduction {
    pub name: Ident,
    pub ty: Ident,
    /// `sum`, `min` or `max`.
    pub op: Ident,
    pub value: Expr,
    pub span: Span,
}

/// `name = value`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StateUpdate {
    pub name: Ident,
    pub value: Expr,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LetBinding {
    pub name: Ident,
    pub value: Expr,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputTarget {
    pub name: Ident,
    /// A texture format name such as `rgba8unorm`, `rg16float`, `r32float`.
    pub format: Ident,
    pub value: Expr,
    /// `{ blend: over }` after the value: how it combines with the target.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub settings: Vec<Setting>,
    pub span: Span,
}

/// `output pass.target`
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputDecl {
    pub pass: Ident,
    pub target: Ident,
    pub span: Span,
}

/// Units a numeric literal can carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum UnitSuffix {
    Px,
    Percent,
    M,
    Mm,
    S,
    Hz,
    Deg,
}

impl UnitSuffix {
    pub fn as_str(self) -> &'static str {
        match self {
            UnitSuffix::Px => "px",
            UnitSuffix::Percent => "%",
            UnitSuffix::M => "m",
            UnitSuffix::Mm => "mm",
            UnitSuffix::S => "s",
            UnitSuffix::Hz => "Hz",
            UnitSuffix::Deg => "deg",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
    And,
    Or,
}

impl BinOp {
    pub fn as_str(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Rem => "%",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Gt => ">",
            BinOp::Ge => ">=",
            BinOp::Eq => "==",
            BinOp::Ne => "!=",
            BinOp::And => "&&",
            BinOp::Or => "||",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum UnOp {
    Neg,
    Not,
}

/// An expression with its span.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum ExprKind {
    /// A number, with an optional unit suffix: `3`, `0.5`, `256px`, `50%`, `8s`.
    /// `is_int` is true when written without a decimal point or exponent.
    Number {
        value: f64,
        is_int: bool,
        unit: Option<UnitSuffix>,
    },
    Bool(bool),
    /// `#rrggbb` or `#rrggbbaa`, as linear-free raw sRGB bytes converted to 0..1.
    Color([f64; 4]),
    Str(String),
    /// A bare name: a parameter, a `let`, a builtin (`uv`, `normal`, ...), an
    /// enum variant (`cubic`), or a pass (`shadow`).
    Name(Ident),
    /// `base.field`: a swizzle (`.rg`), a pass target (`shadow.r`), or a
    /// builtin member (`position.world`, `light.dir`).
    Field {
        base: Box<Expr>,
        field: Ident,
    },
    /// `callee(args, name: value)`.
    Call(Call),
    Unary {
        op: UnOp,
        operand: Box<Expr>,
    },
    Binary {
        op: BinOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    /// `if cond { a } else { b }` as an expression.
    If {
        cond: Box<Expr>,
        then: Box<Expr>,
        otherwise: Box<Expr>,
    },
    /// `{ let a = ...; let b = ...; value }` — a block with local lets.
    Block {
        lets: Vec<LetBinding>,
        value: Box<Expr>,
    },
    /// `lo..hi` as a value (the default of a `range` parameter).
    Range {
        lo: Box<Expr>,
        hi: Box<Expr>,
    },
}

impl Expr {
    /// The sub-expressions directly below this one.
    pub fn children(&self) -> Vec<&Expr> {
        match &self.kind {
            ExprKind::Number { .. } | ExprKind::Bool(_) | ExprKind::Color(_) | ExprKind::Str(_) | ExprKind::Name(_) => {
                Vec::new()
            }
            ExprKind::Field { base, .. } => vec![base],
            ExprKind::Call(c) => c.args.iter().map(|a| &a.value).collect(),
            ExprKind::Unary { operand, .. } => vec![operand],
            ExprKind::Binary { lhs, rhs, .. } | ExprKind::Range { lo: lhs, hi: rhs } => vec![lhs, rhs],
            ExprKind::If { cond, then, otherwise } => vec![cond, then, otherwise],
            ExprKind::Block { lets, value } => lets.iter().map(|l| &l.value).chain([&**value]).collect(),
        }
    }

    /// The height of the tree (a leaf is 1), computed with an explicit stack
    /// so that it works on any tree, however deep.
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(self, 1usize)];
        while let Some((e, d)) = stack.pop() {
            deepest = deepest.max(d);
            stack.extend(e.children().into_iter().map(|c| (c, d + 1)));
        }
        deepest
    }
}

/// A call with positional and named arguments, in source order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Call {
    pub callee: Ident,
    pub args: Vec<Arg>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Arg {
    /// `Some` for `name: value`, `None` for positional.
    pub name: Option<Ident>,
    pub value: Expr,
    pub span: Span,
}
