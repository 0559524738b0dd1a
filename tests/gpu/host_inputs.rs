//! A style over a real renderer's frame (issue 47): Blender (Cycles, CPU,
//! headless) renders a small scene's passes into a multi-layer EXR
//! (`tests/data/blender/render_passes.py`), and `examples/post/ink_over.npr`
//! runs over them with `npr render --inputs`. The script also writes the
//! same scene as an npr scene, which npr's own G-buffer style
//! (`tests/data/blender/gbuffer.npr`) renders into EXR layers, the same
//! style's inputs: the two ink images must agree.
//!
//! Blender runs in the test (about 3 s here) rather than a committed EXR:
//! the test then checks what this Blender writes, not a file that could
//! drift from the script, and nothing binary is committed.

use crate::blender_scene::{blender, channel, npr, scratch};
use npr_runner::inputs::files::{read_exr, ExrChannels};
use std::path::PathBuf;

const STYLE: &str = "examples/post/ink_over.npr";
const INK: [u8; 3] = [20, 20, 20];

/// The style over Blender's passes: the image, and its path (kept for a
/// failure to look at).
fn ink_over_blender() -> (image::RgbaImage, PathBuf) {
    let (exr, toml) = blender();
    let out = scratch("ink_over_blender.png");
    npr(&[
        "render",
        STYLE,
        "--inputs",
        exr.to_str().unwrap(),
        "--scene",
        toml.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    (image::open(&out).expect("read output").to_rgba8(), out)
}

fn inked(img: &image::RgbaImage) -> Vec<Vec<bool>> {
    (0..img.height())
        .map(|y| (0..img.width()).map(|x| img.get_pixel(x, y).0[..3] == INK).collect())
        .collect()
}

/// Whether `m` is set within one pixel (8-neighbourhood) of (x, y).
fn near(m: &[Vec<bool>], x: usize, y: usize) -> bool {
    let (h, w) = (m.len(), m[0].len());
    (y.saturating_sub(1)..(y + 2).min(h)).any(|yy| (x.saturating_sub(1)..(x + 2).min(w)).any(|xx| m[yy][xx]))
}

/// Where Blender's own depth jumps, measured in f64 from the EXR: between
/// a pixel and its right or lower neighbour, the depths (Cycles' 1e10 for
/// the background taken as infinitely far) differ by more than `ratio` of
/// the nearer one. Both pixels of a jump are marked.
fn depth_jumps(exr: &ExrChannels, ratio: f64) -> Vec<Vec<bool>> {
    let z = channel(exr, "ViewLayer.Depth.Z");
    let (w, h) = (exr.width as usize, exr.height as usize);
    let d = |x: usize, y: usize| {
        let v = z[y * w + x] as f64;
        if v >= 1e9 {
            f64::INFINITY
        } else {
            v
        }
    };
    let mut m = vec![vec![false; w]; h];
    for y in 0..h {
        for x in 0..w {
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                if nx >= w || ny >= h {
                    continue;
                }
                let (a, b) = (d(x, y), d(nx, ny));
                let nearer = a.min(b);
                let jump = if a.is_infinite() && b.is_infinite() {
                    0.0
                } else {
                    (a - b).abs()
                };
                if jump > ratio * nearer {
                    m[y][x] = true;
                    m[ny][nx] = true;
                }
            }
        }
    }
    m
}

/// Where Blender's normals turn by more than `threshold` (|Δn|) between a
/// pixel and its right or lower neighbour.
fn normal_creases(exr: &ExrChannels, threshold: f64) -> Vec<Vec<bool>> {
    let c = ["X", "Y", "Z"].map(|a| channel(exr, &format!("ViewLayer.Normal.{a}")));
    let (w, h) = (exr.width as usize, exr.height as usize);
    let n = |x: usize, y: usize| c.map(|ch| ch[y * w + x] as f64);
    let mut m = vec![vec![false; w]; h];
    for y in 0..h {
        for x in 0..w {
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                if nx >= w || ny >= h {
                    continue;
                }
                let (a, b) = (n(x, y), n(nx, ny));
                let diff = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                if diff > threshold {
                    m[y][x] = true;
                    m[ny][nx] = true;
                }
            }
        }
    }
    m
}

