//! glTF 2.0 animation samplers: the value of one channel at a time, with
//! the spec's STEP, LINEAR and CUBICSPLINE interpolation (glTF 2.0 §3.11
//! and Appendix C).
//!
//! - Before the first key the first value holds, after the last the last
//!   (for CUBICSPLINE, the key's value, not its tangents).
//! - LINEAR rotations are spherical (slerp) along the shorter arc, as
//!   Appendix C's reference code does (it negates one quaternion when their
//!   dot product is negative); other properties interpolate componentwise.
//! - CUBICSPLINE is the Hermite spline of Appendix C with the tangents
//!   scaled by the key interval `t_{k+1} − t_k`:
//!   `p(s) = (2s³−3s²+1)·v_k + (s³−2s²+s)·Δ·b_k + (−2s³+3s²)·v_{k+1} + (s³−s²)·Δ·a_{k+1}`,
//!   with `b_k` the out-tangent of key k and `a_{k+1}` the in-tangent of
//!   key k+1; a rotation so made is normalised afterwards (the spec asks it).

/// How a sampler interpolates between keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interpolation {
    Step,
    Linear,
    CubicSpline,
}

/// One sampler's keys: strictly increasing times, and per key `width`
/// values (for CUBICSPLINE `3 · width`: in-tangent, value, out-tangent).
#[derive(Debug, Clone, PartialEq)]
pub struct Sampler {
    pub interpolation: Interpolation,
    pub times: Vec<f32>,
    pub values: Vec<f32>,
    /// Components of one value: 3 (translation, scale), 4 (rotation), or
    /// the number of morph targets (weights).
    pub width: usize,
    /// A rotation quaternion (x, y, z, w): slerped and normalised.
    pub rotation: bool,
}

impl Sampler {
    /// Whether `values` holds exactly the keys `times` and the
    /// interpolation need.
    pub fn values_expected(&self) -> usize {
        let per_key = if self.interpolation == Interpolation::CubicSpline {
            3 * self.width
        } else {
            self.width
        };
        self.times.len() * per_key
    }

    /// The value at key `k` (for CUBICSPLINE the middle of its triple).
    fn value(&self, k: usize) -> &[f32] {
        let w = self.width;
        match self.interpolation {
            Interpolation::CubicSpline => &self.values[(3 * k + 1) * w..(3 * k + 2) * w],
            _ => &self.values[k * w..(k + 1) * w],
        }
    }

    /// The value at time `t` into `out` (`width` components). The sampler
    /// must have been checked: at least one key, `values_expected` values.
    pub fn sample(&self, t: f32, out: &mut [f32]) {
        let w = self.width;
        let n = self.times.len();
        if n == 0 {
            return;
        }
        // The last key at or before `t`.
        let after = self.times.partition_point(|&key| key <= t);
        if after == 0 {
            out.copy_from_slice(self.value(0));
            return;
        }
        if after >= n {
            out.copy_from_slice(self.value(n - 1));
            return;
        }
        let k = after - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        let delta = t1 - t0;
        let s = if delta > 0.0 {
            ((t - t0) / delta).clamp(0.0, 1.0)
        } else {
            0.0
        };
        match self.interpolation {
            Interpolation::Step => out.copy_from_slice(self.value(k)),
            Interpolation::Linear if self.rotation => {
                let q = slerp(self.value(k), self.value(k + 1), s);
                out.copy_from_slice(&q);
            }
            Interpolation::Linear => {
                let (a, b) = (self.value(k), self.value(k + 1));
                for j in 0..w {
                    out[j] = a[j] + (b[j] - a[j]) * s;
                }
            }
            Interpolation::CubicSpline => {
                let v0 = &self.values[(3 * k + 1) * w..(3 * k + 2) * w];
                let b0 = &self.values[(3 * k + 2) * w..(3 * k + 3) * w];
                let a1 = &self.values[(3 * (k + 1)) * w..(3 * (k + 1) + 1) * w];
                let v1 = &self.values[(3 * (k + 1) + 1) * w..(3 * (k + 1) + 2) * w];
                let (s2, s3) = (s * s, s * s * s);
                let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
                let h10 = s3 - 2.0 * s2 + s;
                let h01 = -2.0 * s3 + 3.0 * s2;
                let h11 = s3 - s2;
                for j in 0..w {
                    out[j] = h00 * v0[j] + h10 * delta * b0[j] + h01 * v1[j] + h11 * delta * a1[j];
                }
                if self.rotation {
                    normalize(out);
                }
            }
        }
    }
}

/// Appendix C's slerp: along the shorter arc, and linear (then normalised)
/// where the quaternions are nearly equal, where `sin θ` would divide by ~0.
fn slerp(a: &[f32], b: &[f32], s: f32) -> [f32; 4] {
    let mut d: f32 = (0..4).map(|j| a[j] * b[j]).sum();
    let sign = if d < 0.0 {
        d = -d;
        -1.0
    } else {
        1.0
    };
    let mut q = [0.0f32; 4];
    if d > 0.9995 {
        for j in 0..4 {
            q[j] = a[j] + (sign * b[j] - a[j]) * s;
        }
        normalize(&mut q);
        return q;
    }
    let theta = d.clamp(-1.0, 1.0).acos();
    let sin = theta.sin();
    let (wa, wb) = (((1.0 - s) * theta).sin() / sin, (s * theta).sin() / sin);
    for j in 0..4 {
        q[j] = wa * a[j] + wb * sign * b[j];
    }
    q
}

fn normalize(q: &mut [f32]) {
    let len = q.iter().map(|c| c * c).sum::<f32>().sqrt();
    if len > 0.0 && len.is_finite() {
        for c in q.iter_mut() {
            *c /= len;
        }
    }
}
