//! Error metrics of MetaTexture variants on an analytic ground plane, in f64.
//!
//! A pinhole camera looks at the plane y = 0 with uv = (x, z) per metre, from
//! distances of 1 m to 1000 m and elevations down to grazing angles. For
//! every pixel that sees the plane, the exact screen-space UV gradients come
//! from the ray–plane intersection, and the smooth per-vertex approximation
//! of eqs. 9–10 as printed from the exact tangent-frame projections T_s, B_s
//! (on a plane T_s, B_s are exact; the approximation ∇u ∥ T_s is not; the
//! `uv_gradients` default, the inverse of [T_s B_s], equals the exact gradients
//! here). A variant picks its
//! texture scales (eqs. 1–7, with eq. 11's α when radial compensation is on)
//! and skew shear (eqs. 14–21) from its gradients; the errors are measured
//! with the exact ones:
//! - **scale**: |log₂(period / target)| of each tap's screen-space period
//!   along its axis (target: w, or α·w with radial compensation, i.e. the
//!   same angular size), weighted by the tap's blend weight (0 = exact);
//! - **anisotropy**: |angle between the texture's screen-space axes − 90°|,
//!   weighted likewise;
//! - **contrast**: |σ_M/σ_T − 1| of the blend measured with the f64 reference
//!   on a white-noise example texture (see [`contrast_ratio`]).

use crate::reference::{
    meta_beta, meta_k, meta_skew_sigma, metatexture_grad, ImageF64, MetaSettings, META_MAX_SCALE, META_MIN_LOG2_SCALE,
    SKEW_SIGN,
};

/// One pixel's screen-space gradients (∇u, ∇v) in UV per px.
pub type Gradients = ([f64; 2], [f64; 2]);

/// What the plane gives at one pixel.
#[derive(Debug, Clone, Copy)]
pub struct PlaneSample {
    /// The exact gradients (what fragment derivatives approximate).
    pub exact: Gradients,
    /// Eqs. 9–10 from the exact T_s, B_s with |∇_w u| = |∇_w v| = 1 UV/m.
    pub smooth: Gradients,
    /// Eq. 13's α at this pixel.
    pub alpha: f64,
}

fn len(g: [f64; 2]) -> f64 {
    (g[0] * g[0] + g[1] * g[1]).sqrt()
}

/// Eqs. 9–10 given the exact gradients: T_s, B_s are the columns of the
/// inverse of the matrix whose rows are ∇u, ∇v (uv per metre is 1 here).
pub fn smooth_from_exact(du: [f64; 2], dv: [f64; 2]) -> Gradients {
    let det = du[0] * dv[1] - du[1] * dv[0];
    if det.abs() < 1e-300 {
        return (du, dv);
    }
    let ts = [dv[1] / det, -dv[0] / det];
    let bs = [-du[1] / det, du[0] / det];
    let g = |t: [f64; 2]| {
        let l2 = (t[0] * t[0] + t[1] * t[1]).max(1e-300);
        [t[0] / l2, t[1] / l2]
    };
    (g(ts), g(bs))
}

/// Samples of the plane y = 0 (uv = (x, z)) seen by a camera at distance
/// `distance` from the origin, looking at it from `elevation_deg` above the
/// plane and `azimuth_deg` around it (0 = along +z; an azimuth skews the uv
/// axes on screen), with vertical field of view `fov_deg`, over a `size`²
/// image every `stride` px; pixels that miss the plane are skipped.
pub fn plane_samples(
    distance: f64,
    elevation_deg: f64,
    azimuth_deg: f64,
    fov_deg: f64,
    size: u32,
    stride: u32,
) -> Vec<PlaneSample> {
    let (el, az) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    let fwd = [-el.cos() * az.sin(), -el.sin(), el.cos() * az.cos()];
    let eye = [-distance * fwd[0], -distance * fwd[1], -distance * fwd[2]];
    let right = [az.cos(), 0.0, az.sin()];
    // up = right × fwd.
    let up = [
        right[1] * fwd[2] - right[2] * fwd[1],
        right[2] * fwd[0] - right[0] * fwd[2],
        right[0] * fwd[1] - right[1] * fwd[0],
    ];
    let half = size as f64 / 2.0;
    let focal_px = half / (fov_deg.to_radians() / 2.0).tan();
    let hit = |px: f64, py: f64| -> Option<[f64; 2]> {
        let (sx, sy) = (px - half, half - py);
        let d: [f64; 3] = std::array::from_fn(|i| fwd[i] * focal_px + right[i] * sx + up[i] * sy);
        if d[1] >= -1e-12 {
            return None;
        }
        let t = -eye[1] / d[1];
        Some([eye[0] + t * d[0], eye[2] + t * d[2]])
    };
    let mut out = Vec::new();
    let h = 1e-4;
    for py in (0..size).step_by(stride.max(1) as usize) {
        for px in (0..size).step_by(stride.max(1) as usize) {
            let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
            let (Some(a), Some(b), Some(c), Some(d)) = (hit(x - h, y), hit(x + h, y), hit(x, y - h), hit(x, y + h))
            else {
                continue;
            };
            // Central differences: O(h²) error on a smooth map.
            let du = [(b[0] - a[0]) / (2.0 * h), (d[0] - c[0]) / (2.0 * h)];
            let dv = [(b[1] - a[1]) / (2.0 * h), (d[1] - c[1]) / (2.0 * h)];
            let q = [(x - half) / focal_px, (half - y) / focal_px];
            out.push(PlaneSample {
                exact: (du, dv),
                smooth: smooth_from_exact(du, dv),
                alpha: q[0] * q[0] + q[1] * q[1] + 1.0,
            });
        }
    }
    out
}

