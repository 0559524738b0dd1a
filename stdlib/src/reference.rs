//! CPU reference implementations in f64, one per operator, for the accuracy
//! tests. They follow the WGSL line by line in meaning, not in precision:
//! the GPU runs in f32 and the tests state the tolerance they allow.
//!
//! The MetaTexture extensions and the Edge Breakup operators (Age of Sail
//! §3.2–3.5, §4, eqs. 9–13, 26–30) are in [`breakup`], re-exported here.

mod breakup;
pub use breakup::*;
mod patterns;
pub use patterns::*;
mod halftone;
pub use halftone::*;
mod artmaps;
pub use crate::ops::colour::{luminance, over, overlay, saturation};
pub use crate::ops::filters::{downsample, gaussian, normal_depth_edges, sobel, GAUSSIAN_MAX_RADIUS};
pub use crate::ops::sample::sample;
pub use crate::ops::shading::{half_lambert, lambert, threshold, toon};
pub use artmaps::*;

/// An RGBA image of f64 texels with clamp-to-edge reads (like `textureLoad`
/// with clamped coordinates in the WGSL operators).
#[derive(Debug, Clone)]
pub struct ImageF64 {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f64; 4]>,
}

impl ImageF64 {
    pub fn new(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> [f64; 4]) -> ImageF64 {
        let mut pixels = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                pixels.push(f(x, y));
            }
        }
        ImageF64 { width, height, pixels }
    }

    pub fn load(&self, x: i64, y: i64) -> [f64; 4] {
        let x = x.clamp(0, self.width as i64 - 1) as usize;
        let y = y.clamp(0, self.height as i64 - 1) as usize;
        self.pixels[y * self.width as usize + x]
    }

    /// The texel under `uv` (floor(uv · dims), clamped), as the operators pick it.
    pub fn pixel_of(&self, uv: [f64; 2]) -> (i64, i64) {
        (
            ((uv[0] * self.width as f64).floor() as i64).clamp(0, self.width as i64 - 1),
            ((uv[1] * self.height as f64).floor() as i64).clamp(0, self.height as i64 - 1),
        )
    }
}

pub(crate) fn unit(v: [f64; 3]) -> [f64; 3] {
    let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    // Same guard as the WGSL: a zero vector stays zero.
    let s = 1.0 / l2.max(1e-30).sqrt();
    [v[0] * s, v[1] * s, v[2] * s]
}

pub(crate) fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Operators that have a reference here (checked by the completeness test).
pub const REFERENCED: &[&str] = &[
    "lambert",
    "half_lambert",
    "toon",
    "threshold",
    "gaussian",
    "downsample",
    "sobel",
    "normal_depth_edges",
    "over",
    "luminance",
    "saturation",
    "overlay",
    "sample",
    "metatexture_grad",
    "metatexture",
    "metatexture4_grad",
    "metatexture4",
    "shadow",
    "contour_fade",
    "reprojection_mask",
    "stereo_consistency",
    "radial_alpha",
    "uv_gradients",
    "metatexture_contour_grad",
    "metatexture_contour",
    "live_texture",
    "line_boil",
    "roll_compensate",
    "distance_attenuate",
    "warp",
    "id_share",
    "complex_mul",
    "pattern_uv",
    "halftone_screen",
    "halftone",
    "sample_biased",
    "sample_ripmap",
];

pub fn has_reference(name: &str) -> bool {
    REFERENCED.contains(&name)
        || crate::reference_lsa::REFERENCED.contains(&name)
        || crate::reference_gbuffer::REFERENCED.contains(&name)
}

/// Bilinear filtering with repeat addressing at level 0 (a tileable texture).
pub fn sample_repeat(tex: &ImageF64, uv: [f64; 2]) -> [f64; 4] {
    let (w, h) = (tex.width as i64, tex.height as i64);
    let x = uv[0] * w as f64 - 0.5;
    let y = uv[1] * h as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let at = |i: i64, j: i64| tex.load(i.rem_euclid(w), j.rem_euclid(h));
    let (a, b, c, d) = (at(x0, y0), at(x0 + 1, y0), at(x0, y0 + 1), at(x0 + 1, y0 + 1));
    std::array::from_fn(|i| {
        let top = a[i] * (1.0 - fx) + b[i] * fx;
        let bottom = c[i] * (1.0 - fx) + d[i] * fx;
        top * (1.0 - fy) + bottom * fy
    })
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
