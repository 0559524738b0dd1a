//! The test harness: compare a rendered image with a golden image, either by
//! a per-pixel bound or by NVIDIA's FLIP perceptual metric, and on failure
//! write the actual image and a diff image next to the golden.

use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Copy)]
pub enum Tolerance {
    /// Every channel of every pixel within `max_abs` (0..255), allowing
    /// `outlier_fraction` of pixels to exceed it (rasterization differences
    /// along edges between drivers).
    PerPixel { max_abs: u8, outlier_fraction: f64 },
    /// Mean FLIP error at most `max_mean` (0 = identical, 1 = maximal).
    Flip { max_mean: f32 },
}

#[derive(Debug, Clone)]
pub struct Comparison {
    pub passed: bool,
    pub max_abs: u8,
    pub outlier_fraction: f64,
    pub flip_mean: Option<f32>,
    pub summary: String,
    /// Written on failure: (actual, diff).
    pub written: Option<(PathBuf, PathBuf)>,
}

/// Compare `actual` with the golden PNG at `golden`. If the golden does not
/// exist and `NPR_UPDATE_GOLDENS=1`, it is created (and the comparison passes);
/// otherwise a missing golden is a failure.
pub fn compare_with_golden(actual: &image::RgbaImage, golden: &Path, tol: Tolerance) -> Comparison {
    let update = std::env::var("NPR_UPDATE_GOLDENS").is_ok_and(|v| v == "1");
    compare_with_golden_file(actual, golden, tol, update)
}

/// As [`compare_with_golden`], with the update mode given explicitly.
pub fn compare_with_golden_file(actual: &image::RgbaImage, golden: &Path, tol: Tolerance, update: bool) -> Comparison {
    let expected = match image::open(golden) {
        Ok(img) if !update => img.to_rgba8(),
        _ if update => {
            let ok = npr_runner::output::write_png8(actual, golden).is_ok();
            return Comparison {
                passed: ok,
                max_abs: 0,
                outlier_fraction: 0.0,
                flip_mean: None,
                summary: format!("golden {} written (NPR_UPDATE_GOLDENS=1)", golden.display()),
                written: None,
            };
        }
        Err(e) => {
            let written = write_failure(actual, None, golden);
            return Comparison {
                passed: false,
                max_abs: 255,
                outlier_fraction: 1.0,
                flip_mean: None,
                summary: format!(
                    "cannot read golden {}: {e} (run with NPR_UPDATE_GOLDENS=1 to create it)",
                    golden.display()
                ),
                written,
            };
        }
        Ok(_) => unreachable!("handled by the first arm"),
    };
    if expected.dimensions() != actual.dimensions() {
        let written = write_failure(actual, None, golden);
        return Comparison {
            passed: false,
            max_abs: 255,
            outlier_fraction: 1.0,
            flip_mean: None,
            summary: format!(
                "size {:?} differs from golden {:?}",
                actual.dimensions(),
                expected.dimensions()
            ),
            written,
        };
    }
    let (max_abs, outliers) = per_pixel(
        actual,
        &expected,
        match tol {
            Tolerance::PerPixel { max_abs, .. } => max_abs,
            Tolerance::Flip { .. } => 0,
        },
    );
    let total = (actual.width() * actual.height()).max(1) as f64;
    let outlier_fraction = outliers as f64 / total;
    let (passed, flip_mean, summary) = match tol {
        Tolerance::PerPixel {
            max_abs: bound,
            outlier_fraction: allowed,
        } => (
            outlier_fraction <= allowed,
            None,
            format!(
                "max |Δ| = {max_abs}/255, {:.4}% of pixels over {bound} (allowed {:.4}%)",
                outlier_fraction * 100.0,
                allowed * 100.0
            ),
        ),
        Tolerance::Flip { max_mean } => {
            let mean = flip_mean(actual, &expected);
            (
                mean <= max_mean,
                Some(mean),
                format!("mean FLIP = {mean:.5} (allowed {max_mean}), max |Δ| = {max_abs}/255"),
            )
        }
    };
    let written = if passed {
        None
    } else {
        write_failure(actual, Some(&expected), golden)
    };
    Comparison {
        passed,
        max_abs,
        outlier_fraction,
        flip_mean,
        summary,
        written,
    }
}

/// (largest channel difference, number of pixels whose difference exceeds `bound`).
pub fn per_pixel(a: &image::RgbaImage, b: &image::RgbaImage, bound: u8) -> (u8, usize) {
    let mut max = 0u8;
    let mut over = 0usize;
    for (pa, pb) in a.pixels().zip(b.pixels()) {
        let d =
            pa.0.iter()
                .zip(pb.0.iter())
                .map(|(x, y)| x.abs_diff(*y))
                .max()
                .unwrap_or(0);
        max = max.max(d);
        if d > bound {
            over += 1;
        }
    }
    (max, over)
}