/// The standard test set: distances 1–1000 m × elevations 90°–2° × azimuths 0° and 35°.
pub fn standard_plane_set(size: u32, stride: u32) -> Vec<PlaneSample> {
    let mut v = Vec::new();
    for d in [1.0, 10.0, 100.0, 1000.0] {
        for el in [90.0, 45.0, 10.0, 2.0] {
            for az in [0.0, 35.0] {
                v.extend(plane_samples(d, el, az, 60.0, size, stride));
            }
        }
    }
    v
}

/// A MetaTexture variant as the metrics see it.
#[derive(Debug, Clone, Copy)]
pub struct Variant {
    pub width: f64,
    pub base: f64,
    /// Skew levels n (0 = 4 taps).
    pub skew: i64,
    /// Sign applied to eq. 14's σ ([`SKEW_SIGN`] in the operators).
    pub skew_sign: f64,
    /// Ordinary texture mapping at scale 1 (period w at |∇u| = 1/w).
    pub plain: bool,
    /// Choose levels and skew from the gradients of eqs. 9–10 as printed
    /// (`uv_gradients(mode: paper)`) instead of the exact ones.
    pub smooth: bool,
    /// Radial-angle compensation (eq. 11): target width α·w.
    pub radial: bool,
    /// 0 none, 1 printed (× c), 2 variance-preserving (÷ √c).
    pub contrast: i64,
}

impl Variant {
    pub fn new(width: f64, skew: i64) -> Variant {
        Variant {
            width,
            base: 2.0,
            skew,
            skew_sign: SKEW_SIGN,
            plain: false,
            smooth: false,
            radial: false,
            contrast: 0,
        }
    }
}

/// The errors of one variant over a set of pixels (means, and the range of
/// the base tap's period in units of its target).
#[derive(Debug, Clone, Copy, Default)]
pub struct VariantError {
    pub scale: f64,
    pub anisotropy_deg: f64,
    pub period_min: f64,
    pub period_max: f64,
    /// Fraction of samples whose base period lies in [1, base).
    pub in_octave: f64,
}

