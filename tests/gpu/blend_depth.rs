//! Blending and shared depth on the GPU (lavapipe), checked against their
//! definitions.
//!
//! Blending: a render pass (and an image pass) writes a known colour over a
//! known clear colour into an rgba8unorm target; every pixel must equal the
//! blend formula of `npr_abi::manifest::Blend` within 1/255 (the result is
//! rounded to 8 bits once).
//!
//! Depth: a fronto-parallel wall keeps its depth, and a slope crossing it
//! along the image's middle row is drawn by a pass that tests against that
//! depth. The slope's window depth is affine in the screen row, with m per
//! row and none per column, so a fragment passes where Δ = z_slope − z_wall
//! ≤ N·m (`bias: N px`, slope-scaled) or ≤ b (`bias: b`, depth units). The
//! per-pixel prediction comes from a probe style that writes both surfaces'
//! view depths, converted to window depth with the camera's near and far.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::readback::TargetImage;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer};
use std::path::{Path, PathBuf};

use crate::common;
use common::gpu;

const SIZE: u32 = 32;
const NEAR: f64 = 0.5;
const FAR: f64 = 20.0;

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("blend-depth").join(name);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

fn load_scene(dir: &Path, toml: &str) -> Scene {
    let path = dir.join("scene.toml");
    std::fs::write(&path, toml).expect("write scene");
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// Compile `text` and render it on `scene`: the output target.
fn render(text: &str, dir: &Path, scene: &Scene) -> TargetImage {
    let mut sources = SourceMap::new();
    let compiled = match npr_compiler::compile_source("case.npr", text, dir, &mut sources, &CompileOptions::default()) {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    };
    let program = compiled.program();
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, scene).expect("renderer");
    r.render(scene, &FrameSpec::still(SIZE, SIZE, 0)).expect("render");
    r.read_output().expect("read back")
}

