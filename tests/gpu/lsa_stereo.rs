//! LSA contours in stereo (§4.2): line pixels of one eye should have a line
//! within 2 px of where they reproject in the other eye. Measured on the
//! analytic scenes with a stereo camera, for the per-eye base method and for
//! the full method with the stereo consistency pass (`examples/lsa_stereo.npr`).

use glam::Vec4;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_lab::contours::{ink_mask, Mask};
use npr_runner::{FrameSpec, Renderer, StyleProgram};
use std::path::Path;

use crate::common;
use common::{gpu, root};

fn program(text: &str) -> StyleProgram {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source("style.npr", text, root(), &mut sources, &CompileOptions::default()) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

/// One of the analytic contour scenes, with a stereo camera of baseline `ipd`.
fn stereo_scene(name: &str, ipd: f64) -> npr_runner::scene::Scene {
    let text = std::fs::read_to_string(root().join(format!("tests/data/contours/{name}.toml"))).expect("scene");
    let text = text.replacen("near = ", &format!("ipd = {ipd}\nnear = "), 1);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("lsa-stereo");
    std::fs::create_dir_all(&dir).expect("scratch");
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).expect("write");
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn render(p: &StyleProgram, scene: &npr_runner::scene::Scene, size: u32, eye: u32) -> npr_runner::TargetImage {
    let mut r = Renderer::new(&gpu().device, &gpu().queue, p, scene).expect("renderer");
    let spec = FrameSpec::still(size, size, eye);
    r.render(scene, &spec).expect("render");
    r.read_output().expect("read")
}

const POSITIONS: &str = "style \"p\"\npass g: render(scene) {\n  out pos: rgba32float = vec4(position.world, 1.0)\n  clear: #00000000\n}\noutput g.pos\n";

/// Share of `lines[eye]` pixels on geometry whose surface point, projected
/// into the other eye, has a line pixel of the other eye within 2 px
/// (points that leave the other image are not counted).
fn stereo_agreement(
    scene: &npr_runner::scene::Scene,
    lines: &[Mask; 2],
    positions: &npr_runner::TargetImage,
    eye: u32,
    size: u32,
) -> f64 {
    let pose = scene.camera.pose(0.0);
    let other = 1 - eye;
    let to_other = pose.projection(1.0) * pose.view(other);
    let near_line = lines[other as usize].dilate(2);
    let (mut counted, mut agreed) = (0usize, 0usize);
    for y in 0..size {
        for x in 0..size {
            let p = positions.texel(x, y);
            if !lines[eye as usize].get(x, y) || p[3] < 0.5 {
                continue;
            }
            let c = to_other * Vec4::new(p[0], p[1], p[2], 1.0);
            if c.w <= 0.0 {
                continue;
            }
            let (px, py) = (
                (c.x / c.w * 0.5 + 0.5) * size as f32,
                (0.5 - c.y / c.w * 0.5) * size as f32,
            );
            if px < 0.0 || py < 0.0 || px >= size as f32 || py >= size as f32 {
                continue;
            }
            counted += 1;
            if near_line.get(px as u32, py as u32) {
                agreed += 1;
            }
        }
    }
    assert!(counted > 20, "too few line pixels to measure: {counted}");
    agreed as f64 / counted as f64
}

#[test]
fn the_consistency_pass_makes_lines_agree_between_the_eyes() {
    let stereo_text = std::fs::read_to_string(root().join("examples/lsa_stereo.npr")).expect("example");
    // Lines only: no fade-out band, which is not a line.
    let stereo = program(&stereo_text.replace("param fade: bool = true", "param fade: bool = false"));
    let base = program(&std::fs::read_to_string(root().join("examples/lsa_base.npr")).expect("example"));
    let positions = program(POSITIONS);
    let size = 128;
    // A wide baseline (20 cm) exaggerates what differs between the eyes.
    for name in ["sphere_on_plane", "torus", "cube"] {
        let scene = stereo_scene(name, 0.2);
        let mut report = Vec::new();
        let mut shares = Vec::new();
        for (label, p) in [("base, per eye", &base), ("full + consistency", &stereo)] {
            let lines = [0, 1].map(|eye| ink_mask(&render(p, &scene, size, eye), 0.5));
            let differ = (0..size)
                .flat_map(|y| (0..size).map(move |x| (x, y)))
                .filter(|(x, y)| lines[0].get(*x, *y) != lines[1].get(*x, *y))
                .count();
            assert!(
                differ > 20,
                "{name}, {label}: the eyes see the same lines ({differ} px differ): not stereo"
            );
            let mut per_eye = Vec::new();
            for eye in [0, 1] {
                let pos = render(&positions, &scene, size, eye);
                per_eye.push(stereo_agreement(&scene, &lines, &pos, eye, size));
            }
            let share = (per_eye[0] + per_eye[1]) / 2.0;
            report.push(format!(
                "{label}: {:.1}% ({} + {} line px)",
                100.0 * share,
                lines[0].count(),
                lines[1].count()
            ));
            shares.push(share);
        }
        println!("{name}: {}", report.join("; "));
        assert!(
            shares[1] >= 0.97,
            "{name}: only {:.1}% of stereo lines agree",
            100.0 * shares[1]
        );
        assert!(
            shares[1] >= shares[0] - 0.005,
            "{name}: consistency made agreement worse: {report:?}"
        );
    }
}
