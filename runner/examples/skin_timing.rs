//! Times the deformation of an object playing a clip (issue 48,
//! docs/decisions/0049 and 0053): the Blender arm of `examples/models/`
//! (2 joints, 4 weights a vertex) repeated to 10k, 100k and 1M vertices,
//! and the blob's two morph targets likewise. Prints, in milliseconds per
//! frame:
//! - `cpu`: `Rig::pose` + `Rig::deform` on the CPU (what a frame adds
//!   when a lines pass or a light-view pass reads the deformed vertices);
//! - `rigid`: a whole frame (prepare, encode, submit, wait) of a 64 × 64
//!   style drawing the same mesh as a rigid object;
//! - `cpu-deformed`: the same frame with the object given its mesh
//!   deformed on the CPU and written in place every frame (decision
//!   0049's path, which this stage replaced for the passes);
//! - `gpu-deformed`: the same frame with the object playing the clip,
//!   deformed by the GPU stage (`exec/deform.rs`), at a new pose every frame.
//!
//!
//! Then, for the arm at 10k and 100k vertices, whole frames of two example
//! styles whose CPU or compute stages read the deformed surface: the
//! `lines` pass of `wavy_lines.npr` (silhouettes found and strips built on
//! the CPU from the CPU-deformed mesh every frame) and the Breslav tracker
//! of `halftone.npr` (a compute pass over the deformed samples): each
//! drawn rigid and playing the clip, in the same run.
//!
//! `cargo build --workspace --example skin_timing && target/debug/examples/skin_timing`

use npr_compiler::CompileOptions;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, Renderer};
use std::sync::Arc;

use npr_runner::scene::load_mesh_and_rig;
use npr_runner::scene::rig::Rig;
use std::path::Path;
use std::time::Instant;

/// `rig` with its (single) piece's vertices repeated until there are at
/// least `vertices`.
fn scaled(rig: &Rig, vertices: usize) -> Rig {
    let mut big = rig.clone();
    let n = rig.bind.vertex_count();
    let copies = vertices.div_ceil(n);
    let repeat = |v: &Vec<[f32; 3]>| v.iter().cycle().take(n * copies).copied().collect::<Vec<_>>();
    big.bind.positions = repeat(&rig.bind.positions);
    big.bind.normals = repeat(&rig.bind.normals);
    big.bind.uvs = rig
        .bind
        .uvs
        .as_ref()
        .map(|u| u.iter().cycle().take(n * copies).copied().collect());
    big.bind.tangents = rig
        .bind
        .tangents
        .as_ref()
        .map(|t| t.iter().cycle().take(n * copies).copied().collect());
    big.bind.indices = (0..copies)
        .flat_map(|c| rig.bind.indices.iter().map(move |i| i + (c * n) as u32))
        .collect();
    big.bind.parts = None;
    big.joints = rig.joints.iter().cycle().take(n * copies).copied().collect();
    big.weights = rig.weights.iter().cycle().take(n * copies).copied().collect();
    big.pieces.truncate(1);
    big.pieces[0].vertex_count = n * copies;
    for target in &mut big.pieces[0].targets {
        target.positions = repeat(&target.positions);
        target.normals = target.normals.as_ref().map(repeat);
        target.tangents = target.tangents.as_ref().map(repeat);
    }
    big
}

fn millis_per_frame(rig: &Rig, frames: u32) -> f64 {
    let duration = rig.clips[0].duration;
    std::hint::black_box(rig.deform(&rig.pose(Some((0, 0.0)))));
    let start = Instant::now();
    for f in 0..frames {
        let t = duration * f as f32 / frames as f32;
        std::hint::black_box(rig.deform(&rig.pose(Some((0, t)))));
    }
    start.elapsed().as_secs_f64() * 1000.0 / f64::from(frames)
}

const STYLE: &str = r#"
style "timing"
pass shade: render(scene) {
  let lit = lambert(normal, light.dir)
  out c: rgba8unorm = vec4(lit, lit, lit, 1.0)
  clear: #000000
}
output shade.c
"#;

