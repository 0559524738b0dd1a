//! Golden-image tests: each example style rendered on its scene through the
//! real wgpu runner, compared with `examples/golden/*.png`.
//!
//! Tolerance: every channel within 2/255 except at most 0.5% of pixels (the
//! outliers allowed are edge pixels whose coverage can differ between
//! rasterizers), plus a mean FLIP bound of 0.01. On failure the actual and
//! diff images are written to `target/npr-test-output/`.
//! Regenerate after an intended change with `NPR_UPDATE_GOLDENS=1 cargo test --test gpu golden_images::`.

use lab::harness::{compare_with_golden, compare_with_golden_file, Tolerance};
use runner::FrameSpec;
use std::path::Path;

use crate::common;
use common::gpu;

const SIZE: u32 = 192;

fn render_example(style: &str, scene: &str) -> image::RgbaImage {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut sources = diag::SourceMap::new();
    let scene_name = scene;
    let scene = runner::scene::load_scene(&root.join(scene), &mut sources)
        .unwrap_or_else(|d| panic!("{}", diag::diagnostic::render(&d, &sources, false)));
    // Compiled for its scene, as `npr render` does.
    let opts = compiler::CompileOptions {
        scene: Some(scene.summary(scene_name)),
        ..Default::default()
    };
    let compiled = compiler::compile_file(&root.join(style), &mut sources, &opts)
        .unwrap_or_else(|e| panic!("{style} does not compile: {e:?}"));
    let program = compiled.program();
    let img = runner::render_frame(gpu(), &program, &scene, &FrameSpec::still(SIZE, SIZE, 0))
        .unwrap_or_else(|e| panic!("render failed: {e}: {:?}", e.diagnostics()));
    img.to_rgba8()
}

fn golden(name: &str, style: &str, scene: &str) {
    let actual = render_example(style, scene);
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/golden")
        .join(format!("{name}.png"));
    let per_pixel = compare_with_golden(
        &actual,
        &path,
        Tolerance::PerPixel {
            max_abs: 2,
            outlier_fraction: 0.005,
        },
    );
    assert!(
        per_pixel.passed,
        "{name}: {} (images in {:?})",
        per_pixel.summary, per_pixel.written
    );
    let flip = compare_with_golden(&actual, &path, Tolerance::Flip { max_mean: 0.01 });
    assert!(flip.passed, "{name}: {}", flip.summary);
}

#[test]
fn toon_on_spot() {
    golden("toon_spot", "examples/toon.npr", "examples/scenes/spot.toml");
}

#[test]
fn outline_on_spot() {
    golden("outline_spot", "examples/outline.npr", "examples/scenes/spot.toml");
}

#[test]
fn rounded_shadows_on_spot() {
    golden(
        "rounded_shadows_spot",
        "examples/rounded_shadows.npr",
        "examples/scenes/spot.toml",
    );
}

#[test]
fn toon_on_analytic_spheres() {
    golden("toon_spheres", "examples/toon.npr", "examples/scenes/spheres.toml");
}

#[test]
fn overlay_lines_on_analytic_spheres() {
    // A kept depth tested by a second render pass, and `over` blending.
    golden(
        "overlay_lines_spheres",
        "examples/overlay_lines.npr",
        "examples/scenes/spheres.toml",
    );
}

