//! Edges marked for line art in a glTF file (decision 0063): the custom
//! vertex attribute `_NPR_EDGE_MARK`, a float per face corner that is
//! non-zero where the edge leaving that corner (towards the next corner of
//! its triangle, in the file's winding) is marked.
//!
//! Why a face-corner attribute: Blender 3.4's glTF exporter writes no
//! Freestyle edge marks and skips edge-domain attributes, but it writes
//! face-corner attributes (as `_NAME`, splitting vertices where corners
//! differ), so a corner of a triangulated mesh can carry its outgoing
//! edge's mark exactly. `tests/data/blender/make_marked.py` copies
//! Freestyle's marks into such an attribute. A mesh's marks become one byte
//! per triangle ([`triangle_marks`]), which `lines::edges` turns into marked
//! edges of the welded mesh.

use super::mesh_error::MeshLoadError;
use gltf::accessor::{DataType, Dimensions};
use gltf::buffer::Data as BufferData;

/// The attribute's name without glTF's leading underscore.
pub const ATTRIBUTE: &str = "NPR_EDGE_MARK";

/// Per vertex of `primitive`, whether the edge leaving it is marked; `None`
/// when the primitive has no `_NPR_EDGE_MARK`.
pub fn read_corner_marks(
    primitive: &gltf::Primitive,
    buffers: &[BufferData],
    vertex_count: usize,
    source: &str,
) -> Result<Option<Vec<bool>>, MeshLoadError> {
    let Some(accessor) = primitive.get(&gltf::Semantic::Extras(ATTRIBUTE.to_string())) else {
        return Ok(None);
    };
    let bad = |what: String| {
        MeshLoadError::unreadable(
            format!("cannot read glTF file `{source}`: its `_{ATTRIBUTE}` attribute {what}"),
            "`_NPR_EDGE_MARK` is one float per vertex (a face-corner attribute in Blender), \
             non-zero where the edge leaving the corner is marked",
        )
    };
    if accessor.data_type() != DataType::F32 || accessor.dimensions() != Dimensions::Scalar {
        return Err(bad(format!(
            "is {:?} {:?}, not a float scalar",
            accessor.dimensions(),
            accessor.data_type()
        )));
    }
    if accessor.count() != vertex_count {
        return Err(bad(format!(
            "has {} values for {vertex_count} vertices",
            accessor.count()
        )));
    }
    let values = gltf::accessor::Iter::<f32>::new(accessor, |buffer: gltf::Buffer| {
        buffers.get(buffer.index()).map(|data| &data.0[..])
    })
    .ok_or_else(|| bad("cannot be read from its buffer".to_string()))?;
    Ok(Some(values.map(|v| v != 0.0).collect()))
}

/// A stored triangle's marks: bit k is the edge from `stored[k]` to
/// `stored[(k + 1) % 3]`, marked when the corner it leaves in the file's
/// winding `file` (the same three vertices, maybe reordered) is marked.
/// Out-of-range indices mark nothing (`Mesh::validate` reports them).
pub fn triangle_marks(corner_marks: Option<&[bool]>, file: [u32; 3], stored: [u32; 3]) -> u8 {
    let Some(marks) = corner_marks else {
        return 0;
    };
    let marked = |p: u32, q: u32| {
        (0..3).any(|k| {
            let (from, to) = (file[k], file[(k + 1) % 3]);
            ((from, to) == (p, q) || (from, to) == (q, p)) && marks.get(from as usize).copied().unwrap_or(false)
        })
    };
    (0..3).fold(0u8, |bits, k| {
        if marked(stored[k], stored[(k + 1) % 3]) {
            bits | 1 << k
        } else {
            bits
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mirrored_triangle_keeps_the_marks_of_its_edges() {
        // Corner 1 (vertex 1) marks the edge 1 -> 2.
        let marks = [false, true, false];
        let file = [0, 1, 2];
        assert_eq!(triangle_marks(Some(&marks), file, [0, 1, 2]), 0b010);
        // Stored as [0, 2, 1]: the edge 1-2 is now from corner 1 (2) to corner 2 (1).
        assert_eq!(triangle_marks(Some(&marks), file, [0, 2, 1]), 0b010);
        let marks = [true, false, false];
        assert_eq!(triangle_marks(Some(&marks), file, [0, 2, 1]), 0b100);
        assert_eq!(triangle_marks(None, file, file), 0);
    }
}
