//! Dynamic 2D patterns (Breslav et al. 2007) on the real runner, with the
//! tracker of `examples/lib/dynamic_pattern.npr`: exact recovery of a known
//! image similarity (§3.2), the pattern frame's update (§3.3), the symmetric
//! scale against the plain one over zoom cycles, the GPU's z against an f64
//! solve of the same samples, degenerate frames that hold the frame and
//! never produce NaN, and each object's (and patch's) own first pattern
//! frame. The styles built on it are in `pattern_styles.rs`.

use glam::{DVec2, Mat4, Vec3};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer, StyleProgram};

use crate::common;
use common::{gpu, root};

/// The tracker of `examples/lib/dynamic_pattern.npr` with `edit` applied to
/// its text, and a shading pass that reads its frame.
fn style(edit: impl Fn(String) -> String) -> String {
    let tracker = std::fs::read_to_string(root().join("examples/lib/dynamic_pattern.npr")).expect("tracker");
    format!(
        r#"{}
pass shade: render(scene) {{
  let uv = pattern_uv(pattern.o, pattern.u, pattern.v)
  out c: rgba32float = vec4(uv, pattern.zoom, 1.0)
}}
output shade.c
"#,
        edit(tracker)
    )
}

fn program(text: &str) -> StyleProgram {
    common::compile_text(text)
}

/// A camera at the origin looking down −z at a unit quad (or a sphere) 5 m away.
fn scene(object: &str) -> Scene {
    let text = format!(
        "[camera]\nposition = [0.0, 0.0, 0.0]\ntarget = [0.0, 0.0, -1.0]\nfov = 40.0\nnear = 0.1\nfar = 50.0\n\
         [light]\ndirection = [0.0, 0.0, 1.0]\n\n[[object]]\nprimitive = {object}\n"
    );
    npr_runner::scene::parse_scene(&text, npr_diag::FileId(0), root()).unwrap_or_else(|d| panic!("{d:?}"))
}

const QUAD: &str = "{ kind = \"plane\", size = 1.0, subdivisions = 4 }";
const SPHERE: &str = "{ kind = \"sphere\", radius = 0.5, segments = 32, rings = 16 }";

/// The pattern frame (o, u, v, scale) of object 0.
fn pattern_frame(r: &Renderer) -> (DVec2, DVec2, DVec2, f64) {
    let v = &r.read_object_values("pattern").expect("pattern values")[0];
    let p = |k: usize| DVec2::new(v[k][0] as f64, v[k][1] as f64);
    // The pass's live values in slot order: o, u, v, scale (states).
    (p(0), p(1), p(2), v[3][0] as f64)
}

