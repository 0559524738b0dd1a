//! The GPU deformation stage (`exec/deform.rs`, docs/decisions/0053): its
//! WGSL passes naga's validation; the vertices it writes, read back from
//! the object's vertex buffers, equal the independent f64 reference
//! (`common/skin_reference.rs`) for several poses of the Blender arm (a
//! skin) and several weights of the Blender blob's shape keys (morph
//! targets), and equal the CPU deformation (`Rig::deform`, what the lines
//! and light bounds read) within stated bounds; a compute pass over
//! vertices sees them; and a frame at a new time creates no GPU object.

use crate::skin_reference;

use glam::{DVec3, Vec3};
use npr_abi::manifest::Attribute;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, Renderer, StyleProgram};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        Gpu::headless()
            .unwrap_or_else(|e| panic!("runner tests need a GPU adapter (Mesa's lavapipe: `./setup.sh --tests`): {e}"))
    })
}

/// Position error bound, in metres, for objects about 2 m across: the
/// CPU path's (`gltf_characters.rs`), f32 rounding of the morph, the
/// matrix blend and the product. Lavapipe measured 6.5e-7 at worst.
const POSITION_BOUND: f64 = 4e-6;
/// Bound on the distance between unit normals, the CPU path's
/// (lavapipe: 3.6e-7 at worst).
const NORMAL_BOUND: f64 = 1e-5;

fn models() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models")
}

