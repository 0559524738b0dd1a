//! Bevy `Mesh` assets as npr's meshes ([`npr_runner::scene::Mesh`]): positions,
//! normals, UVs, tangents and indices copied once per asset (and again when
//! the asset changes), in the main world where the mesh data lives, shared
//! with the render world as `Arc`s.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, Mesh, Mesh3d, PrimitiveTopology, VertexAttributeValues};
use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::*;
use std::sync::Arc;

/// `mesh` as npr's mesh; `Err` says why it cannot be (for an E0402
/// diagnostic): not a triangle list, no 3D positions, bad indices or
/// numbers. Missing normals are computed (smooth); missing tangents are
/// derived from the UVs, as for a mesh file.
pub fn npr_mesh(mesh: &Mesh, name: &str) -> Result<npr_runner::scene::Mesh, String> {
    if mesh.primitive_topology() != PrimitiveTopology::TriangleList {
        return Err(format!(
            "its topology is {:?}; npr draws triangle lists",
            mesh.primitive_topology()
        ));
    }
    let positions = match mesh.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(p)) => p.clone(),
        Some(other) => return Err(format!("its positions are {other:?}-typed; npr reads Float32x3")),
        None => return Err("it has no positions".into()),
    };
    let normals = match mesh.attribute(Mesh::ATTRIBUTE_NORMAL) {
        Some(VertexAttributeValues::Float32x3(n)) => Some(n.clone()),
        _ => None,
    };
    let uvs = match mesh.attribute(Mesh::ATTRIBUTE_UV_0) {
        Some(VertexAttributeValues::Float32x2(uv)) => Some(uv.clone()),
        _ => None,
    };
    let tangents = match mesh.attribute(Mesh::ATTRIBUTE_TANGENT) {
        Some(VertexAttributeValues::Float32x4(t)) => Some(t.clone()),
        _ => None,
    };
    let indices: Vec<u32> = match mesh.indices() {
        Some(Indices::U16(i)) => i.iter().map(|&i| i as u32).collect(),
        Some(Indices::U32(i)) => i.clone(),
        None => (0..positions.len() as u32).collect(),
    };
    // Checked before normals and tangents are derived from the indices.
    if indices.is_empty() || !indices.len().is_multiple_of(3) {
        return Err(format!(
            "it has {} indices, not a positive multiple of 3",
            indices.len()
        ));
    }
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
        return Err(format!("index {bad} is out of range ({} vertices)", positions.len()));
    }
    if normals.as_ref().is_some_and(|n| n.len() != positions.len()) {
        return Err("it has a different number of normals than positions".into());
    }
    if uvs.as_ref().is_some_and(|uv| uv.len() != positions.len()) {
        return Err("it has a different number of UVs than positions".into());
    }
    let mesh = npr_runner::scene::Mesh::from_parts(positions, normals, uvs, tangents, indices, name.to_string());
    mesh.validate()?;
    Ok(mesh)
}

/// An npr mesh as a Bevy mesh (positions, normals, UVs, tangents,
/// indices): for tests and examples that show npr's own scenes in Bevy.
pub fn bevy_mesh(mesh: &npr_runner::scene::Mesh) -> Mesh {
    let mut out = Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, mesh.positions.clone())
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, mesh.normals.clone());
    if let Some(uvs) = &mesh.uvs {
        out.insert_attribute(Mesh::ATTRIBUTE_UV_0, uvs.clone());
    }
    if let Some(tangents) = &mesh.tangents {
        out.insert_attribute(Mesh::ATTRIBUTE_TANGENT, tangents.clone());
    }
    out.insert_indices(Indices::U32(mesh.indices.clone()));
    out
}

/// A converted mesh, or why the asset cannot be drawn.
#[derive(Clone)]
pub(crate) enum Converted {
    Mesh(Arc<npr_runner::scene::Mesh>),
    Unusable,
}

/// The npr meshes of the Bevy meshes that entities draw, by asset id.
#[derive(Resource, Default)]
pub(crate) struct NprMeshes {
    pub meshes: HashMap<AssetId<Mesh>, Converted>,
    /// Bumped whenever `meshes` changes: the render world copies the map then.
    pub revision: u64,
}

/// Converts the meshes of `Mesh3d` entities that are new or changed, and
/// forgets those that no entity has any more (despawned, or given
/// another mesh) or whose asset is gone: the render world then removes
/// them from each camera's runtime, so a game that spawns and despawns
/// meshes does not grow the runtimes' mesh tables. A mesh that comes back
/// is converted again.
pub(crate) fn convert_meshes(
    mut events: MessageReader<AssetEvent<Mesh>>,
    assets: Res<Assets<Mesh>>,
    drawn: Query<&Mesh3d>,
    mut cache: ResMut<NprMeshes>,
    mut in_use: Local<HashSet<AssetId<Mesh>>>,
) {
    for event in events.read() {
        if let AssetEvent::Modified { id } | AssetEvent::Removed { id } | AssetEvent::Unused { id } = event {
            if cache.meshes.remove(id).is_some() {
                cache.revision += 1;
            }
        }
    }
    in_use.clear();
    in_use.extend(drawn.iter().map(|m| m.0.id()));
    let before = cache.meshes.len();
    cache.meshes.retain(|id, _| in_use.contains(id));
    if cache.meshes.len() != before {
        cache.revision += 1;
    }
    for Mesh3d(handle) in &drawn {
        let id = handle.id();
        if cache.meshes.contains_key(&id) {
            continue;
        }
        let Some(mesh) = assets.get(id) else { continue };
        let name = handle
            .path()
            .map_or_else(|| format!("Bevy mesh {id}"), |p| p.to_string());
        let converted = match npr_mesh(mesh, &name) {
            Ok(m) => Converted::Mesh(Arc::new(m)),
            Err(why) => {
                let d = npr_diag::Diagnostic::error(
                    npr_diag::codes::UNREADABLE_MESH,
                    format!("npr cannot draw the mesh {name}: {why}"),
                )
                .with_help("give npr's cameras triangle-list meshes with Float32x3 positions");
                error!(
                    "{}",
                    npr_diag::diagnostic::render(&[d], &npr_diag::SourceMap::new(), false)
                );
                Converted::Unusable
            }
        };
        cache.meshes.insert(id, converted);
        cache.revision += 1;
    }
}