/// Complex division a / b.
fn cdiv(a: DVec2, b: DVec2) -> DVec2 {
    let d = b.length_squared();
    DVec2::new(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / d
}

fn cmul(a: DVec2, b: DVec2) -> DVec2 {
    DVec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

/// `world` projected to px (y down) by the scene's camera at `size`.
fn project(scene: &Scene, size: u32, world: glam::DVec3) -> DVec2 {
    let pose = scene.camera.pose(0.0);
    let c = (pose.projection(1.0) * pose.view(0)).as_dmat4() * world.extend(1.0);
    DVec2::new(
        (c.x / c.w * 0.5 + 0.5) * size as f64,
        (0.5 - c.y / c.w * 0.5) * size as f64,
    )
}

/// The quad facing the camera at depth `d`, turned by `angle` about the
/// view axis and shifted by (x, y): its image moves by an exact similarity.
fn placed(x: f32, y: f32, d: f32, angle: f32) -> Mat4 {
    Mat4::from_translation(Vec3::new(x, y, -d))
        * Mat4::from_rotation_z(angle)
        * Mat4::from_rotation_x(std::f32::consts::FRAC_PI_2)
}

#[test]
fn a_known_image_similarity_is_recovered() {
    let size = 96;
    let program = program(&style(|t| t));
    let mut scene = scene(QUAD);
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let spec = |frame: u32| FrameSpec::animated(size, size, frame, FrameSpec::DEFAULT_FPS, 0);
    // Frame 0 has no previous ID image: the frame is held at its first value.
    scene.objects[0].model = placed(0.0, 0.0, 5.0, 0.0);
    r.render(&scene, &spec(0)).expect("frame 0");
    let first = pattern_frame(&r);
    r.render(&scene, &spec(1)).expect("frame 1");
    let still = pattern_frame(&r);
    assert!(
        (still.1 - first.1).length() < 1e-4 * first.1.length(),
        "no motion, no change: {first:?} → {still:?}"
    );
    // Each step: translate, turn and move closer, then compare the tracked z
    // with the image similarity of the quad's projected corners.
    let mut pose = (0.0f32, 0.0f32, 5.0f32, 0.0f32);
    let mut before = still;
    for (k, step) in [
        (0.05, -0.03, -0.2, 0.05),
        (-0.08, 0.02, 0.3, -0.1),
        (0.0, 0.0, -0.5, 0.2),
    ]
    .iter()
    .enumerate()
    {
        let old = pose;
        pose = (old.0 + step.0, old.1 + step.1, old.2 + step.2, old.3 + step.3);
        scene.objects[0].model = placed(pose.0, pose.1, pose.2, pose.3);
        r.render(&scene, &spec(2 + k as u32)).expect("frame");
        let after = pattern_frame(&r);
        // The exact similarity: q' = a + z q from two points of the plane.
        let corner =
            |m: Mat4, x: f64, z: f64| project(&scene, size, m.as_dmat4().transform_point3(glam::DVec3::new(x, 0.0, z)));
        let (m0, m1) = (
            placed(old.0, old.1, old.2, old.3),
            placed(pose.0, pose.1, pose.2, pose.3),
        );
        let (a0, b0) = (corner(m0, -0.4, -0.4), corner(m0, 0.4, 0.3));
        let (a1, b1) = (corner(m1, -0.4, -0.4), corner(m1, 0.4, 0.3));
        let z = cdiv(b1 - a1, b0 - a0);
        let tracked = cdiv(after.1, before.1);
        assert!(
            (tracked - z).length() <= 1e-4 * z.length(),
            "step {k}: tracked z {tracked:?}, image similarity {z:?}"
        );
        assert!(
            (cdiv(after.2, before.2) - z).length() <= 1e-4 * z.length(),
            "v moves by z too"
        );
        // The origin moves as every image point does: o' = a1 + z (o − a0).
        let want_o = a1 + cmul(z, before.0 - a0);
        assert!(
            (after.0 - want_o).length() <= 1e-4 * (want_o - a1).length().max(size as f64),
            "step {k}: o {:?}, want {want_o:?}",
            after.0
        );
        assert!(
            (after.3 / before.3 - z.length()).abs() <= 1e-4 * z.length(),
            "scale × |z|"
        );
        before = after;
    }
}

/// Cumulative scale after `cycles` zoom-in/zoom-out cycles of a sphere.
fn zoom_cycles(edit: impl Fn(String) -> String, cycles: u32) -> f64 {
    let size = 48;
    let program = program(&style(edit));
    let mut scene = scene(SPHERE);
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let mut frame_no = 0;
    let mut render = |scene: &Scene, r: &mut Renderer| {
        let spec = FrameSpec::animated(size, size, frame_no, FrameSpec::DEFAULT_FPS, 0);
        frame_no += 1;
        r.render(scene, &spec).expect("frame");
    };
    for _ in 0..2 {
        scene.objects[0].model = Mat4::from_translation(Vec3::new(0.3, 0.1, -4.0));
        render(&scene, &mut r);
    }
    for _ in 0..cycles {
        scene.objects[0].model = Mat4::from_translation(Vec3::new(0.3, 0.1, -2.5));
        render(&scene, &mut r);
        scene.objects[0].model = Mat4::from_translation(Vec3::new(0.3, 0.1, -4.0));
        render(&scene, &mut r);
    }
    let (o, u, v, scale) = pattern_frame(&r);
    assert!(
        [o.x, o.y, u.x, u.y, v.x, v.y, scale].iter().all(|x| x.is_finite()),
        "finite frame"
    );
    scale
}

#[test]
fn the_symmetric_scale_does_not_drift_over_a_thousand_zoom_cycles() {
    let symmetric = zoom_cycles(|t| t, 1000);
    let plain = zoom_cycles(
        |t| {
            t.replace(
                "param symmetric_scale: bool = true",
                "param symmetric_scale: bool = false",
            )
        },
        1000,
    );
    // The paper's weight: this frame's area and visibility only.
    let this_frame_only = zoom_cycles(
        |t| {
            t.replace(
                "sqrt(area_now * area_before)",
                "if area_before > 0.0 { area_now } else { 0.0 }",
            )
        },
        1000,
    );
    eprintln!(
        "cumulative scale after 1000 zoom cycles: symmetric {symmetric}, plain {plain}, symmetric with this frame's weights only {this_frame_only}"
    );
    assert!(
        (symmetric - 1.0).abs() <= 1e-3,
        "symmetric scale drifted to {symmetric}"
    );
    assert!(
        (plain - 1.0).abs() > 10.0 * (symmetric - 1.0).abs(),
        "the plain form drifts more: {plain} against {symmetric}"
    );
}

/// Renders `models` (object 0's model per frame, after two still frames)
/// at `size`, and returns object 0's frame after each.
fn track(edit: impl Fn(String) -> String, scene: &mut Scene, size: (u32, u32), models: &[Mat4]) -> Vec<[f64; 7]> {
    let program = program(&style(edit));
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, scene).expect("renderer");
    let mut out = Vec::new();
    for (k, m) in models.iter().enumerate() {
        scene.objects[0].model = *m;
        let spec = FrameSpec::animated(size.0, size.1, k as u32, FrameSpec::DEFAULT_FPS, 0);
        r.render(scene, &spec).expect("frame");
        let (o, u, v, zoom) = pattern_frame(&r);
        let f = [o.x, o.y, u.x, u.y, v.x, v.y, zoom];
        assert!(f.iter().all(|x| x.is_finite()), "frame {k} at {size:?}: {f:?}");
        out.push(f);
    }
    out
}

fn held(a: &[f64; 7], b: &[f64; 7]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-6 * x.abs().max(1.0))
}

