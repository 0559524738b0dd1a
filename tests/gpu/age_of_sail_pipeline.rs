//! The Age of Sail pipeline (journal §5) end to end: cast shadows from a
//! `view(light)` depth pass against analytic ground truth, the compiler
//! dropping the depth pass for a scene without casters, and `--dump-passes`
//! reproducing every pass of Fig. 16.

use glam::{Vec3, Vec4};
use npr_abi::SceneSummary;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Renderer};
use std::path::{Path, PathBuf};

use crate::common;
use common::{gpu, root};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("age-of-sail").join(name);
    std::fs::create_dir_all(&dir).expect("scratch");
    dir
}

fn compile(text: &str, scene: Option<SceneSummary>) -> npr_compiler::Compiled {
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        scene,
        ..Default::default()
    };
    match npr_compiler::compile_source("test.npr", text, root(), &mut sources, &opts) {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

fn scene_from(text: &str, name: &str) -> npr_runner::scene::Scene {
    let dir = scratch(name);
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).expect("write scene");
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

const SHADOW_STYLE: &str = r#"
style "cast shadow probe"
param warp: float = 0 in 0..8
pass depth: render(caster) view(light) {
  vertex { shadow_warp: warp }
  out d: r32float = position.light.z
  clear: #ffffff
}
pass probe: render(ground) {
  out lit: r8unorm = shadow(depth.d, bias: 0.002, warp: warp, radius: 0)
  out hit: r8unorm = 1.0
  clear: #000000
}
output probe.lit
"#;

/// A ball of radius 0.5 at height 1.2 over the plane y = 0, lit from
/// straight above: its shadow is exactly the disc x² + z² < 0.25.
const SHADOW_SCENE: &str = r#"
[camera]
position = [0.0, 3.0, -2.6]
target = [0.0, 0.0, 0.0]
fov = 50.0
near = 0.1
far = 20.0

[light]
direction = [0.0, 1.0, 0.0]

[[object]]
name = "ball"
primitive = { kind = "sphere", radius = 0.5, segments = 96, rings = 48 }
translate = [0.0, 1.2, 0.0]
tags = ["caster"]

[[object]]
name = "ground"
primitive = { kind = "plane", size = 3.0, subdivisions = 24 }
tags = ["ground"]
"#;

/// Where the camera ray through pixel (x, y) meets the plane y = 0.
fn ground_hit(scene: &npr_runner::scene::Scene, size: u32, x: u32, y: u32) -> Option<Vec3> {
    let pose = scene.camera.pose(0.0);
    let inv = (pose.projection(1.0) * pose.view(0)).inverse();
    let ndc_x = (x as f32 + 0.5) / size as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / size as f32 * 2.0;
    let unproject = |z: f32| {
        let p = inv * Vec4::new(ndc_x, ndc_y, z, 1.0);
        p.truncate() / p.w
    };
    let (a, b) = (unproject(0.0), unproject(1.0));
    let t = a.y / (a.y - b.y);
    (0.0..=1.0).contains(&t).then(|| a + (b - a) * t)
}

#[test]
fn cast_shadow_matches_the_analytic_disc_with_and_without_the_sigmoid_warp() {
    let scene = scene_from(SHADOW_SCENE, "disc");
    let size = 96;
    for warp in [0.0, 2.0] {
        let text = SHADOW_STYLE.replace("param warp: float = 0", &format!("param warp: float = {warp}"));
        let program = compile(&text, None).program();
        let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
        let spec = FrameSpec::still(size, size, 0);
        r.render(&scene, &spec).expect("render");
        let lit = r.read_output().expect("read");
        let (mut checked, mut wrong, mut dark) = (0, 0, 0);
        for y in 0..size {
            for x in 0..size {
                let Some(p) = ground_hit(&scene, size, x, y) else {
                    continue;
                };
                if p.x.abs() > 1.4 || p.z.abs() > 1.4 {
                    continue; // off the plane
                }
                let radius = (p.x * p.x + p.z * p.z).sqrt();
                // The light frustum spans the caster's bounding sphere (1 m over
                // 96 texels) and the camera's pixels are ≈ 3 cm on the ground:
                // skip a 3 cm band around the boundary.
                if (radius - 0.5).abs() < 0.03 {
                    continue;
                }
                checked += 1;
                let in_shadow = lit.texel(x, y)[0] < 0.5;
                dark += in_shadow as u32;
                if in_shadow != (radius < 0.5) {
                    wrong += 1;
                }
            }
        }
        assert!(checked > 2000, "too few ground pixels: {checked}");
        assert!(dark > 100, "warp {warp}: no shadow at all ({dark} dark pixels)");
        assert_eq!(
            wrong, 0,
            "warp {warp}: {wrong} of {checked} pixels disagree with the analytic shadow disc"
        );
    }
}

const AGE_OF_SAIL: &str = "examples/age_of_sail.npr";

fn compile_example(scene: Option<SceneSummary>) -> npr_compiler::Compiled {
    let text = std::fs::read_to_string(root().join(AGE_OF_SAIL)).expect("example");
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        scene,
        ..Default::default()
    };
    npr_compiler::compile_source(AGE_OF_SAIL, &text, &root().join("examples"), &mut sources, &opts)
        .unwrap_or_else(|e| panic!("{e:?}"))
}

fn pass_names(c: &npr_compiler::Compiled) -> Vec<String> {
    c.manifest.passes.iter().map(|p| p.name.clone()).collect()
}

