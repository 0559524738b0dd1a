//! f64 references of the dynamic 2D patterns' operators (Breslav et al.
//! 2007 §3.1–3.3), of the similarity a tracker computes from weighted
//! point pairs (§3.2), and of the halftone operators (§3.4–3.5): the
//! procedural dot screen, and the tone-corrected halftone that looks its
//! threshold up in a [`HalftoneTable`].

use crate::halftone_table::HalftoneTable;
use crate::image_f64::ImageF64;

/// `npr_id_share`: the share of the (2r+1)² texels centred on `uv` whose
/// r is within 0.5 of `id`; texels outside the image count as another's.
pub fn id_share(ids: &ImageF64, uv: [f64; 2], id: f64, radius: f64) -> f64 {
    let at = uv.map(|x| if x.is_nan() { -1.0 } else { x.clamp(-1.0, 2.0) });
    let c = [
        (at[0] * ids.width as f64).floor() as i64,
        (at[1] * ids.height as f64).floor() as i64,
    ];
    let r = radius.round().clamp(0.0, 8.0) as i64;
    let mut own = 0.0;
    for j in -r..=r {
        for i in -r..=r {
            let (x, y) = (c[0] + i, c[1] + j);
            if x >= 0 && y >= 0 && x < ids.width as i64 && y < ids.height as i64 && (ids.load(x, y)[0] - id).abs() < 0.5
            {
                own += 1.0;
            }
        }
    }
    own / ((2 * r + 1) * (2 * r + 1)) as f64
}

/// `npr_complex_mul`.
pub fn complex_mul(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0]]
}

/// `npr_pattern_uv`: ((q − o)·u/|u|², (q − o)·v/|v|²), 0 for a zero u or v.
pub fn pattern_uv(o: [f64; 2], u: [f64; 2], v: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    let d = [q[0] - o[0], q[1] - o[1]];
    let along = |e: [f64; 2]| {
        let ee = e[0] * e[0] + e[1] * e[1];
        if ee > 0.0 {
            (d[0] * e[0] + d[1] * e[1]) / ee
        } else {
            0.0
        }
    };
    [along(u), along(v)]
}

/// A sample's image position in the previous frame, in this one, and its weight.
pub type PointPair = ([f64; 2], [f64; 2], f64);

/// The weighted least-squares similarity of §3.2 taking the points `p`
/// (previous frame) to `c` (this frame), in the centred form: returns
/// (p̄, c̄, z) with z = (Σw p·c, Σw p×c) / Σw|p|² over the centred points,
/// times |z|⁻¹·√(Σw|c|² / Σw|p|²) when `symmetric` (Horn's scale). `None`
/// when no weight or either spread is zero (a tracker keeps its frame).
pub fn similarity(points: &[PointPair], symmetric: bool) -> Option<([f64; 2], [f64; 2], [f64; 2])> {
    let sw: f64 = points.iter().map(|(_, _, w)| w).sum();
    if sw <= 0.0 {
        return None;
    }
    let mean = |f: &dyn Fn(&PointPair) -> [f64; 2]| {
        let s = points.iter().fold([0.0, 0.0], |a, x| {
            let v = f(x);
            [a[0] + x.2 * v[0], a[1] + x.2 * v[1]]
        });
        [s[0] / sw, s[1] / sw]
    };
    let pbar = mean(&|x| x.0);
    let cbar = mean(&|x| x.1);
    let (mut dot, mut cross, mut pp, mut cc) = (0.0, 0.0, 0.0, 0.0);
    for (p, c, w) in points {
        let (p, c) = ([p[0] - pbar[0], p[1] - pbar[1]], [c[0] - cbar[0], c[1] - cbar[1]]);
        dot += w * (p[0] * c[0] + p[1] * c[1]);
        cross += w * (p[0] * c[1] - p[1] * c[0]);
        pp += w * (p[0] * p[0] + p[1] * p[1]);
        cc += w * (c[0] * c[0] + c[1] * c[1]);
    }
    if pp <= 0.0 || cc <= 0.0 {
        return None;
    }
    let mut z = [dot / pp, cross / pp];
    if symmetric {
        let len = (z[0] * z[0] + z[1] * z[1]).sqrt();
        if len <= 0.0 {
            return None;
        }
        let s = (cc / pp).sqrt() / len;
        z = [z[0] * s, z[1] * s];
    }
    Some((pbar, cbar, z))
}

pub use npr_abi::halftone::screen as halftone_screen;

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