#[test]
fn ink_over_blender_draws_its_lines_on_blenders_depth_discontinuities() {
    let (exr_path, _) = blender();
    let exr = read_exr("passes", exr_path).expect("read Blender's EXR");
    let (img, out) = ink_over_blender();
    assert_eq!(
        (img.width(), img.height()),
        (exr.width, exr.height),
        "rendered at the inputs' size"
    );
    let ink = inked(&img);
    // Every large jump of Blender's depth (silhouettes: a quarter of the
    // nearer depth, far above the style's 8 %) is inked within 1 px.
    let jumps = depth_jumps(&exr, 0.25);
    let (w, h) = (exr.width as usize, exr.height as usize);
    let jump_count = jumps.iter().flatten().filter(|j| **j).count();
    assert!(jump_count > 200, "the scene has silhouettes: {jump_count} jump pixels");
    let missed: Vec<(usize, usize)> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| jumps[y][x] && !near(&ink, x, y))
        .collect();
    assert!(
        missed.is_empty(),
        "{} of {jump_count} depth-jump pixels have no ink within 1 px, e.g. {:?} (image: {})",
        missed.len(),
        &missed[..missed.len().min(8)],
        out.display()
    );
    // And every inked pixel lies within 1 px of a depth jump or a crease
    // of Blender's passes (each at half the style's threshold, so that a
    // pixel just at the style's threshold counts).
    let support_d = depth_jumps(&exr, 0.04);
    let support_n = normal_creases(&exr, 0.3);
    let stray: Vec<(usize, usize)> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| ink[y][x] && !near(&support_d, x, y) && !near(&support_n, x, y))
        .collect();
    assert!(
        stray.is_empty(),
        "{} inked pixels are on no discontinuity of Blender's depth or normals, e.g. {:?} (image: {})",
        stray.len(),
        &stray[..stray.len().min(8)],
        out.display()
    );
}

