//! f64 references for the stereo operators of LSA contours §4.2: the contour
//! fade-out, the reprojection mask (eqs. 9–11) and the consistency bound.
//! They follow `{contour_fade,reprojection_mask,stereo_consistency}.wgsl` beside it.

use crate::image_f64::ImageF64;
use std::f64::consts::FRAC_PI_2;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn len(a: V3) -> f64 {
    dot(a, a).sqrt()
}
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// The contour fade-out of point `p` with normal `n` for eyes `left`, `right`
/// looking along `forward`; `start`, `end` scale ᾱ into c_start, c_end.
pub fn contour_fade(p: V3, n: V3, left: V3, right: V3, forward: V3, start: f64, end: f64) -> f64 {
    let nl = len(n);
    if !(nl > 1e-20 && nl < 1e20) {
        return 0.0;
    }
    let nn = scale(n, 1.0 / nl);
    let fl = len(forward);
    let f = if fl > 1e-20 && fl < 1e20 {
        scale(forward, 1.0 / fl)
    } else {
        [0.0, 0.0, -1.0]
    };
    let centre = scale([left[0] + right[0], left[1] + right[1], left[2] + right[2]], 0.5);
    let radius = 0.5 * len(sub(right, left));
    let in_plane = sub(nn, scale(f, dot(nn, f)));
    let ipl = len(in_plane);
    let vc = if ipl > 1e-6 {
        sub(centre, scale(in_plane, radius / ipl))
    } else {
        centre
    };
    let to_view = sub(vc, p);
    let tl = len(to_view);
    if tl.is_nan() || tl <= 1e-20 {
        return 0.0;
    }
    let phi = (dot(to_view, nn) / tl).clamp(-1.0, 1.0).acos();
    let (a, b) = (sub(left, p), sub(right, p));
    let ab = len(a) * len(b);
    let alpha = if ab > 1e-30 {
        (dot(a, b) / ab).clamp(-1.0, 1.0).acos()
    } else {
        0.0
    };
    let lo = FRAC_PI_2 - start.max(0.0) * alpha;
    let hi = FRAC_PI_2 - end.max(0.0) * alpha;
    if (hi - lo).is_nan() || hi - lo <= 1e-7 {
        return if phi >= FRAC_PI_2 { 1.0 } else { 0.0 };
    }
    ((phi - lo) / (hi - lo)).clamp(0.0, 1.0)
}

fn on_geometry(t: [f64; 4]) -> bool {
    t[3] > 0.5 && t[0].abs() < 1e7 && t[1].abs() < 1e7
}

/// M_{i,j} at pixel `p` of `reproj` (R_{i,j}, xy px, w = coverage) against
/// the other eye's `reproj_other` (R_{j,i}): eqs. 9–11.
pub fn reprojection_mask(
    reproj: &ImageF64,
    reproj_other: &ImageF64,
    p: (i64, i64),
    (m_lo, m_hi): (f64, f64),
    (n_lo, n_hi): (f64, f64),
) -> f64 {
    let r = reproj.load(p.0, p.1);
    if !on_geometry(r) {
        return 1.0;
    }
    let pj = (r[0].floor() as i64, r[1].floor() as i64);
    if pj.0 < 0 || pj.1 < 0 || pj.0 >= reproj_other.width as i64 || pj.1 >= reproj_other.height as i64 {
        return 1.0;
    }
    let back = reproj_other.load(pj.0, pj.1);
    if back[3] <= 0.5 {
        return 1.0;
    }
    // Eq. 9.
    let d = ((back[0] - (p.0 as f64 + 0.5)).powi(2) + (back[1] - (p.1 as f64 + 0.5)).powi(2)).sqrt();
    let mut j_max: f64 = 0.0;
    for dy in -1..=1i64 {
        for dx in -1..=1i64 {
            let q = (p.0 + dx, p.1 + dy);
            if (dx == 0 && dy == 0) || q.0 < 0 || q.1 < 0 || q.0 >= reproj.width as i64 || q.1 >= reproj.height as i64 {
                continue;
            }
            let rq = reproj.load(q.0, q.1);
            if rq[3] <= 0.5 {
                j_max = 1e9;
                continue;
            }
            // Eq. 10.
            let j = [(rq[0] - r[0]) - dx as f64, (rq[1] - r[1]) - dy as f64];
            j_max = j_max.max((j[0] * j[0] + j[1] * j[1]).sqrt());
        }
    }
    let m = ((d - m_lo) / (m_hi - m_lo).max(1e-6)).clamp(0.0, 1.0);
    let n = ((j_max - n_lo) / (n_hi - n_lo).max(1e-6)).clamp(0.0, 1.0);
    // Eq. 11.
    m.max(n)
}

