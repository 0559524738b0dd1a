//! Error metrics of MetaTexture variants on an analytic ground plane, in f64.
//!
//! A pinhole camera looks at the plane y = 0 with uv = (x, z) per metre, from
//! distances of 1 m to 1000 m and elevations down to grazing angles. For
//! every pixel that sees the plane, the exact screen-space UV gradients come
//! from the ray–plane intersection; from them each variant's texture scales
//! (Age of Sail eqs. 1–7), skew shear (eqs. 14–21) and blend weights follow,
//! and three errors are measured:
//! - **scale**: |log₂(period / w)| of each tap's texture period in screen
//!   space along its axis, weighted by the tap's blend weight (0 = exactly the
//!   target width w; plain texture mapping is reported for comparison);
//! - **anisotropy**: |angle between the texture's screen-space axes − 90°|,
//!   weighted likewise;
//! - **contrast**: |σ_M/σ_T − 1| predicted for uncorrelated taps, σ_M/σ_T =
//!   √c (eq. 24) without compensation, c^{3/2} with the printed factor, 1 with
//!   the variance-preserving one (`tests/metatexture.rs` measures these ratios
//!   on a real texture).

use crate::reference::{meta_beta, meta_k, META_MAX_SCALE};

/// One pixel's exact screen-space gradients: (∇u, ∇v) in UV per px.
thread_local! { pub static SKEW_SIGN: std::cell::Cell<f64> = const { std::cell::Cell::new(1.0) }; }

pub type Gradients = ([f64; 2], [f64; 2]);

/// Gradients of uv = (x, z) on the plane y = 0 seen by a camera at height
/// `distance·sin(elevation)`, looking down at `elevation`, with vertical field of
/// view `fov_deg`, over a `size`² image; pixels that miss the plane are skipped.
pub fn plane_gradients(distance: f64, elevation_deg: f64, fov_deg: f64, size: u32, stride: u32) -> Vec<Gradients> {
    let el = elevation_deg.to_radians();
    let eye = [0.0, distance * el.sin(), -distance * el.cos()];
    // Camera basis: forward towards the origin, right along +x, up completes it.
    let fwd = [0.0, -el.sin(), el.cos()];
    let right = [1.0, 0.0, 0.0];
    let up = [0.0, el.cos(), el.sin()];
    let focal = (size as f64 / 2.0) / (fov_deg.to_radians() / 2.0).tan();
    let hit = |px: f64, py: f64| -> Option<[f64; 2]> {
        let (sx, sy) = (px - size as f64 / 2.0, size as f64 / 2.0 - py);
        let d = [
            fwd[0] * focal + right[0] * sx + up[0] * sy,
            fwd[1] * focal + right[1] * sx + up[1] * sy,
            fwd[2] * focal + right[2] * sx + up[2] * sy,
        ];
        if d[1] >= -1e-12 {
            return None;
        }
        let t = -eye[1] / d[1];
        Some([eye[0] + t * d[0], eye[2] + t * d[2]])
    };
    let mut out = Vec::new();
    let h = 1e-3;
    for py in (0..size).step_by(stride.max(1) as usize) {
        for px in (0..size).step_by(stride.max(1) as usize) {
            let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
            let (Some(c), Some(ax), Some(ay)) = (hit(x, y), hit(x + h, y), hit(x, y + h)) else { continue };
            let du = [(ax[0] - c[0]) / h, (ay[0] - c[0]) / h];
            let dv = [(ax[1] - c[1]) / h, (ay[1] - c[1]) / h];
            out.push((du, dv));
        }
    }
    out
}

/// The errors of one variant over a set of pixels (means, and the range of the
/// base tap's period ratio).
#[derive(Debug, Clone, Copy, Default)]
pub struct VariantError {
    pub scale: f64,
    pub anisotropy_deg: f64,
    pub contrast_none: f64,
    pub contrast_printed: f64,
    pub contrast_variance: f64,
    pub period_min: f64,
    pub period_max: f64,
}

fn len(g: [f64; 2]) -> f64 {
    (g[0] * g[0] + g[1] * g[1]).sqrt()
}

/// Angle in degrees between the screen-space texture axes of a coordinate
/// pair whose gradients are (∇a, ∇b): the columns of the inverse Jacobian.
fn axis_angle_deg(da: [f64; 2], db: [f64; 2]) -> f64 {
    // J = [[da.x, da.y], [db.x, db.y]]; J⁻¹ columns ∝ (db.y, −db.x) and (−da.y, da.x).
    let a = [db[1], -db[0]];
    let b = [-da[1], da[0]];
    let (la, lb) = (len(a), len(b));
    if la < 1e-300 || lb < 1e-300 {
        return 90.0;
    }
    ((a[0] * b[0] + a[1] * b[1]) / (la * lb)).clamp(-1.0, 1.0).acos().to_degrees()
}

/// Scale level of one coordinate: (scale k = base^⌊E⌋, blend weight).
fn level(g: [f64; 2], width: f64, base: f64) -> (f64, f64) {
    let lb = base.log2();
    let max_e = META_MAX_SCALE.log2() / lb;
    let e = (-(width * len(g).clamp(1e-30, 1e30)).log2() / lb).clamp(-max_e, max_e);
    let fe = e.floor();
    ((fe * lb).exp2(), meta_beta(e - fe, 1))
}

