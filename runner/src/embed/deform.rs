//! A host's own deforming mesh (skinning on the CPU, cloth, a morph, a
//! sculpting tool): the [`Deformed`] vertices of a registered mesh,
//! checked (E0603) and made into the mesh's deformed copy, which
//! `StyleRuntime::update_mesh` puts in the mesh's place; the renderer
//! then writes its vertices over the mesh's GPU buffers in place
//! (docs/decisions/0045).

use super::meshes::Entry;
use super::{EmbedError, MeshHandle};
use crate::scene::geometry;
use crate::scene::Mesh;
use npr_diag::{codes, Diagnostic};

/// New vertex data for a registered mesh, borrowed from the host's own
/// arrays: one entry per vertex of the mesh, in its order. The triangles
/// (indices) and UVs are the mesh's own and stay: a deformation moves
/// vertices, it does not change which vertices make a triangle.
#[derive(Debug, Clone, Copy)]
pub struct Deformed<'a> {
    /// Object-space positions, finite.
    pub positions: &'a [[f32; 3]],
    /// Unit normals, finite, written as given (skinning transforms them
    /// with the positions). `None`: the smooth, area-weighted normals of
    /// the new positions, as a mesh read from a file without normals gets
    /// (a mesh with hard edges should give its own).
    pub normals: Option<&'a [[f32; 3]]>,
    /// Tangents (xyz unit along +u, w the handedness ±1), finite, for a
    /// mesh with tangents (one with UVs). `None`: made from the UVs, the
    /// new positions and the normals, as a mesh read without tangents gets.
    pub tangents: Option<&'a [[f32; 4]]>,
}

impl<'a> Deformed<'a> {
    /// New positions; normals and tangents made from them.
    pub fn positions(positions: &'a [[f32; 3]]) -> Deformed<'a> {
        Deformed {
            positions,
            normals: None,
            tangents: None,
        }
    }

    /// With the host's own normals.
    pub fn with_normals(mut self, normals: &'a [[f32; 3]]) -> Deformed<'a> {
        self.normals = Some(normals);
        self
    }

    /// With the host's own tangents.
    pub fn with_tangents(mut self, tangents: &'a [[f32; 4]]) -> Deformed<'a> {
        self.tangents = Some(tangents);
        self
    }
}

/// E0603 with `message` and `help`.
fn refuse(message: String, help: &str) -> EmbedError {
    EmbedError::MeshUpdate(Box::new(
        Diagnostic::error(codes::BAD_MESH_UPDATE, message).with_help(help.to_string()),
    ))
}

/// The first vertex with a non-finite component, if any.
fn first_non_finite<const N: usize>(values: &[[f32; N]]) -> Option<usize> {
    values.iter().position(|v| v.iter().any(|c| !c.is_finite()))
}

/// `entry`'s mesh with `vertices`, or why not (E0603); `handle` names it
/// in the messages.
pub(super) fn deformed_mesh(handle: MeshHandle, entry: &Entry, vertices: &Deformed) -> Result<Mesh, EmbedError> {
    let name = format!("mesh handle #{}", handle.index);
    let mesh = &entry.mesh;
    if entry.extras.time_varying.is_some() {
        return Err(refuse(
            format!("{name} is an animated primitive: the runtime writes its vertices at each frame's time"),
            "to deform a primitive's geometry yourself, register it with `add_mesh(primitive.build())`",
        ));
    }
    if entry.extras.rig.is_some() {
        return Err(refuse(
            format!("{name} is a skinned mesh: the GPU deforms it by each instance's pose"),
            "give each instance's `pose` instead, or register the host-deformed mesh with `add_mesh`",
        ));
    }
    if entry.extras.blend.is_some() || entry.extras.patch.is_some() {
        return Err(refuse(
            format!("{name} is a patch of a patched surface: its blended n-ring and weights are made from the whole mesh's vertices"),
            "register the deformed mesh again with `add_patches` (a scene change), or draw it unpatched with `add_mesh`",
        ));
    }
    let count = mesh.vertex_count();
    let help = "give one value per vertex of the registered mesh, in its order: a mesh with other \
                vertices or triangles is another mesh (`add_mesh`, then draw its handle)";
    let lengths = [
        ("positions", Some(vertices.positions.len())),
        ("normals", vertices.normals.map(<[_]>::len)),
        ("tangents", vertices.tangents.map(<[_]>::len)),
    ];
    for (what, len) in lengths {
        if let Some(len) = len.filter(|&len| len != count) {
            return Err(refuse(
                format!("{len} {what} for {name}, which has {count} vertices"),
                help,
            ));
        }
    }
    if vertices.tangents.is_some() && mesh.tangents.is_none() {
        return Err(refuse(
            format!("tangents for {name}, which has none (no UVs)"),
            "give tangents only for a mesh with UVs; leave `tangents` at `None` otherwise",
        ));
    }
    let finite_help = "a vertex must be a finite number: check the deformation for a division by zero \
                       or an uninitialized weight";
    let non_finite = [
        ("position", first_non_finite(vertices.positions)),
        ("normal", vertices.normals.and_then(first_non_finite)),
        ("tangent", vertices.tangents.and_then(first_non_finite)),
    ];
    for (what, bad) in non_finite {
        if let Some(vertex) = bad {
            return Err(refuse(
                format!("the {what} of vertex {vertex} of {name} is not a finite number"),
                finite_help,
            ));
        }
    }
    let positions = vertices.positions.to_vec();
    let normals = match vertices.normals {
        Some(given) => given.to_vec(),
        None => geometry::smooth_normals(&positions, &mesh.indices),
    };
    let tangents = match (&mesh.tangents, vertices.tangents, &mesh.uvs) {
        (None, _, _) => None,
        (Some(_), Some(given), _) => Some(given.to_vec()),
        (Some(_), None, Some(uvs)) => Some(geometry::uv_tangents(&positions, &normals, uvs, &mesh.indices)),
        // Tangents without UVs (a mesh built by hand): nothing to make them from.
        (Some(kept), None, None) => Some(kept.clone()),
    };
    Ok(Mesh {
        positions,
        normals,
        uvs: mesh.uvs.clone(),
        tangents,
        indices: mesh.indices.clone(),
        source: mesh.source.clone(),
        parts: mesh.parts.clone(),
        edge_marks: mesh.edge_marks.clone(),
    })
}