#[test]
fn a_broken_image_fails_the_comparison() {
    // The harness must be able to fail: a golden compared with an altered copy.
    let actual = render_example("examples/toon.npr", "examples/scenes/spot.toml");
    let mut altered = actual.clone();
    for p in altered.pixels_mut().take((SIZE * SIZE / 10) as usize) {
        p.0 = [255, 0, 255, 255];
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("golden-self-test");
    std::fs::create_dir_all(&dir).expect("dir");
    let golden = dir.join("reference.png");
    runner::output::write_png8(&actual, &golden).expect("write");
    let c = compare_with_golden_file(
        &altered,
        &golden,
        Tolerance::PerPixel {
            max_abs: 2,
            outlier_fraction: 0.005,
        },
        false,
    );
    assert!(!c.passed && c.outlier_fraction > 0.05, "{}", c.summary);
    let written = c.written.expect("actual and diff written on failure");
    assert!(written.0.exists() && written.1.exists());
}

#[test]
fn metatexture_on_spot() {
    golden(
        "metatexture_spot",
        "examples/metatexture.npr",
        "examples/scenes/spot.toml",
    );
}

#[test]
fn age_of_sail_on_spot() {
    golden(
        "age_of_sail_spot",
        "examples/age_of_sail.npr",
        "examples/scenes/age_of_sail.toml",
    );
}

#[test]
fn lsa_contours_on_analytic_spheres() {
    golden(
        "lsa_contours_spheres",
        "examples/lsa_contours.npr",
        "examples/scenes/spheres.toml",
    );
}

#[test]
fn lsa_base_on_analytic_spheres() {
    golden(
        "lsa_base_spheres",
        "examples/lsa_base.npr",
        "examples/scenes/spheres.toml",
    );
}

#[test]
fn sobel_outline_on_analytic_spheres() {
    golden(
        "sobel_outline_spheres",
        "examples/sobel_outline.npr",
        "examples/scenes/spheres.toml",
    );
}

#[test]
fn lsa_contours_on_spot() {
    golden(
        "lsa_contours_spot",
        "examples/lsa_contours.npr",
        "examples/scenes/spot.toml",
    );
}

#[test]
fn ocean_on_the_ocean_scene() {
    // Age of Sail §6.1: the animated ocean primitive (at t = 0) with the
    // MetaTexture dither, bathic and sky maps, foam and live texture.
    golden("ocean", "examples/ocean.npr", "examples/scenes/ocean.toml");
}

#[test]
fn edge_breakup_on_spot() {
    golden(
        "edge_breakup_spot",
        "examples/edge_breakup.npr",
        "examples/scenes/spot.toml",
    );
}

#[test]
fn live_contour_on_spheres() {
    golden(
        "live_contour_spheres",
        "examples/live_contour.npr",
        "examples/scenes/spheres.toml",
    );
}

#[test]
fn lsa_stereo_on_a_stereo_sphere_on_plane() {
    // Eye 0 (left) of a stereo frame: both eyes are rendered pass by pass.
    golden(
        "lsa_stereo_sphere_on_plane",
        "examples/lsa_stereo.npr",
        "examples/scenes/stereo_sphere_on_plane.toml",
    );
}

#[test]
fn lsa_base_on_spot() {
    golden("lsa_base_spot", "examples/lsa_base.npr", "examples/scenes/spot.toml");
}

#[test]
fn sobel_outline_on_spot() {
    golden(
        "sobel_outline_spot",
        "examples/sobel_outline.npr",
        "examples/scenes/spot.toml",
    );
}

// fandisk: a CAD part with sharp creases and planar faces, loaded with
// `crease_angle = 30` (split normals at the creases). LSA draws the creases
// as single lines; depth-only Sobel draws only the silhouette and the
// occlusion edges, since depth is continuous across a crease.

#[test]
fn lsa_contours_on_fandisk() {
    golden(
        "lsa_contours_fandisk",
        "examples/lsa_contours.npr",
        "examples/scenes/fandisk.toml",
    );
}

#[test]
fn lsa_base_on_fandisk() {
    golden(
        "lsa_base_fandisk",
        "examples/lsa_base.npr",
        "examples/scenes/fandisk.toml",
    );
}

#[test]
fn sobel_outline_on_fandisk() {
    golden(
        "sobel_outline_fandisk",
        "examples/sobel_outline.npr",
        "examples/scenes/fandisk.toml",
    );
}

#[test]
fn artmap_gallery_on_the_gallery() {
    // Klein et al. 2000 §4.2: hatching, watercolour and ink-blot art-maps,
    // built at load (through the art-map cache), on a room of primitives.
    golden(
        "artmap_gallery",
        "examples/artmap_gallery.npr",
        "examples/scenes/gallery.toml",
    );
}

// Wavy lines (Klein et al. 2000 §5): silhouettes and creases over a toon
// fill, tested at their edge points against the fill's kept depth.

#[test]
fn wavy_lines_on_fandisk() {
    golden(
        "wavy_lines_fandisk",
        "examples/wavy_lines.npr",
        "examples/scenes/fandisk.toml",
    );
}

#[test]
fn wavy_lines_on_cube() {
    golden(
        "wavy_lines_cube",
        "examples/wavy_lines.npr",
        "examples/scenes/cube.toml",
    );
}

#[test]
fn wavy_lines_on_teapot() {
    golden(
        "wavy_lines_teapot",
        "examples/wavy_lines.npr",
        "examples/scenes/teapot.toml",
    );
}
