//! The tone-correction table of a halftone screen (Breslav et al. 2007
//! §3.5), built once at load by the runtime (here, in the contract crate, so that
//! the runner builds it without the stdlib and the stdlib's references use
//! the same one): for each of [`BLENDS`] LOD blends b and
//! [`TONES`] wanted tones T, the threshold t at which the screen of
//! `npr_halftone` (with its edge) leaves a mean paper share of T over a cell.
//!
//! R(t, b) = ∫∫ smoothstep(−e, e, t − h(uv, b)) duv over one cell of the
//! screen h ([`super::screen`], the f64 twin of the WGSL that
//! `npr_halftone` draws, which the stdlib's GPU tests hold to it). R rises monotonically from 0 at t = 0.1 − e to 1 at t = 0.9 + e
//! (h spans [0.1, 0.9]); the table stores R⁻¹(T) for T = i/255.
//!
//! jot-lib (`Halftone_TX::compute_inverse_R`) tabulates R from a 256-bucket
//! histogram of h with a fixed ±0.1 edge, while its shader draws ±0.2, so its
//! correction is for another screen than the one drawn. Here the edge is a
//! parameter of the table, the table stores it (texel (0, 16)), and the
//! shader reads it from there: one edge for both. The integral is a midpoint
//! rule on a [`CELL_SAMPLES`]² grid, exact to ~1e-6 for a smooth periodic h,
//! and the inversion interpolates R on [`THRESHOLD_STEPS`] thresholds.

/// WGSL's `smoothstep(lo, hi, x)` for lo < hi (the operators' f64
/// references in `npr_stdlib::reference` have the same).
fn smoothstep(lo: f64, hi: f64, x: f64) -> f64 {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Table columns: wanted tones 0, 1/255, …, 1.
pub const TONES: usize = 256;
/// Table rows of thresholds: LOD blends 0, 1/15, …, 1.
pub const BLENDS: usize = 16;
/// Texture rows: the [`BLENDS`] rows of thresholds plus one row whose first
/// texel holds the edge.
pub const ROWS: usize = BLENDS + 1;
/// Samples per axis of one screen cell in the integral of R.
pub const CELL_SAMPLES: usize = 64;
/// Thresholds at which R is evaluated before it is inverted.
pub const THRESHOLD_STEPS: usize = 1024;

/// A built table: `threshold[j][i]` for blend j/15 and tone i/255.
#[derive(Clone, Debug, PartialEq)]
pub struct HalftoneTable {
    edge: f64,
    thresholds: Vec<[f64; TONES]>,
}

impl HalftoneTable {
    /// Tabulates and inverts R for the screen with soft edges of half-width
    /// `edge`, which must be positive (the manifest's range,
    /// `npr_abi::HalftoneTableSpec::EDGE_RANGE`, is checked before). With `corrected: false` the threshold is
    /// the tone itself (t = T), the uncorrected halftone, kept so that the
    /// error it makes can be shown.
    pub fn build(edge: f64, corrected: bool) -> HalftoneTable {
        assert!(edge > 0.0, "a halftone table's edge must be positive (got {edge})");
        let thresholds = (0..BLENDS)
            .map(|j| {
                if corrected {
                    inverse_row(edge, j as f64 / (BLENDS - 1) as f64)
                } else {
                    std::array::from_fn(|i| i as f64 / (TONES - 1) as f64)
                }
            })
            .collect();
        HalftoneTable { edge, thresholds }
    }

    /// A table from stored thresholds (`thresholds[j][i]` for blend j/15 and
    /// tone i/255), as read back from its texture.
    pub fn from_thresholds(edge: f64, thresholds: Vec<[f64; TONES]>) -> HalftoneTable {
        HalftoneTable { edge, thresholds }
    }

    /// The edge half-width the table was built for.
    pub fn edge(&self) -> f64 {
        self.edge
    }

    /// The stored threshold for blend row `j` and tone column `i`.
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.thresholds[j][i]
    }

    /// The threshold for `tone` at `blend`, interpolated bilinearly between
    /// the stored texels exactly as `npr_halftone` does.
    pub fn threshold(&self, tone: f64, blend: f64) -> f64 {
        let x = tone.clamp(0.0, 1.0) * (TONES - 1) as f64;
        let y = blend.clamp(0.0, 1.0) * (BLENDS - 1) as f64;
        let (i0, j0) = (x.floor() as usize, y.floor() as usize);
        let (i1, j1) = ((i0 + 1).min(TONES - 1), (j0 + 1).min(BLENDS - 1));
        let (fx, fy) = (x - x.floor(), y - y.floor());
        let row = |j: usize| self.at(i0, j) + (self.at(i1, j) - self.at(i0, j)) * fx;
        row(j0) + (row(j1) - row(j0)) * fy
    }

    /// The texels of the 256 × 17 texture, row-major: thresholds, then the
    /// edge at (0, 16) and zeros.
    pub fn texels(&self) -> Vec<f32> {
        let mut out = Vec::with_capacity(TONES * ROWS);
        for row in &self.thresholds {
            out.extend(row.iter().map(|&t| t as f32));
        }
        out.push(self.edge as f32);
        out.extend(std::iter::repeat_n(0.0, TONES - 1));
        out
    }
}

