//! Skinned meshes in Bevy, drawn by npr with their current pose: the
//! Blender-made arm of `examples/scenes/characters.toml` (two instances
//! bending out of step) as Bevy entities (a joint entity per glTF node,
//! parented as in the file; the mesh with its `ATTRIBUTE_JOINT_INDEX`,
//! `ATTRIBUTE_JOINT_WEIGHT` and a `SkinnedMesh`), its joints' `Transform`s
//! set to the clip's values at a time as an `AnimationPlayer` sets them.
//! At two times the camera's image is compared with `npr render` of the
//! scene file at the same time (its `animation = {...}` sampled by npr),
//! within the headless tests' per-pixel bound (`common::assert_close`).
//! A skinned entity whose joints are gone or do not match its mesh is a
//! logged E0612 and is drawn unskinned; the app keeps running.

use crate::common;

use bevy::mesh::skinning::{SkinnedMesh, SkinnedMeshInverseBindposes};
use bevy::mesh::{Mesh, Mesh3d, VertexAttributeValues};
use bevy::prelude::*;
use bevy::render::render_resource::TextureFormat;
use bevy_mod_npr::{bevy_mesh, NprObject};
use common::*;
use npr_runner::scene::anim_sampler::Sampler;
use npr_runner::scene::rig::{Property, Rig};
use npr_runner::scene::Scene;
use std::sync::Arc;
use std::time::Duration;

const PATIENCE: Duration = Duration::from_secs(120);

/// Scene times compared: the arms' clip is about a second long (the late
/// arm plays at half speed from 0.4 s), so these bend both differently.
const TIMES: [f64; 2] = [0.3, 0.7];

fn bevy_mat4(m: glam::Mat4) -> Mat4 {
    Mat4::from_cols_array(&m.to_cols_array())
}

/// characters.toml without the blob, whose morph targets Bevy keeps only
/// with its `morph` feature (left off: docs/decisions/0055).
fn arms_scene() -> Scene {
    let mut scene = load_scene("characters.toml");
    scene.objects.retain(|o| o.name != "blob");
    assert_eq!(
        scene.objects.iter().filter(|o| o.animation.is_some()).count(),
        2,
        "characters.toml should have two bending arms"
    );
    scene
}

/// Every node's local transform of `rig` playing `clip` at `t`, as Bevy's
/// `AnimationPlayer` writes it into the joints' `Transform`s: the rest
/// translation, rotation and scale, each replaced by its channel's value.
fn local_transforms(rig: &Rig, clip: usize, t: f32) -> Vec<Transform> {
    let mut locals: Vec<Transform> = rig
        .nodes
        .iter()
        .map(|n| Transform::from_matrix(bevy_mat4(n.rest)))
        .collect();
    let mut value = [0.0f32; 4];
    let sample = |s: &Sampler, out: &mut [f32]| s.sample(t, out);
    for channel in &rig.clips[clip].channels {
        let local = &mut locals[channel.node];
        match channel.property {
            Property::Translation => {
                sample(&channel.sampler, &mut value[..3]);
                local.translation = Vec3::new(value[0], value[1], value[2]);
            }
            Property::Scale => {
                sample(&channel.sampler, &mut value[..3]);
                local.scale = Vec3::new(value[0], value[1], value[2]);
            }
            Property::Rotation => {
                sample(&channel.sampler, &mut value);
                local.rotation = Quat::from_xyzw(value[0], value[1], value[2], value[3]).normalize();
            }
            Property::Weights => {}
        }
    }
    locals
}

/// One arm spawned as Bevy entities: its joints (one entity per node,
/// parented as in the file, under a root at the object's transform) and
/// the skinned mesh. Returns the node entities, by node index.
fn spawn_arm(world: &mut World, object: &npr_runner::scene::Object, mesh: Handle<Mesh>) -> Vec<Entity> {
    let rig = &object.animation.as_ref().expect("an arm plays a clip").rig;
    // Visibility on every ancestor, so that the mesh's is inherited.
    let root = world
        .spawn((Transform::from_matrix(bevy_mat4(object.model)), Visibility::default()))
        .id();
    let nodes: Vec<Entity> = rig
        .nodes
        .iter()
        .map(|n| {
            world
                .spawn((Transform::from_matrix(bevy_mat4(n.rest)), Visibility::default()))
                .id()
        })
        .collect();
    for (k, n) in rig.nodes.iter().enumerate() {
        let parent = n.parent.map_or(root, |p| nodes[p]);
        world.entity_mut(nodes[k]).insert(ChildOf(parent));
    }
    let skin = &rig.skins[rig.pieces[0].skin.expect("the arm is skinned")];
    let inverse_bindposes =
        world
            .resource_mut::<Assets<SkinnedMeshInverseBindposes>>()
            .add(SkinnedMeshInverseBindposes::from(
                skin.inverse_bind.iter().map(|m| bevy_mat4(*m)).collect::<Vec<_>>(),
            ));
    world.spawn((
        Mesh3d(mesh),
        // Bevy ignores a skinned mesh entity's own transform; npr places
        // the skinned mesh by it: here the object's, as the scene file's.
        Transform::default(),
        ChildOf(root),
        SkinnedMesh {
            inverse_bindposes,
            joints: skin.joints.iter().map(|&j| nodes[j]).collect(),
        },
        NprObject {
            tags: object.tags.clone(),
            params: object.params.clone(),
            casts_shadows: object.casts_shadows,
        },
    ));
    nodes
}

