//! Patches drawn with their blending weights (Breslav et al. 2007 §3.6):
//! "to render a patch, we render all of its triangles plus those in the
//! 1-ring outside the patch", with strength weight^power, over n rings.
//!
//! The scene is a flat strip facing the camera, two OBJ groups meeting at
//! x = 0 (patch 0 on the left, patch 1 on the right). A plane parallel to
//! the image maps to it affinely, so every pixel centre is an exact surface
//! point; the expected value there is the f64 weights
//! (`npr_runner::scene::patch_weights`, the per-vertex truth tested on its own)
//! interpolated over the triangle under it, raised to the power.
//!
//! Measured: the weights drawn sum to 1 at every pixel; each patch's
//! strength and the normalized cross-fade against f64; the fade confined to
//! the n-ring, monotone, wider with more rings and steeper with a higher
//! power; `blend_rings = 0` the hard seam (which the cross-fade checks
//! reject); the paper's compositing (a pattern's alpha times its strength,
//! `blend: over`) against its formula. The pattern examples on the same
//! strip are in `tests/gpu/patch_blend_styles.rs`; the strip is
//! `tests/common/patch_strip.rs`.

use npr_runner::scene::patch_weights::blend_weights;
use npr_runner::{FrameSpec, Renderer, StyleProgram, TargetImage};
use std::path::Path;

use crate::common;
use common::patch_strip::{
    half_pixel, scratch, strip_obj, strip_scene, surface_point, CELL, CELLS_X, CELLS_Y, DISTANCE, FOV_DEG, H, W,
};
use common::{compile_text, gpu, root};

/// Each patch's strength s = weight^power, accumulated: r = patch 0's, g =
/// patch 1's, a = their sum. Tested against the ID pass's kept depth, so
/// only the front surface accumulates (the same surface drawn again passes).
const ACCUMULATE: &str = r#"style "Patch strengths"
param power: float = POWER in 0.01..64.0
pass ids: render(scene) {
  out id: r32float = object.id
  depth: keep
}
pass acc: render(scene) {
  depth: test(ids)
  let s = pow(patch.weight, power)
  let c = if object.index == 0 { vec3(1.0, 0.0, 0.0) } else { vec3(0.0, 1.0, 0.0) }
  out sum: rgba16float = vec4(c * s, s) { blend: add }
}
output acc.sum
"#;

/// The paper's compositing: each patch's colour over the paper with alpha
/// = its strength, patch 0 drawn first.
const OVER: &str = r#"style "Patch strengths over paper"
param power: float = POWER in 0.01..64.0
pass ids: render(scene) {
  out id: r32float = object.id
  depth: keep
}
pass ink: render(scene) {
  depth: test(ids)
  let c = if object.index == 0 { vec3(0.8, 0.1, 0.2) } else { vec3(0.1, 0.3, 0.9) }
  out color: rgba8unorm = vec4(c, pow(patch.weight, power)) { blend: over }
  clear: #ffffff
}
output ink.color
"#;

/// `style` with `POWER` as its power's default.
fn with_power(style: &str, power: f64) -> StyleProgram {
    compile_text(&style.replace("POWER", &format!("{power:?}")))
}

/// Frame 0 of `program` on `scene`.
fn render(program: &StyleProgram, scene: &npr_runner::scene::Scene) -> TargetImage {
    let mut r = Renderer::new(&gpu().device, &gpu().queue, program, scene).expect("renderer");
    r.render(scene, &FrameSpec::still(W, H, 0)).expect("frame");
    r.read_output().expect("output")
}

/// The f64 truth: the strip mesh and its per-vertex weights over `rings`.
struct Truth {
    mesh: npr_runner::scene::Mesh,
    weights: npr_runner::scene::patch_weights::PatchWeights,
}

impl Truth {
    fn new(dir: &Path, rings: u32) -> Truth {
        let mesh = npr_runner::scene::load_mesh_file(&dir.join("strip.obj")).expect("mesh");
        let parts = mesh.parts.clone().expect("two parts");
        let weights = blend_weights(&mesh, &parts, rings - 1);
        Truth { mesh, weights }
    }

