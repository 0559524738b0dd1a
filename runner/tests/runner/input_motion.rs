//! Motion vectors as Bevy's `MotionVectorPrepass` writes them (the change
//! of UV, in fractions of the image) become the language's pixels in the
//! conversion draw (`npr_runner::inputs::gpu`, mode 5), on the GPU: each
//! texel's value times the image's size, against the f64 product; motion
//! already in pixels passes through as it is.

// The shared test module makes its textures with wgpu directly (not counted).
#![allow(clippy::disallowed_methods)]

use crate::common;

use npr_abi::InputKind;
use npr_runner::artmap::Level;
use npr_runner::inputs::{converted, Conversion, HostImage, MotionConvention, SourceConvention};

/// A 12×5 image of distinct motions, some of them negative.
fn motions() -> Level {
    let (width, height) = (12u32, 5u32);
    let pixels = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| [(x as f32 - 5.5) * 0.013, (y as f32 - 2.0) * -0.021, 0.0, 1.0])
        .collect();
    Level { width, height, pixels }
}

fn convert(source: MotionConvention) -> Level {
    let g = common::gpu();
    let conversion =
        Conversion::resolve(InputKind::Motion, SourceConvention::Motion(source), None, false).expect("motion converts");
    converted(
        &g.device,
        &g.queue,
        &HostImage {
            raw: motions(),
            conversion,
        },
    )
    .expect("convert on the GPU")
}

#[test]
fn motion_in_fractions_of_the_image_becomes_pixels() {
    let raw = motions();
    let out = convert(MotionConvention::ScreenFraction);
    for (i, (r, o)) in raw.pixels.iter().zip(&out.pixels).enumerate() {
        let expected = [r[0] as f64 * raw.width as f64, r[1] as f64 * raw.height as f64];
        for (c, (got, want)) in o.iter().zip(expected).enumerate() {
            // The input texture holds half floats: 11 significant bits.
            let bound = want.abs() / 1024.0 + 1e-6;
            assert!(
                (*got as f64 - want).abs() <= bound,
                "texel {i}, channel {c}: {got} for {want} (bound {bound})"
            );
        }
    }
    // Not the identity: the scale is applied.
    assert!(out
        .pixels
        .iter()
        .zip(&raw.pixels)
        .any(|(o, r)| (o[0] - r[0]).abs() > 0.1));
}

#[test]
fn motion_in_pixels_is_taken_as_it_is() {
    let raw = motions();
    let out = convert(MotionConvention::Pixels);
    for (r, o) in raw.pixels.iter().zip(&out.pixels) {
        for (got, want) in o.iter().zip(r).take(2) {
            assert!((got - want).abs() <= want.abs() / 1024.0 + 1e-6, "{o:?} for {r:?}");
        }
    }
}
