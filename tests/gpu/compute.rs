//! Compute passes on the real runner: per-object reductions against CPU f64
//! sums, per-object state across frames (first value, updates, resets,
//! partial re-renders, time jumps), the previous frame's transforms, tags
//! (the object-centroids example's goldens are sidecar tests,
//! `examples/object_centroids.tests.toml`; its grazing hard scene is a
//! test here).

use glam::{DMat4, DVec3, DVec4};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer, StyleProgram};

use crate::common;
use common::{gpu, root};

fn program(text: &str) -> StyleProgram {
    common::compile_text(text)
}

fn example(path: &str) -> StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    npr_compiler::compile_file(&root().join(path), &mut sources, &Default::default())
        .unwrap_or_else(|e| panic!("{e:?}"))
        .program()
}

fn scene(path: &str) -> Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&root().join(path), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// The slot of value `name` of compute pass `pass` (live values are packed
/// in manifest order).
fn slot(program: &StyleProgram, pass: &str, name: &str) -> usize {
    let p = program.manifest.passes.iter().find(|p| p.name == pass).expect("pass");
    match &p.kind {
        npr_abi::manifest::PassKindManifest::Compute { values, .. } => values
            .iter()
            .position(|v| v.name == name)
            .unwrap_or_else(|| panic!("no live value `{pass}.{name}`")),
        _ => panic!("`{pass}` is not a compute pass"),
    }
}

fn spec(size: u32, frame: u32) -> FrameSpec {
    FrameSpec::animated(size, size, frame, FrameSpec::DEFAULT_FPS, 0)
}

/// `npr_project` in f64: world point → (screen u, v (y down), NDC depth),
/// or `None` behind the eye (where `npr_project` puts it far off screen).
fn project(view_proj: DMat4, p: DVec3) -> Option<(f64, f64, f64)> {
    let c = view_proj * DVec4::new(p.x, p.y, p.z, 1.0);
    if c.w <= 1e-8 {
        return None;
    }
    Some((c.x / c.w * 0.5 + 0.5, 0.5 - c.y / c.w * 0.5, c.z / c.w))
}

/// Per object: (count, Σpx, min px, max px) of its projected vertices, in f64.
type Reduced = (f64, [f64; 2], [f64; 2], [f64; 2]);

/// The example's reduction in f64: the vertices between the near and far
/// planes (NDC depth in 0..1, as `examples/object_centroids.npr` counts
/// them), projected to pixels.
fn cpu_reduction(scene: &Scene, size: u32, time_s: f64) -> Vec<Reduced> {
    let pose = scene.camera.pose(time_s);
    // The camera matrices are the runner's (f32, widened); everything after
    // them — transforms, projection, sums — is f64.
    let view_proj = (pose.projection(1.0) * pose.view(0)).as_dmat4();
    scene
        .objects
        .iter()
        .map(|o| {
            let model = o.model.as_dmat4();
            let mut r: Reduced = (0.0, [0.0; 2], [f64::MAX; 2], [f64::MIN; 2]);
            for p in &o.mesh.positions {
                let w = model.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
                let Some((u, v, _)) = project(view_proj, w).filter(|(_, _, z)| (0.0..1.0).contains(z)) else {
                    continue;
                };
                let px = [u * size as f64, v * size as f64];
                r.0 += 1.0;
                for (k, x) in px.iter().enumerate() {
                    r.1[k] += x;
                    r.2[k] = r.2[k].min(*x);
                    r.3[k] = r.3[k].max(*x);
                }
            }
            r
        })
        .collect()
}

