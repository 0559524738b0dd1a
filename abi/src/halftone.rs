//! `halftone_table(edge: e, correction: on|off)`: the manifest's description
//! of a halftone's tone-correction table (Breslav et al. 2007 §3.5), which
//! the runner builds at load (`stdlib::halftone_table`).

use serde::{Deserialize, Serialize};

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