fn rgb8(img: &image::RgbaImage) -> nv_flip::FlipImageRgb8 {
    let data: Vec<u8> = img.pixels().flat_map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
    nv_flip::FlipImageRgb8::with_data(img.width(), img.height(), &data)
}

/// Mean FLIP error between two same-sized images.
pub fn flip_mean(a: &image::RgbaImage, b: &image::RgbaImage) -> f32 {
    let map = nv_flip::flip(rgb8(b), rgb8(a), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    nv_flip::FlipPool::from_image(&map).mean()
}

/// A picture of where two same-sized images differ: cyan where equal, red
/// where any channel differs, darker the larger the difference (×8, so a
/// difference of a few levels is visible).
pub fn diff_image(actual: &image::RgbaImage, expected: &image::RgbaImage) -> image::RgbaImage {
    image::RgbaImage::from_fn(actual.width(), actual.height(), |x, y| {
        let (a, b) = (actual.get_pixel(x, y).0, expected.get_pixel(x, y).0);
        let d = a.iter().zip(b.iter()).map(|(p, q)| p.abs_diff(*q)).max().unwrap_or(0);
        let v = (d as u32 * 8).min(255) as u8;
        image::Rgba([if d > 0 { 255 } else { 0 }, 255 - v, 255 - v, 255])
    })
}

/// FLIP's error at every pixel of `actual` against `reference` (same size;
/// row-major, 0 = identical, 1 = maximal), and the map coloured with
/// FLIP's magma scale for people to look at.
pub fn flip_error_map(actual: &image::RgbaImage, reference: &image::RgbaImage) -> (Vec<f32>, image::RgbaImage) {
    let map = nv_flip::flip(rgb8(reference), rgb8(actual), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let coloured = map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    let picture = image::RgbaImage::from_fn(map.width(), map.height(), |x, y| {
        let i = 3 * (y * map.width() + x) as usize;
        image::Rgba([coloured[i], coloured[i + 1], coloured[i + 2], 255])
    });
    (map.to_vec(), picture)
}

/// The error that `percentile` % of `errors` are at or under (the
/// nearest-rank percentile: exact, no histogram buckets); 0 for no errors.
pub fn percentile(errors: &[f32], percentile: f64) -> f32 {
    if errors.is_empty() {
        return 0.0;
    }
    let mut sorted = errors.to_vec();
    sorted.sort_by(f32::total_cmp);
    let rank = ((percentile / 100.0) * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

fn write_failure(
    actual: &image::RgbaImage,
    expected: Option<&image::RgbaImage>,
    golden: &Path,
) -> Option<(PathBuf, PathBuf)> {
    let dir = std::env::var_os("NPR_TEST_OUTPUT")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/npr-test-output"));
    let stem = golden
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "image".into());
    let actual_path = dir.join(format!("{stem}.actual.png"));
    let diff_path = dir.join(format!("{stem}.diff.png"));
    npr_runner::output::write_png8(actual, &actual_path).ok()?;
    let diff = match expected {
        Some(e) => diff_image(actual, e),
        None => actual.clone(),
    };
    npr_runner::output::write_png8(&diff, &diff_path).ok()?;
    Some((actual_path, diff_path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_are_nearest_rank() {
        let errors: Vec<f32> = (1..=100).map(|i| i as f32 / 100.0).collect();
        assert_eq!(percentile(&errors, 99.0), 0.99);
        assert_eq!(percentile(&errors, 50.0), 0.5);
        assert_eq!(percentile(&errors, 100.0), 1.0);
        assert_eq!(percentile(&[0.3], 1.0), 0.3);
        assert_eq!(percentile(&[], 99.0), 0.0);
    }

    #[test]
    fn the_flip_map_is_zero_for_equal_images_and_not_for_different_ones() {
        let a = image::RgbaImage::from_pixel(8, 8, image::Rgba([40, 90, 200, 255]));
        let (same, picture) = flip_error_map(&a, &a);
        assert!(same.iter().all(|e| *e == 0.0) && picture.dimensions() == (8, 8));
        let b = image::RgbaImage::from_pixel(8, 8, image::Rgba([240, 90, 20, 255]));
        let (differ, _) = flip_error_map(&b, &a);
        assert!(differ.iter().all(|e| *e > 0.1), "{differ:?}");
    }
}
