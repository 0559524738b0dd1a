//! Whole-image texel conversions (`TargetImage::to_rgba_f32`, `to_rgba8`)
//! against the per-texel definition (`TargetImage::texel`) for every target
//! format, special values included, and `output::encode_png` decoding back
//! to the same pixels at 8 and 16 bits. The conversions were rewritten to
//! run once per image instead of once per texel (the studio converts every
//! frame it serves); these pin that they still give the same values.

use npr_abi::Format;
use npr_runner::TargetImage;

/// Deterministic bytes covering every byte value, with a few f16 and f32
/// special values (NaN, ±infinity, negatives, values above 1) spliced in.
fn image(format: Format, width: u32, height: u32) -> TargetImage {
    let len = (width * height * format.bytes_per_pixel()) as usize;
    let mut state = 0x2545_f491_u32;
    let mut bytes: Vec<u8> = (0..len)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 24) as u8
        })
        .collect();
    let specials: Vec<Vec<u8>> = match format.bytes_per_pixel() / format.channels() {
        2 => [f32::NAN, f32::INFINITY, -2.5, 1.75, 0.5]
            .iter()
            .map(|v| half::f16::from_f32(*v).to_bits().to_le_bytes().to_vec())
            .collect(),
        4 => [f32::NAN, f32::NEG_INFINITY, -0.25, 3.0, 0.999]
            .iter()
            .map(|v| v.to_le_bytes().to_vec())
            .collect(),
        _ => Vec::new(),
    };
    for (i, s) in specials.iter().enumerate() {
        let at = i * s.len() * 3;
        if at + s.len() <= bytes.len() {
            bytes[at..at + s.len()].copy_from_slice(s);
        }
    }
    TargetImage {
        name: "t".into(),
        width,
        height,
        format,
        bytes,
    }
}

/// `to_rgba8` as it was written before, texel by texel. An sRGB target's
/// RGBA8 is its stored (encoded) bytes, as its PNG holds them, while its
/// texels are decoded: the bytes are the definition there.
fn rgba8_per_texel(t: &TargetImage) -> Vec<u8> {
    if t.format == Format::Rgba8unormSrgb {
        return t.bytes.clone();
    }
    let mut out = Vec::new();
    for y in 0..t.height {
        for x in 0..t.width {
            let v = t.texel(x, y);
            let v = if t.format.channels() == 1 {
                [v[0], v[0], v[0], 1.0]
            } else {
                v
            };
            let q = |c: f32| (if c.is_finite() { c } else { 0.0 }.clamp(0.0, 1.0) * 255.0).round() as u8;
            out.extend(v.map(q));
        }
    }
    out
}

#[test]
fn whole_image_conversions_equal_the_per_texel_definition_for_every_format() {
    for &(name, format) in Format::ALL {
        let t = image(format, 7, 5);
        let all = t.to_rgba_f32();
        assert_eq!(all.len(), 35, "{name}");
        for y in 0..t.height {
            for x in 0..t.width {
                let got = all[(y * t.width + x) as usize].map(f32::to_bits);
                assert_eq!(got, t.texel(x, y).map(f32::to_bits), "{name} texel ({x}, {y})");
            }
        }
        assert_eq!(t.to_rgba8().into_raw(), rgba8_per_texel(&t), "{name} as RGBA8");
    }
}

#[test]
fn png_decodes_to_the_same_pixels_at_8_and_16_bits() {
    let unorm = image(Format::Rgba8unorm, 9, 4);
    let png = npr_runner::output::encode_png(&unorm).expect("encode 8-bit");
    let decoded = image::load_from_memory(&png).expect("decode 8-bit");
    assert!(matches!(decoded, image::DynamicImage::ImageRgba8(_)));
    assert_eq!(decoded.to_rgba8().into_raw(), unorm.to_rgba8().into_raw());

    let float = image(Format::Rgba16float, 9, 4);
    let png = npr_runner::output::encode_png(&float).expect("encode 16-bit");
    let image::DynamicImage::ImageRgba16(decoded) = image::load_from_memory(&png).expect("decode 16-bit") else {
        panic!("a float target is a 16-bit RGBA PNG");
    };
    let expected: Vec<u16> = float
        .to_rgba_f32()
        .into_iter()
        .flat_map(|p| p.map(|c| (if c.is_finite() { c } else { 0.0 }.clamp(0.0, 1.0) * 65535.0).round() as u16))
        .collect();
    assert_eq!(decoded.into_raw(), expected);
}

/// The sRGB EOTF in f64 (IEC 61966-2-1).
fn srgb_decode(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn an_srgb_target_reads_back_linear_and_its_exr_holds_linear_light() {
    // Every byte value in every channel.
    let bytes: Vec<u8> = (0..=255u8).flat_map(|b| [b, 255 - b, b, b]).collect();
    let t = TargetImage {
        name: "shade".into(),
        width: 16,
        height: 16,
        format: Format::Rgba8unormSrgb,
        bytes,
    };
    let texels = t.to_rgba_f32();
    for (i, texel) in texels.iter().enumerate() {
        let stored = &t.bytes[i * 4..i * 4 + 4];
        for c in 0..3 {
            let want = srgb_decode(f64::from(stored[c]) / 255.0);
            assert!(
                (f64::from(texel[c]) - want).abs() < 1e-6,
                "texel {i} channel {c}: {} vs {want}",
                texel[c]
            );
        }
        assert_eq!(texel[3], f32::from(stored[3]) / 255.0, "alpha is not encoded");
    }
    // The PNG keeps the encoded bytes (a PNG is sRGB)...
    assert_eq!(t.to_rgba8().into_raw(), t.bytes);
    // ...and an EXR, single or layered, holds the linear values.
    let dir = std::env::temp_dir().join("npr-readback-srgb");
    std::fs::create_dir_all(&dir).expect("scratch");
    let single = dir.join("single.exr");
    npr_runner::output::write_target(&t, &single).expect("write exr");
    let read = image::open(&single).expect("read exr").to_rgba32f();
    for (got, want) in read.pixels().zip(&texels) {
        assert_eq!(got.0, *want);
    }
    let layered = npr_runner::exr_layers::encode_layers(std::slice::from_ref(&t)).expect("layers");
    let read = image::load_from_memory(&layered)
        .expect("read layered exr")
        .to_rgba32f();
    for (got, want) in read.pixels().zip(&texels) {
        assert_eq!(&got.0[..3], &want[..3]);
    }
}