/// Angle in degrees between the screen-space texture axes of a coordinate
/// pair with gradients (∇a, ∇b): the lines b = const and a = const run along
/// ∇b⊥ and ∇a⊥, whose angle equals the angle between ∇a and ∇b.
fn axis_angle_deg(da: [f64; 2], db: [f64; 2]) -> f64 {
    let (la, lb) = (len(da), len(db));
    if la < 1e-300 || lb < 1e-300 {
        return 90.0;
    }
    ((da[0] * db[0] + da[1] * db[1]) / (la * lb))
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// Exponent of one coordinate (eqs. 1–2 with the operators' clamps) and its
/// (scale k = base^⌊E⌋, blend weight).
fn level(g: [f64; 2], width: f64, base: f64) -> (f64, f64) {
    let lb = base.log2();
    let (min_e, max_e) = (META_MIN_LOG2_SCALE / lb, META_MAX_SCALE.log2() / lb);
    let e = (-(width * len(g).clamp(1e-30, 1e30)).log2() / lb).clamp(min_e, max_e);
    let fe = e.floor();
    ((fe * lb).exp2(), meta_beta(e - fe, 1))
}

/// The skew sets of eqs. 16–22: (weight, ψ) pairs.
fn skew_sets(sel: Gradients, skew: i64, sign: f64) -> Vec<(f64, f64)> {
    if skew <= 0 {
        return vec![(1.0, 0.0)];
    }
    let sigma = meta_skew_sigma(sel.0, sel.1, sign);
    let k = skew as f64;
    let fl = (k * sigma).floor();
    let bw = meta_beta(k * sigma - fl, 1);
    vec![(1.0 - bw, (fl / k / 2.0).atan()), (bw, ((fl + 1.0) / k / 2.0).atan())]
}

fn shear(g: Gradients, psi: f64) -> Gradients {
    let (c, s) = (psi.cos(), psi.sin());
    let (du, dv) = g;
    (
        [c * du[0] + s * dv[0], c * du[1] + s * dv[1]],
        [c * dv[0] + s * du[0], c * dv[1] + s * du[1]],
    )
}

/// Scale and anisotropy errors of `v` over `samples`.
pub fn variant_error(samples: &[PlaneSample], v: &Variant) -> VariantError {
    let mut e = VariantError {
        period_min: f64::INFINITY,
        ..Default::default()
    };
    let n = samples.len().max(1) as f64;
    let mut inside = 0usize;
    for s in samples {
        let sel = if v.smooth { s.smooth } else { s.exact };
        let width = if v.radial { v.width * s.alpha } else { v.width };
        let (mut scale, mut aniso) = (0.0, 0.0);
        let sets = if v.plain {
            vec![(1.0, 0.0)]
        } else {
            skew_sets(sel, v.skew, v.skew_sign)
        };
        let mut base_in = true;
        for (w, psi) in sets {
            // The shear is chosen from `sel`, the result measured with the exact gradients.
            let (ga, gb) = shear(s.exact, psi);
            let (sa, sb) = shear(sel, psi);
            aniso += w * (axis_angle_deg(ga, gb) - 90.0).abs();
            let (ka, ba, kb, bb) = if v.plain {
                (1.0, 0.0, 1.0, 0.0)
            } else {
                let (ka, ba) = level(sa, width, v.base);
                let (kb, bb) = level(sb, width, v.base);
                (ka, ba, kb, bb)
            };
            // Screen-space period of a tap at scale k along its gradient, in units of the target.
            let period = |k: f64, g: [f64; 2]| 1.0 / (k * len(g).max(1e-300) * width);
            let (pa, pb) = (period(ka, ga), period(kb, gb));
            e.period_min = e.period_min.min(pa.min(pb));
            e.period_max = e.period_max.max(pa.max(pb));
            base_in &= (1.0 - 1e-9..v.base).contains(&pa) && (1.0 - 1e-9..v.base).contains(&pb);
            let axis = |p: f64, b: f64| (1.0 - b) * p.log2().abs() + b * (p / v.base).log2().abs();
            scale += w * (axis(pa, ba) + axis(pb, bb)) / 2.0;
        }
        inside += base_in as usize;
        e.scale += scale / n;
        e.anisotropy_deg += aniso / n;
    }
    e.in_octave = inside as f64 / n;
    e
}

/// A tileable white-noise example texture (independent texels, 8-bit).
pub fn noise_texture(size: u32, seed: u64) -> ImageF64 {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (((state >> 11) as f64 / (1u64 << 53) as f64) * 255.0).round() / 255.0
    };
    ImageF64::new(size, size, |_, _| [next(), next(), next(), 1.0])
}

fn std_dev(values: &[f64]) -> f64 {
    let mean = values.iter().sum::<f64>() / values.len().max(1) as f64;
    (values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / values.len().max(1) as f64).sqrt()
}

/// σ_M / σ_T of variant `v` (red channel), measured with the f64 reference
/// MetaTexture on `tex` at pseudo-random uvs in [0, 10⁶)², one per gradient sample; σ_T is
/// the example as MetaTexture reads it (bilinear, one level, no blend).
pub fn contrast_ratio(tex: &ImageF64, samples: &[PlaneSample], v: &Variant) -> f64 {
    let mean = tex.pixels.iter().map(|p| p[0]).sum::<f64>() / tex.pixels.len().max(1) as f64;
    let settings = MetaSettings {
        width: v.width,
        beta: 1,
        base: v.base,
        skew: v.skew,
        contrast: v.contrast,
        mean: [mean; 4],
    };
    let mut state = 0x5eed_u64;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut m = Vec::with_capacity(samples.len());
    let mut t = Vec::with_capacity(samples.len());
    for s in samples {
        // Spread over many periods even at the smallest scales (k ≥ 2^-15 on the plane set).
        let uv = [next() * 1e6, next() * 1e6];
        let (du, dv) = if v.smooth { s.smooth } else { s.exact };
        let width = if v.radial { v.width * s.alpha } else { v.width };
        m.push(metatexture_grad(tex, uv, du, dv, &MetaSettings { width, ..settings })[0]);
        // One tap exactly at a level (E integer): the example's own contrast.
        let g = 1.0 / (4.0 * width);
        t.push(metatexture_grad(tex, uv, [g, 0.0], [0.0, g], &MetaSettings { width, ..settings })[0]);
    }
    std_dev(&m) / std_dev(&t).max(1e-300)
}