#[test]
fn ink_over_npr_gbuffer_of_the_same_scene_gives_the_same_lines() {
    let (_, toml) = blender();
    let gbuffer = scratch("npr_gbuffer.exr");
    let (blender_img, blender_out) = ink_over_blender();
    let size = format!("{}x{}", blender_img.width(), blender_img.height());
    npr(&[
        "render",
        "tests/data/blender/gbuffer.npr",
        "--scene",
        toml.to_str().unwrap(),
        "--size",
        &size,
        "--layers",
        "-o",
        gbuffer.to_str().unwrap(),
    ]);
    let out = scratch("ink_over_npr.png");
    npr(&[
        "render",
        STYLE,
        "--inputs",
        gbuffer.to_str().unwrap(),
        "--map",
        "color_in=g.color",
        "--map",
        "depth_in=g.depth",
        "--map",
        "normal_in=g.normal",
        "--scene",
        toml.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let ours = inked(&image::open(&out).expect("read output").to_rgba8());
    let theirs = inked(&blender_img);
    let (h, w) = (ours.len(), ours[0].len());
    let count = |m: &[Vec<bool>]| m.iter().flatten().filter(|v| **v).count();
    assert!(count(&ours) > 200, "npr's G-buffer gives lines: {}", count(&ours));
    // Each line pixel of either image has one of the other's within 1 px.
    for (a, b, what) in [(&ours, &theirs, "npr's"), (&theirs, &ours, "Blender's")] {
        let lone: Vec<(usize, usize)> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| a[y][x] && !near(b, x, y))
            .collect();
        assert!(
            lone.is_empty(),
            "{} line pixels over {what} passes have none of the other within 1 px, e.g. {:?} (images: {} and {})",
            lone.len(),
            &lone[..lone.len().min(8)],
            out.display(),
            blender_out.display()
        );
    }
}

#[test]
fn ink_over_passes_blenders_colour_through_where_it_draws_no_line() {
    let (exr_path, _) = blender();
    let exr = read_exr("passes", exr_path).expect("read Blender's EXR");
    let (img, out) = ink_over_blender();
    let rgb = ["R", "G", "B"].map(|c| channel(&exr, &format!("ViewLayer.Combined.{c}")));
    let w = exr.width as usize;
    let mut checked = 0;
    for (x, y, p) in img.enumerate_pixels() {
        if p.0[..3] == INK {
            continue;
        }
        let i = y as usize * w + x as usize;
        for (c, channel) in rgb.iter().enumerate() {
            // Linear light, stored as a half float, sRGB-encoded at load
            // (`input(color, display)`) and written to an 8-bit target:
            // within one step of the f64 encoding of Blender's value.
            let linear = (channel[i] as f64).clamp(0.0, 1.0);
            let encoded = if linear <= 0.0031308 {
                12.92 * linear
            } else {
                1.055 * linear.powf(1.0 / 2.4) - 0.055
            };
            let expected = (encoded * 255.0).round();
            assert!(
                (p.0[c] as f64 - expected).abs() <= 1.0,
                "pixel ({x}, {y}) channel {c}: {} where Blender's colour encodes to {expected} (image: {})",
                p.0[c],
                out.display()
            );
        }
        checked += 1;
    }
    assert!(
        checked > (img.width() * img.height()) as usize / 2,
        "most pixels carry no line: {checked}"
    );
}

/// Blender's passes, converted at load (by the GPU draw every input goes
/// through, read back), hold what npr's own G-buffer of
/// the mirrored scene holds, value by value: the depth (distance along the
/// view axis, metres) and the world normals (Blender's Z-up turned into
/// npr's Y-up). The line tests above compare thresholds that neither a
/// depth scale nor a rotation of the normals would change; this compares
/// the values themselves.
#[test]
fn blenders_depth_and_normals_convert_to_npr_gbuffer_values() {
    use npr_abi::{InputKind, NormalSpace};
    use npr_runner::inputs::{converted, files, prepare};
    let (exr_path, toml) = blender();
    let gbuffer = scratch("npr_gbuffer_values.exr");
    let exr = read_exr("passes", exr_path).expect("read Blender's EXR");
    npr(&[
        "render",
        "tests/data/blender/gbuffer.npr",
        "--scene",
        toml.to_str().unwrap(),
        "--size",
        &format!("{}x{}", exr.width, exr.height),
        "--layers",
        "-o",
        gbuffer.to_str().unwrap(),
    ]);
    let ours = read_exr("gbuffer", &gbuffer).expect("read npr's EXR");
    let load = |kind: InputKind, exr: &ExrChannels, layer: &str, blender: bool| {
        let raw = files::exr_layer("x", "f", kind, exr, layer).expect("layer");
        let image = prepare(
            "x",
            "f",
            kind,
            files::file_convention(kind, true, blender),
            raw,
            None,
            false,
        )
        .expect("prepare");
        let g = crate::common::gpu();
        converted(&g.device, &g.queue, &image).expect("convert on the GPU")
    };
    let normal = InputKind::Normal {
        space: NormalSpace::World,
    };
    let (bd, od) = (
        load(InputKind::Depth, &exr, "Depth", true),
        load(InputKind::Depth, &ours, "g.depth", false),
    );
    let (bn, on) = (
        load(normal, &exr, "Normal", true),
        load(normal, &ours, "g.normal", false),
    );
    let (w, h) = (exr.width as usize, exr.height as usize);
    let mut compared = 0;
    let mut worst_depth: f64 = 0.0;
    let mut worst_normal: f64 = 0.0;
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            // Away from edges, where a pixel centre may fall on either
            // side of a silhouette in the two tessellations.
            let around = |l: &npr_runner::artmap::Level| {
                [(0, 0), (1, 0), (0, 1), (-1, 0), (0, -1)]
                    .map(|(dx, dy)| l.pixels[(y as i64 + dy) as usize * w + (x as i64 + dx) as usize][0] as f64)
            };
            let (b, o) = (around(&bd), around(&od));
            let rel = |a: f64, c: f64| (a - c).abs() / a.max(c).max(1e-9);
            if b.iter()
                .zip(&o)
                .any(|(b, o)| *b == 0.0 || *o == 0.0 || rel(*b, *o) > 0.02)
            {
                continue;
            }
            let i = y * w + x;
            worst_depth = worst_depth.max(rel(bd.pixels[i][0] as f64, od.pixels[i][0] as f64));
            let dn: f64 = (0..3)
                .map(|c| (bn.pixels[i][c] as f64 - on.pixels[i][c] as f64).powi(2))
                .sum::<f64>();
            worst_normal = worst_normal.max(dn.sqrt());
            compared += 1;
        }
    }
    assert!(compared > (w * h) / 2, "most pixels are surfaces in both: {compared}");
    // Depth: the same surfaces, tessellated alike (64×32 spheres), half
    // floats in npr's target: within 0.5 %.
    assert!(
        worst_depth < 0.005,
        "depth differs by {:.3} % of itself",
        worst_depth * 100.0
    );
    // Normals: Cycles interpolates smooth-shaded normals as npr does; the
    // spheres' tessellations match, so within 0.05 (about 3°).
    assert!(worst_normal < 0.05, "normals differ by {worst_normal}");
    let all_background = |l: &npr_runner::artmap::Level| l.pixels.iter().filter(|p| p[0] == 0.0).count();
    assert!(
        all_background(&bd) > 0 && all_background(&od) > 0,
        "both have background (0)"
    );
}
