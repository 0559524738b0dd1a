//! Why a mesh file could not be used: the one error type of every mesh
//! reader (OBJ, glTF, the rig) and of the loader that picks among them. A
//! leaf, so that the loader and the readers it calls do not import each
//! other for it.

use super::mesh::MAX_TRIANGLES;
use npr_diag::codes;
use std::path::Path;

/// Why a mesh file could not be used. The scene parser attaches the span of
/// the `mesh = "..."` string and turns this into a [`npr_diag::Diagnostic`].
#[derive(Debug, Clone, PartialEq)]
pub struct MeshLoadError {
    /// [`codes::UNREADABLE_MESH`] or [`codes::LIMIT_EXCEEDED`].
    pub code: &'static str,
    pub message: String,
    pub help: String,
}

impl MeshLoadError {
    pub fn unreadable(message: impl Into<String>, help: impl Into<String>) -> Self {
        MeshLoadError {
            code: codes::UNREADABLE_MESH,
            message: message.into(),
            help: help.into(),
        }
    }

    pub fn too_many_triangles(path: &Path, triangles: usize) -> Self {
        MeshLoadError {
            code: codes::LIMIT_EXCEEDED,
            message: format!(
                "mesh `{}` has {triangles} triangles, more than the limit of {MAX_TRIANGLES}",
                path.display()
            ),
            help: "decimate the mesh (e.g. Blender's Decimate modifier or MeshLab's quadric edge collapse)".into(),
        }
    }
}