    /// Each patch's weight at surface point (x, y), interpolated over the
    /// triangle under it; `None` off the strip or within `margin` metres of
    /// its border (where a pixel may be partly covered).
    fn weights_at(&self, (x, y): (f64, f64), margin: f64) -> Option<[f64; 2]> {
        let hx = CELLS_X as f64 / 2.0 * CELL - margin;
        let hy = CELLS_Y as f64 / 2.0 * CELL - margin;
        if x.abs() > hx || y.abs() > hy {
            return None;
        }
        let p = |v: u32| self.mesh.positions[v as usize].map(f64::from);
        for t in self.mesh.indices.chunks_exact(3) {
            let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
            let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
            let l1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / det;
            let l2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / det;
            let l0 = 1.0 - l1 - l2;
            if l0 >= -1e-12 && l1 >= -1e-12 && l2 >= -1e-12 {
                let w = |patch: u32| {
                    l0 * self.weights.weight(t[0] as usize, patch)
                        + l1 * self.weights.weight(t[1] as usize, patch)
                        + l2 * self.weights.weight(t[2] as usize, patch)
                };
                return Some([w(0), w(1)]);
            }
        }
        None
    }
}

/// Largest |GPU − f64| of each patch's strength and of their sum, over the
/// strip's pixels.
struct Errors {
    strength: f64,
    sum: f64,
    pixels: usize,
}

fn strength_errors(img: &TargetImage, truth: &Truth, power: f64) -> Errors {
    let mut e = Errors {
        strength: 0.0,
        sum: 0.0,
        pixels: 0,
    };
    for py in 0..H {
        for px in 0..W {
            let Some(w) = truth.weights_at(surface_point(px, py), 1.5 * half_pixel()) else {
                continue;
            };
            let got = img.texel(px, py);
            let s = w.map(|w| w.powf(power));
            e.strength = e
                .strength
                .max((f64::from(got[0]) - s[0]).abs())
                .max((f64::from(got[1]) - s[1]).abs());
            e.sum = e.sum.max((f64::from(got[3]) - (s[0] + s[1])).abs());
            e.pixels += 1;
        }
    }
    e
}

/// The row of pixels the cross-fade is measured along (off the grid's lines).
const ROW: u32 = H / 2 - 3;

/// Along [`ROW`], inside the strip: (pixel column, x in metres, patch 0's
/// share r/(r+g)).
fn cross_fade(img: &TargetImage) -> Vec<(u32, f64, f64)> {
    (0..W)
        .filter_map(|px| {
            let (x, _) = surface_point(px, ROW);
            if x.abs() > CELLS_X as f64 / 2.0 * CELL - 2.0 * half_pixel() {
                return None;
            }
            let t = img.texel(px, ROW);
            Some((px, x, f64::from(t[0]) / f64::from(t[0] + t[1])))
        })
        .collect()
}

/// The width in metres over which patch 0's share falls from 0.9 to 0.1.
fn fade_width(row: &[(u32, f64, f64)]) -> f64 {
    let first = |level: f64| {
        row.iter()
            .find(|(_, _, f)| *f < level)
            .map(|(_, x, _)| *x)
            .expect("crossing")
    };
    first(0.1) - first(0.9)
}

/// f16 rounding of values up to 2 (2⁻¹⁰ relative), two additions, and f32 interpolation.
const F16_TOLERANCE: f64 = 2e-3;

#[test]
fn the_weights_drawn_sum_to_one_and_each_matches_f64() {
    let dir = scratch("sum");
    for rings in [1, 3] {
        let scene = strip_scene(&dir, Some(rings));
        let truth = Truth::new(&dir, rings);
        let img = render(&with_power(ACCUMULATE, 1.0), &scene);
        let e = strength_errors(&img, &truth, 1.0);
        assert!(e.pixels > 6_000, "{} pixels on the strip", e.pixels);
        // The sum against 1 directly (the f64 weights sum to 1 by construction).
        let mut worst = 0.0f64;
        for py in 0..H {
            for px in 0..W {
                if truth.weights_at(surface_point(px, py), 1.5 * half_pixel()).is_some() {
                    worst = worst.max((f64::from(img.texel(px, py)[3]) - 1.0).abs());
                }
            }
        }
        println!(
            "{rings} rings, power 1: Σ weight − 1 ≤ {worst:.2e}; strength error ≤ {:.2e} over {} px",
            e.strength, e.pixels
        );
        assert!(worst <= F16_TOLERANCE, "{rings} rings: the weights sum to 1 ± {worst}");
        assert!(
            e.strength <= F16_TOLERANCE,
            "{rings} rings: strength off by {}",
            e.strength
        );
    }
}

