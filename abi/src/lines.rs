//! The contract of a `lines` pass (Klein et al. 2000, §5) between the
//! compiler and the runner: which feature edges it draws ([`LineEdges`]),
//! the strips' shape in px ([`LineShape`]), each setting an affine function
//! of style parameters and time ([`LineScalar`]) that the runner evaluates
//! on the CPU per frame (the strips are built there), and the vertex the
//! compiled shader reads ([`LineVertex`], [`LINE_VERTEX_WGSL`]).

use serde::{Deserialize, Serialize};

/// Which feature edges a `lines` pass draws.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LineEdges {
    /// Edges between a front and a back face, per eye and frame.
    pub silhouettes: bool,
    /// Creases: edges whose dihedral angle exceeds this, in degrees (found
    /// once per mesh); `None` draws no creases.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crease_deg: Option<f64>,
}

/// The edge types one line set draws (decision 0056), a union: Freestyle's
/// and Blender Line Art's names. Each is found exactly as the runner's
/// `lines::edges` and `lines::intersections` document.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct EdgeTypes {
    /// Edges between a front and a back face, per eye and frame.
    #[serde(default, skip_serializing_if = "is_false")]
    pub silhouette: bool,
    /// Edges with one face: an open mesh's rim.
    #[serde(default, skip_serializing_if = "is_false")]
    pub border: bool,
    /// Two-face edges whose dihedral angle exceeds this, in degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crease_deg: Option<f64>,
    /// Edges between faces of different parts of a mesh (OBJ `o`/`g`, glTF
    /// primitives: one material each).
    #[serde(default, skip_serializing_if = "is_false")]
    pub material_boundary: bool,
    /// Where two surfaces (or one surface and itself) pass through each
    /// other: lines across faces, not mesh edges.
    #[serde(default, skip_serializing_if = "is_false")]
    pub intersection: bool,
    /// Edges the mesh's file marks (Freestyle's edge marks; a glTF file's
    /// `_NPR_EDGE_MARK` face-corner attribute, decision 0063).
    #[serde(default, skip_serializing_if = "is_false")]
    pub marked: bool,
}

fn is_false(v: &bool) -> bool {
    !*v
}

impl EdgeTypes {
    /// Whether the union is empty.
    pub fn is_empty(&self) -> bool {
        *self == EdgeTypes::default()
    }

    /// Every edge `other` selects is selected here too (a lower crease
    /// threshold takes every edge a higher one does).
    pub fn covers(&self, other: &EdgeTypes) -> bool {
        (self.silhouette || !other.silhouette)
            && (self.border || !other.border)
            && (self.material_boundary || !other.material_boundary)
            && (self.intersection || !other.intersection)
            && (self.marked || !other.marked)
            && match (self.crease_deg, other.crease_deg) {
                (_, None) => true,
                (Some(mine), Some(theirs)) => mine <= theirs,
                (None, Some(_)) => false,
            }
    }
}

/// One line set of a `lines` pass (decision 0056): the objects (a tag, or
/// the pass's objects), the edge types, and the strips' shape. A pass's sets
/// are listed highest priority first: an edge two sets select is drawn once,
/// by the first, and a strip vertex carries its set's index in that list
/// (`LineVertex::line.w`), which the shader's `line.color` reads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineSet {
    pub name: String,
    /// Only the pass's objects that also have this tag.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tag: Option<String>,
    pub edges: EdgeTypes,
    pub shape: LineShape,
    /// The priority as written (higher first; ties in the order written).
    pub priority: i64,
    /// Which lines by their quantitative invisibility (decision 0063);
    /// `None` draws every line the set selects and leaves hiding to the
    /// pass's depth test, as before QI.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub visibility: Option<LineVisibility>,
    /// Dashes along the screen arc length: `(on, off)` in px.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dash: Option<[f64; 2]>,
}

/// The QIs a set shows, inclusive: `(lowest, highest)`.
pub type QiRange = (u32, u32);

impl LineVisibility {
    /// The QIs a set of this visibility shows; a set without one shows
    /// every QI (the depth test hides what is behind).
    pub fn qi_range(visibility: Option<LineVisibility>) -> QiRange {
        match visibility {
            Some(LineVisibility::Visible) => (0, 0),
            Some(LineVisibility::Hidden) => (1, u32::MAX),
            Some(LineVisibility::Behind(n)) => (n, n),
            Some(LineVisibility::All) | None => (0, u32::MAX),
        }
    }

    /// Whether a set of this visibility shows a piece of QI `qi`.
    pub fn shows(visibility: Option<LineVisibility>, qi: u32) -> bool {
        let (lo, hi) = LineVisibility::qi_range(visibility);
        (lo..=hi).contains(&qi)
    }
}

/// Which lines a set draws by their quantitative invisibility (QI: the
/// number of surfaces between the eye and the line; decision 0063).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LineVisibility {
    /// QI 0.
    Visible,
    /// QI 1 or more.
    Hidden,
    /// QI exactly n (`hidden(n)`).
    Behind(u32),
    /// Every QI.
    All,
}

