//! Triangle meshes as the renderer consumes them: flat vertex arrays with a
//! single index buffer, plus the vertex attributes a style can ask for.

use super::geometry;

/// The most triangles one mesh (file or primitive) may have: `npr_diag::limits`,
/// where every limit is listed.
pub use npr_diag::limits::MAX_TRIANGLES;

/// An indexed triangle mesh. All vertex arrays have one entry per vertex.
///
/// Coordinates are the file's own (no recentring or rescaling): the object's
/// transform in the scene places it. UVs follow wgpu's convention (v = 0 at
/// the top of an image); OBJ's bottom-left `vt` are flipped on load.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub positions: Vec<[f32; 3]>,
    /// Unit length; computed (smooth, area-weighted) when the file has none.
    pub normals: Vec<[f32; 3]>,
    pub uvs: Option<Vec<[f32; 2]>>,
    /// xyz: unit tangent along +u, orthogonal to the normal; w: handedness
    /// (±1), so that bitangent = w · cross(normal, tangent) points along -v,
    /// towards the image's top (glTF's convention; +1 for an unmirrored map).
    /// Present exactly when `uvs` is (derived from UVs when the file has none).
    pub tangents: Option<Vec<[f32; 4]>>,
    /// Counter-clockwise triangles (seen from the side the normal points to).
    pub indices: Vec<u32>,
    /// The file path, or a description like `sphere(radius=1, segments=64, rings=32)`.
    pub source: String,
    /// Per triangle, the part of the file it came from (OBJ `o`/`g`, glTF
    /// primitive), numbered from 0; `None` for a mesh of one part. A scene's
    /// `patches = "parts"` splits the object along these (§3.6).
    pub parts: Option<Vec<u32>>,
    /// Per triangle, its edges marked in the file for line art (Freestyle's
    /// edge marks; decision 0063): bit k is the edge from corner k to corner
    /// k+1 (mod 3). `None` when the file marks no edge.
    pub edge_marks: Option<Vec<u8>>,
}

/// A vertex attribute a style may require of every mesh in the scene: the
/// manifest's (one definition, in the ABI).
pub use npr_abi::Attribute;

impl Mesh {
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Whether the mesh carries `attribute`.
    pub fn has(&self, attribute: Attribute) -> bool {
        match attribute {
            Attribute::Position | Attribute::Normal => true,
            Attribute::Uv => self.uvs.is_some(),
            Attribute::Tangent => self.tangents.is_some(),
            // 1 at every vertex of an object without patches (§3.6).
            Attribute::PatchWeight => true,
            // The current position where nothing deforms (decision 0053).
            Attribute::PreviousPosition => true,
        }
    }

    /// Axis-aligned bounds `(min, max)`; `None` for a mesh without vertices.
    pub fn bounds(&self) -> Option<([f32; 3], [f32; 3])> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        }))
    }

    /// Builds a mesh from raw arrays, filling in what is missing: smooth
    /// normals when `normals` is `None`, tangents from UVs when `tangents` is
    /// `None`. Call [`Mesh::validate`] first when the data comes from a file.
    pub fn from_parts(
        positions: Vec<[f32; 3]>,
        normals: Option<Vec<[f32; 3]>>,
        uvs: Option<Vec<[f32; 2]>>,
        tangents: Option<Vec<[f32; 4]>>,
        indices: Vec<u32>,
        source: String,
    ) -> Mesh {
        let normals = match normals {
            Some(given) => geometry::repair_normals(&positions, &indices, given),
            None => geometry::smooth_normals(&positions, &indices),
        };
        let tangents = match (&uvs, tangents) {
            (None, _) => None,
            (Some(_), Some(given)) if given.len() == positions.len() => {
                Some(geometry::repair_tangents(&normals, given))
            }
            (Some(uvs), _) => Some(geometry::uv_tangents(&positions, &normals, uvs, &indices)),
        };
        Mesh {
            positions,
            normals,
            uvs,
            tangents,
            indices,
            source,
            parts: None,
            edge_marks: None,
        }
    }

    /// The mesh with `parts` (one per triangle), or without them when every
    /// triangle is in the same part.
    pub fn with_parts(mut self, parts: Vec<u32>) -> Mesh {
        debug_assert_eq!(parts.len(), self.indices.len() / 3);
        self.parts = if parts.iter().any(|&p| p != parts[0]) {
            Some(parts)
        } else {
            None
        };
        self
    }

    /// The mesh with `marks` (one byte of edge bits per triangle, see
    /// [`Mesh::edge_marks`]), or without them when no edge is marked.
    pub fn with_edge_marks(mut self, marks: Vec<u8>) -> Mesh {
        debug_assert_eq!(marks.len(), self.indices.len() / 3);
        self.edge_marks = if marks.iter().any(|&m| m != 0) {
            Some(marks)
        } else {
            None
        };
        self
    }

    /// The mesh with its normals split where faces meet at more than
    /// `crease_deg` degrees (`geometry::crease_normals`): vertices on a
    /// crease are duplicated, UVs copied, tangents recomputed for the new
    /// normals. For CAD parts whose file has no normals.
    pub fn with_crease_normals(&self, crease_deg: f32) -> Mesh {
        let split = geometry::crease_normals(&self.positions, &self.indices, crease_deg);
        let uvs = self
            .uvs
            .as_ref()
            .map(|uvs| split.source.iter().map(|&v| uvs[v]).collect::<Vec<_>>());
        let tangents = uvs
            .as_ref()
            .map(|uvs| geometry::uv_tangents(&split.positions, &split.normals, uvs, &split.indices));
        Mesh {
            positions: split.positions,
            normals: split.normals,
            uvs,
            tangents,
            indices: split.indices,
            source: format!("{} (creases > {crease_deg}°)", self.source),
            // The split keeps every triangle in its place.
            parts: self.parts.clone(),
            edge_marks: self.edge_marks.clone(),
        }
    }

    /// Checks the invariants the renderer relies on, for data read from a
    /// file: a whole number of triangles, indices in range, finite numbers,
    /// attribute arrays as long as the position array. The message says what
    /// is wrong, for an E0402 diagnostic.
    pub fn validate(&self) -> Result<(), String> {
        let vertex_count = self.positions.len();
        if self.indices.is_empty() {
            return Err("it contains no triangles".into());
        }
        if !self.indices.chunks_exact(3).remainder().is_empty() {
            return Err(format!("its index count {} is not a multiple of 3", self.indices.len()));
        }
        if let Some(bad) = self.indices.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(format!(
                "index {bad} is out of range (the mesh has {vertex_count} vertices)"
            ));
        }
        if self.positions.iter().flatten().any(|c| !c.is_finite()) {
            return Err("a vertex position is not a finite number".into());
        }
        let lengths = [
            ("normals", Some(self.normals.len())),
            ("UVs", self.uvs.as_ref().map(Vec::len)),
            ("tangents", self.tangents.as_ref().map(Vec::len)),
        ];
        for (name, len) in lengths {
            if let Some(len) = len.filter(|&len| len != vertex_count) {
                return Err(format!("it has {len} {name} for {vertex_count} vertices"));
            }
        }
        if let Some(uvs) = &self.uvs {
            if uvs.iter().flatten().any(|c| !c.is_finite()) {
                return Err("a UV coordinate is not a finite number".into());
            }
        }
        Ok(())
    }
}
