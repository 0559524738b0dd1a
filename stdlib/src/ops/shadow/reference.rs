//! f64 references for the Age of Sail pipeline operators (§5): shadow-map
//! visibility with the sigmoid-warped depth pass.

use crate::image_f64::ImageF64;

/// The depth pass's sigmoid warp of a light-space coordinate in [−1, 1]:
/// x' = tanh(k·x) / tanh(k); the identity for k → 0. Odd, monotonic, and it
/// fixes −1, 0 and 1, so the map still covers the light's whole frustum.
pub fn shadow_warp(x: f64, k: f64) -> f64 {
    let k = k.clamp(0.0, 16.0);
    if k > 1e-4 {
        (k * x).tanh() / k.tanh()
    } else {
        x
    }
}

/// Lit fraction of `p_light` (light NDC) against `depth_map` (channel r):
/// see `shadow.wgsl` beside it.
pub fn shadow(depth_map: &ImageF64, p_light: [f64; 3], bias: f64, warp: f64, radius: i64) -> f64 {
    if p_light[0].abs() > 1.0 || p_light[1].abs() > 1.0 || p_light[2] > 1.0 || p_light.iter().any(|v| v.is_nan()) {
        return 1.0;
    }
    let uv = [
        shadow_warp(p_light[0], warp) * 0.5 + 0.5,
        shadow_warp(p_light[1], warp) * -0.5 + 0.5,
    ];
    let (px, py) = depth_map.pixel_of(uv);
    let r = radius.clamp(0, 3);
    let mut lit = 0.0;
    for j in -r..=r {
        for i in -r..=r {
            if p_light[2] - bias <= depth_map.load(px + i, py + j)[0] {
                lit += 1.0;
            }
        }
    }
    lit / ((2 * r + 1) * (2 * r + 1)) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warp_fixes_the_frustum_edges_and_magnifies_the_centre() {
        for k in [0.0, 0.5, 2.0, 16.0] {
            assert!((shadow_warp(1.0, k) - 1.0).abs() < 1e-12);
            assert!((shadow_warp(-1.0, k) + 1.0).abs() < 1e-12);
            assert_eq!(shadow_warp(0.0, k), 0.0);
        }
        // Slope at the centre is k / tanh(k) > 1: more texels per metre there.
        let h = 1e-6;
        let slope = (shadow_warp(h, 2.0) - shadow_warp(-h, 2.0)) / (2.0 * h);
        assert!((slope - 2.0 / 2f64.tanh()).abs() < 1e-6);
        // Monotonic.
        let mut last = -2.0;
        for i in 0..=200 {
            let x = -1.0 + i as f64 / 100.0;
            let y = shadow_warp(x, 3.0);
            assert!(y > last);
            last = y;
        }
    }

    #[test]
    fn a_point_behind_an_occluder_is_dark_and_in_front_is_lit() {
        // Occluder at depth 0.4 in the left half of the map, nothing (1.0) on the right.
        let map = ImageF64::new(16, 16, |x, _| [if x < 8 { 0.4 } else { 1.0 }, 0.0, 0.0, 1.0]);
        assert_eq!(shadow(&map, [-0.5, 0.0, 0.6], 0.01, 0.0, 1), 0.0);
        assert_eq!(shadow(&map, [-0.5, 0.0, 0.3], 0.01, 0.0, 1), 1.0);
        assert_eq!(shadow(&map, [0.5, 0.0, 0.9], 0.01, 0.0, 1), 1.0);
        // On the boundary the 3×3 filter gives a partial value.
        let edge = shadow(&map, [-1.0 / 16.0, 0.0, 0.6], 0.01, 0.0, 1);
        assert!(edge > 0.0 && edge < 1.0, "{edge}");
        // Outside the map: lit.
        assert_eq!(shadow(&map, [-1.5, 0.0, 0.9], 0.01, 0.0, 1), 1.0);
        assert_eq!(shadow(&map, [f64::NAN, 0.0, f64::NAN], 0.01, 0.0, 1), 1.0);
    }
}
