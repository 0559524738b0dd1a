//! What the render world needs from the main world each frame, copied in
//! Bevy's `ExtractSchedule`: per [`crate::NprStyle`] camera an
//! [`ExtractedNprCamera`] on its render entity; once, the
//! [`ExtractedNprScene`] (the compiled styles, the visible mesh entities
//! with their transforms, tags, params and skinned poses, the converted
//! meshes, the lights and the time). Copies are of small values and `Arc`s; the mesh
//! map only when it changed.

use crate::asset::NprStyleAsset;
use crate::components::{NprLight, NprObject, NprParams, NprStyle};
use crate::meshes::{Converted, NprMeshes};
use crate::runtimes::NprRuntimes;
use bevy::camera::Projection;
use bevy::mesh::skinning::{SkinnedMesh, SkinnedMeshInverseBindposes};
use bevy::mesh::{Mesh, Mesh3d};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::sync_world::RenderEntity;
use bevy::render::Extract;
use std::collections::BTreeMap;

/// A camera drawn by a style, on its render-world entity.
#[derive(Component, Clone)]
pub(crate) struct ExtractedNprCamera {
    /// The main-world entity, named in diagnostics.
    pub main: Entity,
    pub style: AssetId<NprStyleAsset>,
    pub params: BTreeMap<String, String>,
    /// npr's camera at the Bevy camera's pose; `Err` why there is none
    /// (a projection npr does not draw).
    pub camera: Result<npr_runner::scene::Camera, String>,
}

/// A visible mesh entity.
pub(crate) struct ExtractedObject {
    pub entity: Entity,
    pub mesh: AssetId<Mesh>,
    /// Object to world, as npr's glam.
    pub transform: glam::Mat4,
    pub object: Option<NprObject>,
    /// A `SkinnedMesh` entity's joint matrices in its mesh's skin space
    /// (`skins.rs`), or why there are none; `None` for an entity without one.
    pub joints: Option<Result<Vec<glam::Mat4>, String>>,
}

/// The scene every npr camera draws this frame.
#[derive(Resource, Default)]
pub(crate) struct ExtractedNprScene {
    pub styles: HashMap<AssetId<NprStyleAsset>, NprStyleAsset>,
    /// Sorted by entity, so that a still scene keeps its order (and the
    /// runtime its GPU resources) from frame to frame.
    pub objects: Vec<ExtractedObject>,
    pub meshes: HashMap<AssetId<Mesh>, Converted>,
    pub mesh_revision: u64,
    pub lights: npr_runner::embed::Lights,
    pub time_s: f64,
    pub frame: u32,
}

/// Bevy's matrix as npr's (Bevy may use another glam release).
pub(crate) fn npr_mat4(m: Mat4) -> glam::Mat4 {
    glam::Mat4::from_cols_array(&m.to_cols_array())
}

fn npr_vec3(v: Vec3) -> glam::Vec3 {
    glam::Vec3::from_array(v.to_array())
}

/// npr's camera for a Bevy camera at `transform` with `projection`.
fn npr_camera(transform: &GlobalTransform, projection: &Projection) -> Result<npr_runner::scene::Camera, String> {
    let Projection::Perspective(p) = projection else {
        return Err("its projection is not perspective; npr's cameras are".into());
    };
    let position = transform.translation();
    let mut camera =
        npr_runner::scene::Camera::looking_at(npr_vec3(position), npr_vec3(position + *transform.forward()));
    camera.up = npr_vec3(*transform.up());
    camera.fov_y_rad = p.fov;
    camera.near = p.near;
    camera.far = p.far;
    Ok(camera)
}

fn npr_light(light: &NprLight, transform: &GlobalTransform) -> npr_runner::scene::Light {
    let c = light.color.to_srgba();
    npr_runner::scene::Light {
        direction: npr_vec3(*transform.back()),
        color: [c.red, c.green, c.blue],
        intensity: light.intensity,
    }
}

/// What a camera drawn by a style is extracted from.
type NprCameraData = (
    Entity,
    &'static RenderEntity,
    &'static NprStyle,
    &'static NprParams,
    &'static GlobalTransform,
    &'static Projection,
);

/// What a mesh entity is extracted from.
type MeshEntityData = (
    Entity,
    &'static Mesh3d,
    &'static GlobalTransform,
    &'static InheritedVisibility,
    Option<&'static NprObject>,
    Option<&'static SkinnedMesh>,
);

/// Frames extracted so far.
#[derive(Default)]
pub(crate) struct FrameCounter(u32);

#[allow(clippy::too_many_arguments)]
pub(crate) fn extract_npr(
    mut commands: Commands,
    cameras: Extract<Query<NprCameraData>>,
    objects: Extract<Query<MeshEntityData>>,
    lights: Extract<Query<(Entity, &NprLight, &GlobalTransform)>>,
    joints: Extract<Query<&GlobalTransform>>,
    bindposes: Extract<Res<Assets<SkinnedMeshInverseBindposes>>>,
    styles: Extract<Res<Assets<NprStyleAsset>>>,
    meshes: Extract<Res<NprMeshes>>,
    time: Extract<Res<Time>>,
    mut scene: ResMut<ExtractedNprScene>,
    mut runtimes: ResMut<NprRuntimes>,
    mut drawn_before: Local<Vec<Entity>>,
    mut frames: Local<FrameCounter>,
) {
    let mut drawn = Vec::new();
    scene.styles.clear();
    for (main, render_entity, style, params, transform, projection) in &cameras {
        let style_id = style.0.id();
        if let Some(asset) = styles.get(style_id) {
            scene.styles.insert(style_id, asset.clone());
        }
        commands.entity(render_entity.id()).insert(ExtractedNprCamera {
            main,
            style: style_id,
            params: params.values.clone(),
            camera: npr_camera(transform, projection),
        });
        drawn.push(render_entity.id());
    }
    // Cameras that lost their style (or were despawned) lose their effect and runtime.
    for gone in drawn_before.iter().filter(|e| !drawn.contains(e)) {
        if let Ok(mut entity) = commands.get_entity(*gone) {
            entity.try_remove::<ExtractedNprCamera>();
        }
        runtimes.forget(*gone);
    }
    *drawn_before = drawn;

    scene.objects.clear();
    for (entity, mesh, transform, visibility, object, skinned) in &objects {
        if visibility.get() {
            scene.objects.push(ExtractedObject {
                entity,
                mesh: mesh.0.id(),
                transform: npr_mat4(transform.to_matrix()),
                object: object.cloned(),
                joints: skinned.map(|s| crate::skins::joint_matrices(transform, s, &joints, &bindposes)),
            });
        }
    }
    scene.objects.sort_by_key(|o| o.entity);

    if scene.mesh_revision != meshes.revision || scene.meshes.len() != meshes.meshes.len() {
        scene.meshes = meshes.meshes.clone();
        scene.mesh_revision = meshes.revision;
    }

    let mut sorted: Vec<_> = lights.iter().collect();
    sorted.sort_by_key(|(e, _, _)| *e);
    let mut found = sorted.into_iter().map(|(_, l, t)| npr_light(l, t));
    scene.lights = match found.next() {
        Some(key) => npr_runner::embed::Lights {
            key,
            more: [found.next(), found.next(), found.next()],
        },
        None => npr_runner::embed::Lights::default(),
    };
    scene.time_s = time.elapsed_secs_f64();
    // The style's `frame`: 0 at the first frame drawn, as `npr render`'s first.
    scene.frame = frames.0;
    frames.0 = frames.0.wrapping_add(1);
}