#[test]
fn a_scene_without_shadow_casters_compiles_without_the_depth_pass() {
    let with = SceneSummary {
        tags: ["caster".to_string()].into(),
        name: "with casters".into(),
    };
    let without = SceneSummary {
        tags: Default::default(),
        name: "without casters".into(),
    };
    let unknown = compile_example(None);
    let casters = compile_example(Some(with));
    let none = compile_example(Some(without));
    assert!(
        pass_names(&unknown).contains(&"depth".to_string()),
        "no scene: keep the depth pass"
    );
    assert!(pass_names(&casters).contains(&"depth".to_string()));
    assert!(
        !pass_names(&none).contains(&"depth".to_string()),
        "{:?}",
        pass_names(&none)
    );
    assert_eq!(pass_names(&none).len() + 1, pass_names(&casters).len());
    // The shadow pass no longer contains the shadow-map lookup.
    let shadow_wgsl = none.shader("shadow.wgsl").expect("shadow pass");
    assert!(!shadow_wgsl.contains("npr_shadow"), "{shadow_wgsl}");
    assert!(casters
        .shader("shadow.wgsl")
        .expect("shadow pass")
        .contains("npr_shadow("));
    // `--report` says why.
    let report = none.report.render();
    assert!(
        report.contains("scene_has(caster)") && report.contains("false"),
        "{report}"
    );
    assert!(report.contains("pass `depth`"), "{report}");
    insta::assert_snapshot!("age_of_sail_report_without_casters", report);
}

#[test]
fn dump_passes_reproduces_every_pass_even_where_textures_are_shared() {
    let dir = scratch("dump");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .current_dir(root())
        .args([
            "render",
            AGE_OF_SAIL,
            "--scene",
            "examples/scenes/age_of_sail.toml",
            "--size",
            "96x96",
            "--dump-passes",
        ])
        .arg(&dir)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let index = std::fs::read_to_string(dir.join("contact_sheet.txt")).expect("index");
    for pass in [
        "warp",
        "depth",
        "shadow",
        "blur1y",
        "blur2y",
        "final_shadow",
        "colour",
        "final",
    ] {
        assert!(index.contains(&format!("{pass}.")), "{pass} missing from {index}");
    }
    // `colour.color` shares its texture with `shadow.rgb` (dead by then): the
    // dump must show the colour pass, whose sky is its clear colour #9fb6c8,
    // not the shadow pass's black background.
    let colour = image::open(dir.join("10_colour.color.png")).expect("dump").to_rgba8();
    let sky = colour.get_pixel(1, 1).0;
    assert!(
        (sky[0] as i32 - 0x9f).abs() <= 1 && (sky[1] as i32 - 0xb6).abs() <= 1 && (sky[2] as i32 - 0xc8).abs() <= 1,
        "sky pixel of the colour pass is {sky:?}"
    );
    let shadow = image::open(dir.join("02_shadow.rgb.png")).expect("dump").to_rgba8();
    assert_eq!(&shadow.get_pixel(1, 1).0[..3], &[0, 0, 0], "shadow pass background");
}

fn error_text(text: &str) -> String {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source("bad.npr", text, root(), &mut sources, &CompileOptions::default()) {
        Err(npr_compiler::CompileError::User(d)) => npr_diag::diagnostic::render(&d, &sources, false),
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("internal error: {e}"),
    }
}

#[test]
fn misused_pipeline_constructs_point_at_the_source() {
    let bad_view = error_text(
        "style \"x\"\npass depth: render(caster) view(sun) {\n  out d: r32float = position.light.z\n}\noutput depth.d\n",
    );
    insta::assert_snapshot!("bad_view", bad_view);
    let warp_outside_light_view = error_text(
        "style \"x\"\npass p: render(scene) {\n  vertex { shadow_warp: 2.0 }\n  out d: r32float = 1.0\n}\noutput p.d\n",
    );
    insta::assert_snapshot!("shadow_warp_outside_light_view", warp_outside_light_view);
    let uv_in_vertex = error_text(
        "style \"x\"\npass p: render(scene) {\n  vertex { inflate: uv.x * 2px }\n  out d: r32float = 1.0\n}\noutput p.d\n",
    );
    insta::assert_snapshot!("per_fragment_builtin_in_vertex", uv_in_vertex);
    let bad_scene_has = error_text(
        "style \"x\"\npass p: render(scene) {\n  out d: r32float = if scene_has(\"caster\") { 1.0 } else { 0.0 }\n}\noutput p.d\n",
    );
    insta::assert_snapshot!("bad_scene_has", bad_scene_has);
}

#[test]
fn compiling_for_a_scene_without_casters_renders_the_same_image() {
    // No object is tagged `caster`: the depth pass is dropped when the
    // compiler knows the scene, and renders nothing when it does not.
    let scene = scene_from(
        r#"
[camera]
position = [2.0, 1.5, -2.5]
target = [0.0, 0.3, 0.0]
[[object]]
primitive = { kind = "sphere", radius = 0.5 }
translate = [0.0, 0.5, 0.0]
[[object]]
primitive = { kind = "plane", size = 4.0 }
"#,
        "no-casters",
    );
    let render = |c: &npr_compiler::Compiled| {
        npr_runner::render_frame(gpu(), &c.program(), &scene, &FrameSpec::still(64, 64, 0))
            .expect("render")
            .to_rgba8()
    };
    let blind = compile_example(None);
    let informed = compile_example(Some(scene.summary("no casters")));
    assert_eq!(informed.manifest.passes.len() + 1, blind.manifest.passes.len());
    let (a, b) = (render(&blind), render(&informed));
    let max_diff = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..4).map(move |c| (p.0[c] as i32 - q.0[c] as i32).abs()))
        .max()
        .unwrap_or(0);
    assert!(max_diff <= 1, "images differ by up to {max_diff}/255");
}
