//! f64 references of the MetaTexture operators (Harvill et al., Age of
//! Sail, journal 2019, §3): the level and blend of eqs. 1–8 (eqs. 4–5
//! corrected), skew compensation (eqs. 14–23, σ negated: [`SKEW_SIGN`]),
//! contrast compensation (eqs. 24–25) and the contour orientation of §3.5.
//! The variants that take fragment derivatives are the gradient ones with
//! ∇u = (∂u/∂x, ∂u/∂y), ∇v = (∂v/∂x, ∂v/∂y).

use crate::image_f64::{sample_repeat, ImageF64};

fn dot2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// MetaTexture settings (see `metatexture_grad.wgsl`).
#[derive(Debug, Clone, Copy)]
pub struct MetaSettings {
    pub width: f64,
    /// 0 linear, 1 cubic, 2 quintic.
    pub beta: i64,
    pub base: f64,
    pub skew: i64,
    /// 0 none, 1 printed (× c), 2 variance-preserving (÷ √c).
    pub contrast: i64,
    pub mean: [f64; 4],
}

impl Default for MetaSettings {
    fn default() -> Self {
        MetaSettings {
            width: 256.0,
            beta: 1,
            base: 2.0,
            skew: 0,
            contrast: 0,
            mean: [0.5; 4],
        }
    }
}

/// The largest texture scale MetaTexture uses (keeps k·uv precise in f32).
pub const META_MAX_SCALE: f64 = 4096.0;
/// log₂ of the smallest texture scale (far away and at grazing angles k·uv
/// only shrinks, so this bound is only there to keep 2^E a normal f32).
pub const META_MIN_LOG2_SCALE: f64 = -40.0;

/// The sign applied to eq. 14's skew σ. The shear of eqs. 20–21 gives
/// ∇u'·∇v' = ∇u·∇v + ½ sin 2ψ (|∇u|² + |∇v|²), so ψ = atan(σ/2) straightens the
/// screen-space axes only when σ has the opposite sign of ∇u·∇v; as printed
/// (sign +1) it skews them further. Measured in `metrics` (test
/// `skew_sign_that_reduces_anisotropy`): on a plane seen at 10° elevation
/// from 35° round (pixels with |cos∠(∇u, ∇v)| > 0.2), the mean
/// |axis angle − 90°| is 41.1° without skew compensation, 51.5° with the
/// printed sign and 26.2° with this one (n = 4). The printed sign is right
/// for the gradients of eqs. 9–10 as printed (∇u ∥ T_s, ∇v ∥ B_s), whose dot
/// product has the opposite sign of the true gradients' (26.2° there too):
/// the operators take true gradients (derivatives, or `uv_gradients`'
/// default inverse mode), hence −1.
pub const SKEW_SIGN: f64 = -1.0;

/// Eqs. 14–15 (with [`SKEW_SIGN`] as `sign`): the skew factor σ.
pub fn meta_skew_sigma(du: [f64; 2], dv: [f64; 2], sign: f64) -> f64 {
    let len = |g: [f64; 2]| (g[0] * g[0] + g[1] * g[1]).sqrt().max(1e-30);
    let (lu, lv) = (len(du), len(dv));
    let eps = lu.min(lv) / lu.max(lv);
    sign * eps.atan() * ((du[0] * dv[0] + du[1] * dv[1]) / (lu * lv))
}

/// β of eq. 7.
pub fn meta_beta(x: f64, kind: i64) -> f64 {
    let t = x.clamp(0.0, 1.0);
    match kind {
        0 => t,
        1 => t * t * (3.0 - 2.0 * t),
        _ => t * t * t * (t * (t * 6.0 - 15.0) + 10.0),
    }
}

/// k(t) of eq. 25.
pub fn meta_k(t: f64) -> f64 {
    2.0 * t * t - 2.0 * t + 1.0
}

