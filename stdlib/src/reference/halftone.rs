//! f64 references of the halftone operators (Breslav et al. 2007 §3.4–3.5):
//! the procedural dot screen, and the tone-corrected halftone that looks its
//! threshold up in a [`HalftoneTable`](crate::halftone_table::HalftoneTable).

use crate::halftone_table::HalftoneTable;

/// `npr_halftone_screen`: the mean over both axes of 0.5 + 0.4·cos(2πx), at
/// the period 1 and at the period ½, mixed by `blend` (jot-lib's procedural
/// dots, `Halftone_TX::procedural_dots`).
pub fn halftone_screen(uv: [f64; 2], blend: f64) -> f64 {
    let b = blend.clamp(0.0, 1.0);
    let turn = std::f64::consts::TAU;
    let axis = |x: f64| {
        let coarse = 0.5 + 0.4 * (x.rem_euclid(1.0) * turn).cos();
        let fine = 0.5 + 0.4 * ((2.0 * x).rem_euclid(1.0) * turn).cos();
        coarse + (fine - coarse) * b
    };
    0.5 * (axis(uv[0]) + axis(uv[1]))
}

/// GLSL/WGSL `smoothstep(lo, hi, x)` for lo < hi.
pub fn smoothstep(lo: f64, hi: f64, x: f64) -> f64 {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// `npr_halftone`: the paper's share at `uv` for the wanted `tone`, with the
/// threshold interpolated bilinearly from `table` and the edge the table
/// holds.
pub fn halftone(table: &HalftoneTable, uv: [f64; 2], tone: f64, blend: f64) -> f64 {
    let b = blend.clamp(0.0, 1.0);
    let threshold = table.threshold(tone, b);
    let e = table.edge();
    smoothstep(-e, e, threshold - halftone_screen(uv, b))
}