/// E(p) bounded by M + (1 − M) · max_{W̄₅(R_{i,j}(p))} E_other.
pub fn stereo_consistency(e: &ImageF64, e_other: &ImageF64, reproj: &ImageF64, mask: f64, p: (i64, i64)) -> f64 {
    let ep = e.load(p.0, p.1)[0];
    let r = reproj.load(p.0, p.1);
    let m = mask.clamp(0.0, 1.0);
    if !on_geometry(r) || m >= 1.0 {
        return ep;
    }
    let c = (r[0].floor() as i64, r[1].floor() as i64);
    let mut best: f64 = 0.0;
    for dy in -2..=2 {
        for dx in -2..=2 {
            let q = (c.0 + dx, c.1 + dy);
            if q.0 >= 0 && q.1 >= 0 && q.0 < e_other.width as i64 && q.1 < e_other.height as i64 {
                best = best.max(e_other.load(q.0, q.1)[0]);
            }
        }
    }
    ep.min(m + (1.0 - m) * best)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LEFT: V3 = [-0.032, 0.0, 0.0];
    const RIGHT: V3 = [0.032, 0.0, 0.0];
    const FORWARD: V3 = [0.0, 0.0, -1.0];

    #[test]
    fn fade_is_dark_at_the_contour_and_clear_facing_the_viewer() {
        // A sphere of radius 0.5 at 2 m: the fade band hugs its silhouette.
        let centre = [0.0, 0.0, -2.0];
        let at = |theta: f64| {
            // A point on the sphere's horizontal great circle, θ from facing the viewer.
            let n = [theta.sin(), 0.0, theta.cos()];
            contour_fade(
                [centre[0] + 0.5 * n[0], centre[1], centre[2] + 0.5 * n[2]],
                n,
                LEFT,
                RIGHT,
                FORWARD,
                7.0 / 4.0,
                7.0 / 16.0,
            )
        };
        assert_eq!(at(0.0), 0.0, "facing the viewer");
        assert_eq!(at(1.0), 0.0, "well inside the silhouette");
        // The silhouette seen from the centre is at cos θ = r / d = 0.25 (θ ≈ 75.5°
        // from the axis, measured here towards +x): beyond it, fully dark.
        assert_eq!(at(1.9), 1.0);
        // Monotonic in between.
        let mut last = 0.0;
        for i in 0..=100 {
            let v = at(1.0 + 0.9 * i as f64 / 100.0);
            assert!(v >= last - 1e-12, "not monotonic at step {i}: {v} < {last}");
            last = v;
        }
        // The ramp's width in φ is c_start − c_end = (7/4 − 7/16)·ᾱ.
        let alpha = (dot(sub(LEFT, [0.5, 0.0, -2.0]), sub(RIGHT, [0.5, 0.0, -2.0]))
            / (len(sub(LEFT, [0.5, 0.0, -2.0])) * len(sub(RIGHT, [0.5, 0.0, -2.0]))))
        .acos();
        assert!(alpha > 0.01 && alpha < 0.04, "{alpha}");
    }

    #[test]
    fn fade_in_mono_is_a_step_and_degenerate_inputs_are_zero() {
        let eye = [0.0, 0.0, 0.0];
        let p = [0.0, 0.0, -2.0];
        assert_eq!(contour_fade(p, [0.0, 0.0, 1.0], eye, eye, FORWARD, 1.75, 0.4375), 0.0);
        assert_eq!(contour_fade(p, [0.0, 0.0, -1.0], eye, eye, FORWARD, 1.75, 0.4375), 1.0);
        assert_eq!(contour_fade(p, [0.0; 3], LEFT, RIGHT, FORWARD, 1.75, 0.4375), 0.0);
        assert_eq!(
            contour_fade(LEFT, [0.0, 0.0, 1.0], LEFT, LEFT, FORWARD, 1.75, 0.4375),
            0.0
        );
        let v = contour_fade(p, [f64::NAN, 0.0, 1.0], LEFT, RIGHT, [0.0; 3], 1.75, 0.4375);
        assert!(v == 0.0, "{v}");
    }

    /// A synthetic R for a fronto-parallel plane: every pixel lands `shift` px
    /// to the right in the other eye, and back.
    fn shifted(w: u32, h: u32, shift: f64) -> ImageF64 {
        ImageF64::new(w, h, |x, y| [x as f64 + 0.5 + shift, y as f64 + 0.5, 0.0, 1.0])
    }

    #[test]
    fn mask_is_zero_for_a_consistent_shift_and_one_across_a_jump_or_occlusion() {
        let (w, h) = (16, 8);
        let this = shifted(w, h, 3.0);
        let other = shifted(w, h, -3.0);
        let ranges = ((2.0, 4.0), (3.0, 6.0));
        assert_eq!(reprojection_mask(&this, &other, (5, 4), ranges.0, ranges.1), 0.0);
        // Pixels that land outside the other image: no correspondence.
        assert_eq!(reprojection_mask(&this, &other, (14, 4), ranges.0, ranges.1), 1.0);
        // A depth jump: the right half moves 10 px further: |J| = 10 at the seam.
        let jump = ImageF64::new(w, h, |x, y| {
            [
                x as f64 + 0.5 + if x >= 8 { 13.0 } else { 3.0 },
                y as f64 + 0.5,
                0.0,
                1.0,
            ]
        });
        assert_eq!(reprojection_mask(&jump, &other, (7, 4), ranges.0, ranges.1), 1.0);
        // A round trip 3 px off: m(3) = ½.
        let off = shifted(w, h, 0.0);
        let back = ImageF64::new(w, h, |x, y| [x as f64 + 3.5, y as f64 + 0.5, 0.0, 1.0]);
        assert!((reprojection_mask(&off, &back, (4, 4), ranges.0, ranges.1) - 0.5).abs() < 1e-12);
        // Background here or there.
        let empty = ImageF64::new(w, h, |_, _| [0.0; 4]);
        assert_eq!(reprojection_mask(&empty, &other, (4, 4), ranges.0, ranges.1), 1.0);
        assert_eq!(reprojection_mask(&this, &empty, (4, 4), ranges.0, ranges.1), 1.0);
    }

    #[test]
    fn consistency_keeps_lines_the_other_eye_confirms() {
        let (w, h) = (16, 8);
        let reproj = shifted(w, h, 3.0);
        let line_at = |col: u32| ImageF64::new(w, h, move |x, _| [if x == col { 1.0 } else { 0.0 }, 0.0, 0.0, 1.0]);
        let e = line_at(5);
        // The other eye's line is where this one lands (5 + 3 = 8): kept.
        assert_eq!(stereo_consistency(&e, &line_at(8), &reproj, 0.0, (5, 3)), 1.0);
        // 2 px off is still inside W̄₅; 3 px off is not.
        assert_eq!(stereo_consistency(&e, &line_at(10), &reproj, 0.0, (5, 3)), 1.0);
        assert_eq!(stereo_consistency(&e, &line_at(11), &reproj, 0.0, (5, 3)), 0.0);
        // An unreliable reprojection (M = 1) keeps the line; M = ¼ bounds it to ¼.
        assert_eq!(stereo_consistency(&e, &line_at(11), &reproj, 1.0, (5, 3)), 1.0);
        assert_eq!(stereo_consistency(&e, &line_at(11), &reproj, 0.25, (5, 3)), 0.25);
    }
}