/// The arm's bind mesh as a Bevy mesh with its joints and weights.
fn skinned_bevy_mesh(rig: &Rig) -> Mesh {
    bevy_mesh(&rig.bind)
        .with_inserted_attribute(
            Mesh::ATTRIBUTE_JOINT_INDEX,
            VertexAttributeValues::Uint16x4(rig.joints.clone()),
        )
        .with_inserted_attribute(Mesh::ATTRIBUTE_JOINT_WEIGHT, rig.weights.clone())
}

/// The scene's rigid objects and light as Bevy entities, and its arms
/// skinned (one mesh asset, shared); per arm object, its node entities.
fn spawn(app: &mut App, scene: &Scene) -> Vec<(usize, Vec<Entity>)> {
    let rigid = Scene {
        objects: scene
            .objects
            .iter()
            .filter(|o| o.animation.is_none())
            .cloned()
            .collect(),
        ..scene.clone()
    };
    bevy_mod_npr::spawn_npr_scene(app.world_mut(), &rigid);
    let rig: Arc<Rig> = scene
        .objects
        .iter()
        .find_map(|o| o.animation.as_ref().map(|a| a.rig.clone()))
        .expect("an arm");
    let mesh = app
        .world_mut()
        .resource_mut::<Assets<Mesh>>()
        .add(skinned_bevy_mesh(&rig));
    scene
        .objects
        .iter()
        .enumerate()
        .filter(|(_, o)| o.animation.is_some())
        .map(|(k, o)| (k, spawn_arm(app.world_mut(), o, mesh.clone())))
        .collect()
}

/// Sets every arm's joints to its clip at scene time `time_s`.
fn pose_at(app: &mut App, scene: &Scene, arms: &[(usize, Vec<Entity>)], time_s: f64) {
    for (k, nodes) in arms {
        let animation = scene.objects[*k].animation.as_ref().expect("an arm");
        let locals = local_transforms(&animation.rig, animation.clip, animation.clip_time(time_s));
        for (entity, local) in nodes.iter().zip(locals) {
            *app.world_mut().get_mut::<Transform>(*entity).expect("a node") = local;
        }
    }
}

/// `npr render` of `scene` with its clips at scene time `time_s`: the
/// frame at time 0 (Bevy's clock is stopped there, and the style's `rim`
/// is animated) of the scene with each clip's `offset` moved on by
/// `speed · time_s`, which is the clip time `time_s` gives.
fn npr_render_at(style: &std::path::Path, scene: &Scene, time_s: f64) -> image::RgbaImage {
    let gpu = npr_runner::Gpu::headless()
        .unwrap_or_else(|e| panic!("no GPU adapter (install Mesa's lavapipe: ./setup.sh --tests): {e}"));
    let mut scene = scene.clone();
    for animation in scene.objects.iter_mut().filter_map(|o| o.animation.as_mut()) {
        let at = animation.clip_time(time_s);
        animation.offset += animation.speed * time_s;
        assert_eq!(animation.clip_time(0.0), at, "the shifted clip plays the same time");
    }
    let spec = npr_runner::FrameSpec::still(SIZE, SIZE, 0);
    npr_runner::render_frame(&gpu, &compile(style), &scene, &spec)
        .unwrap_or_else(|e| panic!("npr render: {e:?}"))
        .to_rgba8()
}

/// Updates until the camera's runtime has drawn with the style and Bevy's
/// pipelines are ready, then one more frame (the image complete).
fn wait_for_drawing(app: &mut App, camera: Entity) {
    update_until(app, "the camera to draw with \"Toon\"", PATIENCE, |app| {
        let ready = app
            .sub_app(bevy::render::RenderApp)
            .world()
            .resource::<bevy::render::render_resource::PipelineCache>()
            .waiting_pipelines()
            .next()
            .is_none();
        ready && runtime_of(app, camera).is_some_and(|(_, builds)| builds > 0)
    });
    app.update();
}

