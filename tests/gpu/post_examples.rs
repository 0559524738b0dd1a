//! The styles of `examples/post/` over a real renderer's frame (issue 47):
//! Blender's passes of a small scene (`blender_scene.rs`), each style
//! checked against what it must do, not against a stored image.
//!
//! - `lsa_over.npr` rebuilds positions from the host's depth and the camera:
//!   its contours over Blender's passes are those `lsa_contours.npr` finds
//!   in npr's own G-buffer of the mirrored scene, within 1 px.
//! - `breakup_over.npr` only moves the host's colour: every pixel is a
//!   pixel of Blender's colour at most `roughness` px away, and with no
//!   roughness it is Blender's colour unchanged.
//! - `watercolor_over.npr` with its density terms off is the blurred
//!   colour (eq. 1 with d = 1), and with edge darkening alone only darkens
//!   (d >= 1), most where the colour changes.

use crate::blender_scene::{blender, channel, npr, scratch};
use npr_runner::inputs::files::{read_exr, ExrChannels};

/// Line pixels of an LSA style's line-density target (`thin.e`, read
/// from `npr render --layers`): the largest direction error over one half,
/// the middle of the remapped range.
fn lsa_lines(exr: &ExrChannels) -> Vec<Vec<bool>> {
    let e = ["R", "G", "B", "A"].map(|c| channel(exr, &format!("thin.e.{c}")));
    let (w, h) = (exr.width as usize, exr.height as usize);
    (0..h)
        .map(|y| {
            (0..w)
                .map(|x| e.iter().map(|c| c[y * w + x]).fold(0.0f32, f32::max) > 0.5)
                .collect()
        })
        .collect()
}

/// Whether `m` is set within `r` pixels (Chebyshev) of (x, y).
fn near(m: &[Vec<bool>], x: usize, y: usize, r: usize) -> bool {
    let (h, w) = (m.len(), m[0].len());
    (y.saturating_sub(r)..(y + r + 1).min(h)).any(|yy| (x.saturating_sub(r)..(x + r + 1).min(w)).any(|xx| m[yy][xx]))
}

#[test]
fn lsa_over_blenders_passes_finds_the_contours_lsa_finds_in_npr_own_gbuffer() {
    let (exr, toml) = blender();
    let passes = read_exr("passes", exr).expect("read Blender's EXR");
    let size = format!("{}x{}", passes.width, passes.height);
    let over = scratch("lsa_over_blender.exr");
    npr(&[
        "render",
        "examples/post/lsa_over.npr",
        "--inputs",
        exr.to_str().unwrap(),
        "--scene",
        toml.to_str().unwrap(),
        "--layers",
        "-o",
        over.to_str().unwrap(),
    ]);
    let own = scratch("lsa_contours_npr.exr");
    npr(&[
        "render",
        "examples/lsa_contours.npr",
        "--scene",
        toml.to_str().unwrap(),
        "--size",
        &size,
        "--layers",
        "-o",
        own.to_str().unwrap(),
    ]);
    let theirs = lsa_lines(&read_exr("over", &over).expect("read lsa_over's layers"));
    let ours = lsa_lines(&read_exr("own", &own).expect("read lsa_contours' layers"));
    let (h, w) = (ours.len(), ours[0].len());
    let count = |m: &[Vec<bool>]| m.iter().flatten().filter(|v| **v).count();
    assert!(
        count(&ours) > 150 && count(&theirs) > 150,
        "both find contours: {} and {}",
        count(&ours),
        count(&theirs)
    );
    // Each line pixel of either has one of the other's within 1 px.
    for (a, b, what) in [
        (&theirs, &ours, "over Blender's passes"),
        (&ours, &theirs, "in npr's G-buffer"),
    ] {
        let lone: Vec<(usize, usize)> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| a[y][x] && !near(b, x, y, 1))
            .collect();
        assert!(
            lone.is_empty(),
            "{} of {} line pixels {what} have none of the other's within 1 px, e.g. {:?} (layers: {} and {})",
            lone.len(),
            count(a),
            &lone[..lone.len().min(8)],
            over.display(),
            own.display()
        );
    }
}

/// Blender's beauty pass as `input(color, display)` gives it to a style:
/// linear light clamped to [0, 1], sRGB-encoded, in f64; per pixel, RGB.
fn blender_display_colour(passes: &ExrChannels) -> Vec<[f64; 3]> {
    let rgb = ["R", "G", "B"].map(|c| channel(passes, &format!("ViewLayer.Combined.{c}")));
    (0..rgb[0].len())
        .map(|i| {
            rgb.map(|ch| {
                let linear = (ch[i] as f64).clamp(0.0, 1.0);
                if linear <= 0.0031308 {
                    12.92 * linear
                } else {
                    1.055 * linear.powf(1.0 / 2.4) - 0.055
                }
            })
        })
        .collect()
}