fn compile(text: &str) -> StyleProgram {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source(
        "deform.npr",
        text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

fn scene(text: &str) -> Scene {
    npr_runner::scene::parse_scene(text, npr_diag::FileId(0), &models()).unwrap_or_else(|d| panic!("scene: {d:?}"))
}

/// Draws the deformed surface with its normals, and sums its world
/// positions over the vertices in a compute pass (no lines, no light
/// view: the renderer deforms on the GPU only).
const STYLE: &str = r#"
style "deformed"
pass sums: compute(vertices) {
  reduce n: float = sum(1.0)
  reduce p: vec3 = sum(position)
}
pass shade: render(scene) {
  let lit = lambert(normal, light.dir)
  out c: rgba32float = vec4(lit + 0.0 * sums.n, sums.p)
  clear: #000000
}
output shade.c
"#;

const ARM: &str = "[camera]\nposition = [0.0, 1.0, 4.5]\ntarget = [0.0, 1.0, 0.0]\n\
                   [[object]]\nmesh = \"arm.glb\"\nrotate = [0.0, 70.0, 0.0]\nanimation = { clip = \"bend\" }\n";

const BLOB: &str = "[camera]\nposition = [0.0, 0.8, 6.5]\ntarget = [0.0, 0.8, 0.0]\n\
                    [[object]]\nmesh = \"blob.glb\"\nanimation = { clip = \"pulse\", speed = 0.5 }\n";

fn frame(time_s: f64) -> FrameSpec {
    FrameSpec {
        width: 32,
        height: 32,
        time_s,
        frame: 0,
        eye: 0,
    }
}

fn vec3s(floats: &[f32]) -> Vec<Vec3> {
    floats.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect()
}

/// Renders `scene` at each time with one renderer and checks the object's
/// vertex buffers after each frame against the f64 reference and the CPU
/// deformation; returns the pose's morph weights at each time.
fn check(text: &str, file: &str, clip: &str, times: &[f64]) -> Vec<Vec<f32>> {
    let scene = scene(text);
    let program = compile(STYLE);
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let animation = scene.objects[0].animation.clone().expect("the object plays a clip");
    let model = scene.objects[0].model.as_dmat4();
    let mut weights = Vec::new();
    for (f, &time_s) in times.iter().enumerate() {
        let before = npr_runner::gpu_count::created_on_this_thread().total();
        r.render(&scene, &frame(time_s)).expect("frame");
        let created = npr_runner::gpu_count::created_on_this_thread().total() - before;
        if f > 0 {
            assert_eq!(created, 0, "a frame at a new pose creates no GPU object");
        }
        let positions = vec3s(&r.read_vertices(0, Attribute::Position).expect("positions"));
        let normals = vec3s(&r.read_vertices(0, Attribute::Normal).expect("normals"));
        let clip_t = animation.clip_time(time_s);
        let reference = skin_reference::deform(&models().join(file), Some((clip, f64::from(clip_t))));
        let pose = animation.rig.pose(Some((animation.clip, clip_t)));
        let cpu = animation.rig.deform(&pose);
        assert_eq!(positions.len(), reference.positions.len());
        let (mut dp, mut dn, mut cpu_dp, mut cpu_dn) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for (i, (p, n)) in positions.iter().zip(&normals).enumerate() {
            dp = dp.max((p.as_dvec3() - reference.positions[i]).length());
            dn = dn.max((n.as_dvec3() - reference.normals[i]).length());
            cpu_dp = cpu_dp.max(f64::from((*p - Vec3::from_array(cpu.positions[i])).length()));
            cpu_dn = cpu_dn.max(f64::from((*n - Vec3::from_array(cpu.normals[i])).length()));
        }
        // The compute pass saw the frame's vertices: their world sum.
        let sums = r.read_object_values("sums").expect("sums");
        let got = DVec3::new(
            f64::from(sums[0][1][0]),
            f64::from(sums[0][1][1]),
            f64::from(sums[0][1][2]),
        );
        let world: Vec<DVec3> = reference.positions.iter().map(|p| model.transform_point3(*p)).collect();
        let want: DVec3 = world.iter().sum();
        let sum_error = (got - want).length();
        // Each vertex within POSITION_BOUND (the model is a rotation), and
        // the f32 reduction's rounding (a tree of depth log2(n) < 16, each
        // level's rounding 6e-8 relative), 1e-6 of the sum of magnitudes.
        let sum_bound = world.len() as f64 * POSITION_BOUND + 1e-6 * world.iter().map(|p| p.length()).sum::<f64>();
        eprintln!(
            "{file} at t = {time_s} (clip {clip_t}): GPU vs f64: position {dp:e} m, normal {dn:e}; \
             GPU vs CPU: {cpu_dp:e}, {cpu_dn:e}; compute sum of {} vertices: error {sum_error:e} (bound {sum_bound:e})",
            sums[0][0][0]
        );
        assert!(
            dp <= POSITION_BOUND && dn <= NORMAL_BOUND,
            "{file} at t = {time_s}: GPU vs f64 position {dp}, normal {dn}"
        );
        assert!(
            cpu_dp <= POSITION_BOUND && cpu_dn <= NORMAL_BOUND,
            "{file} at t = {time_s}: GPU vs CPU position {cpu_dp}, normal {cpu_dn}"
        );
        assert_eq!(
            sums[0][0][0] as usize,
            positions.len(),
            "the compute pass counts every vertex"
        );
        assert!(
            sum_error <= sum_bound,
            "{file} at t = {time_s}: the compute pass's sum is off by {sum_error} (bound {sum_bound})"
        );
        let node = animation.rig.pieces[0].node;
        weights.push(pose.weights.get(node).cloned().unwrap_or_default());
    }
    weights
}

#[test]
fn the_deformation_stage_is_valid_wgsl() {
    npr_compiler::back::validate::validate_wgsl("deform.wgsl", npr_runner::exec::deform::DEFORM_WGSL)
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn the_gpu_skinned_arm_equals_its_f64_reference() {
    check(ARM, "arm.glb", "bend", &[0.0, 0.2, 0.55, 0.8, 1.3]);
}

#[test]
fn the_gpu_morphed_blob_equals_its_f64_reference_at_several_weights() {
    let weights = check(BLOB, "blob.glb", "pulse", &[0.0, 0.3, 1.1, 1.7, 2.5]);
    // Several distinct weight vectors, both targets used.
    let distinct = weights
        .iter()
        .enumerate()
        .filter(|(i, w)| weights[..*i].iter().all(|v| v != *w))
        .count();
    assert!(distinct >= 4, "morph weights at the frames: {weights:?}");
    for k in 0..2 {
        assert!(
            weights.iter().any(|w| w.get(k).copied().unwrap_or(0.0) > 0.1),
            "target {k} is weighted at some frame: {weights:?}"
        );
    }
}

/// Screen motion of each vertex from the previous frame, in px, summed
/// (and its length summed) over the object's vertices.
const MOTION: &str = r#"
style "motion"
pass motion: compute(vertices) {
  let moved = (project(position).xy - project_previous(position.previous).xy) * resolution
  reduce n: float = sum(1.0)
  reduce d: vec2 = sum(moved)
  reduce travel: float = sum(length(moved))
}
pass sampled: compute(samples) {
  count: 300
  seed: 5
  let moved = (project(position).xy - project_previous(position.previous).xy) * resolution
  reduce n: float = sum(1.0)
  reduce d: vec2 = sum(moved)
}
pass shade: render(scene) {
  out c: rgba32float = vec4(motion.d + sampled.d, motion.travel + sampled.n, motion.n)
  clear: #000000
}
output shade.c
"#;

/// `position.previous` sees the previous pose: between two frames of the
/// bending arm, each vertex's screen motion (`project(position)` against
/// `project_previous(position.previous)`) summed over the vertices equals
/// the f64 reference's (both poses skinned in f64, projected with the
/// same camera), within the position bound's image on screen; and so does
/// a pass over surface samples (the same points of the triangles in both
/// poses, Breslav et al. 2007 §3.1).
#[test]
fn position_previous_sees_the_previous_pose() {
    let scene = scene(ARM);
    let program = compile(MOTION);
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let animation = scene.objects[0].animation.clone().expect("the arm plays a clip");
    let model = scene.objects[0].model.as_dmat4();
    let size = 256u32;
    let spec = |time_s: f64| FrameSpec {
        width: size,
        height: size,
        time_s,
        frame: 0,
        eye: 0,
    };
    // A frame's motion: the first has none; then the arm bends between frames.
    r.render(&scene, &spec(0.3)).expect("frame");
    let first = r.read_object_values("motion").expect("motion");
    assert_eq!(first[0][2][0], 0.0, "no motion at the first frame: {first:?}");
    let (t0, t1) = (0.3, 0.4);
    r.render(&scene, &spec(t1)).expect("frame");
    let got = r.read_object_values("motion").expect("motion");
    let pose = scene.camera.pose(t1);
    let view_proj = (pose.projection(1.0) * pose.view(0)).as_dmat4();
    let screen = |p: DVec3| {
        let c = view_proj * model.transform_point3(p).extend(1.0);
        let ndc = c.truncate() / c.w;
        glam::DVec2::new(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * f64::from(size)
    };
    let reference = |t: f64| {
        let clip_t = f64::from(animation.clip_time(t));
        skin_reference::deform(&models().join("arm.glb"), Some(("bend", clip_t))).positions
    };
    let (before, after) = (reference(t0), reference(t1));
    let (mut d, mut travel) = (glam::DVec2::ZERO, 0.0f64);
    for (a, b) in after.iter().zip(&before) {
        let moved = screen(*a) - screen(*b);
        d += moved;
        travel += moved.length();
    }
    let n = after.len() as f64;
    // A vertex within POSITION_BOUND in each pose moves at most 2 ×
    // POSITION_BOUND × (px per metre at the arm's nearest, < 200) further
    // on screen; and 1e-4 px of f32 projection rounding per vertex.
    let per_vertex = 2.0 * POSITION_BOUND * 200.0 + 1e-4;
    let got_d = glam::DVec2::new(f64::from(got[0][1][0]), f64::from(got[0][1][1]));
    let got_travel = f64::from(got[0][2][0]);
    eprintln!(
        "arm from t = {t0} to {t1}: {n} vertices; summed screen motion {got_d:?} px (f64: {d:?}), \
         travel {got_travel} px (f64: {travel})"
    );
    assert_eq!(got[0][0][0] as usize, after.len());
    assert!(
        travel > n,
        "the arm moves more than a pixel a vertex on average ({travel} px over {n})"
    );
    assert!(
        (got_d - d).length() <= n * per_vertex * std::f64::consts::SQRT_2 + 1e-5 * travel,
        "summed motion {got_d:?} against {d:?}"
    );
    assert!(
        (got_travel - travel).abs() <= n * per_vertex * 2.0 + 1e-5 * travel,
        "travel {got_travel} against {travel}"
    );
    // The samples: the same triangles and barycentrics in both poses.
    let sampled = r.read_object_values("sampled").expect("sampled");
    let mesh = &scene.objects[0].mesh;
    let drawn = npr_runner::scene::samples::stratified(mesh, 300, npr_runner::scene::samples::object_seed(5, 0));
    let at = |positions: &[DVec3], s: &npr_runner::scene::samples::Sample| {
        let [a, b, c] = s.triangle.map(|i| positions[i as usize]);
        let (b1, b2) = (f64::from(s.b1), f64::from(s.b2));
        a * (1.0 - b1 - b2) + b * b1 + c * b2
    };
    let mut sample_d = glam::DVec2::ZERO;
    for s in &drawn.samples {
        sample_d += screen(at(&after, s)) - screen(at(&before, s));
    }
    let m = drawn.samples.len() as f64;
    let got_sample_d = glam::DVec2::new(f64::from(sampled[0][1][0]), f64::from(sampled[0][1][1]));
    eprintln!("{m} samples: summed screen motion {got_sample_d:?} px (f64: {sample_d:?})");
    assert_eq!(sampled[0][0][0] as usize, drawn.samples.len());
    assert!(
        sample_d.length() > m,
        "the samples move more than a pixel each on average"
    );
    assert!(
        (got_sample_d - sample_d).length() <= m * per_vertex * std::f64::consts::SQRT_2 + 1e-5 * sample_d.length(),
        "samples' summed motion {got_sample_d:?} against {sample_d:?}"
    );
}

/// The previous pose survives a scene change (an object spawned beside
/// the arm): at the first frame after it, the arm's `position.previous`
/// is its pose of the frame before the change, so its screen motion is
/// what a renderer without the change sees between the same two frames,
/// not zero (docs/decisions/0055).
#[test]
fn the_previous_pose_survives_a_scene_change() {
    let scene = scene(ARM);
    let program = compile(MOTION);
    let spec = |time_s: f64, frame: u32| FrameSpec {
        width: 128,
        height: 128,
        time_s,
        frame,
        eye: 0,
    };
    let mut steady = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let mut changed = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let mut more = scene.clone();
    let mut other = scene.objects[0].clone();
    other.name = "spawned".into();
    other.animation = None;
    other.model = glam::Mat4::from_translation(glam::Vec3::new(3.0, 0.0, -4.0));
    more.objects.push(other);
    for (k, t) in [0.3, 0.4].into_iter().enumerate() {
        steady.render(&scene, &spec(t, k as u32)).expect("frame");
        if k == 1 {
            changed.set_scene(&more).expect("a scene change");
            changed.render(&more, &spec(t, k as u32)).expect("frame");
        } else {
            changed.render(&scene, &spec(t, k as u32)).expect("frame");
        }
    }
    let want = steady.read_object_values("motion").expect("motion");
    let got = changed.read_object_values("motion").expect("motion");
    let travel = |v: &Vec<Vec<[f32; 4]>>| v[0][2][0];
    assert!(
        travel(&want) > want[0][0][0],
        "the arm moves more than a pixel a vertex between the frames: {want:?}"
    );
    assert_eq!(
        got[0][..3],
        want[0][..3],
        "the arm's motion at the first frame after the scene change"
    );
}
