//! Deterministic synthetic images for the operators' GPU cases: ramps,
//! checkers (steps, hard for blurs), noise, and a small generator.

use crate::image_f64::ImageF64;

/// A 64-bit LCG: the same sequence on every machine.
pub struct Lcg(pub u64);

impl Lcg {
    pub fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// (x/w, y/h, ½, 1).
pub fn ramp(w: u32, h: u32) -> ImageF64 {
    ImageF64::new(w, h, |x, y| {
        [f64::from(x) / f64::from(w), f64::from(y) / f64::from(h), 0.5, 1.0]
    })
}

/// 3×3-texel checks: (s, 1 − s, s/2, 1).
pub fn checker(w: u32, h: u32) -> ImageF64 {
    ImageF64::new(w, h, |x, y| {
        let s = if (x / 3 + y / 3) % 2 == 0 { 1.0 } else { 0.0 };
        [s, 1.0 - s, s * 0.5, 1.0]
    })
}

/// Independent uniform texels in [0, 1)⁴.
pub fn noise(w: u32, h: u32, seed: u64) -> ImageF64 {
    let mut g = Lcg(seed);
    ImageF64::new(w, h, |_, _| [g.uniform(), g.uniform(), g.uniform(), g.uniform()])
}
