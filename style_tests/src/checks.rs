//! What `npr test` checks of the images a test rendered, as functions of
//! the images alone (the rendering is in `run.rs`): every float target
//! finite, the output not one colour, two runs equal byte for byte, and
//! the output against its golden within the declared tolerance.

use super::declare::Golden;
use npr_runner::TargetImage;

/// Where a target holds NaN or ±Inf.
#[derive(Debug, Clone, PartialEq)]
pub struct NonFinite {
    /// Texels with at least one non-finite channel.
    pub count: usize,
    /// The first of them, row by row from the top left.
    pub first: (u32, u32),
    pub first_value: [f32; 4],
}

/// The non-finite texels of `target`, if any. An 8-bit target cannot hold
/// one (the conversion to unorm hides a NaN as 0), which is why every float
/// target is read back and not only the output.
pub fn non_finite(target: &TargetImage) -> Option<NonFinite> {
    if target.format.is_unorm() {
        return None;
    }
    let texels = target.to_rgba_f32();
    let bad = |t: &[f32; 4]| t.iter().any(|c| !c.is_finite());
    let first = texels.iter().position(bad)?;
    Some(NonFinite {
        count: texels.iter().filter(|t| bad(t)).count(),
        first: (
            (first % target.width as usize) as u32,
            (first / target.width as usize) as u32,
        ),
        first_value: texels[first],
    })
}

/// The colour of an image that has only one, `None` for any other.
pub fn single_colour(image: &image::RgbaImage) -> Option<[u8; 4]> {
    let mut pixels = image.pixels();
    let first = pixels.next()?.0;
    pixels.all(|p| p.0 == first).then_some(first)
}

/// The first byte at which two renders of the same frame differ.
pub fn first_difference(a: &[u8], b: &[u8]) -> Option<usize> {
    if a.len() != b.len() {
        return Some(a.len().min(b.len()));
    }
    a.iter().zip(b).position(|(x, y)| x != y)
}

/// The mean absolute change of a channel (0..1) between two frames of the
/// same size: what `flicker` bounds over a still camera.
pub fn frame_change(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let total: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(x, y)| u64::from(x.abs_diff(*y)))
        .sum();
    total as f64 / (255.0 * a.as_raw().len().max(1) as f64)
}

/// The output compared with its golden under each declared bound.
#[derive(Debug, Clone)]
pub struct GoldenVerdict {
    pub passed: bool,
    /// One line per bound: measured, allowed, and whether it held.
    pub lines: Vec<String>,
    /// The coloured FLIP map (when a FLIP bound was declared) and the diff,
    /// for the files written on failure.
    pub flip_picture: Option<image::RgbaImage>,
    pub diff: image::RgbaImage,
}

/// Compare `actual` with `expected` (the same size) under `golden`'s bounds.
pub fn compare(actual: &image::RgbaImage, expected: &image::RgbaImage, golden: &Golden) -> GoldenVerdict {
    let mut passed = true;
    let mut lines = Vec::new();
    let mut check = |ok: bool, line: String| {
        passed &= ok;
        lines.push(format!("{} {line}", if ok { "ok:" } else { "FAILED:" }));
    };
    if let Some(bound) = golden.per_pixel {
        let (max_abs, over) = npr_lab::harness::per_pixel(actual, expected, bound.max);
        let share = over as f64 / f64::from((actual.width() * actual.height()).max(1));
        check(
            share <= bound.outliers,
            format!(
                "per pixel: {:.3}% of pixels differ by more than {}/255 (allowed {:.3}%), largest difference {max_abs}/255",
                share * 100.0,
                bound.max,
                bound.outliers * 100.0
            ),
        );
    }
    let mut flip_picture = None;
    if let Some(bound) = &golden.flip {
        let (errors, picture) = npr_lab::harness::flip_error_map(actual, expected);
        flip_picture = Some(picture);
        if let Some(max_mean) = bound.mean {
            let mean = errors.iter().map(|e| f64::from(*e)).sum::<f64>() / errors.len().max(1) as f64;
            check(mean <= max_mean, format!("FLIP mean {mean:.5} (allowed {max_mean})"));
        }
        for (pct, max) in &bound.percentiles {
            let at = f64::from(npr_lab::harness::percentile(&errors, *pct));
            check(at <= *max, format!("FLIP p{pct} {at:.5} (allowed {max})"));
        }
    }
    GoldenVerdict {
        passed,
        lines,
        flip_picture,
        diff: npr_lab::harness::diff_image(actual, expected),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::declare::{FlipBound, PerPixelBound};
    use npr_diag::Span;
    use npr_runner::scene::toml_fields::At;

    fn golden(flip: Option<FlipBound>, per_pixel: Option<PerPixelBound>) -> Golden {
        Golden {
            path: At {
                value: "g.png".into(),
                span: Span::default(),
            },
            flip,
            per_pixel,
        }
    }

    #[test]
    fn a_float_target_with_nan_is_found_at_its_first_texel() {
        let mut bytes = Vec::new();
        for v in [1.0f32, f32::NAN, 2.0, f32::INFINITY] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let t = TargetImage {
            name: "n".into(),
            width: 2,
            height: 2,
            format: npr_abi::Format::R32float,
            bytes,
        };
        let found = non_finite(&t).expect("non-finite texels");
        assert_eq!((found.count, found.first), (2, (1, 0)));
    }

    #[test]
    fn one_colour_is_blank_and_two_are_not() {
        let mut img = image::RgbaImage::from_pixel(4, 4, image::Rgba([9, 9, 9, 255]));
        assert_eq!(single_colour(&img), Some([9, 9, 9, 255]));
        img.put_pixel(3, 3, image::Rgba([9, 9, 10, 255]));
        assert_eq!(single_colour(&img), None);
    }

    #[test]
    fn frame_change_is_the_mean_channel_difference() {
        let a = image::RgbaImage::from_pixel(2, 2, image::Rgba([0, 0, 0, 255]));
        let mut b = a.clone();
        b.put_pixel(0, 0, image::Rgba([255, 255, 255, 255]));
        // 3 channels of 16 moved by 1.0.
        assert!((frame_change(&a, &b) - 3.0 / 16.0).abs() < 1e-12);
        assert_eq!(frame_change(&a, &a), 0.0);
    }

    #[test]
    fn each_declared_bound_is_checked() {
        let a = image::RgbaImage::from_pixel(64, 64, image::Rgba([100, 100, 100, 255]));
        let mut b = a.clone();
        b.put_pixel(0, 0, image::Rgba([200, 100, 100, 255]));
        let lenient = PerPixelBound { max: 2, outliers: 0.02 };
        let strict = PerPixelBound { max: 2, outliers: 0.0 };
        assert!(compare(&b, &a, &golden(None, Some(lenient))).passed);
        assert!(!compare(&b, &a, &golden(None, Some(strict))).passed);
        // FLIP spreads a pixel's error over its neighbours, but most of
        // the image is untouched: the median error is 0...
        let p50 = FlipBound {
            mean: None,
            percentiles: vec![(50.0, 0.0)],
        };
        assert!(compare(&b, &a, &golden(Some(p50), None)).passed);
        // ...and a zero mean does not hold.
        let p50_and_mean = FlipBound {
            mean: Some(0.0),
            percentiles: vec![(50.0, 0.05)],
        };
        let v = compare(&b, &a, &golden(Some(p50_and_mean), Some(lenient)));
        assert!(!v.passed && v.lines.len() == 3, "{:?}", v.lines);
    }
}