#[test]
fn patterns_cross_fade_over_the_n_ring_as_f64_says() {
    let dir = scratch("fade");
    let mut widths = Vec::new();
    for (rings, power) in [(1, 0.5), (3, 0.5), (3, 1.0), (3, 4.0)] {
        let scene = strip_scene(&dir, Some(rings));
        let truth = Truth::new(&dir, rings);
        let img = render(&with_power(ACCUMULATE, power), &scene);
        let e = strength_errors(&img, &truth, power);
        println!(
            "{rings} rings, power {power}: strength error ≤ {:.2e}, sum error ≤ {:.2e}",
            e.strength, e.sum
        );
        assert!(e.strength <= F16_TOLERANCE && e.sum <= 2.0 * F16_TOLERANCE);
        let row = cross_fade(&img);
        // Monotone from patch 0 to patch 1, and only within the n-ring:
        // exactly one patch beyond n cells of the seam (plus a pixel).
        for pair in row.windows(2) {
            assert!(
                pair[1].2 <= pair[0].2 + 1e-3,
                "{rings} rings, power {power}: the share rises at x = {}",
                pair[1].1
            );
        }
        let reach = rings as f64 * CELL + 2.0 * half_pixel();
        for (_, x, f) in &row {
            if *x < -reach {
                assert_eq!(*f, 1.0, "{rings} rings: x = {x} is patch 0's alone");
            }
            if *x > reach {
                assert_eq!(*f, 0.0, "{rings} rings: x = {x} is patch 1's alone");
            }
        }
        // The normalized share against f64 (f16 strengths: 2e-3 each).
        for (px, x, f) in &row {
            let w = truth.weights_at(surface_point(*px, ROW), 0.0).expect("on the strip");
            let s = w.map(|w| w.powf(power));
            let want = s[0] / (s[0] + s[1]);
            assert!(
                (f - want).abs() <= 5e-3,
                "{rings} rings, power {power}: share {f} at x = {x}, f64 {want}"
            );
        }
        let width = fade_width(&row);
        println!(
            "  the share falls from 0.9 to 0.1 over {width:.3} m ({:.2} cells)",
            width / CELL
        );
        widths.push(((rings, power), width));
    }
    let width = |key: (u32, f64)| widths.iter().find(|(k, _)| *k == key).expect("measured").1;
    // More rings widen the fade; a higher power sharpens it.
    assert!(width((3, 0.5)) > 1.5 * width((1, 0.5)), "{widths:?}");
    assert!(
        width((3, 0.5)) > width((3, 1.0)) && width((3, 1.0)) > width((3, 4.0)),
        "{widths:?}"
    );
}

#[test]
fn no_rings_is_the_hard_seam_which_the_cross_fade_checks_reject() {
    let dir = scratch("hard");
    let hard_scene = strip_scene(&dir, Some(0));
    let hard = render(&with_power(ACCUMULATE, 0.5), &hard_scene);
    // Every pixel belongs to one patch, at full strength: a step.
    let row = cross_fade(&hard);
    assert!(row.iter().all(|(_, _, f)| *f == 0.0 || *f == 1.0), "{row:?}");
    let steps = row.windows(2).filter(|p| p[0].2 != p[1].2).count();
    assert_eq!(steps, 1, "one step at the seam: {row:?}");
    // What the 1-ring cross-fade check expects is far from it near the seam:
    // the old drawing (each patch over its own faces) fails that test.
    let truth = Truth::new(&dir, 1);
    let worst = row
        .iter()
        .map(|(px, _, f)| {
            let w = truth.weights_at(surface_point(*px, ROW), 0.0).expect("on the strip");
            let s = w.map(|w| w.sqrt());
            (f - s[0] / (s[0] + s[1])).abs()
        })
        .fold(0.0f64, f64::max);
    println!("hard seam against the 1-ring cross-fade: off by up to {worst:.3}");
    assert!(worst > 0.3, "{worst}");
}