#[test]
fn degenerate_frames_hold_the_pattern_frame_and_stay_finite() {
    let at = |x: f32| placed(x, 0.0, 5.0, 0.0);
    // Leaving the view and coming back: held while off screen.
    let mut s = scene(QUAD);
    let f = track(
        |t| t,
        &mut s,
        (64, 64),
        &[at(0.0), at(0.0), at(0.1), at(30.0), at(30.0), at(0.1), at(0.15)],
    );
    assert!(held(&f[3], &f[2]) && held(&f[4], &f[3]), "held off screen: {f:?}");
    assert!(
        held(&f[5], &f[4]),
        "the first frame back has no previous sight of it: held"
    );
    assert!(!held(&f[6], &f[5]), "tracking resumes");
    // Fully hidden behind a larger quad in front.
    let mut s = scene(QUAD);
    let mut wall = s.objects[0].clone();
    wall.model = placed(0.0, 0.0, 2.0, 0.0) * Mat4::from_scale(Vec3::splat(3.0));
    s.objects.push(wall);
    let f = track(|t| t, &mut s, (64, 64), &[at(0.0), at(0.0), at(0.1), at(0.2)]);
    assert!(f.windows(2).all(|w| held(&w[0], &w[1])), "hidden: always held: {f:?}");
    // One sample: no spread to solve for.
    let mut s = scene(QUAD);
    let f = track(
        |t| t.replace("count: 400", "count: 1"),
        &mut s,
        (64, 64),
        &[at(0.0), at(0.0), at(0.1)],
    );
    assert!(f.windows(2).all(|w| held(&w[0], &w[1])), "one sample: held: {f:?}");
    // Zero area: the object scaled to nothing.
    let mut s = scene(QUAD);
    let flat = Mat4::from_scale(Vec3::ZERO);
    let f = track(|t| t, &mut s, (64, 64), &[at(0.0), at(0.0), flat, flat, at(0.0)]);
    assert!(held(&f[3], &f[2]), "zero area: held: {f:?}");
    // A cut: the object teleports; finite whatever the solve gives.
    let mut s = scene(QUAD);
    track(
        |t| t,
        &mut s,
        (64, 64),
        &[at(0.0), at(0.0), placed(-1.0, 0.8, 9.0, 2.0), at(0.0)],
    );
    // Tiny images.
    for size in [(1, 1), (3, 7)] {
        let mut s = scene(QUAD);
        track(|t| t, &mut s, size, &[at(0.0), at(0.0), at(0.05), at(0.1)]);
    }
}

