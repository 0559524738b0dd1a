//! `halftone_table(edge: e, correction: on|off)`: the manifest's description
//! of a halftone's tone-correction table (Breslav et al. 2007 §3.5), which
//! the runner builds at load ([`table`]), and the screen both draw.

pub mod table;

use serde::{Deserialize, Serialize};

/// `npr_halftone_screen`: the mean over both axes of 0.5 + 0.4·cos(2πx), at
/// the period 1 and at the period ½, mixed by `blend` (jot-lib's procedural
/// dots, `Halftone_TX::procedural_dots`). The f64 twin of the operator's
/// WGSL: the table is built on it, and the stdlib's reference draws it.
pub fn screen(uv: [f64; 2], blend: f64) -> f64 {
    let b = blend.clamp(0.0, 1.0);
    let turn = std::f64::consts::TAU;
    let axis = |x: f64| {
        let coarse = 0.5 + 0.4 * (x.rem_euclid(1.0) * turn).cos();
        let fine = 0.5 + 0.4 * ((2.0 * x).rem_euclid(1.0) * turn).cos();
        coarse + (fine - coarse) * b
    };
    0.5 * (axis(uv[0]) + axis(uv[1]))
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HalftoneTableSpec {
    /// Half-width of the dots' soft edge, in screen height units: the
    /// `smoothstep(−edge, edge, …)` both the table and `npr_halftone` use.
    pub edge: f32,
    /// Off: the threshold is the tone itself (the uncorrected halftone).
    pub corrected: bool,
}

impl HalftoneTableSpec {
    /// The edges a table may have: above 0 (a hard step has no smoothstep)
    /// and at most 0.5, a ramp already wider than the screen's whole range.
    pub const EDGE_RANGE: (f32, f32) = (0.005, 0.5);

    /// Whether `edge` is in [`Self::EDGE_RANGE`].
    pub fn edge_ok(edge: f64) -> bool {
        edge >= Self::EDGE_RANGE.0 as f64 && edge <= Self::EDGE_RANGE.1 as f64
    }
}
