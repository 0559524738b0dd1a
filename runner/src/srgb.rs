//! The sRGB transfer function (IEC 61966-2-1), in both directions: what
//! the GPU does when it samples or writes an `_srgb` texture. The runner
//! applies it where it stands in for the GPU: building mip levels of an
//! sRGB image, and reading an `rgba8unorm_srgb` target back as the values
//! a shader reads from it (linear), which is what an EXR must hold.

/// An sRGB-encoded value in 0..1 as linear light.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light in 0..1 as an sRGB-encoded value.
pub fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Channel `c` (0 = red) of an 8-bit unorm texel `byte` as a shader reads
/// it: `byte / 255`, decoded from sRGB for the colour channels of an sRGB
/// format (alpha is never encoded).
pub fn unorm8_as_read(byte: u8, c: usize, srgb: bool) -> f32 {
    let v = f32::from(byte) / 255.0;
    if srgb && c < 3 {
        srgb_to_linear(v)
    } else {
        v
    }
}