/// Issue 34's sweep found the example blank on a ground plane seen at a
/// grazing angle (`style_tests/hard_scenes/grazing.toml`): half the plane's vertices
/// are behind the eye, and counted at `npr_project`'s far-off-screen
/// point they dragged the centroid a billion pixels away. The reduction
/// counts only the vertices in front (between near and far), so the
/// centroid is theirs, in f64 within 1e-4 of its size, and the image has
/// dots: more than the two colours of paper and background.
#[test]
fn centroids_on_a_grazing_plane_count_only_the_vertices_in_front() {
    let program = example("examples/object_centroids.npr");
    let scene = scene("style_tests/hard_scenes/grazing.toml");
    let size = 64;
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    r.render(&scene, &spec(size, 0)).expect("frame");
    let (count, centroid) = (slot(&program, "screen", "count"), slot(&program, "extent", "centroid"));
    let screen = r.read_object_values("screen").expect("screen values");
    let extent = r.read_object_values("extent").expect("extent values");
    let cpu = cpu_reduction(&scene, size, spec(size, 0).time_s);
    let all = scene.objects[0].mesh.positions.len() as f64;
    assert!(
        cpu[0].0 > 0.0 && cpu[0].0 < all,
        "the hard scene has vertices behind the eye and in front: {} of {all} in front",
        cpu[0].0
    );
    assert_eq!(screen[0][count][0] as f64, cpu[0].0, "vertices counted");
    for (k, got) in extent[0][centroid].iter().take(2).enumerate() {
        let want = cpu[0].1[k] / cpu[0].0;
        let got = *got as f64;
        assert!(
            (got - want).abs() <= 1e-4 * want.abs().max(size as f64),
            "centroid[{k}] {got} vs {want} px"
        );
    }
    let img = r.read_output().expect("read");
    let mut colours: Vec<[u8; 4]> = img.bytes.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 2, "the plane shows dots, not one colour: {colours:?}");
}

/// The example's reductions (`screen`) and derived values (`extent`) equal
/// the f64 ones over three frames of a moving camera: counts exactly, sums
/// to a relative 2e-6 of Σ|px| (a pairwise f32 tree over ≤ 2¹² terms),
/// extremes and centroids to 2e-3 px (f32 projection of a 96 px image).
#[test]
fn centroids_match_a_cpu_f64_reduction() {
    let program = example("examples/object_centroids.npr");
    let scene = scene("examples/scenes/orbit.toml");
    let size = 96;
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    for frame in [0u32, 12, 24] {
        r.render(&scene, &spec(size, frame)).expect("frame");
        let gpu_screen = r.read_object_values("screen").expect("screen values");
        let (count, total, lo, hi) = (
            slot(&program, "screen", "count"),
            slot(&program, "screen", "total"),
            slot(&program, "screen", "lo"),
            slot(&program, "screen", "hi"),
        );
        let (centroid_slot, size_slot) = (slot(&program, "extent", "centroid"), slot(&program, "extent", "size"));
        let gpu_extent = r.read_object_values("extent").expect("extent values");
        let cpu = cpu_reduction(&scene, size, spec(size, frame).time_s);
        assert_eq!(gpu_screen.len(), scene.objects.len());
        for (o, ((g, e), c)) in gpu_screen.iter().zip(&gpu_extent).zip(&cpu).enumerate() {
            let name = &scene.objects[o].name;
            assert_eq!(g[count][0] as f64, c.0, "frame {frame}, {name}: vertex count");
            let abs_sum: f64 = scene.objects[o].mesh.positions.len() as f64 * size as f64 * 4.0;
            for k in 0..2 {
                let err = (g[total][k] as f64 - c.1[k]).abs();
                assert!(
                    err <= 2e-6 * abs_sum.max(c.1[k].abs()),
                    "frame {frame}, {name}: Σpx[{k}] {} vs {}",
                    g[total][k],
                    c.1[k]
                );
                assert!(
                    (g[lo][k] as f64 - c.2[k]).abs() <= 2e-3,
                    "frame {frame}, {name}: min[{k}] {} vs {}",
                    g[lo][k],
                    c.2[k]
                );
                assert!(
                    (g[hi][k] as f64 - c.3[k]).abs() <= 2e-3,
                    "frame {frame}, {name}: max[{k}] {} vs {}",
                    g[hi][k],
                    c.3[k]
                );
                let centroid = c.1[k] / c.0.max(1.0);
                assert!(
                    (e[centroid_slot][k] as f64 - centroid).abs() <= 2e-3,
                    "frame {frame}, {name}: centroid[{k}] {} vs {centroid}",
                    e[centroid_slot][k]
                );
                let extent = (c.3[k] - c.2[k]).max(1.0);
                assert!(
                    (e[size_slot][k] as f64 - extent).abs() <= 4e-3,
                    "frame {frame}, {name}: size[{k}]"
                );
            }
        }
    }
}