/// `style` over Blender's passes with `sets` (`--set` arguments), as 8-bit RGB.
fn render_over(style: &str, name: &str, sets: &[&str]) -> (image::RgbImage, std::path::PathBuf) {
    let (exr, toml) = blender();
    let out = scratch(name);
    let mut args = vec![
        "render",
        style,
        "--inputs",
        exr.to_str().unwrap(),
        "--scene",
        toml.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    for set in sets {
        args.extend(["--set", set]);
    }
    npr(&args);
    (image::open(&out).expect("read output").to_rgb8(), out)
}

#[test]
fn breakup_over_moves_blenders_colour_by_at_most_its_roughness() {
    let passes = read_exr("passes", &blender().0).expect("read Blender's EXR");
    let (w, h) = (passes.width as usize, passes.height as usize);
    let expected: Vec<[f64; 3]> = blender_display_colour(&passes)
        .into_iter()
        .map(|c| c.map(|v| (v * 255.0).round()))
        .collect();
    let matches = |p: &image::Rgb<u8>, i: usize| (0..3).all(|c| (p.0[c] as f64 - expected[i][c]).abs() <= 1.0);
    // No roughness: Blender's colour unchanged (within one 8-bit step of
    // the f64 encoding: the input is stored as a half float).
    let (still, still_out) = render_over(
        "examples/post/breakup_over.npr",
        "breakup_still.png",
        &["roughness=0px"],
    );
    for (x, y, p) in still.enumerate_pixels() {
        assert!(
            matches(p, y as usize * w + x as usize),
            "pixel ({x}, {y}) is {:?}, Blender's colour is {:?} (image: {})",
            p.0,
            expected[y as usize * w + x as usize],
            still_out.display()
        );
    }
    // Roughness 6 px: each pixel is one of Blender's within 6 px (the warp
    // reads the nearest texel, so 7 with rounding), and the edges moved.
    let (rough, rough_out) = render_over(
        "examples/post/breakup_over.npr",
        "breakup_rough.png",
        &["roughness=6px"],
    );
    let reach = 7i64;
    let mut moved = 0;
    for (x, y, p) in rough.enumerate_pixels() {
        let (x, y) = (x as i64, y as i64);
        let found = (-reach..=reach).any(|dy| {
            (-reach..=reach).any(|dx| {
                let (sx, sy) = (x + dx, y + dy);
                sx >= 0 && sy >= 0 && sx < w as i64 && sy < h as i64 && matches(p, sy as usize * w + sx as usize)
            })
        });
        assert!(
            found,
            "pixel ({x}, {y}) {:?} is no colour of Blender's within {reach} px (image: {})",
            p.0,
            rough_out.display()
        );
        if !matches(p, y as usize * w + x as usize) {
            moved += 1;
        }
    }
    assert!(
        moved > w * h / 100,
        "the breakup moves the colour at its edges: {moved} pixels changed (image: {})",
        rough_out.display()
    );
}

/// The separable Gaussian of `gaussian.wgsl` in f64 (taps at texel centres,
/// weights exp(−d²/2σ²) normalised, radius ⌈3σ⌉, clamp to edge), x then y.
fn gaussian_f64(img: &[[f64; 3]], w: usize, h: usize, sigma: f64) -> Vec<[f64; 3]> {
    let radius = (3.0 * sigma).ceil() as i64;
    let weights: Vec<f64> = (-radius..=radius)
        .map(|i| (-(i * i) as f64 / (2.0 * sigma * sigma)).exp())
        .collect();
    let total: f64 = weights.iter().sum();
    let pass = |src: &[[f64; 3]], dx: i64, dy: i64| -> Vec<[f64; 3]> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as i64, (i / w) as i64);
                let mut acc = [0.0; 3];
                for (k, wt) in (-radius..=radius).zip(&weights) {
                    let sx = (x + dx * k).clamp(0, w as i64 - 1) as usize;
                    let sy = (y + dy * k).clamp(0, h as i64 - 1) as usize;
                    for c in 0..3 {
                        acc[c] += wt * src[sy * w + sx][c];
                    }
                }
                acc.map(|v| v / total)
            })
            .collect()
    };
    pass(&pass(img, 1, 0), 0, 1)
}

#[test]
fn watercolor_over_is_the_blurred_colour_with_its_density_off_and_edge_darkening_only_darkens() {
    let passes = read_exr("passes", &blender().0).expect("read Blender's EXR");
    let (w, h) = (passes.width as usize, passes.height as usize);
    let sigma = 1.5;
    let blurred = gaussian_f64(&blender_display_colour(&passes), w, h, sigma);
    let off = ["grain=0", "turbulence=0", "edge_darkening=0", "softness=1.5"];
    let (plain, plain_out) = render_over("examples/post/watercolor_over.npr", "watercolor_plain.png", &off);
    // d = 1: eq. 1 leaves the blurred colour, within one 8-bit step (the
    // blur runs on half floats).
    for (x, y, p) in plain.enumerate_pixels() {
        let b = blurred[y as usize * w + x as usize];
        for (c, (got, want)) in p.0.iter().zip(b).enumerate() {
            assert!(
                (*got as f64 - (want * 255.0).round()).abs() <= 1.0,
                "pixel ({x}, {y}) channel {c}: {got} where the f64 blur gives {:.1} (image: {})",
                want * 255.0,
                plain_out.display()
            );
        }
    }
    // Edge darkening alone: d = 1 + 0.8·edge >= 1, so C' = C − (C − C²)(d − 1)
    // is never lighter than C, and is darker on the colour's edges.
    let edges = ["grain=0", "turbulence=0", "edge_darkening=0.8", "softness=1.5"];
    let (dark, dark_out) = render_over("examples/post/watercolor_over.npr", "watercolor_edges.png", &edges);
    let mut darker = 0;
    for (x, y, p) in dark.enumerate_pixels() {
        let q = plain.get_pixel(x, y);
        assert!(
            (0..3).all(|c| p.0[c] <= q.0[c].saturating_add(1)),
            "pixel ({x}, {y}) is lighter with edge darkening: {:?} against {:?} (image: {})",
            p.0,
            q.0,
            dark_out.display()
        );
        if (0..3).any(|c| p.0[c] + 8 < q.0[c]) {
            darker += 1;
        }
    }
    assert!(
        darker > w * h / 100,
        "edge darkening darkens the colour's edges: {darker} pixels by more than 8 steps (image: {})",
        dark_out.display()
    );
}