/// Errors of a variant: `skew` levels (0 = 4 taps), `base`, target `width`;
/// `plain` measures ordinary texture mapping (one tap at scale 1) instead.
pub fn variant_error(grads: &[Gradients], width: f64, base: f64, skew: i64, plain: bool) -> VariantError {
    let mut e = VariantError { period_min: f64::INFINITY, period_max: 0.0, ..Default::default() };
    let n = grads.len().max(1) as f64;
    for (du, dv) in grads {
        // Each set: (weight, gradients of its coordinates).
        let sets: Vec<(f64, [f64; 2], [f64; 2])> = if skew <= 0 || plain {
            vec![(1.0, *du, *dv)]
        } else {
            let (lu, lv) = (len(*du).max(1e-30), len(*dv).max(1e-30));
            let eps = lu.min(lv) / lu.max(lv);
            let sigma = SKEW_SIGN.with(|c| c.get()) * eps.atan() * ((du[0] * dv[0] + du[1] * dv[1]) / (lu * lv));
            let k = skew as f64;
            let fl = (k * sigma).floor();
            let bw = meta_beta(k * sigma - fl, 1);
            [(1.0 - bw, fl), (bw, fl + 1.0)]
                .iter()
                .map(|(w, level)| {
                    let psi = (level / k / 2.0).atan();
                    let (c, s) = (psi.cos(), psi.sin());
                    (*w, [c * du[0] + s * dv[0], c * du[1] + s * dv[1]], [c * dv[0] + s * du[0], c * dv[1] + s * du[1]])
                })
                .collect()
        };
        let (mut scale, mut aniso, mut c_total) = (0.0, 0.0, 0.0);
        for (w, ga, gb) in &sets {
            aniso += w * (axis_angle_deg(*ga, *gb) - 90.0).abs();
            if plain {
                let p = [1.0 / (len(*ga) * width), 1.0 / (len(*gb) * width)];
                scale += w * (p[0].log2().abs() + p[1].log2().abs()) / 2.0;
                e.period_min = e.period_min.min(p[0].min(p[1]));
                e.period_max = e.period_max.max(p[0].max(p[1]));
                c_total += w;
                continue;
            }
            let (ka, ba) = level(*ga, width, base);
            let (kb, bb) = level(*gb, width, base);
            // Period of a tap at scale k along the gradient: 1 / (k |∇|), in units of w.
            let period = |k: f64, g: [f64; 2]| 1.0 / (k * len(g).max(1e-300) * width);
            let (pa, pb) = (period(ka, *ga), period(kb, *gb));
            e.period_min = e.period_min.min(pa.min(pb));
            e.period_max = e.period_max.max(pa.max(pb));
            let axis = |p: f64, b: f64| (1.0 - b) * p.log2().abs() + b * (p / base).log2().abs();
            scale += w * (axis(pa, ba) + axis(pb, bb)) / 2.0;
            c_total += w * meta_k(ba) * meta_k(bb);
        }
        let c = if skew > 0 && !plain {
            let bw = sets.get(1).map_or(0.0, |s| s.0);
            c_total * meta_k(bw)
        } else {
            c_total
        };
        e.scale += scale / n;
        e.anisotropy_deg += aniso / n;
        if !plain {
            e.contrast_none += (c.sqrt() - 1.0).abs() / n;
            e.contrast_printed += (c.powf(1.5) - 1.0).abs() / n;
        }
    }
    e.contrast_variance = 0.0;
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base_tap_period_stays_in_one_octave_where_plain_mapping_diverges() {
        let mut grads = Vec::new();
        for d in [1.0, 10.0, 100.0, 1000.0] {
            for el in [90.0, 45.0, 10.0, 2.0] {
                grads.extend(plane_gradients(d, el, 60.0, 64, 4));
            }
        }
        assert!(grads.len() > 500);
        let meta = variant_error(&grads, 32.0, 2.0, 0, false);
        // Eq. 1–3: the base tap's period lies in [1, 2) × w (up to the 4096 scale clamp).
        assert!(meta.period_min >= 1.0 - 1e-9 && meta.period_max < 2.0, "{meta:?}");
        let plain = variant_error(&grads, 32.0, 2.0, 0, true);
        assert!(plain.period_max / plain.period_min > 1e3, "{plain:?}");
        assert!(meta.scale < plain.scale / 10.0);
    }

    #[test]
    fn skew_compensation_reduces_anisotropy_at_grazing_angles() {
        // A plane seen at 10° from off to the side: strongly sheared gradients.
        let grads: Vec<Gradients> = plane_gradients(5.0, 10.0, 90.0, 64, 2).into_iter().filter(|(du, dv)| {
            let c = (du[0] * dv[0] + du[1] * dv[1]) / (len(*du) * len(*dv));
            c.abs() > 0.2
        }).collect();
        assert!(!grads.is_empty());
        let none = variant_error(&grads, 32.0, 2.0, 0, false);
        let four = variant_error(&grads, 32.0, 2.0, 4, false);
        SKEW_SIGN.with(|c| c.set(-1.0));
        let flipped = variant_error(&grads, 32.0, 2.0, 4, false);
        eprintln!("none {} printed-sign {} flipped {}", none.anisotropy_deg, four.anisotropy_deg, flipped.anisotropy_deg);
        assert!(four.anisotropy_deg < none.anisotropy_deg, "{} vs {}", four.anisotropy_deg, none.anisotropy_deg);
    }
}
