//! A host's skinned and morphing meshes through the embedding API
//! (`StyleRuntime::add_skinned_mesh`, `Instance::pose`) draw what a scene
//! file's clips draw, byte for byte: the Blender-made characters of
//! `examples/scenes/characters.toml` (two arms bending out of step, the
//! blob pulsing its morph targets) are registered from their rigs' bind
//! meshes, joints, weights and morph targets, and each frame every
//! instance gets its pose as a host computes it (the clip sampled at the
//! object's clip time; joint matrices `world · inverseBind`, in skin
//! space). Both go through the one GPU deformation stage, so the pixels
//! are the same as `npr render`'s renderer on the scene file, at several
//! times, for a plain style and for a `lines` style (whose silhouettes
//! are built on the CPU from the same pose). A frame of new poses creates
//! no GPU object.
//!
//! On a difference the runtime's image, the renderer's and their
//! difference (×8) are written under `$CARGO_TARGET_TMPDIR/embed-skinned/`.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{compile, examples, gpu, host_target, read_host, render_frame, write_mismatch};

use npr_runner::embed::{Frame, Instance, Lights, MeshHandle, SkinPose, Skinning, StyleRuntime, Target};
use npr_runner::scene::rig::{Pose, Rig};
use npr_runner::scene::{Object, Scene};
use npr_runner::{FrameSpec, Renderer};
use std::sync::Arc;

const WIDTH: u32 = 96;
const HEIGHT: u32 = 72;

/// Scene times of the frames, in order: the arms' clip is about a second
/// long, so these are poses all over it.
const TIMES: [f64; 4] = [0.0, 0.3, 0.55, 1.7];

fn load(scene: &str) -> Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&examples().join("scenes").join(scene), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// A glTF rig of one primitive as a host's skin: its joints and weights
/// (an unskinned piece, moved by its node, as one joint every vertex
/// follows with weight 1) and its morph targets.
fn skinning_of(rig: &Rig) -> Skinning {
    assert_eq!(rig.pieces.len(), 1, "the test characters have one primitive each");
    let piece = &rig.pieces[0];
    let vertices = rig.bind.vertex_count();
    let (joint_count, joints, weights) = match piece.skin {
        Some(skin) => (rig.skins[skin].joints.len(), rig.joints.clone(), rig.weights.clone()),
        None => (1, vec![[0; 4]; vertices], vec![[1.0, 0.0, 0.0, 0.0]; vertices]),
    };
    Skinning {
        joint_count,
        joints,
        weights,
        morph_targets: piece.targets.clone(),
    }
}

/// `pose` of `rig` as a host gives it: the skin's joint matrices (or the
/// unskinned piece's node's world matrix) and the piece's morph weights,
/// written into `out` in place.
fn host_pose(rig: &Rig, pose: &Pose, out: &mut SkinPose) {
    let piece = &rig.pieces[0];
    match piece.skin {
        Some(skin) => {
            for (j, m) in out.joints.iter_mut().enumerate() {
                *m = rig.skin_joint_matrix(skin, j, pose);
            }
        }
        None => out.joints[0] = pose.world[piece.node],
    }
    out.morph_weights.copy_from_slice(&pose.weights[piece.node]);
}

/// The host's side: a mesh handle per distinct rig (the two arms share
/// one) or still mesh, and one instance per scene object.
fn register(runtime: &mut StyleRuntime, scene: &Scene) -> Vec<Instance> {
    let mut rigs: Vec<(*const Rig, MeshHandle)> = Vec::new();
    scene
        .objects
        .iter()
        .map(|o: &Object| {
            let instance = match &o.animation {
                Some(animation) => {
                    let key = Arc::as_ptr(&animation.rig);
                    let handle = match rigs.iter().find(|(k, _)| *k == key) {
                        Some((_, h)) => *h,
                        None => {
                            let skin = skinning_of(&animation.rig);
                            let h = runtime
                                .add_skinned_mesh(animation.rig.bind.clone(), skin)
                                .unwrap_or_else(|e| panic!("{}: {:?}", o.name, e.diagnostics()));
                            rigs.push((key, h));
                            h
                        }
                    };
                    let s = skinning_of(&animation.rig);
                    Instance::new(handle, o.model).with_pose(SkinPose::bind(s.joint_count, s.morph_targets.len()))
                }
                None => Instance::new(runtime.add_mesh((*o.mesh).clone()), o.model),
            };
            Instance {
                tags: o.tags.clone(),
                casts_shadows: o.casts_shadows,
                ..instance
            }
        })
        .collect()
}