/// The mean paper share R(t, blend) of the screen over one cell.
pub fn mean_paper(edge: f64, blend: f64, threshold: f64) -> f64 {
    let heights = cell_heights(blend);
    heights
        .iter()
        .map(|&h| smoothstep(-edge, edge, threshold - h))
        .sum::<f64>()
        / heights.len() as f64
}

/// The screen's heights at the midpoints of a [`CELL_SAMPLES`]² grid over one
/// cell (the screen has the period 1 at every blend).
fn cell_heights(blend: f64) -> Vec<f64> {
    let n = CELL_SAMPLES;
    let mut out = Vec::with_capacity(n * n);
    for y in 0..n {
        for x in 0..n {
            let uv = [(x as f64 + 0.5) / n as f64, (y as f64 + 0.5) / n as f64];
            out.push(super::screen(uv, blend));
        }
    }
    out
}

/// R⁻¹ at the tones i/255 for one blend: R on [`THRESHOLD_STEPS`] + 1
/// thresholds spanning the screen's range widened by the edge, inverted by
/// linear interpolation (R is non-decreasing, and strictly increasing where
/// it is neither 0 nor 1).
fn inverse_row(edge: f64, blend: f64) -> [f64; TONES] {
    let mut heights = cell_heights(blend);
    heights.sort_by(f64::total_cmp);
    let lo = heights[0] - edge;
    let hi = heights[heights.len() - 1] + edge;
    let steps = THRESHOLD_STEPS;
    let ts: Vec<f64> = (0..=steps).map(|k| lo + (hi - lo) * k as f64 / steps as f64).collect();
    let n = heights.len() as f64;
    let rs: Vec<f64> = ts
        .iter()
        .map(|&t| {
            // Heights below t − edge count fully; only those within the edge
            // need smoothstep.
            let below = heights.partition_point(|&h| h <= t - edge);
            let within = heights[below..].iter().take_while(|&&h| h < t + edge);
            (below as f64 + within.map(|&h| smoothstep(-edge, edge, t - h)).sum::<f64>()) / n
        })
        .collect();
    std::array::from_fn(|i| {
        let tone = i as f64 / (TONES - 1) as f64;
        // The first threshold whose R reaches the tone, and its predecessor.
        let k = rs.partition_point(|&r| r < tone).min(steps);
        if k == 0 {
            return ts[0];
        }
        let (r0, r1) = (rs[k - 1], rs[k]);
        let f = if r1 > r0 { (tone - r0) / (r1 - r0) } else { 1.0 };
        ts[k - 1] + (ts[k] - ts[k - 1]) * f
    })
}
