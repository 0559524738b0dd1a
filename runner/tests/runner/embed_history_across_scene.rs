//! A scene change keeps the history (issue 32, docs/decisions/0046): a game
//! that spawns or despawns an object must not wipe every trail on screen.
//!
//! The reference each check compares with is independent of the scene
//! change: a runtime whose objects never change, which holds every object
//! from frame 0 and keeps the one not (or no longer) in the scene far off
//! to the side, out of the view (the styles here cast no shadows, so an
//! object out of the view affects no pixel), and moves it into place at
//! the spawn frame (off it at the despawn frame). The frames after a
//! spawn or despawn must equal the reference's byte for byte: the trails
//! (`previous(...)`) and the pattern tracker's per-object state
//! (Breslav et al. 2007, `examples/lib/dynamic_pattern.npr`) go on. A
//! per-object frame counter (a compute pass's `state`) checks that state
//! follows objects by [`Instance::id`] through a spawn that reorders the
//! list and a despawn that shifts it, and that a new object starts from
//! its first value, and a motion style that `position.previous` does too.
//! A new size, and `restart_history`, still start the history over.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{examples, gpu, host_target, render_frame, write_mismatch};

use glam::{Mat4, Vec3};
use npr_runner::embed::{Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::scene::{primitives, Camera};
use std::path::Path;

const SIZE: (u32, u32) = (64, 48);
/// Where an object that is not in the scene waits in the reference: far
/// to the side of the view.
const AWAY: Vec3 = Vec3::new(1000.0, 0.0, 0.0);

fn compiled(
    result: Result<npr_compiler::Compiled, npr_compiler::CompileError>,
    sources: &npr_diag::SourceMap,
) -> npr_runner::StyleProgram {
    match result {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, sources, false)),
        Err(e) => panic!("{e:?}"),
    }
}

fn example(name: &str) -> npr_runner::StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    let result = npr_compiler::compile_file(&examples().join(name), &mut sources, &Default::default());
    compiled(result, &sources)
}

fn camera() -> Camera {
    Camera::looking_at(Vec3::new(0.0, 0.8, 4.5), Vec3::ZERO)
}

/// One object of a test: its mesh (index into [`Run::handles`]), its lane
/// (x at frame 0) and its id.
#[derive(Clone, Copy)]
struct Object {
    mesh: usize,
    lane: f32,
    id: u64,
}

const A: Object = Object {
    mesh: 0,
    lane: -1.4,
    id: 11,
};
const B: Object = Object {
    mesh: 1,
    lane: 0.0,
    id: 22,
};
const C: Object = Object {
    mesh: 2,
    lane: 1.4,
    id: 33,
};

/// Where `o` is at frame `k` (moving right and turning, so it leaves a trail).
fn placed(o: &Object, k: u32) -> Mat4 {
    Mat4::from_translation(Vec3::new(o.lane + 0.06 * k as f32, 0.0, 0.0)) * Mat4::from_rotation_y(0.15 * k as f32)
}

/// A host runtime with the three test meshes registered.
struct Run {
    runtime: StyleRuntime,
    handles: Vec<MeshHandle>,
    target: wgpu::Texture,
    other_size: wgpu::Texture,
}