/// The tracker's z on the GPU against the §3.2 similarity computed in f64
/// (`npr_stdlib::reference::similarity`) from the same samples, projected in
/// f64, weighted from the read-back ID images of both frames, over random
/// motions of a sphere (which is not a similarity in the image: z is the
/// least-squares fit, so this checks the sums, not just exact cases).
#[test]
fn the_gpu_similarity_matches_an_f64_solve_of_the_same_samples() {
    use glam::{DMat4, DVec3};
    use npr_stdlib::reference::ImageF64;
    let size = 96u32;
    let program = program(&style(|t| t));
    let ids_target = program
        .manifest
        .targets
        .iter()
        .position(|t| t.name == "ids.id")
        .expect("ids.id");
    let mut scene = scene(SPHERE);
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    assert!(r.target_survives_frame(ids_target), "the ID image is a history target");
    let mesh = scene.objects[0].mesh.clone();
    let drawn = npr_runner::scene::samples::stratified(&mesh, 400, npr_runner::scene::samples::object_seed(1, 0));
    let pose = scene.camera.pose(0.0);
    let view_proj = (pose.projection(1.0) * pose.view(0)).as_dmat4();
    let read_ids = |r: &Renderer| npr_lab::patterns_f64::ids_f64(&r.read_target(ids_target).expect("ids"));
    let mut rng = 0x1234_5678_9abc_def0u64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut model = DMat4::from_translation(DVec3::new(0.1, -0.05, -4.0));
    let mut worst = 0.0f64;
    let mut previous: Option<(DMat4, ImageF64, DVec2)> = None;
    for frame in 0..8u32 {
        scene.objects[0].model = model.as_mat4();
        let spec = FrameSpec::animated(size, size, frame, FrameSpec::DEFAULT_FPS, 0);
        r.render(&scene, &spec).expect("frame");
        let ids = read_ids(&r);
        let (_, u, _, _) = pattern_frame(&r);
        if let Some((before, ids_before, u_before)) = previous.take() {
            let (then, now) = (
                npr_lab::patterns_f64::View {
                    model: before,
                    view_proj,
                    ids: &ids_before,
                },
                npr_lab::patterns_f64::View {
                    model,
                    view_proj,
                    ids: &ids,
                },
            );
            let (_, _, z) = npr_lab::patterns_f64::solve(&mesh, &drawn, (&then, &now), (size, size), (1.0, 2.0, true))
                .expect("the sphere is visible in both frames");
            let z = DVec2::from(z);
            let tracked = cdiv(u, u_before);
            let error = (tracked - z).length() / z.length();
            worst = worst.max(error);
            // f32 sums of centred moments: 1e-7 measured; 1e-5 leaves room
            // for a sample whose window straddles a texel edge.
            assert!(
                error <= 1e-5,
                "frame {frame}: GPU z {tracked:?}, f64 z {z:?} (relative error {error:e})"
            );
        }
        previous = Some((model, ids, u));
        // A random small motion: a shift, a turn about a random axis, a dolly.
        let axis = DVec3::new(next(), next(), next()).normalize_or(DVec3::Y);
        model = DMat4::from_translation(DVec3::new(0.08 * next(), 0.08 * next(), 0.3 * next()))
            * model
            * DMat4::from_axis_angle(axis, 0.2 * next());
    }
    eprintln!("worst relative error of z against f64: {worst:e}");
}