const COUNTER: &str = r#"style "Counter"
pass count: compute(objects) {
  state k: float = 10.0 * object.index
  k = k + 1.0
  out seen: float = k
}
pass shade: render(scene) {
  out c: rg32float = vec2(count.k, count.seen)
}
output shade.c
"#;

/// Per object, the `k` and `seen` slots of the counter.
fn counts(r: &Renderer, program: &StyleProgram) -> Vec<(f32, f32)> {
    let (k, seen) = (slot(program, "count", "k"), slot(program, "count", "seen"));
    r.read_object_values("count")
        .expect("values")
        .iter()
        .map(|v| (v[k][0], v[seen][0]))
        .collect()
}

/// State starts from its first value (read per object), is updated once
/// per frame, is not advanced by a partial re-render, and restarts on a
/// resize; `out` values see the state's previous value.
#[test]
fn state_counts_frames_per_object_and_restarts_on_resize() {
    let program = program(COUNTER);
    assert!(
        program.manifest.is_path_dependent(),
        "state makes a style path-dependent"
    );
    let scene = scene("examples/scenes/spheres.toml");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    for n in 1..=4u32 {
        r.render(&scene, &spec(16, n - 1)).expect("frame");
        for (i, (k, seen)) in counts(&r, &program).into_iter().enumerate() {
            assert_eq!(k, 10.0 * i as f32 + n as f32, "frame {n}, object {i}: state");
            assert_eq!(
                seen,
                10.0 * i as f32 + n as f32 - 1.0,
                "frame {n}, object {i}: out reads the old state"
            );
        }
    }
    // The render pass reads this frame's state of the object it draws.
    let img = r.read_output().expect("read").to_rgba_f32();
    let drawn: std::collections::BTreeSet<u32> = img.iter().map(|t| t[0] as u32).collect();
    assert!(drawn.is_subset(&[0, 4, 14, 24].into()), "{drawn:?}");
    assert!(drawn.len() >= 3, "at least two objects and the background: {drawn:?}");
    r.render_until_target(&scene, &spec(16, 3), 0).expect("partial");
    assert_eq!(
        counts(&r, &program)[0].0,
        4.0,
        "a partial re-render does not advance state"
    );
    r.render(&scene, &spec(24, 0)).expect("resized");
    assert_eq!(
        counts(&r, &program)[1].0,
        11.0,
        "a new size restarts state from its first value"
    );
}

