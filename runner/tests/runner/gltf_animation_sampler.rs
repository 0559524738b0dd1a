//! glTF animation samplers against analytic values (glTF 2.0 Appendix C):
//! STEP holds, LINEAR is componentwise or (rotations) slerp along the
//! shorter arc, CUBICSPLINE reproduces a cubic exactly when its tangents
//! are the cubic's derivatives (which holds only if they are scaled by the
//! key interval), and a cubic-spline rotation comes out unit length.

use npr_runner::scene::anim_sampler::{Interpolation, Sampler};

fn sampler(interpolation: Interpolation, times: &[f32], values: &[f32], width: usize, rotation: bool) -> Sampler {
    let s = Sampler {
        interpolation,
        times: times.to_vec(),
        values: values.to_vec(),
        width,
        rotation,
    };
    assert_eq!(s.values.len(), s.values_expected(), "test sampler is malformed");
    s
}

fn at(s: &Sampler, t: f32) -> Vec<f32> {
    let mut out = vec![f32::NAN; s.width];
    s.sample(t, &mut out);
    out
}

fn close(a: &[f32], b: &[f64], tol: f64) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert!((f64::from(*x) - y).abs() <= tol, "{a:?} vs {b:?}");
    }
}

#[test]
fn step_holds_each_key_until_the_next_and_clamps_outside() {
    let s = sampler(Interpolation::Step, &[0.0, 1.0, 2.0], &[1.0, 5.0, -3.0], 1, false);
    close(&at(&s, -1.0), &[1.0], 0.0);
    close(&at(&s, 0.0), &[1.0], 0.0);
    close(&at(&s, 0.999), &[1.0], 0.0);
    close(&at(&s, 1.0), &[5.0], 0.0);
    close(&at(&s, 1.5), &[5.0], 0.0);
    close(&at(&s, 2.0), &[-3.0], 0.0);
    close(&at(&s, 7.0), &[-3.0], 0.0);
}

#[test]
fn linear_translation_and_weights_are_componentwise() {
    let s = sampler(
        Interpolation::Linear,
        &[1.0, 3.0],
        &[0.0, 0.0, 0.0, 4.0, 8.0, -4.0],
        3,
        false,
    );
    close(&at(&s, 1.5), &[1.0, 2.0, -1.0], 1e-6);
    close(&at(&s, 0.0), &[0.0, 0.0, 0.0], 0.0);
    close(&at(&s, 9.0), &[4.0, 8.0, -4.0], 0.0);
    // Two morph weights over three keys.
    let w = sampler(
        Interpolation::Linear,
        &[0.0, 1.0, 2.0],
        &[0.0, 1.0, 1.0, 0.0, 0.5, 0.5],
        2,
        false,
    );
    close(&at(&w, 0.25), &[0.25, 0.75], 1e-6);
    close(&at(&w, 1.5), &[0.75, 0.25], 1e-6);
}

/// (x, y, z, w) of a turn of `deg` degrees about +Z.
fn about_z(deg: f64) -> [f64; 4] {
    let h = deg.to_radians() / 2.0;
    [0.0, 0.0, h.sin(), h.cos()]
}

fn f32s(q: [f64; 4]) -> Vec<f32> {
    q.iter().map(|&c| c as f32).collect()
}

#[test]
fn linear_rotation_is_slerp_along_the_shorter_arc() {
    let mut values = f32s(about_z(0.0));
    values.extend(f32s(about_z(90.0)));
    let s = sampler(Interpolation::Linear, &[0.0, 3.0], &values, 4, true);
    // Constant angular speed: a third of the time is a third of the angle
    // (nlerp would give 28.2° at s = 1/3, not 30°).
    close(&at(&s, 1.0), &about_z(30.0), 1e-6);
    close(&at(&s, 1.5), &about_z(45.0), 1e-6);
    // The same end rotation written as −q: still the 90° way round, not 270°.
    let mut flipped = f32s(about_z(0.0));
    flipped.extend(about_z(90.0).iter().map(|&c| -c as f32));
    let s = sampler(Interpolation::Linear, &[0.0, 3.0], &flipped, 4, true);
    close(&at(&s, 1.0), &about_z(30.0), 1e-6);
    // Nearly equal rotations (the spec's linear branch) stay unit length.
    let mut near = f32s(about_z(10.0));
    near.extend(f32s(about_z(10.5)));
    let s = sampler(Interpolation::Linear, &[0.0, 1.0], &near, 4, true);
    close(&at(&s, 0.5), &about_z(10.25), 1e-5);
}

/// f(t) = t³ − 2t + 1 and f'(t) = 3t² − 2.
fn cubic(t: f64) -> f64 {
    t * t * t - 2.0 * t + 1.0
}
fn cubic_slope(t: f64) -> f64 {
    3.0 * t * t - 2.0
}

#[test]
fn cubic_spline_tangents_are_scaled_by_the_key_interval() {
    // Keys 2 s apart: unscaled tangents would miss f by up to ~1.5.
    let times = [1.0f32, 3.0, 3.5];
    let mut values = Vec::new();
    for &t in &times {
        let t = f64::from(t);
        // in-tangent, value, out-tangent
        values.extend([cubic_slope(t) as f32, cubic(t) as f32, cubic_slope(t) as f32]);
    }
    let s = sampler(Interpolation::CubicSpline, &times, &values, 1, false);
    for t in [1.0, 1.25, 1.5, 2.0, 2.75, 3.0, 3.2, 3.5] {
        close(&at(&s, t as f32), &[cubic(t)], 2e-5 * cubic(t).abs().max(1.0));
    }
    // Outside the keys: the first and last values, never a tangent.
    close(&at(&s, 0.0), &[cubic(1.0)], 0.0);
    close(&at(&s, 9.0), &[cubic(3.5)], 0.0);
}

#[test]
fn cubic_spline_rotation_is_normalised() {
    // Zero tangents: the Hermite blend of q0 and q1 is shorter than 1
    // between them; normalised, the symmetric midpoint is the 45° turn.
    let mut values = vec![0.0f32; 4];
    values.extend(f32s(about_z(0.0)));
    values.extend([0.0f32; 4]);
    values.extend([0.0f32; 4]);
    values.extend(f32s(about_z(90.0)));
    values.extend([0.0f32; 4]);
    let s = sampler(Interpolation::CubicSpline, &[0.0, 2.0], &values, 4, true);
    let mid = at(&s, 1.0);
    close(&mid, &about_z(45.0), 1e-6);
    for t in [0.3f32, 0.7, 1.6] {
        let q = at(&s, t);
        let len: f32 = q.iter().map(|c| c * c).sum::<f32>().sqrt();
        assert!((len - 1.0).abs() < 1e-6, "|q({t})| = {len}");
    }
}
