//! The host's [`Instance`]s as the renderer's [`Scene`]: one scene object
//! per instance, updated in place each frame (transform, params, a skinned
//! mesh's pose, camera, lights), and rebuilt only when the objects' structure changes (their
//! meshes, tags, images, shadow flags or ids, or their number). An object
//! is named by its [`Instance::id`] (`entity 7`) or, without one, by its
//! position (`object 2`): the renderer's scene change carries an object's
//! state over to the new object of the same name.

use super::meshes::MeshTable;
use super::{skin, EmbedError, Frame, Instance, MeshHandle};
use crate::scene::gltf_material::MeshMaterial;
use crate::scene::{Camera, Mesh, Object, Scene, TextureBinding};
use std::collections::BTreeMap;
use std::sync::Arc;

/// What the renderer's GPU resources depend on, per object.
#[derive(Debug, Clone, PartialEq)]
struct Shape {
    mesh: MeshHandle,
    tags: Vec<String>,
    casts_shadows: bool,
    images: BTreeMap<String, TextureBinding>,
    /// Who it is: ids that change (an entity despawned and another spawned
    /// in the same frame) are a scene change, which remaps its state.
    id: Option<u64>,
    /// Whether it has a pose (the GPU stage deforms it, into buffers of
    /// its own).
    posed: bool,
    /// Whether it plays a clip (the GPU stage deforms it too).
    animated: bool,
    /// Its glTF material, by identity: its image is a scene-level resource.
    material: Option<Arc<MeshMaterial>>,
}

impl Shape {
    fn of(instance: &Instance) -> Shape {
        Shape {
            mesh: instance.mesh,
            tags: instance.tags.clone(),
            casts_shadows: instance.casts_shadows,
            images: instance.images.clone(),
            id: instance.id,
            posed: instance.pose.is_some(),
            animated: instance.animation.is_some(),
            material: instance.material.clone(),
        }
    }

    fn matches(&self, instance: &Instance) -> bool {
        self.mesh == instance.mesh
            && self.tags == instance.tags
            && self.casts_shadows == instance.casts_shadows
            && self.images == instance.images
            && self.id == instance.id
            && self.posed == instance.pose.is_some()
            && self.animated == instance.animation.is_some()
            && match (&self.material, &instance.material) {
                (None, None) => true,
                (Some(a), Some(b)) => Arc::ptr_eq(a, b),
                _ => false,
            }
    }
}

/// The scene the runtime's renderer draws.
pub(super) struct HostScene {
    scene: Scene,
    /// Per object of `scene`, what it was built from.
    shapes: Vec<Shape>,
    /// The mesh table's revision the scene was built at: a removed mesh
    /// must be refused even when the instances did not change.
    mesh_revision: u64,
}

impl Default for HostScene {
    fn default() -> HostScene {
        HostScene {
            scene: Scene::empty(),
            shapes: Vec::new(),
            mesh_revision: u64::MAX,
        }
    }
}

/// The renderer's identity of an object from one scene to the next.
fn name_of(index: usize, instance: &Instance) -> String {
    match instance.id {
        Some(id) => format!("entity {id}"),
        None => format!("object {index}"),
    }
}

fn object(index: usize, instance: &Instance, meshes: &MeshTable) -> Result<Object, EmbedError> {
    let entry = meshes.entry(instance.mesh)?;
    let pose = match (&instance.pose, &entry.extras.rig) {
        (Some(pose), Some(rig)) => Some(skin::host_pose(rig, pose)),
        _ => None,
    };
    Ok(Object {
        name: name_of(index, instance),
        mesh: entry.mesh.clone(),
        model: instance.transform,
        tags: instance.tags.clone(),
        params: instance.params.clone(),
        param_spans: BTreeMap::new(),
        textures: instance.images.clone(),
        mesh_span: npr_diag::Span::default(),
        time_varying: entry.extras.time_varying,
        casts_shadows: instance.casts_shadows,
        spin: glam::Vec3::ZERO,
        blend: entry.extras.blend.clone(),
        patch: entry.extras.patch.clone(),
        animation: instance.animation.clone(),
        pose,
        material: instance.material.clone(),
    })
}

impl HostScene {
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Bring the scene to `frame`; true when its structure changed (the
    /// renderer's scene-level resources must be made anew). On an error
    /// (a removed mesh) the scene keeps its objects (those before the
    /// first changed one may have taken this frame's transform and params,
    /// which the renderer has not seen: the next frame sets them again).
    pub fn sync(&mut self, frame: &Frame, meshes: &MeshTable) -> Result<bool, EmbedError> {
        // Poses are checked before anything changes: one table look-up per
        // posed instance.
        for (k, instance) in frame.objects.iter().enumerate() {
            if let Some(pose) = &instance.pose {
                let entry = meshes.entry(instance.mesh)?;
                skin::check_pose(|| name_of(k, instance), instance.mesh, entry, pose)?;
            }
        }
        let same = self.mesh_revision == meshes.revision
            && self.shapes.len() == frame.objects.len()
            && self.move_objects(frame.objects);
        if !same {
            let objects = frame
                .objects
                .iter()
                .enumerate()
                .map(|(k, i)| object(k, i, meshes))
                .collect::<Result<Vec<_>, _>>()?;
            self.scene.objects = objects;
            self.shapes = frame.objects.iter().map(Shape::of).collect();
            self.mesh_revision = meshes.revision;
        }
        set_camera(&mut self.scene.camera, frame.camera);
        self.scene.light = frame.lights.key;
        self.scene.more_lights = frame.lights.more;
        Ok(!same)
    }
}

impl HostScene {
    /// Give each object its instance's transform and params while the
    /// instances keep the shapes the scene was built from; false at the
    /// first that does not (the scene is then built anew). One pass over
    /// the objects, which a host's frame walks several times
    /// (docs/PERFORMANCE.md, "A host's frame").
    fn move_objects(&mut self, instances: &[Instance]) -> bool {
        for ((o, shape), i) in self.scene.objects.iter_mut().zip(&self.shapes).zip(instances) {
            if !shape.matches(i) {
                return false;
            }
            o.model = i.transform;
            if o.params != i.params {
                o.params.clone_from(&i.params);
            }
            if let (Some(host), Some(pose)) = (&mut o.pose, &i.pose) {
                skin::copy_pose(host, pose);
            }
            if o.animation != i.animation {
                o.animation.clone_from(&i.animation);
            }
        }
        true
    }

    /// Every object drawing `old` draws `new` from now on (a deformed copy
    /// of it, `StyleRuntime::update_mesh`): the scene's structure is the
    /// same, and the renderer writes the new vertices in place.
    pub fn replace_mesh(&mut self, old: &Arc<Mesh>, new: &Arc<Mesh>) {
        for object in &mut self.scene.objects {
            if Arc::ptr_eq(&object.mesh, old) {
                object.mesh = new.clone();
            }
        }
    }
}

/// `camera` as `from`. A host's camera is mostly the same as the last
/// frame's, and `Camera`'s (derived) `clone_from` allocates its key list
/// anew: compared first, cloned only when it changed.
fn set_camera(camera: &mut Camera, from: &Camera) {
    if camera != from {
        camera.clone_from(from);
    }
}
