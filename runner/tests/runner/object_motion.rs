//! Objects may move and change their per-object params between frames: each
//! `Renderer::render` writes every object's uniform block (model matrix,
//! normal matrix, params) from the `Scene` it is given, and refits the light
//! camera to the moved shadow casters. A renderer reused across the change
//! draws what a fresh renderer built for the changed scene draws.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, Renderer, StyleProgram};
use std::path::Path;
use std::sync::OnceLock;

fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| Gpu::headless().unwrap_or_else(|e| panic!("runner tests need a GPU adapter: {e}")))
}

const SIZE: u32 = 64;

/// A shadow-casting ball over a ground plane: a light-view depth pass of the
/// casters, a lit and tinted render pass, and an image pass after it.
const STYLE: &str = r#"
style "moving objects"
object param tint: color = #ffffff
pass depth: render(caster) view(light) {
  out d: r32float = position.light.z
  clear: #ffffff
}
pass shade: render(scene) {
  let lit = lambert(normal, light.dir) * shadow(depth.d, bias: 0.002, radius: 0)
  out c: rgba8unorm = vec4(lit, lit, lit, 1.0) * tint
  clear: #000000
}
pass post: image(shade) {
  out o: rgba8unorm = shade.c
}
output post.o
"#;

const SCENE: &str = r##"
[camera]
position = [0.0, 3.0, -2.6]
target = [0.0, 0.0, 0.0]
fov = 50.0
near = 0.1
far = 20.0

[light]
direction = [0.3, 1.0, 0.2]

[[object]]
name = "ball"
primitive = { kind = "sphere", radius = 0.4, segments = 32, rings = 16 }
translate = [0.0, 0.9, 0.0]
tags = ["caster"]

[[object]]
name = "ground"
primitive = { kind = "plane", size = 3.0, subdivisions = 4 }
params = { tint = "#c0ffa0" }
"##;

fn program() -> StyleProgram {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source(
        "moving.npr",
        STYLE,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

/// Loaded once: tests running in parallel would race on the scene file.
fn scene() -> Scene {
    static SCENE_ONCE: OnceLock<Scene> = OnceLock::new();
    SCENE_ONCE.get_or_init(load).clone()
}

fn load() -> Scene {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("object-motion");
    std::fs::create_dir_all(&dir).expect("scratch");
    let path = dir.join("scene.toml");
    std::fs::write(&path, SCENE).expect("write scene");
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn draw(r: &mut Renderer, scene: &Scene) -> Vec<u8> {
    r.render(scene, &FrameSpec::still(SIZE, SIZE, 0)).expect("render");
    r.read_output().expect("read").bytes
}

fn fresh(program: &StyleProgram, scene: &Scene) -> Vec<u8> {
    let mut r = Renderer::new(&gpu().device, &gpu().queue, program, scene).expect("renderer");
    draw(&mut r, scene)
}

/// (largest per-channel difference, pixels that differ at all).
fn compare(a: &[u8], b: &[u8]) -> (u8, usize) {
    let max = a.iter().zip(b).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
    let pixels = a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p != q).count();
    (max, pixels)
}

#[test]
fn moved_objects_and_changed_params_are_drawn_by_the_same_renderer() {
    let program = program();
    let mut scene = scene();
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let first = draw(&mut r, &scene);

    // Move the ball (and with it its shadow and the light camera) sideways.
    let ball = scene.objects.iter().position(|o| o.name == "ball").expect("ball");
    scene.objects[ball].model = glam::Mat4::from_translation(glam::Vec3::new(0.7, 0.6, 0.3));
    let moved = draw(&mut r, &scene);
    let (max, pixels) = compare(&moved, &fresh(&program, &scene));
    assert!(
        max <= 1,
        "moved ball: the reused renderer differs from a fresh one by up to {max}/255"
    );
    let (_, changed) = compare(&first, &moved);
    assert!(
        changed > 100,
        "moving the ball changed only {changed} pixels ({pixels} differ from a fresh renderer)"
    );

    // Change a per-object param: the ground's tint.
    let ground = scene.objects.iter().position(|o| o.name == "ground").expect("ground");
    scene.objects[ground]
        .params
        .insert("tint".into(), vec![0.2, 0.4, 1.0, 1.0]);
    let tinted = draw(&mut r, &scene);
    let (max, _) = compare(&tinted, &fresh(&program, &scene));
    assert!(
        max <= 1,
        "new tint: the reused renderer differs from a fresh one by up to {max}/255"
    );
    let (_, changed) = compare(&moved, &tinted);
    assert!(
        changed > SIZE as usize * SIZE as usize / 4,
        "the new tint changed only {changed} pixels"
    );
}

#[test]
fn a_scene_with_other_objects_is_refused() {
    let program = program();
    let mut scene = scene();
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    scene.objects.pop();
    let err = r
        .render(&scene, &FrameSpec::still(SIZE, SIZE, 0))
        .expect_err("one object fewer");
    assert!(err.is_user_error(), "{err}");
}

#[test]
fn a_bad_param_set_between_frames_is_a_user_error() {
    let program = program();
    let mut scene = scene();
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    scene.objects[0].params.insert("tint".into(), vec![1.0, 0.0]);
    let err = r
        .render(&scene, &FrameSpec::still(SIZE, SIZE, 0))
        .expect_err("two components for a colour");
    assert!(err.is_user_error(), "{err}");
}