/// A plane filling the view, facing the camera.
const WALL_SCENE: &str = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\nnear = 0.5\nfar = 20.0\n\n[[object]]\nprimitive = { kind = \"plane\", size = 10.0 }\nrotate = [90.0, 0.0, 0.0]\n";

/// What `blend` makes of fragment `s` over target `d` (straight alpha).
fn blend(mode: &str, s: [f64; 4], d: [f64; 4]) -> [f64; 4] {
    match mode {
        "over" => {
            let c = |i: usize| s[i] * s[3] + d[i] * (1.0 - s[3]);
            [c(0), c(1), c(2), s[3] + d[3] * (1.0 - s[3])]
        }
        "add" => std::array::from_fn(|i| (s[i] + d[i]).min(1.0)),
        "multiply" => std::array::from_fn(|i| s[i] * d[i]),
        other => panic!("no formula for `{other}`"),
    }
}

fn byte(v: f64) -> f64 {
    (v * 255.0).round() / 255.0
}

/// Every pixel of `img` is `want` within one 8-bit step.
fn assert_uniform(img: &TargetImage, want: [f64; 4], what: &str) {
    for y in 0..img.height {
        for x in 0..img.width {
            let got = img.texel(x, y);
            for c in 0..4 {
                let err = (got[c] as f64 - byte(want[c])).abs() * 255.0;
                assert!(
                    err <= 1.0 + 1e-6,
                    "{what}: pixel ({x}, {y}) is {got:?}, want {want:?} (channel {c} off by {err:.2}/255)"
                );
            }
        }
    }
}

#[test]
fn blend_modes_match_their_formulas() {
    let dir = scratch("blend");
    let scene = load_scene(&dir, WALL_SCENE);
    // The clear colours are whole bytes, so they are stored exactly; the
    // fragment's value is blended before rounding.
    let cases: &[(&str, [f64; 4], &str)] = &[
        ("over", [0.8, 0.4, 0.2, 0.6], "#336699"),
        ("over", [0.8, 0.4, 0.2, 0.6], "#33669940"),
        ("add", [0.3, 0.2, 0.1, 0.25], "#33669940"),
        ("add", [0.9, 0.2, 0.1, 0.25], "#336699"),
        ("multiply", [0.8, 0.4, 0.2, 0.6], "#3366ccc0"),
    ];
    for (mode, s, clear) in cases {
        let hex = |i: usize| u8::from_str_radix(&clear[1 + 2 * i..3 + 2 * i], 16).expect("hex") as f64 / 255.0;
        let d = [hex(0), hex(1), hex(2), if clear.len() == 9 { hex(3) } else { 1.0 }];
        let want = blend(mode, *s, d);
        let value = format!("vec4({}, {}, {}, {})", s[0], s[1], s[2], s[3]);
        for kind in ["render(scene)", "image()"] {
            let text = format!(
                "style \"Blend\"\npass p: {kind} {{\n  out c: rgba8unorm = {value} {{ blend: {mode} }}\n  clear: {clear}\n}}\noutput p.c\n"
            );
            let img = render(&text, &dir, &scene);
            assert_uniform(&img, want, &format!("`{mode}` of {s:?} over {clear} in a {kind} pass"));
        }
    }
}

#[test]
fn replace_ignores_the_clear_colour() {
    let dir = scratch("replace");
    let scene = load_scene(&dir, WALL_SCENE);
    let text = "style \"Replace\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(0.8, 0.4, 0.2, 0.6) { blend: replace }\n  clear: #336699\n}\noutput p.c\n";
    assert_uniform(&render(text, &dir, &scene), [0.8, 0.4, 0.2, 0.6], "replace");
}

/// The wall (z = 0, facing the camera) and the slope, a plane through the
/// wall's x axis tilted 20° from it: its lower half comes out of the wall
/// towards the camera, its upper half goes behind it.
const WALL_AND_SLOPE: &str = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\nnear = 0.5\nfar = 20.0\n\n[[object]]\nname = \"wall\"\nprimitive = { kind = \"plane\", size = 10.0 }\nrotate = [90.0, 0.0, 0.0]\ntags = [\"wall\"]\n\n[[object]]\nname = \"slope\"\nprimitive = { kind = \"plane\", size = 10.0 }\nrotate = [70.0, 0.0, 0.0]\ntags = [\"slope\"]\n";

/// Window depth (0 at near, 1 at far) of a point at view depth `d` metres.
fn window_depth(d: f64) -> f64 {
    FAR / (FAR - NEAR) * (1.0 - NEAR / d)
}

/// Per pixel: (wall, slope) window depths, from their view depths.
fn probe(dir: &Path, scene: &Scene) -> Vec<[f64; 2]> {
    let text = "style \"Probe\"\npass wall: render(wall) {\n  out d: r32float = depth\n}\npass slope: render(slope) {\n  out d: r32float = depth\n}\npass both: image(wall, slope) {\n  out d: rg32float = vec2(wall.d, slope.d)\n}\noutput both.d\n";
    let img = render(text, dir, scene);
    (0..SIZE * SIZE)
        .map(|i| {
            let t = img.texel(i % SIZE, i / SIZE);
            assert!(t[0] > 0.0 && t[1] > 0.0, "pixel {i}: both planes cover the view: {t:?}");
            [window_depth(t[0] as f64), window_depth(t[1] as f64)]
        })
        .collect()
}

/// The slope drawn with `depth: test(wall, ...)` (channel r) and the wall
/// drawn again the same way after it (channel g): 1 where they passed.
fn depth_tested(dir: &Path, scene: &Scene, test: &str) -> Vec<[bool; 2]> {
    let text = format!(
        "style \"Depth\"\npass wall: render(wall) {{\n  out unused: r8unorm = 1.0\n  depth: keep\n}}\n\
         pass slope: render(slope) {{\n  out seen: r8unorm = 1.0\n  depth: {test}\n}}\n\
         pass again: render(wall) {{\n  out seen: r8unorm = 1.0\n  depth: test(wall)\n}}\n\
         pass both: image(slope, again) {{\n  out seen: rg8unorm = vec2(slope.seen, again.seen)\n}}\noutput both.seen\n"
    );
    let img = render(&text, dir, scene);
    (0..SIZE * SIZE)
        .map(|i| {
            let t = img.texel(i % SIZE, i / SIZE);
            [t[0] > 0.5, t[1] > 0.5]
        })
        .collect()
}

#[test]
fn depth_test_rejects_occluded_fragments_and_the_bias_moves_the_threshold() {
    let dir = scratch("depth");
    let scene = load_scene(&dir, WALL_AND_SLOPE);
    let depths = probe(&dir, &scene);
    let at = |x: u32, y: u32| depths[(y * SIZE + x) as usize];
    // The slope's depth per row (the steepest gradient: none along a row).
    let m = (at(SIZE / 2, 4)[1] - at(SIZE / 2, SIZE - 5)[1]) / (SIZE - 9) as f64;
    assert!(m > 1e-4, "the slope's depth falls down the image by {m} per row");
    for y in 0..SIZE {
        let row: Vec<f64> = (0..SIZE).map(|x| at(x, y)[1]).collect();
        let spread = row.iter().fold(0.0f64, |a, z| a.max((z - row[0]).abs()));
        assert!(
            spread < 0.02 * m,
            "row {y}: the slope's depth varies along the row by {spread}"
        );
    }
    // (`depth:` setting, depth offset the bias allows, rows visible by the geometry).
    let b = 4.0 * m;
    let cases = [
        ("test(wall)".to_string(), 0.0, 16),
        ("test(wall, bias: 3px)".to_string(), 3.0 * m, 19),
        (format!("test(wall, bias: {b})"), b, 20),
    ];
    for (test, allowed, rows) in cases {
        let seen = depth_tested(&dir, &scene, &test);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let [wall, slope] = at(x, y);
                let excess = slope - wall - allowed;
                // Within a quarter row of the threshold the prediction is not sharp.
                if excess.abs() < 0.25 * m {
                    continue;
                }
                let [slope_seen, wall_again] = seen[(y * SIZE + x) as usize];
                assert_eq!(
                    slope_seen,
                    excess < 0.0,
                    "`depth: {test}`, pixel ({x}, {y}): the slope is {:.2} rows of depth behind the wall",
                    (slope - wall) / m
                );
                // The slope pass wrote no depth, so the wall passes again everywhere.
                assert!(
                    wall_again,
                    "`depth: {test}`, pixel ({x}, {y}): the wall drawn again was rejected"
                );
            }
        }
        // The lower half, plus one row per px (or per m of depth) of bias.
        let visible_rows = (0..SIZE).filter(|y| seen[(y * SIZE) as usize][0]).count();
        assert_eq!(visible_rows, rows, "`depth: {test}`: rows where the slope shows");
        assert!(
            (0..SIZE).all(|y| seen[(y * SIZE + SIZE - 1) as usize][0] == (y >= SIZE - rows as u32)),
            "`depth: {test}`: the visible rows are the lowest ones"
        );
    }
}
