//! glTF 2.0 meshes (`.gltf` with embedded or external buffers, or `.glb`).
//!
//! Every triangle-list primitive reachable from the default scene (or the
//! first scene, or all root nodes when there is none) is merged into one
//! mesh, with each node's world transform baked into its vertices. The
//! first material's values and base colour image are read by
//! `gltf_material` (decision 0058). Edges marked for line art are read by
//! `edge_marks` (decision 0063).

use super::edge_marks;
use super::gltf_material::{self, MeshMaterial};
use super::gltf_rig::{self, MAX_NODE_DEPTH};
use super::mesh::{Mesh, MAX_TRIANGLES};
use super::mesh_error::MeshLoadError;
use super::rig::Rig;
use glam::{Mat3, Mat4, Vec3, Vec4};
use gltf::buffer::Data as BufferData;
use gltf::mesh::Mode;
use std::path::Path;

/// The file's mesh (its rest pose), and its rig when it has skins, morph
/// targets or animations (`gltf_rig`); a file without them is merged with
/// its node transforms baked in, as before rigs were read; and its material.
pub fn parse_gltf(
    bytes: &[u8],
    base_dir: &Path,
    source: &str,
) -> Result<(Mesh, Option<Rig>, Option<MeshMaterial>), MeshLoadError> {
    let malformed = |what: String| {
        MeshLoadError::unreadable(
            format!("cannot read glTF file `{source}`: {what}"),
            "the file is not valid glTF 2.0; check it with the Khronos glTF validator",
        )
    };
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice(bytes)
        .map_err(|err| gltf_material::validation_error(&err, source).unwrap_or_else(|| malformed(err.to_string())))?;
    let buffers =
        gltf::import_buffers(&document, Some(base_dir), blob).map_err(|err| malformed(format!("buffer: {err}")))?;
    let material = gltf_material::read_material(&document, &buffers, base_dir, source)?;

    if gltf_rig::has_rig(&document) {
        let rig = gltf_rig::read_rig(&document, &buffers, source)?;
        if rig.bind.triangle_count() > MAX_TRIANGLES {
            return Err(MeshLoadError::too_many_triangles(
                Path::new(source),
                rig.bind.triangle_count(),
            ));
        }
        let rest = rig.deform(&rig.pose(None));
        return Ok((rest, Some(rig), material));
    }
    let mut merged = MergedPrimitives::new();
    // Each primitive drawn is a part (§3.6 `patches = "parts"`).
    let mut parts: Vec<u32> = Vec::new();
    let roots: Vec<gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => root_nodes(&document),
    };
    let mut pending: Vec<(gltf::Node, Mat4, usize)> =
        roots.into_iter().rev().map(|node| (node, Mat4::IDENTITY, 0)).collect();
    while let Some((node, parent, depth)) = pending.pop() {
        if depth > MAX_NODE_DEPTH {
            return Err(malformed(format!("the node hierarchy is deeper than {MAX_NODE_DEPTH}")));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                merged.append(&primitive, &buffers, world, source)?;
                let part = parts.last().map_or(0, |&p| p + 1);
                parts.resize(merged.indices.len() / 3, part);
                if merged.indices.len() / 3 > MAX_TRIANGLES {
                    return Err(MeshLoadError::too_many_triangles(
                        Path::new(source),
                        merged.indices.len() / 3,
                    ));
                }
            }
        }
        // Reversed so that children pop in document order.
        let children: Vec<gltf::Node> = node.children().collect();
        pending.extend(children.into_iter().rev().map(|child| (child, world, depth + 1)));
    }
    let mesh = Mesh::from_parts(
        merged.positions,
        merged.normals,
        merged.uvs,
        merged.tangents,
        merged.indices,
        source.to_string(),
    )
    .with_parts(parts)
    .with_edge_marks(merged.edge_marks);
    Ok((mesh, None, material))
}

/// Nodes that are nobody's child.
fn root_nodes(document: &gltf::Document) -> Vec<gltf::Node<'_>> {
    let mut is_child = vec![false; document.nodes().len()];
    for node in document.nodes() {
        for child in node.children() {
            if let Some(flag) = is_child.get_mut(child.index()) {
                *flag = true;
            }
        }
    }
    document
        .nodes()
        .filter(|node| !is_child.get(node.index()).copied().unwrap_or(true))
        .collect()
}

