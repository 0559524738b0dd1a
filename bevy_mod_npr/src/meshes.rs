//! Bevy `Mesh` assets as npr's meshes ([`npr_runner::scene::Mesh`]): positions,
//! normals, UVs, tangents and indices copied once per asset (and again when
//! the asset changes), in the main world where the mesh data lives, shared
//! with the render world as `Arc`s.
//!
//! A mesh kept only in the render world (`RenderAssetUsages::RENDER_WORLD`)
//! loses its data in the main world when Bevy extracts it, at the end of
//! the frame it was added. So, while a camera is drawn by a style, npr
//! converts such a mesh in that frame (after the asset events, before
//! extraction), whether an entity draws it yet or not, and keeps the
//! conversion while the asset lives: a mesh despawned and spawned again is
//! drawn from it. The cost is npr's CPU copy of those meshes. A mesh whose
//! data is gone before npr saw it (made before any styled camera existed)
//! is logged (E0402) and skipped; nothing panics.
//!
//! A mesh with joint indices and weights (`ATTRIBUTE_JOINT_INDEX`,
//! `ATTRIBUTE_JOINT_WEIGHT`: a glTF skin's `JOINTS_0`/`WEIGHTS_0`) keeps
//! them as npr's [`Skinning`]: an entity drawing it with a `SkinnedMesh`
//! is deformed by its joints' pose each frame (`extract.rs`), through the
//! embedding API's skinned meshes (docs/decisions/0055).

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, Mesh, Mesh3d, MeshAccessError, PrimitiveTopology, VertexAttributeValues};
use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::*;
use npr_runner::embed::Skinning;
use std::sync::Arc;

/// `mesh` as npr's mesh; `Err` says why it cannot be (for an E0402
/// diagnostic): not a triangle list, no 3D positions, bad indices or
/// numbers. Missing normals are computed (smooth); missing tangents are
/// derived from the UVs, as for a mesh file.
pub fn npr_mesh(mesh: &Mesh, name: &str) -> Result<npr_runner::scene::Mesh, String> {
    npr_mesh_of(mesh, name).map(|(m, _)| m).map_err(|e| match e {
        Unreadable::Invalid(why) => why,
        Unreadable::InRenderWorldOnly => IN_RENDER_WORLD_ONLY.to_string(),
    })
}

const IN_RENDER_WORLD_ONLY: &str =
    "its data was extracted to the render world (RenderAssetUsages::RENDER_WORLD) before npr could read it";

/// Why a Bevy mesh cannot be npr's.
enum Unreadable {
    /// The mesh is not one npr draws (the reason).
    Invalid(String),
    /// Its data is no longer in the main world.
    InRenderWorldOnly,
}

impl From<MeshAccessError> for Unreadable {
    fn from(e: MeshAccessError) -> Unreadable {
        match e {
            MeshAccessError::ExtractedToRenderWorld => Unreadable::InRenderWorldOnly,
            MeshAccessError::NotFound => Unreadable::Invalid(e.to_string()),
        }
    }
}

impl From<String> for Unreadable {
    fn from(why: String) -> Unreadable {
        Unreadable::Invalid(why)
    }
}

impl From<&str> for Unreadable {
    fn from(why: &str) -> Unreadable {
        Unreadable::Invalid(why.to_string())
    }
}