/// One term of a [`LineScalar`]: `coefficient × first component of param`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParamTerm {
    /// A name in `Manifest::params`.
    pub param: String,
    pub coefficient: f64,
}

/// `constant + Σ coefficient·param + per_second·time`: a setting of a
/// `lines` pass, affine in the style's parameters (at the frame's time,
/// keyframes included) and the frame's time, so it can be animated and
/// still be evaluated on the CPU without a second expression evaluator.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct LineScalar {
    pub constant: f64,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub params: Vec<ParamTerm>,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub per_second: f64,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl LineScalar {
    pub fn constant(value: f64) -> LineScalar {
        LineScalar {
            constant: value,
            ..LineScalar::default()
        }
    }

    /// The value at `time_s`, with `param(name)` giving a parameter's first
    /// component at that time (`None` for a name the manifest lacks, which
    /// validation excludes).
    pub fn eval(&self, time_s: f64, param: impl Fn(&str) -> Option<f64>) -> Option<f64> {
        let mut v = self.constant + self.per_second * time_s;
        for t in &self.params {
            v += t.coefficient * param(&t.param)?;
        }
        Some(v)
    }

    /// Every number in it is finite.
    pub fn is_finite(&self) -> bool {
        self.constant.is_finite()
            && self.per_second.is_finite()
            && self.params.iter().all(|t| t.coefficient.is_finite())
    }
}

/// The shape of a pass's strips: width, amplitude and wavelength in px on
/// screen, phase in radians, taper as the share of a piece's length over
/// which each open end narrows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineShape {
    pub width: LineScalar,
    pub amplitude: LineScalar,
    pub wavelength: LineScalar,
    pub phase: LineScalar,
    pub taper: LineScalar,
}

impl LineShape {
    /// The settings by name, in the order the style language documents them.
    pub fn named(&self) -> [(&'static str, &LineScalar); 5] {
        [
            ("width", &self.width),
            ("amplitude", &self.amplitude),
            ("wavelength", &self.wavelength),
            ("phase", &self.phase),
            ("taper", &self.taper),
        ]
    }
}

/// The smallest wavelength the runner builds strips for (px): the backbone
/// is resampled every λ/16 px, so a smaller λ would only multiply samples.
pub const MIN_WAVELENGTH_PX: f64 = 1.0;
/// The widest line (px).
pub const MAX_LINE_WIDTH_PX: f64 = 256.0;
/// The largest taper: each open end narrows over at most half the line.
pub const MAX_TAPER: f64 = 0.5;

/// One strip vertex as the GPU reads it (vertex buffer 0 of a `lines` pass).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LineVertex {
    /// x, y in NDC; z the NDC depth of the edge point, biased towards the
    /// eye; w the arc length in px.
    pub position: [f32; 4],
    /// x, y: the undisplaced edge point in the pass's px (where visibility
    /// is tested); z: −1 on one side of the strip, +1 on the other
    /// (`line.across`); w: the index of the line set that drew it (0 for a
    /// pass without sets).
    pub line: [f32; 4],
}

/// The vertex input of a `lines` pass's shader, matching [`LineVertex`].
pub const LINE_VERTEX_WGSL: &str = "struct LineIn {
    // x, y: NDC; z: NDC depth of the edge point, biased towards the eye; w: arc length in px.
    @location(0) position: vec4<f32>,
    // x, y: the undisplaced edge point in px; z: -1 on one side of the strip, +1 on the other.
    @location(1) line: vec4<f32>,
}
";

/// The vertex attributes of [`LineVertex`] in location order: (byte offset,
/// components).
pub const LINE_VERTEX_ATTRIBUTES: [(u64, u32); 2] = [(0, 4), (16, 4)];

/// A `lines` pass with `depth: test(pass)` reads that pass's kept depth in
/// its vertex shader, as group 1, binding 0 (there is no object group):
/// visibility is decided at the undisplaced edge point, not per fragment,
/// because the strip's own fragments lie off the edge, where the surface
/// inside a silhouette bulges towards the eye (see `npr_runner::lines::draw`).
pub const LINE_DEPTH_WGSL: &str = "@group(1) @binding(0) var kept_depth: texture_depth_2d;\n";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn affine_settings_evaluate_params_and_time() {
        let s = LineScalar {
            constant: 1.0,
            params: vec![ParamTerm {
                param: "w".into(),
                coefficient: 2.0,
            }],
            per_second: 0.5,
        };
        assert_eq!(s.eval(4.0, |n| (n == "w").then_some(3.0)), Some(1.0 + 6.0 + 2.0));
        assert_eq!(s.eval(0.0, |_| None), None);
    }

    #[test]
    fn the_wgsl_vertex_matches_the_rust_one() {
        assert_eq!(std::mem::size_of::<LineVertex>(), 32);
        let (last_offset, last_components) = LINE_VERTEX_ATTRIBUTES[1];
        assert_eq!(last_offset as usize + 4 * last_components as usize, 32);
        assert!(LINE_VERTEX_WGSL.contains("@location(0) position: vec4<f32>"));
        assert!(LINE_VERTEX_WGSL.contains("@location(1) line: vec4<f32>"));
    }
}