/// Per time of [`TIMES`]: (the runtime's frame, the renderer's).
fn render_both(style: &str) -> Vec<(npr_runner::readback::TargetImage, npr_runner::readback::TargetImage)> {
    let program = compile(style);
    let scene = load("characters.toml");
    assert!(
        scene.objects.iter().filter(|o| o.animation.is_some()).count() == 3,
        "characters.toml should have three animated objects"
    );
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, program.clone()).expect("runtime");
    let mut instances = register(&mut runtime, &scene);
    let mut renderer = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let lights = Lights {
        key: scene.light,
        more: scene.more_lights,
    };
    let texture = host_target(WIDTH, HEIGHT, wgpu::TextureFormat::Rgba8Unorm, &[]);
    let view = texture.create_view(&Default::default());
    let mut frames = Vec::new();
    for (k, &time_s) in TIMES.iter().enumerate() {
        // The host's animation: each posed instance's clip at its time.
        for (instance, object) in instances.iter_mut().zip(&scene.objects) {
            if let (Some(animation), Some(pose)) = (&object.animation, instance.pose.as_mut()) {
                let sampled = animation.rig.pose(Some((animation.clip, animation.clip_time(time_s))));
                host_pose(&animation.rig, &sampled, pose);
            }
        }
        let frame = Frame {
            camera: &scene.camera,
            objects: &instances,
            lights: &lights,
            time_s,
            frame_index: k as u32,
            eye: 0,
        };
        let before = npr_runner::gpu_count::created_on_this_thread();
        render_frame(&mut runtime, &frame, Target::View(&view))
            .unwrap_or_else(|e| panic!("{style} at {time_s} s: {:?}", e.diagnostics()));
        let after = npr_runner::gpu_count::created_on_this_thread();
        assert!(
            k == 0 || after == before,
            "{style} at {time_s} s: a frame of new poses created GPU objects: {before:?} → {after:?}"
        );
        let hosted = read_host(&texture);
        let spec = FrameSpec {
            width: WIDTH,
            height: HEIGHT,
            time_s,
            frame: k as u32,
            eye: 0,
        };
        renderer.render(&scene, &spec).expect("render");
        frames.push((hosted, renderer.read_output().expect("read back the output")));
    }
    assert_eq!(
        runtime.builds(),
        1,
        "{style}: the runtime rebuilt its scene between frames"
    );
    frames
}

/// Every frame equals the renderer's byte for byte, and the characters
/// moved between frames (a static drawing would pass the equality too).
fn assert_equal_and_moving(
    frames: &[(npr_runner::readback::TargetImage, npr_runner::readback::TargetImage)],
    name: &str,
) {
    let mut failures = Vec::new();
    for ((hosted, direct), time_s) in frames.iter().zip(TIMES) {
        if hosted.bytes != direct.bytes {
            let pixels = hosted
                .bytes
                .chunks(4)
                .zip(direct.bytes.chunks(4))
                .filter(|(a, b)| a != b)
                .count();
            let at = format!("{name}_t{time_s}");
            let dir = write_mismatch("embed-skinned", &at, hosted, direct);
            failures.push(format!(
                "at {time_s} s: {pixels} pixels differ (images: {}/{at}_*.png)",
                dir.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{name}: the posed instances differ from the scene file's clips:\n{}",
        failures.join("\n")
    );
    for (k, pair) in frames.windows(2).enumerate() {
        let changed = pair[0]
            .1
            .bytes
            .chunks(4)
            .zip(pair[1].1.bytes.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            changed > 20,
            "{name}: the characters barely moved between {} s and {} s ({changed} pixels changed)",
            TIMES[k],
            TIMES[k + 1]
        );
    }
}

#[test]
fn characters_posed_through_the_api_render_as_their_clips() {
    let frames = render_both("toon.npr");
    assert_equal_and_moving(&frames, "toon");
}

/// A `lines` pass builds its silhouettes on the CPU from the pose
/// deformed there (`Rig::deform` of the host's pose, as of the clip's).
#[test]
fn characters_posed_through_the_api_draw_their_lines_as_their_clips() {
    let frames = render_both("wavy_lines.npr");
    assert_equal_and_moving(&frames, "wavy_lines");
}
