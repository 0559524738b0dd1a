//! The independent baseline of `npr bench overhead` (`npr_lab::bench_overhead`)
//! draws the same image as the runner, so that the benchmark compares the
//! same work; and it refuses styles it does not implement. Not timed: the
//! benchmark itself is `npr bench overhead` (docs/PERFORMANCE.md).

use npr_lab::bench_overhead::{image_diff, same_image, OverheadError, SAME_IMAGE};
use npr_runner::scene::Scene;
use npr_runner::StyleProgram;

use crate::common;
use common::{gpu, root};

fn load(style: &str, scene: &str) -> (StyleProgram, Scene) {
    let mut sources = npr_diag::SourceMap::new();
    let loaded = npr_runner::scene::load_scene(&root().join(scene), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let opts = npr_compiler::CompileOptions {
        scene: Some(loaded.summary(scene)),
        ..Default::default()
    };
    let compiled = npr_compiler::compile_file(&root().join(style), &mut sources, &opts)
        .unwrap_or_else(|e| panic!("{style} does not compile: {e:?}"));
    (compiled.program(), loaded)
}

/// The baseline's output equals the runner's at frames 0 and 24 (1 s: toon's
/// animated `rim` is 0.2 there, neither a key nor its default), and the
/// image is not trivial
/// (several colours), so that equality says something.
fn assert_same_image(style: &str, scene: &str, size: u32) {
    let (program, scene_data) = load(style, scene);
    let d = same_image(gpu(), &program, &scene_data, (size, size), &[0, 24]).unwrap_or_else(|e| panic!("{style}: {e}"));
    assert!(d.max_abs <= SAME_IMAGE, "{style} on {scene}: {d}");
    println!("{style} on {scene}, {size}x{size}: {d}");
    let img = npr_runner::render_frame(
        gpu(),
        &program,
        &scene_data,
        &npr_runner::FrameSpec::still(size, size, 0),
    )
    .expect("render")
    .to_rgba8();
    let mut colours: Vec<[u8; 4]> = img.pixels().map(|p| p.0).collect();
    colours.sort();
    colours.dedup();
    assert!(colours.len() >= 3, "{style} on {scene}: only {} colours", colours.len());
}

#[test]
fn rounded_shadows_on_spot_is_the_runners_image() {
    assert_same_image("examples/rounded_shadows.npr", "examples/scenes/spot.toml", 64);
}

#[test]
fn toon_on_several_objects_is_the_runners_image() {
    assert_same_image("examples/toon.npr", "examples/scenes/spheres.toml", 64);
}

/// The comparison sees a change: rounded shadows with another threshold band.
#[test]
fn the_image_check_sees_a_different_image() {
    let (program, scene) = load("examples/rounded_shadows.npr", "examples/scenes/spot.toml");
    let mut other = program.clone();
    for wgsl in other.shaders.values_mut() {
        *wgsl = wgsl.replace("0.42f, 0.5f", "0.2f, 0.3f");
    }
    assert_ne!(program.shaders, other.shaders, "the folded band is in the WGSL");
    let spec = npr_runner::FrameSpec::still(64, 64, 0);
    let a = npr_runner::render_frame(gpu(), &program, &scene, &spec).expect("render");
    let b = npr_runner::render_frame(gpu(), &other, &scene, &spec).expect("render");
    let d = image_diff(&a, &b).expect("same size and format");
    assert!(d.max_abs > SAME_IMAGE && d.texels_differing > 10, "{d}");
}

#[test]
fn styles_the_baseline_does_not_implement_are_refused() {
    for (style, scene, what) in [
        (
            "examples/afterimage.npr",
            "examples/scenes/orbit.toml",
            "earlier frames",
        ),
        (
            "examples/object_centroids.npr",
            "examples/scenes/spheres.toml",
            "compute passes",
        ),
        (
            "examples/overlay_lines.npr",
            "examples/scenes/spheres.toml",
            "depth: keep",
        ),
    ] {
        let (program, scene_data) = load(style, scene);
        match same_image(gpu(), &program, &scene_data, (32, 32), &[0]) {
            Err(e @ OverheadError::Unsupported(_)) => {
                assert!(e.to_string().contains(what), "{style}: {e}")
            }
            other => panic!("{style}: expected a refusal, got {other:?}"),
        }
    }
}
