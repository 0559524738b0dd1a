//! The golden comparison of `npr_lab::harness` must be able to fail: an example
//! rendered through the real wgpu runner, compared with an altered copy.
//!
//! The examples' own golden-image tests (style + scene + golden +
//! tolerance) are declared beside each style in `examples/*.tests.toml`
//! and run by `npr test examples/` (tests/general/style_tests_examples.rs),
//! the way a user tests a style. Bless them after an intended change with
//! `npr test examples/ --bless`.

use npr_lab::harness::{compare_with_golden_file, Tolerance};
use npr_runner::FrameSpec;
use std::path::Path;

use crate::common;
use common::gpu;

const SIZE: u32 = 192;

fn render_example(style: &str, scene: &str) -> image::RgbaImage {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut sources = npr_diag::SourceMap::new();
    let scene_name = scene;
    let scene = npr_runner::scene::load_scene(&root.join(scene), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    // Compiled for its scene, as `npr render` does.
    let opts = npr_compiler::CompileOptions {
        scene: Some(scene.summary(scene_name)),
        ..Default::default()
    };
    let compiled = npr_compiler::compile_file(&root.join(style), &mut sources, &opts)
        .unwrap_or_else(|e| panic!("{style} does not compile: {e:?}"));
    let program = compiled.program();
    let img = npr_runner::render_frame(gpu(), &program, &scene, &FrameSpec::still(SIZE, SIZE, 0))
        .unwrap_or_else(|e| panic!("render failed: {e}: {:?}", e.diagnostics()));
    img.to_rgba8()
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
    npr_runner::output::write_png8(&actual, &golden).expect("write");
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
