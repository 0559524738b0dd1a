//! The IR of a `lines` pass (Klein et al. 2000, §5): the objects whose
//! edges it draws, which edges, the strips' shape settings as expressions
//! (checked to be affine in parameters and time by `typecheck::lines`, and
//! folded to `npr_abi::lines::LineScalar`s when the manifest is written), and
//! its depth test, and its line sets (decision 0056).

use super::{ExprId, PassDepth};
use serde::Serialize;

/// `lines(tag) { silhouettes: ... creases: ... width: ... }`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinesKind {
    /// `lines(tag)`: only objects with the tag; `None` (`lines(scene)`) takes all.
    pub tag: Option<String>,
    pub edges: npr_abi::lines::LineEdges,
    pub shape: LineSettings,
    /// `Own` (no test) or `depth: test(pass, bias: ...)`; never `Keep`.
    pub depth: PassDepth,
    /// The pass's line sets (decision 0056), highest priority first (ties
    /// in the order written); with any, they replace `edges` and `shape`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sets: Vec<LineSet>,
}

/// `set name { edges: silhouette | border, width: 3px, color: ink }`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LineSet {
    pub name: String,
    /// The set's name where it is written.
    pub span: npr_diag::Span,
    /// `tag: name`: only the pass's objects that also have this tag.
    pub tag: Option<String>,
    pub edges: npr_abi::lines::EdgeTypes,
    /// Each unset setting is the pass's own (its default or its setting).
    pub shape: LineSettings,
    /// `color: value`, what `line.color` is on this set's strips (opaque
    /// black when unset).
    pub color: Option<ExprId>,
    /// `priority: n` (0 when unset); higher first.
    pub priority: i64,
    /// `visibility:` (decision 0063); `None` when unset.
    pub visibility: Option<npr_abi::lines::LineVisibility>,
    /// `dash: 6px` or `dash: dashes(6px, 4px)`: (on, off) in px.
    pub dash: Option<[f64; 2]>,
}

/// The shape settings of a `lines` pass, each an expression of the pass's
/// scope (a default is a constant node made by resolve).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct LineSettings {
    /// px.
    pub width: ExprId,
    /// px.
    pub amplitude: ExprId,
    /// px.
    pub wavelength: ExprId,
    /// Radians.
    pub phase: ExprId,
    /// Share of a piece's length over which each open end narrows, 0..0.5.
    pub taper: ExprId,
}

impl LineSettings {
    /// (name, expression) in the order the language documents them.
    pub fn named(&self) -> [(&'static str, ExprId); 5] {
        [
            ("width", self.width),
            ("amplitude", self.amplitude),
            ("wavelength", self.wavelength),
            ("phase", self.phase),
            ("taper", self.taper),
        ]
    }

    pub fn roots(&self) -> [ExprId; 5] {
        self.named().map(|(_, e)| e)
    }

    pub fn get_mut(&mut self, name: &str) -> Option<&mut ExprId> {
        match name {
            "width" => Some(&mut self.width),
            "amplitude" => Some(&mut self.amplitude),
            "wavelength" => Some(&mut self.wavelength),
            "phase" => Some(&mut self.phase),
            "taper" => Some(&mut self.taper),
            _ => None,
        }
    }
}