/// The concatenation of primitives, in world space. An attribute becomes
/// `None` as soon as one primitive lacks it.
struct MergedPrimitives {
    positions: Vec<[f32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    uvs: Option<Vec<[f32; 2]>>,
    tangents: Option<Vec<[f32; 4]>>,
    indices: Vec<u32>,
    /// Per triangle, its marked edges (`edge_marks::triangle_marks`).
    edge_marks: Vec<u8>,
}

impl MergedPrimitives {
    fn new() -> Self {
        MergedPrimitives {
            positions: Vec::new(),
            normals: Some(Vec::new()),
            uvs: Some(Vec::new()),
            tangents: Some(Vec::new()),
            indices: Vec::new(),
            edge_marks: Vec::new(),
        }
    }

    fn append(
        &mut self,
        primitive: &gltf::Primitive,
        buffers: &[BufferData],
        world: Mat4,
        source: &str,
    ) -> Result<(), MeshLoadError> {
        // Points and lines have no surface to shade; strips and fans are
        // rare in exported files and not read.
        if primitive.mode() != Mode::Triangles {
            return Ok(());
        }
        let reader = primitive.reader(|buffer| buffers.get(buffer.index()).map(|data| &data.0[..]));
        let Some(positions) = reader.read_positions() else {
            return Ok(());
        };
        let first_vertex = u32::try_from(self.positions.len()).map_err(|_| {
            MeshLoadError::unreadable(
                format!("glTF file `{source}` has more vertices than 32-bit indices can address"),
                "split or decimate the mesh",
            )
        })?;
        let local_positions: Vec<[f32; 3]> = positions.collect();
        let vertex_count = local_positions.len();

        // Normals transform with the inverse transpose; a mirroring transform
        // (negative determinant) flips handedness and triangle winding.
        let linear = Mat3::from_mat4(world);
        let mirrored = linear.determinant() < 0.0;
        let normal_matrix = linear.inverse().transpose();
        self.positions.extend(
            local_positions
                .iter()
                .map(|p| world.transform_point3(Vec3::from_array(*p)).to_array()),
        );

        let normals: Option<Vec<[f32; 3]>> = reader
            .read_normals()
            .map(|normals| normals.collect())
            .filter(|normals: &Vec<[f32; 3]>| normals.len() == vertex_count);
        extend_or_drop(&mut self.normals, normals, |n| {
            (normal_matrix * Vec3::from_array(n)).normalize_or_zero().to_array()
        });
        let uvs: Option<Vec<[f32; 2]>> = reader
            .read_tex_coords(0)
            .map(|uvs| uvs.into_f32().collect())
            .filter(|uvs: &Vec<[f32; 2]>| uvs.len() == vertex_count);
        extend_or_drop(&mut self.uvs, uvs, |uv| uv);
        let tangents: Option<Vec<[f32; 4]>> = reader
            .read_tangents()
            .map(|tangents| tangents.collect())
            .filter(|tangents: &Vec<[f32; 4]>| tangents.len() == vertex_count);
        extend_or_drop(&mut self.tangents, tangents, |t| {
            let direction = linear * Vec3::new(t[0], t[1], t[2]);
            let handedness = if mirrored { -t[3] } else { t[3] };
            Vec4::from((direction, handedness)).to_array()
        });

        let local_indices: Vec<u32> = match reader.read_indices() {
            Some(indices) => indices.into_u32().collect(),
            None => (0..vertex_count as u32).collect(),
        };
        let corner_marks = edge_marks::read_corner_marks(primitive, buffers, vertex_count, source)?;
        for triangle in local_indices.chunks_exact(3) {
            let [a, b, c] = [triangle[0], triangle[1], triangle[2]];
            let ordered = if mirrored { [a, c, b] } else { [a, b, c] };
            self.edge_marks
                .push(edge_marks::triangle_marks(corner_marks.as_deref(), [a, b, c], ordered));
            for index in ordered {
                // Out-of-range indices are kept out of range (not wrapped) so
                // that `Mesh::validate` reports them.
                self.indices.push(index.saturating_add(first_vertex));
            }
        }
        Ok(())
    }
}

fn extend_or_drop<T: Copy>(merged: &mut Option<Vec<T>>, part: Option<Vec<T>>, convert: impl Fn(T) -> T) {
    match (merged.as_mut(), part) {
        (Some(all), Some(part)) => all.extend(part.into_iter().map(convert)),
        _ => *merged = None,
    }
}