/// `position.previous` and `project_previous` see the previous frame's
/// transform and camera (the current ones on the first frame), and a tag
/// limits a pass to its objects (the others' slots stay zero).
#[test]
fn previous_transforms_and_tags() {
    let text = r#"style "Motion"
pass motion: compute(vertices, ground) {
  reduce moved: vec3 = sum(position - position.previous)
  reduce shift: vec2 = sum(project(position).xy - project_previous(position.previous).xy)
  reduce n: float = sum(1.0)
}
pass shade: render(scene) {
  out c: rgba32float = vec4(motion.moved, motion.n + motion.shift.x + motion.shift.y)
}
output shade.c
"#;
    let program = program(text);
    let (moved, shift, count) = (
        slot(&program, "motion", "moved"),
        slot(&program, "motion", "shift"),
        slot(&program, "motion", "n"),
    );
    let mut scene = scene("examples/scenes/orbit.toml");
    let ground = scene.objects.iter().position(|o| o.has_tag("ground")).expect("ground");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    r.render(&scene, &spec(16, 0)).expect("frame 0");
    let v = r.read_object_values("motion").expect("values");
    let n = scene.objects[ground].mesh.positions.len() as f32;
    assert_eq!(v[ground][count][0], n);
    assert!(
        v[ground][moved][..3].iter().all(|x| *x == 0.0),
        "no motion on the first frame: {:?}",
        v[ground][moved]
    );
    assert!(
        v[ground][shift][..2].iter().all(|x| *x == 0.0),
        "no motion on the first frame: {:?}",
        v[ground][shift]
    );
    for (o, values) in v.iter().enumerate().filter(|(o, _)| *o != ground) {
        assert!(
            values.iter().flatten().all(|x| *x == 0.0),
            "object {o} has no `ground` tag: {values:?}"
        );
    }
    // Move the ground by d and the camera by one frame: Σ(p − p_prev) = n·d.
    let d = DVec3::new(0.25, -0.5, 1.0);
    let before = scene.objects[ground].model;
    scene.objects[ground].model = glam::Mat4::from_translation(d.as_vec3()) * before;
    r.render(&scene, &spec(16, 1)).expect("frame 1");
    let v = r.read_object_values("motion").expect("values");
    for k in 0..3 {
        let want = n as f64 * d[k];
        assert!(
            (v[ground][moved][k] as f64 - want).abs() <= 1e-4 * n as f64,
            "Σ moved[{k}] = {} vs {want}",
            v[ground][moved][k]
        );
    }
    // The screen shift against f64 projections with both frames' cameras.
    let vp = |t: f64| {
        let pose = scene.camera.pose(t);
        (pose.projection(1.0) * pose.view(0)).as_dmat4()
    };
    let (now, then) = (vp(1.0 / FrameSpec::DEFAULT_FPS), vp(0.0));
    let mut want = [0.0f64; 2];
    for p in &scene.objects[ground].mesh.positions {
        let p = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
        // Behind the eye `npr_project` gives (-1e9, -1e9), as here.
        let uv = |vp, w| project(vp, w).map_or((-1e9, -1e9), |(u, v, _)| (u, v));
        let a = uv(now, scene.objects[ground].model.as_dmat4().transform_point3(p));
        let b = uv(then, before.as_dmat4().transform_point3(p));
        want[0] += a.0 - b.0;
        want[1] += a.1 - b.1;
    }
    for k in 0..2 {
        assert!(
            (v[ground][shift][k] as f64 - want[k]).abs() <= 1e-4,
            "Σ shift[{k}] = {} vs {}",
            v[ground][shift][k],
            want[k]
        );
    }
    assert!(
        want[0].abs() + want[1].abs() > 1e-3,
        "the test must move something on screen: {want:?}"
    );
}

/// A path-dependent style with state gives the same frame alone
/// (`--time`, replayed) as in a sequence (`--frames`).
#[test]
fn a_frame_with_state_rendered_alone_equals_the_same_frame_of_a_sequence() {
    let dir = std::env::temp_dir().join(format!("npr-compute-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let style = dir.join("lag.npr");
    // The dot screen follows each object's centroid with a lag: state.
    std::fs::write(
        &style,
        r#"style "Lag"
pass screen: compute(vertices) {
  reduce total: vec2 = sum(project(position).xy * resolution)
  reduce count: float = sum(1.0)
}
pass follow: compute(objects) {
  state centre: vec2 = screen.total / max(screen.count, 1.0)
  centre = mix(centre, screen.total / max(screen.count, 1.0), 0.3)
}
pass shade: render(scene) {
  let cell = fract((frag_coord - follow.centre) / 6.0)
  out c: rgba8unorm = vec4(cell, 0.5, 1.0)
}
output shade.c
"#,
    )
    .expect("style");
    let (in_sequence, alone, _) =
        common::sequence_and_alone(style.to_str().unwrap(), "examples/scenes/orbit.toml", &dir.join("out"));
    assert_eq!(alone, in_sequence, "frame 6 alone differs from frame 6 of the sequence");
    let _ = std::fs::remove_dir_all(&dir);
}