/// Every object starts from its own pattern frame (§3.3 leaves o₀ free):
/// object k's first o is a·u₀ + b·v₀ with (a, b) = fract(k·(1/g, 1/g²)), g
/// the plastic number (the R2 sequence), u₀ and v₀ the tracker's first axes
/// (12 px at 30°). Checked in f64 on the four patches of a sphere (each an
/// object of its own), at the first frame and after frames that hold it;
/// and any two of the first 64 objects (`MAX_PATCHES`) start at least
/// 0.0785 of a period apart on the torus of offsets, the first 6 (the
/// patched cow) at least 0.271.
#[test]
fn each_object_and_patch_starts_from_its_own_pattern_frame() {
    let g = 1.324_717_957_244_746_f64;
    let offset = |k: u32| {
        let a = k as f64 / g;
        (a.fract(), (a / g).fract())
    };
    let (period, angle) = (12.0, 30f64.to_radians());
    let u0 = DVec2::new(angle.cos(), angle.sin()) * period;
    let v0 = DVec2::new(-angle.sin(), angle.cos()) * period;
    let text = "[camera]\nposition = [0.0, 0.0, 0.0]\ntarget = [0.0, 0.0, -1.0]\n[[object]]\n\
                primitive = { kind = \"sphere\", radius = 0.5, segments = 32, rings = 16 }\ntranslate = [0.0, 0.0, -4.0]\npatches = 4\n";
    let scene = npr_runner::scene::parse_scene(text, npr_diag::FileId(0), root()).unwrap_or_else(|d| panic!("{d:?}"));
    assert_eq!(scene.objects.len(), 4);
    let program = program(&style(|t| t));
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    for frame in 0..3 {
        let spec = FrameSpec::animated(64, 64, frame, FrameSpec::DEFAULT_FPS, 0);
        r.render(&scene, &spec).expect("frame");
        let values = r.read_object_values("pattern").expect("pattern values");
        for (k, v) in values.iter().enumerate() {
            let p = |i: usize| DVec2::new(v[i][0] as f64, v[i][1] as f64);
            let (a, b) = offset(k as u32);
            let want = u0 * a + v0 * b;
            assert!(
                (p(0) - want).length() <= 1e-4 * period,
                "frame {frame}, object {k}: o {:?}, want {want:?} = {a:.4}·u₀ + {b:.4}·v₀",
                p(0)
            );
            assert!((p(1) - u0).length() <= 1e-4 * period && (p(2) - v0).length() <= 1e-4 * period);
        }
    }
    // The offsets on the torus [0, 1)² (a period along u and v).
    let apart = |n: u32| {
        let mut least = f64::INFINITY;
        for i in 0..n {
            for j in 0..i {
                let ((a, b), (c, d)) = (offset(i), offset(j));
                let wrap = |x: f64| x.abs().min(1.0 - x.abs());
                least = least.min(wrap(a - c).hypot(wrap(b - d)));
            }
        }
        least
    };
    assert!(apart(64) >= 0.0785 && apart(6) >= 0.271, "{} {}", apart(64), apart(6));
}