impl Run {
    fn new(program: npr_runner::StyleProgram) -> Run {
        let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, program).expect("runtime");
        let handles = [
            primitives::sphere(0.45, 24, 12),
            primitives::cube(0.6),
            primitives::torus(0.4, 0.15, 24, 12),
        ]
        .into_iter()
        .map(|m| runtime.add_mesh(m))
        .collect();
        let texture = |(w, h): (u32, u32)| host_target(w, h, wgpu::TextureFormat::Rgba8Unorm, &[]);
        Run {
            runtime,
            handles,
            target: texture(SIZE),
            other_size: texture((SIZE.0 + 16, SIZE.1 + 8)),
        }
    }

    /// `objects` at frame `k` (with their ids when `ids`); those in `away`
    /// wait out of the view.
    fn instances(&self, objects: &[Object], away: &[u64], k: u32, ids: bool) -> Vec<Instance> {
        objects
            .iter()
            .map(|o| {
                let transform = if away.contains(&o.id) {
                    Mat4::from_translation(AWAY)
                } else {
                    placed(o, k)
                };
                let instance = Instance::new(self.handles[o.mesh], transform);
                if ids {
                    instance.with_id(o.id)
                } else {
                    instance
                }
            })
            .collect()
    }

    /// Render frame `k` of `instances` (at the other size with `resized`),
    /// submit and wait.
    fn frame(&mut self, instances: &[Instance], k: u32, resized: bool) {
        let (camera, lights) = (camera(), Lights::default());
        let frame = Frame {
            camera: &camera,
            objects: instances,
            lights: &lights,
            time_s: f64::from(k) / 24.0,
            frame_index: k,
            eye: 0,
        };
        let view = if resized { &self.other_size } else { &self.target }.create_view(&Default::default());
        render_frame(&mut self.runtime, &frame, Target::View(&view))
            .unwrap_or_else(|e| panic!("frame {k}: {:?}", e.diagnostics()));
        gpu().device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    }

    fn output(&self) -> npr_runner::TargetImage {
        let manifest = self.runtime.manifest();
        let name = manifest.targets[manifest.output].name.clone();
        self.runtime.read_target(&name).expect("read the output")
    }
}

/// Panics, with both images written, unless `changed` equals `reference` byte for byte.
fn assert_same(what: &str, changed: &npr_runner::TargetImage, reference: &npr_runner::TargetImage) {
    if changed.bytes == reference.bytes {
        return;
    }
    let name = what.replace([' ', ','], "-");
    let dir = write_mismatch("embed-history-across-scene", &name, changed, reference);
    let differing = changed
        .bytes
        .iter()
        .zip(&reference.bytes)
        .filter(|(a, b)| a != b)
        .count();
    panic!(
        "{what}: {differing} bytes differ from the reference (images in {})",
        dir.display()
    );
}

/// `before` for frames `0..change`, then `after`, in a runtime whose scene
/// changes at frame `change`; against the reference, which holds
/// `all` from frame 0 and keeps away, before the change, those of `all`
/// not in `before`, and after it those not in `after`. Frames `change ..
/// change + 3` must be the same.
fn check_against_reference(style: &str, before: &[Object], after: &[Object], all: &[Object], change: u32) {
    let ids = |objects: &[Object]| objects.iter().map(|o| o.id).collect::<Vec<_>>();
    let away_from = |present: &[Object]| {
        let present = ids(present);
        all.iter()
            .map(|o| o.id)
            .filter(|id| !present.contains(id))
            .collect::<Vec<_>>()
    };
    let mut changed = Run::new(example(style));
    let mut reference = Run::new(example(style));
    let mut first_after = None;
    for k in 0..change + 3 {
        let (now, away) = if k < change {
            (before, away_from(before))
        } else {
            (after, away_from(after))
        };
        let instances = changed.instances(now, &[], k, true);
        changed.frame(&instances, k, false);
        let instances = reference.instances(all, &away, k, true);
        reference.frame(&instances, k, false);
        if k >= change {
            let output = changed.output();
            assert_same(
                &format!("{style}, frame {} after the change", k - change),
                &output,
                &reference.output(),
            );
            first_after.get_or_insert(output);
        }
    }
    assert_eq!(
        (changed.runtime.scene_changes(), changed.runtime.builds()),
        (1, 1),
        "{style}: the scene change was not one `set_scene`"
    );
    // What restarting would have given instead (without a history to
    // keep, the check above would say nothing).
    let mut fresh = Run::new(example(style));
    let instances = fresh.instances(after, &[], change, true);
    fresh.frame(&instances, change, false);
    assert_ne!(
        first_after.map(|o| o.bytes),
        Some(fresh.output().bytes),
        "{style}: the frame after the change is what a new runtime renders: no history to keep"
    );
}