/// The mesh's joint indices and weights, if it has both, as npr's
/// skinning (its joint count: one past the highest joint index with a
/// weight); `Err` for arrays of another length than the positions or of
/// a format Bevy does not draw.
fn skinning_of(mesh: &Mesh, vertices: usize) -> Result<Option<Skinning>, Unreadable> {
    let joints: Vec<[u16; 4]> = match mesh.try_attribute_option(Mesh::ATTRIBUTE_JOINT_INDEX)? {
        Some(VertexAttributeValues::Uint16x4(j)) => j.clone(),
        Some(VertexAttributeValues::Uint8x4(j)) => j.iter().map(|j| j.map(u16::from)).collect(),
        Some(other) => return Err(format!("its joint indices are {other:?}-typed; npr reads Uint16x4").into()),
        None => return Ok(None),
    };
    let weights: Vec<[f32; 4]> = match mesh.try_attribute_option(Mesh::ATTRIBUTE_JOINT_WEIGHT)? {
        Some(VertexAttributeValues::Float32x4(w)) => w.clone(),
        Some(VertexAttributeValues::Unorm16x4(w)) => w.iter().map(|w| w.map(|x| f32::from(x) / 65535.0)).collect(),
        Some(VertexAttributeValues::Unorm8x4(w)) => w.iter().map(|w| w.map(|x| f32::from(x) / 255.0)).collect(),
        Some(other) => return Err(format!("its joint weights are {other:?}-typed; npr reads Float32x4").into()),
        None => return Ok(None),
    };
    if joints.len() != vertices || weights.len() != vertices {
        return Err(format!(
            "it has {} joint index sets and {} weight sets for {vertices} vertices",
            joints.len(),
            weights.len()
        )
        .into());
    }
    let joint_count = joints
        .iter()
        .zip(&weights)
        .flat_map(|(j, w)| (0..4).filter(|&k| w[k] > 0.0).map(move |k| usize::from(j[k]) + 1))
        .max()
        .unwrap_or(0);
    Ok(Some(Skinning {
        joint_count,
        joints,
        weights,
        morph_targets: Vec::new(),
    }))
}

fn npr_mesh_of(mesh: &Mesh, name: &str) -> Result<(npr_runner::scene::Mesh, Option<Skinning>), Unreadable> {
    if mesh.primitive_topology() != PrimitiveTopology::TriangleList {
        return Err(format!(
            "its topology is {:?}; npr draws triangle lists",
            mesh.primitive_topology()
        )
        .into());
    }
    let positions = match mesh.try_attribute_option(Mesh::ATTRIBUTE_POSITION)? {
        Some(VertexAttributeValues::Float32x3(p)) => p.clone(),
        Some(other) => return Err(format!("its positions are {other:?}-typed; npr reads Float32x3").into()),
        None => return Err("it has no positions".into()),
    };
    let normals = match mesh.try_attribute_option(Mesh::ATTRIBUTE_NORMAL)? {
        Some(VertexAttributeValues::Float32x3(n)) => Some(n.clone()),
        _ => None,
    };
    let uvs = match mesh.try_attribute_option(Mesh::ATTRIBUTE_UV_0)? {
        Some(VertexAttributeValues::Float32x2(uv)) => Some(uv.clone()),
        _ => None,
    };
    let tangents = match mesh.try_attribute_option(Mesh::ATTRIBUTE_TANGENT)? {
        Some(VertexAttributeValues::Float32x4(t)) => Some(t.clone()),
        _ => None,
    };
    let indices: Vec<u32> = match mesh.try_indices_option()? {
        Some(Indices::U16(i)) => i.iter().map(|&i| i as u32).collect(),
        Some(Indices::U32(i)) => i.clone(),
        None => (0..positions.len() as u32).collect(),
    };
    // Checked before normals and tangents are derived from the indices.
    if indices.is_empty() || !indices.len().is_multiple_of(3) {
        return Err(format!("it has {} indices, not a positive multiple of 3", indices.len()).into());
    }
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
        return Err(format!("index {bad} is out of range ({} vertices)", positions.len()).into());
    }
    if normals.as_ref().is_some_and(|n| n.len() != positions.len()) {
        return Err("it has a different number of normals than positions".into());
    }
    if uvs.as_ref().is_some_and(|uv| uv.len() != positions.len()) {
        return Err("it has a different number of UVs than positions".into());
    }
    let skinning = skinning_of(mesh, positions.len())?;
    let mesh = npr_runner::scene::Mesh::from_parts(positions, normals, uvs, tangents, indices, name.to_string());
    mesh.validate()?;
    Ok((mesh, skinning))
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
    /// The mesh, with its joints and weights if it has them.
    Mesh(Arc<npr_runner::scene::Mesh>, Option<Arc<Skinning>>),
    Unusable,
}

/// The npr meshes of the Bevy meshes that entities draw, by asset id.
#[derive(Resource, Default)]
pub(crate) struct NprMeshes {
    pub meshes: HashMap<AssetId<Mesh>, Converted>,
    /// Bumped whenever `meshes` changes: the render world copies the map then.
    pub revision: u64,
    /// Render-world-only meshes that no entity draws now: their data is
    /// gone from the main world, so their conversion waits here for an
    /// entity to draw them again (not shared with the render world).
    pub kept: HashMap<AssetId<Mesh>, Converted>,
}

