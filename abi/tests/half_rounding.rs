//! `HalfRounding::round`, the bit-level definition the WGSL helper
//! `npr_round_f16` implements, against the `half` crate's binary16: to
//! nearest even is `f16::from_f32`; toward zero is the binary16 next to it
//! on zero's side whenever `from_f32` rounded away from zero.

use half::f16;
use npr_abi::formats::HalfRounding;

fn toward_zero(x: f32) -> f32 {
    let h = f16::from_f32(x);
    let hx = h.to_f32();
    if hx.is_infinite() {
        return f16::MAX.to_f32().copysign(x);
    }
    if hx.abs() > x.abs() {
        // One binary16 step toward zero (the bit pattern's magnitude minus one).
        f16::from_bits(h.to_bits() - 1).to_f32()
    } else {
        hx
    }
}

/// Every binary16 value, the midpoints between neighbours, and points a
/// quarter of a step to each side of them, positive and negative.
fn cases() -> Vec<f32> {
    let mut v = Vec::new();
    for bits in 0u16..0x7bff {
        let (a, b) = (f16::from_bits(bits).to_f64(), f16::from_bits(bits + 1).to_f64());
        for t in [0.0, 0.25, 0.5, 0.75] {
            let x = (a + (b - a) * t) as f32;
            v.push(x);
            v.push(-x);
        }
    }
    v.extend([65504.0, 65510.0, 65519.0, 65520.0, 65536.0, 1.0e6, -70000.0]);
    v
}

#[test]
fn nearest_even_is_binary16_conversion() {
    for x in cases() {
        let want = f16::from_f32(x).to_f32();
        let got = HalfRounding::NearestEven.round(x);
        assert_eq!(got.to_bits(), want.to_bits(), "{x:e}: {got:e} against {want:e}");
    }
}

#[test]
fn toward_zero_never_rounds_away() {
    let mut differs = 0;
    for x in cases() {
        let want = toward_zero(x);
        let got = HalfRounding::TowardZero.round(x);
        assert_eq!(got.to_bits(), want.to_bits(), "{x:e}: {got:e} against {want:e}");
        assert!(got.abs() <= x.abs(), "{x:e} → {got:e}");
        differs += usize::from(got != HalfRounding::NearestEven.round(x));
    }
    // The two modes differ on about half the points between binary16 values.
    assert!(differs > 50_000, "{differs}");
}