/// Predicted σ_M/σ_T for uncorrelated taps with blend weights b (eq. 24):
/// √c without compensation, c^{3/2} with the printed factor, 1 with ÷√c.
pub fn predicted_contrast(blend: &[f64], mode: i64) -> f64 {
    let c: f64 = blend.iter().map(|b| meta_k(*b)).product();
    match mode {
        1 => c.powf(1.5),
        2 => 1.0,
        _ => c.sqrt(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base_tap_period_stays_in_one_octave_where_plain_mapping_diverges() {
        let samples = standard_plane_set(64, 4);
        assert!(samples.len() > 1000, "{}", samples.len());
        let meta = variant_error(&samples, &Variant::new(32.0, 0));
        // Eqs. 1–3: the base tap's period lies in [1, 2) × w everywhere.
        assert!(meta.period_min >= 1.0 - 1e-9 && meta.period_max < 2.0, "{meta:?}");
        assert_eq!(meta.in_octave, 1.0);
        let plain = variant_error(
            &samples,
            &Variant {
                plain: true,
                ..Variant::new(32.0, 0)
            },
        );
        assert!(plain.period_max / plain.period_min > 1e4, "{plain:?}");
        assert!(meta.scale < plain.scale / 10.0, "{meta:?} vs {plain:?}");
    }

    #[test]
    fn skew_sign_that_reduces_anisotropy() {
        // A plane seen at 10° from 35° round: strongly sheared gradients.
        let samples: Vec<PlaneSample> = plane_samples(5.0, 10.0, 35.0, 90.0, 64, 2)
            .into_iter()
            .filter(|s| {
                let (du, dv) = s.exact;
                ((du[0] * dv[0] + du[1] * dv[1]) / (len(du) * len(dv))).abs() > 0.2
            })
            .collect();
        assert!(samples.len() > 100);
        let none = variant_error(&samples, &Variant::new(32.0, 0)).anisotropy_deg;
        let chosen = variant_error(&samples, &Variant::new(32.0, 4)).anisotropy_deg;
        let printed = variant_error(
            &samples,
            &Variant {
                skew_sign: 1.0,
                ..Variant::new(32.0, 4)
            },
        )
        .anisotropy_deg;
        // With eqs. 9–10 as printed (∇u ∥ T_s, ∇v ∥ B_s), ∇u·∇v has the opposite
        // sign of the true one, so there the printed σ is the right one.
        let paper_printed = variant_error(
            &samples,
            &Variant {
                skew_sign: 1.0,
                smooth: true,
                ..Variant::new(32.0, 4)
            },
        )
        .anisotropy_deg;
        println!("anisotropy: none {none:.1}°, printed sign {printed:.1}°, negated {chosen:.1}°; eqs. 9–10 gradients with the printed sign {paper_printed:.1}°");
        assert!(chosen < 0.8 * none, "{chosen} vs {none}");
        assert!(
            printed > none,
            "the printed sign should skew further: {printed} vs {none}"
        );
        assert!(paper_printed < 0.8 * none, "{paper_printed} vs {none}");
    }

    #[test]
    fn smooth_gradients_equal_exact_ones_when_the_axes_are_orthogonal() {
        let (du, dv) = ([0.3, 0.0], [0.0, 0.7]);
        let (su, sv) = smooth_from_exact(du, dv);
        assert!((su[0] - 0.3).abs() < 1e-12 && su[1].abs() < 1e-12);
        assert!((sv[1] - 0.7).abs() < 1e-12 && sv[0].abs() < 1e-12);
        // Sheared: eqs. 9–10 keep ∇u ∥ T_s, which is ⟂ ∇v, not ∇u itself.
        let (su, _) = smooth_from_exact([0.3, 0.1], [0.0, 0.7]);
        assert!((su[0] * 0.0 + su[1] * 0.7).abs() < 1e-12);
    }
}