/// Is the mesh's data taken from the main world when Bevy extracts it?
fn render_world_only(mesh: &Mesh) -> bool {
    !mesh.asset_usage.contains(RenderAssetUsages::MAIN_WORLD)
}

/// Converts the meshes of `Mesh3d` entities that are new or changed, and
/// forgets those that no entity has any more (despawned, or given
/// another mesh) or whose asset is gone: the render world then removes
/// them from each camera's runtime, so a game that spawns and despawns
/// meshes does not grow the runtimes' mesh tables. A mesh that comes back
/// is converted again, or taken from `kept` when it is render-world-only.
/// Runs after the asset events, before Bevy's extraction takes a new
/// render-world-only mesh's data.
pub(crate) fn convert_meshes(
    mut events: MessageReader<AssetEvent<Mesh>>,
    assets: Res<Assets<Mesh>>,
    drawn: Query<&Mesh3d>,
    styled_cameras: Query<(), With<crate::components::NprStyle>>,
    mut cache: ResMut<NprMeshes>,
    mut in_use: Local<HashSet<AssetId<Mesh>>>,
) {
    for event in events.read() {
        match event {
            AssetEvent::Modified { id } | AssetEvent::Removed { id } | AssetEvent::Unused { id } => {
                cache.kept.remove(id);
                if cache.meshes.remove(id).is_some() {
                    cache.revision += 1;
                }
                // A modified render-world-only mesh has its data again
                // until this frame's extraction: convert it now.
                if let (AssetEvent::Modified { id }, Some(mesh)) = (event, assets.get(*id)) {
                    if render_world_only(mesh) {
                        let converted = convert(mesh, &format!("Bevy mesh {id}"));
                        cache.kept.insert(*id, converted);
                    }
                }
            }
            // Only while a camera is drawn by a style: a game that uses no
            // npr camera keeps its memory setting's saving.
            AssetEvent::Added { id } if !styled_cameras.is_empty() => {
                if let Some(mesh) = assets.get(*id).filter(|m| render_world_only(m)) {
                    let converted = convert(mesh, &format!("Bevy mesh {id}"));
                    cache.kept.insert(*id, converted);
                }
            }
            _ => {}
        }
    }
    in_use.clear();
    in_use.extend(drawn.iter().map(|m| m.0.id()));
    let unused: Vec<AssetId<Mesh>> = cache
        .meshes
        .keys()
        .filter(|id| !in_use.contains(*id))
        .copied()
        .collect();
    for id in unused {
        let converted = cache.meshes.remove(&id).expect("listed above");
        cache.revision += 1;
        if assets.get(id).is_some_and(render_world_only) {
            cache.kept.insert(id, converted);
        }
    }
    for Mesh3d(handle) in &drawn {
        let id = handle.id();
        if cache.meshes.contains_key(&id) {
            continue;
        }
        let converted = match cache.kept.remove(&id) {
            Some(kept) => kept,
            None => {
                let Some(mesh) = assets.get(id) else { continue };
                let name = handle
                    .path()
                    .map_or_else(|| format!("Bevy mesh {id}"), |p| p.to_string());
                convert(mesh, &name)
            }
        };
        cache.meshes.insert(id, converted);
        cache.revision += 1;
    }
}

/// `mesh` converted, or `Unusable` with its diagnostic logged.
fn convert(mesh: &Mesh, name: &str) -> Converted {
    match npr_mesh_of(mesh, name) {
        Ok((m, skinning)) => Converted::Mesh(Arc::new(m), skinning.map(Arc::new)),
        Err(e) => {
            let (why, help) = match e {
                Unreadable::Invalid(why) => (why, "give npr's cameras triangle-list meshes with Float32x3 positions"),
                Unreadable::InRenderWorldOnly => (
                    IN_RENDER_WORLD_ONLY.to_string(),
                    "npr reads a render-world-only mesh in the frame its asset is added or modified; add \
                     NprPlugin before the mesh is created, or keep RenderAssetUsages::MAIN_WORLD",
                ),
            };
            let d = npr_diag::Diagnostic::error(
                npr_diag::codes::UNREADABLE_MESH,
                format!("npr cannot draw the mesh {name}: {why}"),
            )
            .with_help(help);
            error!(
                "{}",
                npr_diag::diagnostic::render(&[d], &npr_diag::SourceMap::new(), false)
            );
            Converted::Unusable
        }
    }
}