#[test]
fn skinned_arms_bend_as_npr_render_draws_their_clip() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("skinned_arms");
    let style = dir.join("toon.npr");
    std::fs::copy(repo().join("examples/toon.npr"), &style).expect("copy the style");
    let scene = arms_scene();
    let mut app = app(&dir);
    let image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let arms = spawn(&mut app, &scene);
    pose_at(&mut app, &scene, &arms, TIMES[0]);
    let handle = app.world().resource::<AssetServer>().load("toon.npr");
    let camera = spawn_camera(&mut app, &scene, handle, &image);
    wait_for_drawing(&mut app, camera);
    let mut drawn = Vec::new();
    for (k, &time_s) in TIMES.iter().enumerate() {
        pose_at(&mut app, &scene, &arms, time_s);
        // The frame after the joints moved (propagated, extracted, drawn), then its image complete.
        app.update();
        app.update();
        let actual = read_image(&app, &image);
        let expected = npr_render_at(&style, &scene, time_s);
        assert_close(&format!("skinned_arms_{k}"), &actual, &expected);
        drawn.push(actual);
    }
    // The two times differ (a static drawing cannot pass both).
    let moved = drawn[0].pixels().zip(drawn[1].pixels()).filter(|(a, b)| a != b).count();
    assert!(
        moved > 100,
        "the arms barely moved between the two times ({moved} pixels)"
    );
    assert!(logged_codes(&app).is_empty(), "{:?}", logged_codes(&app));
}

#[test]
fn skinned_meshes_with_missing_or_mismatched_joints_are_logged_and_drawn_unskinned() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("skinned_bad_joints");
    std::fs::copy(repo().join("examples/toon.npr"), dir.join("toon.npr")).expect("copy the style");
    let scene = arms_scene();
    let mut app = app(&dir);
    let image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let arms = spawn(&mut app, &scene);
    let handle = app.world().resource::<AssetServer>().load("toon.npr");
    let camera = spawn_camera(&mut app, &scene, handle, &image);
    wait_for_drawing(&mut app, camera);
    assert!(logged_codes(&app).is_empty(), "{:?}", logged_codes(&app));
    // The first arm's last joint despawned.
    let (_, nodes) = &arms[0];
    let skinned: Vec<(Entity, SkinnedMesh)> = app
        .world_mut()
        .query::<(Entity, &SkinnedMesh)>()
        .iter(app.world())
        .map(|(e, s)| (e, s.clone()))
        .collect();
    let (first, skin) = skinned
        .iter()
        .find(|(_, s)| nodes.contains(&s.joints[0]))
        .expect("the first arm's skinned mesh");
    app.world_mut().despawn(*skin.joints.last().expect("joints"));
    for _ in 0..3 {
        app.update();
    }
    assert!(logged_codes(&app).contains(&"E0612"), "{:?}", logged_codes(&app));
    // The second arm's SkinnedMesh names one joint fewer than its mesh's indices.
    let (second, other) = skinned.iter().find(|(e, _)| e != first).expect("the second arm");
    let mut fewer = other.clone();
    fewer.joints.pop();
    let bindposes: Vec<Mat4> = app
        .world()
        .resource::<Assets<SkinnedMeshInverseBindposes>>()
        .get(&fewer.inverse_bindposes)
        .expect("bindposes")
        .iter()
        .take(fewer.joints.len())
        .copied()
        .collect();
    fewer.inverse_bindposes = app
        .world_mut()
        .resource_mut::<Assets<SkinnedMeshInverseBindposes>>()
        .add(SkinnedMeshInverseBindposes::from(bindposes));
    app.world_mut().entity_mut(*second).insert(fewer);
    for _ in 0..3 {
        app.update();
    }
    let e0612 = logged_codes(&app).iter().filter(|c| **c == "E0612").count();
    assert_eq!(e0612, 2, "one E0612 per bad skin: {:?}", logged_codes(&app));
    // Both are drawn (unskinned), and the app goes on drawing.
    let runtime_builds = runtime_of(&mut app, camera).map(|(_, b)| b);
    app.update();
    assert_eq!(runtime_of(&mut app, camera).map(|(_, b)| b), runtime_builds);
    let drawn = read_image(&app, &image);
    let first_pixel = drawn.get_pixel(0, 0).0;
    assert!(
        drawn.pixels().filter(|p| p.0 != first_pixel).count() > 100,
        "nothing is drawn after the bad skins"
    );
}
