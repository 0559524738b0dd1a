//! npr's scenes (TOML files read by `npr_runner::scene::load_scene`) as Bevy
//! entities: each object a `Mesh3d` with its transform, tags and params,
//! the key light an [`NprLight`], the camera a `Camera3d` at the scene's
//! camera (at time 0). For tests and benchmarks that compare with `npr
//! render`, and for apps that keep their scenes in npr's format.

use crate::components::{NprLight, NprObject};
use crate::meshes::bevy_mesh;
use bevy::prelude::*;

fn vec3(v: glam::Vec3) -> Vec3 {
    Vec3::from_array(v.to_array())
}

/// Spawn `scene`'s objects and key light into `world`.
pub fn spawn_npr_scene(world: &mut World, scene: &npr_runner::scene::Scene) {
    for object in &scene.objects {
        let mesh = world.resource_mut::<Assets<Mesh>>().add(bevy_mesh(&object.mesh));
        world.spawn((
            Mesh3d(mesh),
            Transform::from_matrix(Mat4::from_cols_array(&object.model.to_cols_array())),
            NprObject {
                tags: object.tags.clone(),
                params: object.params.clone(),
                casts_shadows: object.casts_shadows,
            },
        ));
    }
    let light = scene.light;
    world.spawn((
        NprLight {
            color: Color::srgb(light.color[0], light.color[1], light.color[2]),
            intensity: light.intensity,
        },
        Transform::default().looking_to(-vec3(light.direction), Vec3::Y),
    ));
}

/// A `Camera3d` at `scene`'s camera (its pose at time 0, its field of
/// view and clip planes), without MSAA: add `NprStyle` and a target.
pub fn npr_scene_camera(scene: &npr_runner::scene::Scene) -> impl Bundle {
    let pose = scene.camera.pose(0.0);
    (
        Camera3d::default(),
        Msaa::Off,
        Transform::from_translation(vec3(pose.eye)).looking_at(vec3(pose.target), vec3(pose.up)),
        Projection::Perspective(PerspectiveProjection {
            fov: pose.fov_y_rad,
            near: pose.near,
            far: pose.far,
            ..Default::default()
        }),
    )
}
