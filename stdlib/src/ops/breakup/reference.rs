//! f64 references for the MetaTexture extensions (Age of Sail §3.2 smooth
//! gradients, §3.3 radial angle, §6.1 live texture; §3.5's contour
//! orientation is with MetaTexture in `ops/metatexture`) and the Edge
//! Breakup operators (§4.2 line boil, §4.3 camera roll, §4.4 distance, the
//! warp itself). Each follows its WGSL file beside it.

use crate::image_f64::ImageF64;

fn dot2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Eqs. 12–13: α = |Q|² + 1 with Q = (s_x/P₀₀, s_y/P₁₁), s the NDC position of `screen_uv`.
pub fn radial_alpha(screen_uv: [f64; 2], focal: [f64; 2]) -> f64 {
    let s = [screen_uv[0] * 2.0 - 1.0, 1.0 - screen_uv[1] * 2.0];
    let q = [s[0] / focal[0].abs().max(1e-6), s[1] / focal[1].abs().max(1e-6)];
    let a = dot2(q, q) + 1.0;
    // NaN (a screen position from a triangle clipped at the eye plane) gives 1.
    if a >= 1.0 {
        a.min(1e12)
    } else {
        1.0
    }
}

/// §3.2: (∇u, ∇v) packed (∇u.x, ∇u.y, ∇v.x, ∇v.y) from T_s, B_s and the
/// densities; `mode` 0 = rows of [T_s B_s]⁻¹, 1 = eqs. 9–10 as printed.
pub fn uv_gradients(tangent: [f64; 2], bitangent: [f64; 2], density: [f64; 2], mode: i64) -> [f64; 4] {
    let rho = [density[0].abs(), density[1].abs()];
    let out = if mode == 1 {
        let g = |t: [f64; 2], d: f64| {
            let s = d / dot2(t, t).max(1e-20);
            [t[0] * s, t[1] * s]
        };
        let (u, v) = (g(tangent, rho[0]), g(bitangent, rho[1]));
        [u[0], u[1], v[0], v[1]]
    } else {
        let det = tangent[0] * bitangent[1] - tangent[1] * bitangent[0];
        let d = if det >= 0.0 { 1.0 } else { -1.0 } * det.abs().max(1e-20);
        [
            rho[0] * bitangent[1] / d,
            -rho[0] * bitangent[0] / d,
            -rho[1] * tangent[1] / d,
            rho[1] * tangent[0] / d,
        ]
    };
    out.map(|x| x.clamp(-1e30, 1e30))
}

/// Eq. 29 as printed.
pub const LIVE_L1: [f64; 3] = [0.707, 0.0, -0.707];
/// Eq. 30 as printed.
pub const LIVE_L2: [f64; 3] = [-0.408, 0.816, -0.408];

/// Eqs. 27–30 with ft = 2π·f·t (f in cycles per second); the three equal components of T'.
pub fn live_texture(t: [f64; 4], freq: f64, time: f64) -> f64 {
    let d = |l: [f64; 3]| t[0] * l[0] + t[1] * l[1] + t[2] * l[2];
    let phase = std::f64::consts::TAU * (freq * time).rem_euclid(1.0);
    0.5 + d(LIVE_L1) * phase.cos() + d(LIVE_L2) * phase.sin()
}

/// §4.2: the drawing index k = ⌊t·rate⌋ mod cycle (1e-3 of a step of slack for frame-time rounding).
pub fn line_boil_step(rate: f64, cycle: i64, time: f64) -> f64 {
    let n = cycle.max(1) as f64;
    let s = (time * rate.max(0.0) + 1e-3).floor();
    s - n * (s / n).floor()
}

/// §4.2: uv + amount · R₂(k).
pub fn line_boil(uv: [f64; 2], amount: f64, rate: f64, cycle: i64, time: f64) -> [f64; 2] {
    let k = line_boil_step(rate, cycle, time);
    let r = [(k * 0.7548776662466927).fract(), (k * 0.5698402909980532).fract()];
    [uv[0] + amount * r[0], uv[1] + amount * r[1]]
}

/// §4.3: `offset` expressed in the frame (ê, ê⊥) of the screen-space ∇u.
pub fn roll_compensate(offset: [f64; 2], grad_u: [f64; 2]) -> [f64; 2] {
    let l = dot2(grad_u, grad_u).sqrt();
    // NaN fails this range check too (no frame to rotate into).
    if !(1e-30..=1e30).contains(&l) || l == 1e-30 {
        return offset;
    }
    let e = [grad_u[0] / l, grad_u[1] / l];
    [offset[0] * e[0] - offset[1] * e[1], offset[0] * e[1] + offset[1] * e[0]]
}

/// Eq. 26: ρ' = ρ / (1 + (d/falloff)²).
pub fn distance_attenuate(rho: f64, d: f64, falloff: f64) -> f64 {
    let x = d.abs() / falloff.max(1e-6);
    rho / (1.0 + x * x)
}

/// §4: `src` at uv + offset·strength/size (nearest texel, clamped).
pub fn warp(src: &ImageF64, offset: [f64; 2], strength: f64, uv: [f64; 2]) -> [f64; 4] {
    let d = [offset[0] * strength, offset[1] * strength].map(|x| if x.is_nan() { 0.0 } else { x.clamp(-1e6, 1e6) });
    let p = [uv[0] * src.width as f64 + d[0], uv[1] * src.height as f64 + d[1]];
    src.load(p[0].floor() as i64, p[1].floor() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radial_alpha_is_1_at_the_centre_and_3_in_a_corner_at_90_degrees() {
        // With a 90° field of view (P₀₀ = 1) α = 3 in a corner.
        assert_eq!(radial_alpha([0.5, 0.5], [1.0, 1.0]), 1.0);
        assert!((radial_alpha([1.0, 0.0], [1.0, 1.0]) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn distance_attenuation_stays_in_0_rho() {
        for d in [0.0, 1e-3, 1.0, 7.5, 1e5, 1e20, -3.0] {
            for falloff in [0.001, 1.0, 1e5] {
                let r = distance_attenuate(2.0, d, falloff);
                assert!((0.0..=2.0).contains(&r), "ρ' out of [0, ρ]: {r}");
            }
        }
    }
}
