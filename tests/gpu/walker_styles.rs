//! Every example style draws the animated walker (issue 48): each
//! `examples/*.npr` compiled for `examples/scenes/walker.toml` and rendered
//! at 64×64 at scene times 0 s and 0.25 s (a quarter stride: the legs from
//! together to their widest swing), frames 0 and 6 of one renderer.
//!
//! What is checked, per style:
//! - no error from the runner (wgpu validation errors are caught in
//!   `gpu_error::scoped` and come back as one), and no NaN or infinity in
//!   either output;
//! - the image changes where the figure is: of the pixels within
//!   [`NEAR_FIGURE_PX`] of the figure's projected vertices at either time
//!   (the f64 CPU pose of the same clip, projected by the scene's camera),
//!   at least [`MIN_CHANGED`] differ by more than [`CHANGE`] between the
//!   two times. A style that drew the rest pose both times, or nothing of
//!   the figure, changes none of them there.
//!
//! Where a style's whole image changes with time on its own (animated
//! parameters, line boil, a noise that moves), the pixels away from the
//! figure change too; that is allowed, and the figure's pixels must still
//! change. A failure writes both images to
//! `target/npr-test-output/walker_styles/`.

use npr_runner::{FrameSpec, Renderer};
use std::path::{Path, PathBuf};

use crate::common::{gpu, root};

const SIZE: u32 = 64;
/// Frames 0 and 6 at 24 fps: scene times 0 s and 0.25 s.
const FRAMES: [u32; 2] = [0, 6];
/// How close to a projected vertex of the figure a pixel counts as the
/// figure's (vertices lie under 1.5 px apart at this size; lines and
/// inflation reach a little past the surface).
const NEAR_FIGURE_PX: f64 = 2.5;
/// A change larger than 8-bit rounding and dithering.
const CHANGE: f32 = 4.0 / 255.0;
/// Pixels of the figure that must change: of its 672, every style changed
/// 87 to 672 when this was written (the outline least: its lines only).
const MIN_CHANGED: usize = 40;

fn example_styles() -> Vec<PathBuf> {
    let mut styles: Vec<PathBuf> = std::fs::read_dir(root().join("examples"))
        .expect("examples/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "npr"))
        .collect();
    styles.sort();
    styles
}

/// Pixels (row-major, `SIZE`²) within [`NEAR_FIGURE_PX`] of the walker's
/// vertices at `time_s`, projected through the scene camera.
fn near_figure(scene: &npr_runner::scene::Scene, time_s: f64, mask: &mut [bool]) {
    let posed = scene.posed(time_s);
    let walker = posed
        .objects
        .iter()
        .find(|o| o.name == "walker")
        .expect("the scene's walker");
    let camera = scene.camera.pose(time_s);
    let view_projection = camera.projection(1.0).as_dmat4() * camera.view(0).as_dmat4();
    let model = walker.model.as_dmat4();
    let r = NEAR_FIGURE_PX;
    for p in &walker.mesh.positions {
        let clip = view_projection * (model * glam::Vec3::from_array(*p).as_dvec3().extend(1.0));
        let ndc = clip.truncate() / clip.w;
        let (x, y) = (
            (ndc.x + 1.0) * 0.5 * f64::from(SIZE),
            (1.0 - ndc.y) * 0.5 * f64::from(SIZE),
        );
        for py in ((y - r).floor().max(0.0) as u32)..((y + r).ceil().min(f64::from(SIZE)) as u32) {
            for px in ((x - r).floor().max(0.0) as u32)..((x + r).ceil().min(f64::from(SIZE)) as u32) {
                let (cx, cy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                if (cx - x).hypot(cy - y) <= r {
                    mask[(py * SIZE + px) as usize] = true;
                }
            }
        }
    }
}

fn load(path: &Path) -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

#[test]
fn every_example_style_draws_the_walking_figure() {
    let scene_path = root().join("examples/scenes/walker.toml");
    let scene = load(&scene_path);
    let mut figure = vec![false; (SIZE * SIZE) as usize];
    for frame in FRAMES {
        near_figure(&scene, f64::from(frame) / FrameSpec::DEFAULT_FPS, &mut figure);
    }
    let figure_pixels = figure.iter().filter(|m| **m).count();
    assert!(
        figure_pixels > 200,
        "the walker covers only {figure_pixels} pixels: the scene's camera misses it"
    );
    let g = gpu();
    let mut failures = Vec::new();
    let mut report = Vec::new();
    for style in example_styles() {
        let name = style.file_stem().expect("stem").to_string_lossy().into_owned();
        let mut sources = npr_diag::SourceMap::new();
        let opts = npr_compiler::CompileOptions {
            scene: Some(scene.summary("walker")),
            ..Default::default()
        };
        let program = match npr_compiler::compile_file(&style, &mut sources, &opts) {
            Ok(c) => c.program(),
            Err(npr_compiler::CompileError::User(d)) => {
                failures.push(format!(
                    "{name}: does not compile for the walker: {}",
                    npr_diag::diagnostic::render(&d, &sources, false)
                ));
                continue;
            }
            Err(e) => {
                failures.push(format!("{name}: {e:?}"));
                continue;
            }
        };
        let mut renderer = match Renderer::new(&g.device, &g.queue, &program, &scene) {
            Ok(r) => r,
            Err(e) => {
                failures.push(format!("{name}: renderer: {e}: {:?}", e.diagnostics()));
                continue;
            }
        };
        let mut images = Vec::new();
        for frame in FRAMES {
            let spec = FrameSpec::animated(SIZE, SIZE, frame, FrameSpec::DEFAULT_FPS, 0);
            if let Err(e) = renderer.render(&scene, &spec) {
                failures.push(format!("{name}: frame {frame}: {e}: {:?}", e.diagnostics()));
                break;
            }
            images.push(renderer.read_output().expect("read back the output"));
        }
        if images.len() != FRAMES.len() {
            continue;
        }
        let pixels: Vec<Vec<[f32; 4]>> = images.iter().map(|i| i.to_rgba_f32()).collect();
        if let Some(frame) = pixels
            .iter()
            .position(|p| p.iter().any(|c| c.iter().any(|x| !x.is_finite())))
        {
            failures.push(format!("{name}: frame {} has a NaN or infinite texel", FRAMES[frame]));
        }
        let changed = |i: usize| {
            pixels[0][i]
                .iter()
                .zip(&pixels[1][i])
                .any(|(a, b)| (a - b).abs() > CHANGE)
        };
        let on_figure = (0..figure.len()).filter(|&i| figure[i] && changed(i)).count();
        let elsewhere = (0..figure.len()).filter(|&i| !figure[i] && changed(i)).count();
        report.push(format!(
            "{name}: {on_figure} of {figure_pixels} figure pixels changed, {elsewhere} of {} elsewhere",
            figure.len() - figure_pixels
        ));
        if on_figure < MIN_CHANGED {
            let dir = root().join("target/npr-test-output/walker_styles");
            std::fs::create_dir_all(&dir).expect("output dir");
            for (image, frame) in images.iter().zip(FRAMES) {
                npr_runner::output::write_png8(&image.to_rgba8(), &dir.join(format!("{name}_{frame}.png")))
                    .expect("write the image");
            }
            failures.push(format!(
                "{name}: only {on_figure} pixels of the figure changed between 0 s and 0.25 s (at least {MIN_CHANGED} expected); images in {}",
                dir.display()
            ));
        }
    }
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