/// Eqs. 1, 2 and 7: (E, per-axis scale base^⌊E⌋, blend weights B).
pub fn meta_level(du: [f64; 2], dv: [f64; 2], s: &MetaSettings) -> ([f64; 2], [f64; 2], [f64; 2]) {
    let lb = s.base.max(1.0001).log2();
    let max_e = META_MAX_SCALE.log2() / lb;
    let min_e = META_MIN_LOG2_SCALE / lb;
    let len = |g: [f64; 2]| (g[0] * g[0] + g[1] * g[1]).sqrt().clamp(1e-30, 1e30);
    let e = [
        (-(s.width.max(1e-6) * len(du)).log2() / lb).clamp(min_e, max_e),
        (-(s.width.max(1e-6) * len(dv)).log2() / lb).clamp(min_e, max_e),
    ];
    let fe = [e[0].floor(), e[1].floor()];
    let scale = [(fe[0] * lb).exp2(), (fe[1] * lb).exp2()];
    let blend = [meta_beta(e[0] - fe[0], s.beta), meta_beta(e[1] - fe[1], s.beta)];
    (e, scale, blend)
}

fn meta_four(tex: &ImageF64, uv: [f64; 2], scale: [f64; 2], blend: [f64; 2], base: f64) -> [f64; 4] {
    let tap = |kx: f64, ky: f64| sample_repeat(tex, [(kx * uv[0]).rem_euclid(1.0), (ky * uv[1]).rem_euclid(1.0)]);
    // Eq. 8 with U1 = ⟨u0, b·v0⟩ and U2 = ⟨b·u0, v0⟩ (eqs. 4–5 corrected).
    let t0 = tap(scale[0], scale[1]);
    let t1 = tap(scale[0], base * scale[1]);
    let t2 = tap(base * scale[0], scale[1]);
    let t3 = tap(base * scale[0], base * scale[1]);
    let (bu, bv) = (blend[0], blend[1]);
    std::array::from_fn(|i| (1.0 - bv) * ((1.0 - bu) * t0[i] + bu * t2[i]) + bv * ((1.0 - bu) * t1[i] + bu * t3[i]))
}

/// MetaTexture M (eq. 8, or eq. 23 with skew) with contrast compensation.
pub fn metatexture_grad(tex: &ImageF64, uv: [f64; 2], du: [f64; 2], dv: [f64; 2], s: &MetaSettings) -> [f64; 4] {
    let (m, c) = if s.skew <= 0 {
        let (_, scale, blend) = meta_level(du, dv, s);
        (
            meta_four(tex, uv, scale, blend, s.base),
            meta_k(blend[0]) * meta_k(blend[1]),
        )
    } else {
        let sigma = meta_skew_sigma(du, dv, SKEW_SIGN);
        let n = s.skew as f64;
        let fl = (n * sigma).floor();
        let psi0 = (fl / n / 2.0).atan();
        let psi1 = ((fl + 1.0) / n / 2.0).atan();
        let bw = meta_beta(n * sigma - fl, s.beta);
        let set = |psi: f64| {
            let (c, sn) = (psi.cos(), psi.sin());
            // Eqs. 20–21: a symmetric shear.
            let uvp = [uv[0] * c + uv[1] * sn, uv[1] * c + uv[0] * sn];
            let dup = [c * du[0] + sn * dv[0], c * du[1] + sn * dv[1]];
            let dvp = [c * dv[0] + sn * du[0], c * dv[1] + sn * du[1]];
            let (_, scale, blend) = meta_level(dup, dvp, s);
            (meta_four(tex, uvp, scale, blend, s.base), blend)
        };
        let (m0, b0) = set(psi0);
        let (m1, b1) = set(psi1);
        let m: [f64; 4] = std::array::from_fn(|i| (1.0 - bw) * m0[i] + bw * m1[i]);
        // Eq. 24 as the sum of the eight squared weights (each set its own B_u, B_v).
        let c = (1.0 - bw).powi(2) * meta_k(b0[0]) * meta_k(b0[1]) + bw * bw * meta_k(b1[0]) * meta_k(b1[1]);
        (m, c)
    };
    match s.contrast {
        1 => std::array::from_fn(|i| s.mean[i] + (m[i] - s.mean[i]) * c),
        2 => std::array::from_fn(|i| s.mean[i] + (m[i] - s.mean[i]) / c.max(1e-6).sqrt()),
        _ => m,
    }
}

