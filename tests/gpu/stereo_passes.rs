//! Stereo frames whose passes read the other eye (`other_eye(...)`, needed by
//! the LSA contours' reprojection and consistency passes): both eyes are
//! rendered pass by pass, each reading its own targets and the other eye's,
//! and `project_other_eye` maps a world point into the other eye's image.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Renderer, StyleProgram};
use std::path::Path;

use crate::common;
use common::gpu;

fn compile(text: &str) -> npr_compiler::Compiled {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source(
        "stereo.npr",
        text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

fn scene(ipd: Option<f64>) -> npr_runner::scene::Scene {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("stereo-passes");
    std::fs::create_dir_all(&dir).expect("scratch");
    let ipd_line = ipd.map(|i| format!("ipd = {i}")).unwrap_or_default();
    let text = format!(
        r#"
[camera]
position = [0.0, 0.6, -3.0]
target = [0.0, 0.3, 0.0]
fov = 40.0
{ipd_line}
[[object]]
primitive = {{ kind = "sphere", radius = 0.6, segments = 64, rings = 32 }}
translate = [0.0, 0.3, 0.0]
[[object]]
primitive = {{ kind = "plane", size = 6.0, subdivisions = 4 }}
"#
    );
    let path = dir.join(format!("scene_{}.toml", ipd.is_some()));
    // Tests run in parallel and write the same file: atomically, so a
    // reader never sees another test's half-written copy.
    npr_runner::output::write_atomic(&path, text.as_bytes()).expect("write scene");
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn render(program: &StyleProgram, scene: &npr_runner::scene::Scene, eye: u32, size: u32) -> Vec<[f32; 4]> {
    let mut r = Renderer::new(&gpu().device, &gpu().queue, program, scene).expect("renderer");
    let spec = FrameSpec::still(size, size, eye);
    r.render(scene, &spec).expect("render");
    r.read_output().expect("read").to_rgba_f32()
}

const EYE_STYLE: &str = r#"
style "eyes"
pass mark: render(scene) {
  out e: r16float = float(eye) + 0.25
  clear: #000000
}
pass both: image(mark) {
  out c: rgba16float = vec4(mark.e, other_eye(mark.e), 0.0, 1.0)
}
output both.c
"#;

#[test]
fn each_eye_reads_its_own_target_and_the_other_eyes() {
    let c = compile(&EYE_STYLE.replace("float(eye)", "eye"));
    assert!(c.manifest.is_stereo());
    let program = c.program();
    let scene = scene(Some(0.064));
    for eye in [0u32, 1] {
        let px = render(&program, &scene, eye, 16);
        // The centre pixel sees the sphere in both eyes.
        let centre = px[8 * 16 + 8];
        let own = eye as f32 + 0.25;
        let other = (1 - eye) as f32 + 0.25;
        assert!(
            (centre[0] - own).abs() < 1e-3 && (centre[1] - other).abs() < 1e-3,
            "eye {eye}: {centre:?}"
        );
    }
    let mono = compile("style \"m\"\npass a: render(scene) {\n  out e: r16float = 1.0\n}\noutput a.e\n");
    assert!(!mono.manifest.is_stereo());
}

const REPROJECT_STYLE: &str = r#"
style "reprojection"
pass g: render(scene) {
  out pos: rgba16float = vec4(position.world, 1.0)
  clear: #00000000
}
pass check: image(g) {
  // Where this pixel's surface point lands in the other eye, and what the
  // other eye saw there.
  let q = project_other_eye(g.pos.xyz)
  let seen = sample(other_eye(g.pos), uv: q.xy)
  out err: rgba32float = vec4(distance(seen.xyz, g.pos.xyz), g.pos.w * seen.w, q.x, q.y)
}
output check.err
"#;

#[test]
fn reprojection_into_the_other_eye_finds_the_same_surface_point() {
    let program = compile(REPROJECT_STYLE).program();
    let scene = scene(Some(0.064));
    let size = 64;
    for eye in [0u32, 1] {
        let px = render(&program, &scene, eye, size);
        // Points on geometry in both eyes, and inside the other eye's view.
        let inside = |p: &&[f32; 4]| (0.0..=1.0).contains(&p[2]) && (0.0..=1.0).contains(&p[3]);
        let both: Vec<&[f32; 4]> = px.iter().filter(|p| p[1] > 0.99).filter(inside).collect();
        assert!(
            both.len() > size as usize * size as usize / 2,
            "eye {eye}: {} covered",
            both.len()
        );
        let close = both.iter().filter(|p| p[0] < 0.02).count();
        let share = close as f64 / both.len() as f64;
        println!(
            "eye {eye}: {:.2}% of {} points reproject within 2 cm",
            100.0 * share,
            both.len()
        );
        // Disocclusions (seen by one eye only) and bilinear mixing across
        // silhouettes are the misses (99.4% on lavapipe).
        assert!(
            share > 0.98,
            "eye {eye}: only {:.1}% reproject within 2 cm",
            100.0 * share
        );
        // With a real baseline the other eye's uv differs from this pixel's.
        let moved = px.iter().enumerate().filter(|(i, p)| {
            let x = (*i as u32 % size) as f32 + 0.5;
            p[1] > 0.99 && (p[2] * size as f32 - x).abs() > 0.5
        });
        assert!(moved.count() > both.len() / 2, "eye {eye}: reprojection did not move");
    }
}

#[test]
fn other_eye_of_something_that_is_not_a_target_is_an_error() {
    let mut sources = SourceMap::new();
    let text = "style \"x\"\npass a: render(scene) {\n  out e: r16float = 1.0\n}\npass b: image(a) {\n  out c: r16float = other_eye(a.e * 2.0)\n}\noutput b.c\n";
    match npr_compiler::compile_source(
        "bad.npr",
        text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) {
        Err(npr_compiler::CompileError::User(d)) => {
            insta::assert_snapshot!(
                "other_eye_not_a_target",
                npr_diag::diagnostic::render(&d, &sources, false)
            )
        }
        _ => panic!("expected a user error"),
    }
}