#[test]
fn a_spawn_keeps_the_trails_of_the_other_objects() {
    // After an odd number of frames (the despawn after an even one): the
    // frame parity goes on either way.
    check_against_reference("afterimage.npr", &[A, B], &[A, B, C], &[A, B, C], 5);
}

#[test]
fn a_despawn_keeps_the_trails_of_the_others() {
    check_against_reference("afterimage.npr", &[A, B, C], &[A, C], &[A, B, C], 6);
}

#[test]
fn a_spawn_keeps_the_pattern_trackers_state_of_the_other_objects() {
    check_against_reference("halftone.npr", &[A, B], &[A, B, C], &[A, B, C], 5);
}

#[test]
fn a_new_size_still_starts_the_history_over() {
    let mut run = Run::new(example("afterimage.npr"));
    for k in 0..4 {
        let instances = run.instances(&[A, B], &[], k, true);
        run.frame(&instances, k, false);
    }
    let instances = run.instances(&[A, B], &[], 4, true);
    run.frame(&instances, 4, true);
    let mut fresh = Run::new(example("afterimage.npr"));
    let instances = fresh.instances(&[A, B], &[], 4, true);
    fresh.frame(&instances, 4, true);
    assert_same("afterimage, the frame at a new size", &run.output(), &fresh.output());
}

#[test]
fn restart_history_starts_it_over() {
    let mut run = Run::new(example("halftone.npr"));
    for k in 0..5 {
        let instances = run.instances(&[A, B], &[], k, true);
        run.frame(&instances, k, false);
    }
    run.runtime.restart_history();
    let instances = run.instances(&[A, B], &[], 5, true);
    run.frame(&instances, 5, false);
    let mut fresh = Run::new(example("halftone.npr"));
    let instances = fresh.instances(&[A, B], &[], 5, true);
    fresh.frame(&instances, 5, false);
    assert_same(
        "halftone, the frame after restart_history",
        &run.output(),
        &fresh.output(),
    );
}

/// A style whose output's red channel is each object's frame count: its
/// compute state, 1 at the object's first frame.
const COUNTER: &str = "style \"Counter\"\n\
    pass count: compute(objects) {\n  state n: float = 0.0\n  n = n + 1.0\n}\n\
    pass shade: render(scene) {\n  out c: rgba8unorm = vec4(count.n / 255.0, 0.0, 0.0, 1.0)\n  clear: #000000\n}\n\
    output shade.c\n";

fn counter() -> npr_runner::StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    let result = npr_compiler::compile_source(
        "counter.npr",
        COUNTER,
        Path::new("."),
        &mut sources,
        &Default::default(),
    );
    compiled(result, &sources)
}

/// The red value on screen at the origin of an object placed by `model`.
fn red_at(image: &npr_runner::TargetImage, model: Mat4) -> u8 {
    let pose = camera().pose(0.0);
    let clip = pose.projection(SIZE.0 as f32 / SIZE.1 as f32) * pose.view(0) * model.w_axis;
    let (x, y) = (clip.x / clip.w, clip.y / clip.w);
    let px = (((x * 0.5 + 0.5) * SIZE.0 as f32) as usize).min(SIZE.0 as usize - 1);
    let py = (((0.5 - y * 0.5) * SIZE.1 as f32) as usize).min(SIZE.1 as usize - 1);
    image.bytes[(py * SIZE.0 as usize + px) * 4]
}

