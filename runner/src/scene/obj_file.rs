//! Wavefront OBJ meshes, read with `tobj` (triangulated, single index).

use super::mesh::Mesh;
use super::mesh_error::MeshLoadError;

/// Parses OBJ text. Every model (`o`/`g`) in the file is merged into one
/// mesh, each triangle remembering its model as its part; materials are
/// ignored. `vt` are flipped to v = 0 at the image top.
/// Normals and UVs are kept only if every model has them; missing normals
/// are computed, missing UVs leave the mesh without UVs (and tangents).
pub fn parse_obj(bytes: &[u8], source: &str) -> Result<Mesh, MeshLoadError> {
    // Other tobj features (merging, reordering) add fields; the update keeps
    // this compiling whichever are enabled elsewhere in the build.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // Materials are irrelevant to npr: refuse to open .mtl files at all.
    let (models, _materials) = tobj::load_obj_buf(&mut &bytes[..], &options, |_| Err(tobj::LoadError::OpenFileFailed))
        .map_err(|err| {
            MeshLoadError::unreadable(
                format!("cannot parse OBJ file `{source}`: {err}"),
                "the file is not valid Wavefront OBJ; re-export it from a modelling tool",
            )
        })?;

    let mut merged = MergedArrays::default();
    let mut parts = Vec::new();
    for (part, model) in models.iter().enumerate() {
        merged.append(&model.mesh, source)?;
        parts.resize(merged.indices.len() / 3, part as u32);
    }
    Ok(Mesh::from_parts(
        merged.positions,
        merged.normals,
        merged.uvs,
        None,
        merged.indices,
        source.to_string(),
    )
    .with_parts(parts))
}

/// The concatenation of the file's models. An attribute becomes `None` as
/// soon as one model lacks it.
struct MergedArrays {
    positions: Vec<[f32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    uvs: Option<Vec<[f32; 2]>>,
    indices: Vec<u32>,
}

impl Default for MergedArrays {
    fn default() -> Self {
        MergedArrays {
            positions: Vec::new(),
            normals: Some(Vec::new()),
            uvs: Some(Vec::new()),
            indices: Vec::new(),
        }
    }
}

impl MergedArrays {
    fn append(&mut self, mesh: &tobj::Mesh, source: &str) -> Result<(), MeshLoadError> {
        let too_big = || {
            MeshLoadError::unreadable(
                format!("OBJ file `{source}` has more vertices than 32-bit indices can address"),
                "split or decimate the mesh",
            )
        };
        let first_vertex = u32::try_from(self.positions.len()).map_err(|_| too_big())?;
        let vertex_count = mesh.positions.len() / 3;
        self.positions
            .extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));

        // With single indexing tobj gives either one normal/UV per vertex or none.
        if mesh.normals.len() == vertex_count * 3 && vertex_count > 0 {
            if let Some(normals) = &mut self.normals {
                normals.extend(mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
            }
        } else if vertex_count > 0 {
            self.normals = None;
        }
        if mesh.texcoords.len() == vertex_count * 2 && vertex_count > 0 {
            if let Some(uvs) = &mut self.uvs {
                uvs.extend(mesh.texcoords.chunks_exact(2).map(|t| [t[0], 1.0 - t[1]]));
            }
        } else if vertex_count > 0 {
            self.uvs = None;
        }

        for &index in &mesh.indices {
            let shifted = index.checked_add(first_vertex).ok_or_else(too_big)?;
            self.indices.push(shifted);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const QUAD_WITH_UVS: &str = "\
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 2/2 3/3 4/4
";

    #[test]
    fn a_quad_is_triangulated_and_v_is_flipped() {
        let mesh = parse_obj(QUAD_WITH_UVS.as_bytes(), "quad.obj").expect("valid OBJ");
        assert_eq!(mesh.triangle_count(), 2);
        let uvs = mesh.uvs.as_ref().expect("has vt");
        let bottom_left = mesh
            .positions
            .iter()
            .position(|p| *p == [0.0, 0.0, 0.0])
            .expect("vertex");
        assert_eq!(uvs[bottom_left], [0.0, 1.0]);
        assert!(mesh.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]));
        // Unmirrored mapping (u right, image top up): handedness +1.
        assert!(mesh
            .tangents
            .as_ref()
            .expect("from UVs")
            .iter()
            .all(|t| *t == [1.0, 0.0, 0.0, 1.0]));
    }

    #[test]
    fn two_objects_are_merged_with_offset_indices() {
        let text = "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n";
        let mesh = parse_obj(text.as_bytes(), "two.obj").expect("valid OBJ");
        assert_eq!(mesh.vertex_count(), 6);
        assert_eq!(mesh.triangle_count(), 2);
        assert!(mesh.indices.iter().all(|&i| (i as usize) < 6));
        assert!(mesh.validate().is_ok());
        assert!(mesh.uvs.is_none() && mesh.tangents.is_none());
    }

    #[test]
    fn garbage_is_an_error_or_an_empty_mesh_never_a_panic() {
        for text in [
            "f 1 2 3\n",
            "v 1 2\nf 1 1 1\n",
            "v a b c\n",
            "f 0 -9 7/8/9\n",
            "\u{0}\u{1}",
        ] {
            if let Ok(mesh) = parse_obj(text.as_bytes(), "bad.obj") {
                assert!(mesh.validate().is_err(), "{text:?} gave a usable mesh");
            }
        }
    }
}