#[test]
fn the_papers_compositing_is_each_pattern_over_the_last_with_its_strength() {
    let dir = scratch("over");
    let power = 0.5;
    let scene = strip_scene(&dir, Some(2));
    let truth = Truth::new(&dir, 2);
    let img = render(&with_power(OVER, power), &scene);
    let (c0, c1) = ([0.8, 0.1, 0.2], [0.1, 0.3, 0.9]);
    let mut worst = 0.0f64;
    let mut blended = 0;
    for py in 0..H {
        for px in 0..W {
            let Some(w) = truth.weights_at(surface_point(px, py), 1.5 * half_pixel()) else {
                continue;
            };
            let s = w.map(|w| w.powf(power));
            if s[0] > 0.05 && s[1] > 0.05 {
                blended += 1;
            }
            let got = img.texel(px, py);
            for c in 0..3 {
                // Patch 0 over white, then patch 1 over that.
                let want = s[1] * c1[c] + (1.0 - s[1]) * (s[0] * c0[c] + (1.0 - s[0]));
                worst = worst.max((f64::from(got[c]) - want).abs() * 255.0);
            }
        }
    }
    println!("over: off by ≤ {worst:.2}/255; {blended} px with both patterns above 5%");
    assert!(blended > 500, "{blended}");
    // Two blends into an 8-bit target, each within 1/255: Vulkan leaves the
    // rounding of fixed-point blending to the implementation (lavapipe's
    // truncates: 1.7/255 measured here).
    assert!(worst <= 2.0, "{worst}/255");
}

#[test]
fn an_object_without_patches_draws_weight_one_over_its_own_faces() {
    let dir = scratch("plain");
    std::fs::write(dir.join("strip.obj"), strip_obj()).expect("obj");
    let text = format!(
        "[camera]\nposition = [0.0, 0.0, {DISTANCE}]\ntarget = [0.0, 0.0, 0.0]\nfov = {FOV_DEG}\nnear = 0.5\nfar = 20.0\n\n[[object]]\nname = \"strip\"\nmesh = \"strip.obj\"\n"
    );
    let path = dir.join("plain.toml");
    std::fs::write(&path, text).expect("scene");
    let mut sources = npr_diag::SourceMap::new();
    let scene = npr_runner::scene::load_scene(&path, &mut sources).expect("scene");
    assert!(scene.objects.iter().all(|o| o.blend.is_none()));
    let img = render(&with_power(ACCUMULATE, 0.5), &scene);
    let truth = Truth::new(&dir, 1);
    let mut pixels = 0;
    for py in 0..H {
        for px in 0..W {
            if truth.weights_at(surface_point(px, py), 1.5 * half_pixel()).is_some() {
                assert_eq!(img.texel(px, py), [1.0, 0.0, 0.0, 1.0], "pixel ({px}, {py})");
                pixels += 1;
            } else if truth.weights_at(surface_point(px, py), -1.5 * half_pixel()).is_none() {
                assert_eq!(img.texel(px, py), [0.0, 0.0, 0.0, 0.0], "off the strip: ({px}, {py})");
            }
        }
    }
    assert!(pixels > 6_000, "{pixels}");
}

#[test]
fn patch_weight_exists_in_render_passes_only() {
    for (kind, body) in [
        ("image()", "out c: rgba8unorm = vec4(patch.weight)"),
        ("compute(vertices)", "reduce w: float = sum(patch.weight)"),
        ("compute(samples)", "count: 10\n  reduce w: float = sum(patch.weight)"),
    ] {
        let text = format!("style \"Case\"\npass p: {kind} {{\n  {body}\n}}\npass q: image() {{\n  out c: rgba8unorm = vec4(1.0)\n}}\noutput q.c\n");
        let text = if kind.starts_with("image") {
            text.replace("output q.c", "output p.c")
        } else {
            text
        };
        let mut sources = npr_diag::SourceMap::new();
        let err = match npr_compiler::compile_source("case.npr", &text, root(), &mut sources, &Default::default()) {
            Err(npr_compiler::CompileError::User(d)) => npr_diag::diagnostic::render(&d, &sources, false),
            other => panic!("{kind}: {:?}", other.map(|_| ())),
        };
        assert!(
            err.contains("`patch.weight` is not available in") && err.contains(npr_diag::codes::BAD_PASS_INPUT),
            "{kind}:\n{err}"
        );
    }
}