/// Milliseconds per whole frame of `scene` (GPU work waited for), the
/// scene time moving every frame. With `cpu_rig`, the object is drawn
/// rigid and given its mesh deformed on the CPU each frame, written in
/// place (decision 0049's path, through 0045's).
fn frame_millis(
    gpu: &Gpu,
    program: &npr_runner::StyleProgram,
    scene: &Scene,
    cpu_rig: Option<&Rig>,
    frames: u32,
) -> f64 {
    let mut r = Renderer::new(&gpu.device, &gpu.queue, program, scene).expect("renderer");
    let spec = |f: u32| FrameSpec {
        width: 64,
        height: 64,
        time_s: 0.013 * f64::from(f),
        frame: f,
        eye: 0,
    };
    let wait = || {
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("the device finishes the frame");
    };
    let mut scene = scene.clone();
    let mut frame = |f: u32| {
        if let Some(rig) = cpu_rig {
            let t = spec(f).time_s as f32 % rig.clips[0].duration;
            scene.objects[0].mesh = Arc::new(rig.deform(&rig.pose(Some((0, t)))));
        }
        r.render(&scene, &spec(f)).expect("frame");
        wait();
    };
    frame(0);
    let start = Instant::now();
    for f in 1..=frames {
        frame(f);
    }
    start.elapsed().as_secs_f64() * 1000.0 / f64::from(frames)
}

/// An example style of `examples/`, compiled as `npr compile` does.
fn example(name: &str) -> npr_runner::StyleProgram {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    let text = std::fs::read_to_string(examples.join(name)).expect("example style");
    npr_compiler::compile_source(
        name,
        &text,
        &examples,
        &mut npr_diag::SourceMap::new(),
        &CompileOptions::default(),
    )
    .unwrap_or_else(|_| panic!("{name} compiles"))
    .program()
}

/// `file` (a character in `dir`) playing `clip` in a timing scene, and its rig.
fn playing(dir: &Path, file: &str, clip: &str) -> (Scene, Rig) {
    let (_, rig) = load_mesh_and_rig(&dir.join(file)).expect("test character");
    let text = format!(
        "[camera]\nposition = [0.0, 1.0, 6.0]\ntarget = [0.0, 1.0, 0.0]\n\
         [[object]]\nmesh = \"{file}\"\nanimation = {{ clip = \"{clip}\", loop = true }}\n"
    );
    let scene = npr_runner::scene::parse_scene(&text, npr_diag::FileId(0), dir).expect("timing scene");
    (scene, rig.expect("a rig"))
}

/// `base`'s character scaled to about `vertices` vertices: the scaled rig,
/// the scene playing its clip, and the same scene with it rigid.
fn animated_and_rigid(base: &Scene, rig: &Rig, vertices: usize) -> (Rig, Scene, Scene) {
    let big = scaled(rig, vertices);
    let mut animated = base.clone();
    animated.objects[0].mesh = Arc::new(big.bind.clone());
    if let Some(animation) = animated.objects[0].animation.as_mut() {
        animation.rig = Arc::new(big.clone());
    }
    let mut rigid = animated.clone();
    rigid.objects[0].animation = None;
    (big, animated, rigid)
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models");
    let gpu = Gpu::headless().expect("a GPU adapter (lavapipe: ./setup.sh --tests)");
    println!("adapter: {}", gpu.adapter_info.name);
    let mut sources = npr_diag::SourceMap::new();
    let program = npr_compiler::compile_source(
        "timing.npr",
        STYLE,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|_| panic!("the timing style compiles"))
    .program();
    for (file, clip) in [("arm.glb", "bend"), ("blob.glb", "pulse")] {
        let (base, rig) = playing(&dir, file, clip);
        for vertices in [10_000, 100_000, 1_000_000] {
            let (big, animated, rigid) = animated_and_rigid(&base, &rig, vertices);
            let frames = (2_000_000 / vertices).clamp(3, 100) as u32;
            let cpu = millis_per_frame(&big, frames);
            let still = frame_millis(&gpu, &program, &rigid, None, frames);
            let on_cpu = frame_millis(&gpu, &program, &rigid, Some(&big), frames);
            let on_gpu = frame_millis(&gpu, &program, &animated, None, frames);
            println!(
                "{file}: {} vertices: cpu deform {cpu:.2} ms; frame rigid {still:.2} ms, \
                 cpu-deformed {on_cpu:.2} ms (+{:.2}), gpu-deformed {on_gpu:.2} ms (+{:.2})",
                big.bind.vertex_count(),
                on_cpu - still,
                on_gpu - still
            );
        }
    }
    let (base, rig) = playing(&dir, "arm.glb", "bend");
    for style in ["wavy_lines.npr", "halftone.npr"] {
        let program = example(style);
        for vertices in [10_000, 100_000] {
            let (big, animated, rigid) = animated_and_rigid(&base, &rig, vertices);
            let frames = (1_000_000 / vertices).clamp(3, 100) as u32;
            let still = frame_millis(&gpu, &program, &rigid, None, frames);
            let deformed = frame_millis(&gpu, &program, &animated, None, frames);
            println!(
                "{style}, arm: {} vertices: frame rigid {still:.2} ms, playing the clip {deformed:.2} ms (x{:.2})",
                big.bind.vertex_count(),
                deformed / still
            );
        }
    }
}
