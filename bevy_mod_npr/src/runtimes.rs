//! The render world's state of every camera drawn by a style: its
//! runtime, what it was given, and the diagnostics already logged. Its own
//! module because two systems share it: extraction forgets the cameras no
//! longer drawn, and the draw system builds and runs the runtimes.

use crate::report::Reports;
use bevy::mesh::Mesh;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use npr_runner::embed::{Instance, MeshHandle, StyleRuntime};
use std::collections::BTreeMap;
use std::sync::Arc;

/// One camera's runtime and what it was given.
pub(crate) struct CameraRuntime {
    pub(crate) runtime: StyleRuntime,
    /// The style asset's revision it runs.
    pub(crate) revision: u64,
    /// Bevy mesh → the npr mesh registered (compared by pointer) and its handle.
    pub(crate) meshes: HashMap<AssetId<Mesh>, (Arc<npr_runner::scene::Mesh>, MeshHandle)>,
    /// The parameter values given to the runtime so far.
    pub(crate) params: BTreeMap<String, String>,
    pub(crate) instances: Vec<Instance>,
    /// The revision of the scene's mesh map when `meshes` was last pruned.
    pub(crate) mesh_revision: u64,
}

/// The runtimes of the cameras drawn by a style, by render entity, and the
/// diagnostics already logged.
#[derive(Resource, Default)]
pub struct NprRuntimes {
    pub(crate) cameras: HashMap<Entity, CameraRuntime>,
    pub(crate) reports: Reports,
}

impl NprRuntimes {
    /// Drop the runtime of a camera that is no longer drawn by a style.
    pub(crate) fn forget(&mut self, camera: Entity) {
        self.cameras.remove(&camera);
        self.reports.forget(camera);
    }

    /// How many times the runtime of the camera with render entity
    /// `camera` built its GPU resources (a test's window on hot reload and
    /// resizing); `None` when it has no runtime.
    pub fn builds(&self, camera: Entity) -> Option<u64> {
        self.cameras.get(&camera).map(|c| c.runtime.builds())
    }

    /// How many meshes the camera's runtime has registered: those of the
    /// entities drawn since Bevy last forgot a mesh (no entity has it any
    /// more, or its asset is gone), not one per mesh ever drawn.
    pub fn mesh_count(&self, camera: Entity) -> Option<usize> {
        self.cameras.get(&camera).map(|c| c.runtime.mesh_count())
    }

    /// The name of the style the camera's runtime runs.
    pub fn style_name(&self, camera: Entity) -> Option<&str> {
        self.cameras.get(&camera).map(|c| c.runtime.manifest().style.as_str())
    }

    /// The codes of every diagnostic logged so far (tests check them).
    pub fn logged_codes(&self) -> Vec<&'static str> {
        self.reports.codes()
    }

    /// The text of every diagnostic logged so far, as npr prints it.
    pub fn logged_messages(&self) -> Vec<String> {
        self.reports.messages()
    }
}