/// Frames of `scenes` (objects, and for each the count it must show),
/// one frame each, in one runtime; `ids` whether instances carry them.
fn check_counts(scenes: &[(&[Object], &[u8])], ids: bool) {
    let mut run = Run::new(counter());
    for (k, (objects, counts)) in scenes.iter().enumerate() {
        let k = k as u32;
        let instances = run.instances(objects, &[], k, ids);
        run.frame(&instances, k, false);
        let image = run.output();
        let seen: Vec<u8> = objects.iter().map(|o| red_at(&image, placed(o, k))).collect();
        assert_eq!(
            seen,
            *counts,
            "frame {k} (ids: {ids}): the objects' frame counts (ids {:?})",
            objects.iter().map(|o| o.id).collect::<Vec<_>>()
        );
    }
}

/// A style whose output's red channel is how far each object's vertices
/// moved since the previous frame (`position.previous`: by the object's
/// previous transform, its current one at its first frame).
const MOTION: &str = "style \"Motion\"\n\
    pass moved: compute(vertices) {\n  reduce d: float = max(length(position - position.previous))\n}\n\
    pass shade: render(scene) {\n  out c: rgba8unorm = vec4(moved.d, 0.0, 0.0, 1.0)\n  clear: #000000\n}\n\
    output shade.c\n";

/// Each test object's step per frame: its own, `n / 255` so that the
/// output's red is `n`.
fn step(o: &Object) -> u8 {
    match o.id {
        11 => 20,
        22 => 40,
        _ => 60,
    }
}

/// Where `o` is at frame `k` of the motion test (sliding right by its step).
fn sliding(o: &Object, k: u32) -> Mat4 {
    Mat4::from_translation(Vec3::new(o.lane + f32::from(step(o)) / 255.0 * k as f32, 0.0, 0.0))
}

#[test]
fn previous_transforms_follow_objects_by_id() {
    let mut sources = npr_diag::SourceMap::new();
    let result = npr_compiler::compile_source("motion.npr", MOTION, Path::new("."), &mut sources, &Default::default());
    let mut run = Run::new(compiled(result, &sources));
    let scenes: [&[Object]; 4] = [&[A, B], &[A, B], &[C, A, B], &[C, B]];
    for (k, objects) in scenes.iter().enumerate() {
        let k = k as u32;
        let instances: Vec<Instance> = objects
            .iter()
            .map(|o| Instance::new(run.handles[o.mesh], sliding(o, k)).with_id(o.id))
            .collect();
        run.frame(&instances, k, false);
        let image = run.output();
        let seen: Vec<u8> = objects.iter().map(|o| red_at(&image, sliding(o, k))).collect();
        // Still at its first frame (frame 0, and C at frame 2), an object
        // has not moved; after it, each its own step.
        let first = |o: &Object| k == 0 || (o.id == C.id && k == 2);
        let expected: Vec<u8> = objects.iter().map(|o| if first(o) { 0 } else { step(o) }).collect();
        assert_eq!(
            seen,
            expected,
            "frame {k}: how far each object moved (ids {:?})",
            objects.iter().map(|o| o.id).collect::<Vec<_>>()
        );
    }
}

#[test]
fn compute_state_follows_objects_by_id_through_spawns_and_despawns() {
    check_counts(
        &[
            (&[A], &[1]),
            (&[A], &[2]),
            // B spawns.
            (&[A, B], &[3, 1]),
            (&[A, B], &[4, 2]),
            // C spawns at the front: A and B move down the list.
            (&[C, A, B], &[1, 5, 3]),
            // A despawns: B moves up.
            (&[C, B], &[2, 4]),
            // A comes back: a new object.
            (&[C, B, A], &[3, 5, 1]),
        ],
        true,
    );
}

#[test]
fn without_ids_an_object_continues_the_one_at_its_position() {
    check_counts(
        &[
            (&[A, B], &[1, 1]),
            (&[A, B], &[2, 2]),
            // Appended: the others keep their counts.
            (&[A, B, C], &[3, 3, 1]),
            // The first removed: B takes A's place (and its count), C B's.
            (&[B, C], &[4, 4]),
        ],
        false,
    );
}