/// §3.5: the blend weight towards the 90°-rotated orientation, β(½ + log₂(|∇u|/|∇v|)/band).
pub fn contour_weight(du: [f64; 2], dv: [f64; 2], band: f64, beta: i64) -> f64 {
    let len = |g: [f64; 2]| dot2(g, g).sqrt().clamp(1e-30, 1e30);
    let r = len(du).log2() - len(dv).log2();
    meta_beta(0.5 + r / band.max(1e-3), beta)
}

/// §3.5: MetaTexture re-oriented to indicate contour (`orient` 0 = off).
pub fn metatexture_contour_grad(
    tex: &ImageF64,
    uv: [f64; 2],
    du: [f64; 2],
    dv: [f64; 2],
    s: &MetaSettings,
    orient: i64,
    band: f64,
) -> [f64; 4] {
    if orient == 0 {
        return metatexture_grad(tex, uv, du, dv, s);
    }
    let w = contour_weight(du, dv, band, s.beta);
    let m0 = if w < 1.0 {
        metatexture_grad(tex, uv, du, dv, s)
    } else {
        [0.0; 4]
    };
    let m1 = if w > 0.0 {
        metatexture_grad(tex, [uv[1], -uv[0]], dv, [-du[0], -du[1]], s)
    } else {
        [0.0; 4]
    };
    let m: [f64; 4] = std::array::from_fn(|i| m0[i] + (m1[i] - m0[i]) * w);
    let c = meta_k(w);
    match s.contrast {
        1 => std::array::from_fn(|i| s.mean[i] + (m[i] - s.mean[i]) * c),
        2 => std::array::from_fn(|i| s.mean[i] + (m[i] - s.mean[i]) / c.max(1e-6).sqrt()),
        _ => m,
    }
}

/// (∇u, ∇v) from the screen derivatives of uv.
pub fn gradients(duv_dx: [f64; 2], duv_dy: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    ([duv_dx[0], duv_dy[0]], [duv_dx[1], duv_dy[1]])
}

/// `metatexture`: [`metatexture_grad`] with the gradients of the screen derivatives of uv.
pub fn metatexture(tex: &ImageF64, uv: [f64; 2], duv_dx: [f64; 2], duv_dy: [f64; 2], s: &MetaSettings) -> [f64; 4] {
    let (du, dv) = gradients(duv_dx, duv_dy);
    metatexture_grad(tex, uv, du, dv, s)
}

/// `metatexture4_grad`: [`metatexture_grad`] without skew compensation.
pub fn metatexture4_grad(tex: &ImageF64, uv: [f64; 2], du: [f64; 2], dv: [f64; 2], s: &MetaSettings) -> [f64; 4] {
    metatexture_grad(tex, uv, du, dv, &MetaSettings { skew: 0, ..*s })
}

/// `metatexture4`: [`metatexture4_grad`] with the gradients of the screen derivatives of uv.
pub fn metatexture4(tex: &ImageF64, uv: [f64; 2], duv_dx: [f64; 2], duv_dy: [f64; 2], s: &MetaSettings) -> [f64; 4] {
    let (du, dv) = gradients(duv_dx, duv_dy);
    metatexture4_grad(tex, uv, du, dv, s)
}

/// `metatexture_contour`: [`metatexture_contour_grad`] with the gradients of the screen derivatives of uv.
pub fn metatexture_contour(
    tex: &ImageF64,
    uv: [f64; 2],
    duv_dx: [f64; 2],
    duv_dy: [f64; 2],
    s: &MetaSettings,
    orient: i64,
    band: f64,
) -> [f64; 4] {
    let (du, dv) = gradients(duv_dx, duv_dy);
    metatexture_contour_grad(tex, uv, du, dv, s, orient, band)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isotropic_gradients_blend_the_orientations_half_and_half() {
        // 10× anisotropy picks one orientation.
        assert_eq!(contour_weight([1.0, 0.0], [0.0, 1.0], 1.0, 1), 0.5);
        assert_eq!(contour_weight([1.0, 0.0], [0.0, 0.1], 1.0, 1), 1.0);
        assert_eq!(contour_weight([0.1, 0.0], [0.0, 1.0], 1.0, 1), 0.0);
    }
}
