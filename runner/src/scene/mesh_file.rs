//! Loading a mesh file named in a scene: picks the reader by extension,
//! turns OS and parser failures into messages for E0402 diagnostics, and
//! enforces the triangle limit.

use super::gltf_material::MeshMaterial;
use super::mesh::{Mesh, MAX_TRIANGLES};
pub use super::mesh_error::MeshLoadError;
use super::rig::Rig;
use super::{gltf_file, obj_file};
use std::path::Path;

/// The file extensions a scene may name, for messages.
pub const SUPPORTED_EXTENSIONS: &str = "`.obj`, `.gltf` or `.glb`";

/// Reads, parses and checks one mesh file. Never panics: a panic inside a
/// third-party parser (on a malformed file) is caught and reported as E0402.
pub fn load_mesh_file(path: &Path) -> Result<Mesh, MeshLoadError> {
    load_mesh_and_rig(path).map(|(mesh, _)| mesh)
}

/// [`load_mesh_file`], with the file's rig (a glTF file's skins, morph
/// targets and animations; the mesh is then its rest pose).
pub fn load_mesh_and_rig(path: &Path) -> Result<(Mesh, Option<Rig>), MeshLoadError> {
    load_mesh_file_parts(path).map(|loaded| (loaded.mesh, loaded.rig))
}

/// What one mesh file holds for a scene.
#[derive(Debug)]
pub struct LoadedMesh {
    /// The mesh (a rigged glTF file's rest pose).
    pub mesh: Mesh,
    /// A glTF file's skins, morph targets and animations.
    pub rig: Option<Rig>,
    /// A glTF file's material (`gltf_material`).
    pub material: Option<MeshMaterial>,
}

/// [`load_mesh_and_rig`], with the file's material.
pub fn load_mesh_file_parts(path: &Path) -> Result<LoadedMesh, MeshLoadError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    if !matches!(extension.as_str(), "obj" | "gltf" | "glb") {
        return Err(MeshLoadError::unreadable(
            format!("unsupported mesh format `{}`", path.display()),
            format!("npr reads {SUPPORTED_EXTENSIONS} meshes; convert the file, or use a `primitive`"),
        ));
    }
    let bytes = std::fs::read(path).map_err(|err| {
        MeshLoadError::unreadable(
            format!("cannot read mesh file `{}`: {err}", path.display()),
            "mesh paths are relative to the folder of the scene file",
        )
    })?;
    let source = path.display().to_string();
    let base_dir = path.parent().unwrap_or(Path::new("."));
    // A reader that panics on a malformed file is an error about the file
    // (an expected panic: `npr` prints the error alone).
    let parsed = npr_diag::panics::catch(|| match extension.as_str() {
        "obj" => obj_file::parse_obj(&bytes, &source).map(|mesh| (mesh, None, None)),
        _ => gltf_file::parse_gltf(&bytes, base_dir, &source),
    });
    let (mesh, rig, material) = parsed.unwrap_or_else(|why| {
        Err(MeshLoadError::unreadable(
            format!("the mesh reader failed on `{source}`: {why}"),
            "the file is probably malformed; re-export it from a modelling tool",
        ))
    })?;
    if mesh.triangle_count() > MAX_TRIANGLES {
        return Err(MeshLoadError::too_many_triangles(path, mesh.triangle_count()));
    }
    mesh.validate().map_err(|problem| {
        MeshLoadError::unreadable(
            format!("mesh `{source}` is unusable: {problem}"),
            "re-export the mesh as triangles from a modelling tool",
        )
    })?;
    Ok(LoadedMesh { mesh, rig, material })
}
