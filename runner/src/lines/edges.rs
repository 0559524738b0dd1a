//! Feature edges of a triangle mesh for the `lines` pass (Klein et al. 2000,
//! §5: "we draw wavy lines over silhouette edges and creases at the
//! intersections of non-coplanar polygons"), in f64 on the CPU.
//!
//! - [`EdgeMesh::new`] welds the mesh's vertices by position (meshes split
//!   vertices at UV seams and hard normals, so the cube has 24 vertices but
//!   8 corners), drops zero-length edges and zero-area faces, and finds
//!   every edge's faces once. This is the per-mesh, static part.
//! - [`EdgeMesh::creases`]: edges whose dihedral angle exceeds a threshold,
//!   plus boundary and non-manifold edges. Static: found once per mesh and
//!   threshold, and cached by the caller.
//! - [`EdgeMesh::silhouettes`]: edges between a front- and a back-facing
//!   face as seen from one eye (object space). Per frame and per eye.
//! - [`EdgeMesh::borders`], [`EdgeMesh::creases_over`],
//!   [`EdgeMesh::part_boundaries`]: the static edge types of line sets
//!   (decision 0056), each alone: an open mesh's rim, a dihedral angle over
//!   a threshold between two faces, and edges between faces of different
//!   parts (`Mesh::parts`: OBJ `o`/`g`, glTF primitives, so one material
//!   each in a glTF file). [`EdgeMesh::marked`]: edges the file marks
//!   (decision 0063). Intersection lines are not mesh edges: they are
//!   in `intersections.rs`.
//! - [`chain`]: edges joined into polylines through vertices of degree 2,
//!   so a line's phase runs on continuously along a chain (BRIEF §5: without
//!   chaining the phase jumps at every edge).
//!
//! Why the CPU: extraction is O(edges) with a hash map built once; per frame
//! the silhouette test is one dot product per face, and chaining is a graph
//! walk that a compute pass would have to do serially or with a
//! list-ranking pass per frame. Measured (`npr bench lines`, against the
//! compute pass of `lab/src/silhouettes_gpu.rs` with its read-back): the
//! per-frame classification is 2.7–83× faster here on lavapipe, from 336
//! to 386,560 edges (docs/PERFORMANCE.md). It also keeps an exact f64 form
//! that the tests check against analytic truth.

use std::collections::HashMap;

use glam::DVec3;

use super::viewpoint::Viewpoint;
use crate::scene::Mesh;

/// Why an edge is a feature edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EdgeKind {
    /// The dihedral angle is over the threshold (two faces).
    Crease,
    /// One face only (an open mesh's rim): always a hard edge.
    Boundary,
    /// Three or more faces meet: always a hard edge.
    NonManifold,
    /// Front and back faces differ from the eye.
    Silhouette,
}

/// One undirected edge between welded vertices `a < b`, with its faces.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    pub a: u32,
    pub b: u32,
    /// Indices into [`EdgeMesh::faces`]; one or more.
    pub faces: Vec<u32>,
}

/// A mesh reduced to what edge extraction needs: welded f64 positions,
/// non-degenerate faces with unit normals, and the edge-face adjacency.
#[derive(Debug, Clone)]
pub struct EdgeMesh {
    pub positions: Vec<DVec3>,
    /// Welded vertex indices, counter-clockwise.
    pub faces: Vec<[u32; 3]>,
    /// Unit normals of `faces` (counter-clockwise is front).
    pub normals: Vec<DVec3>,
    pub edges: Vec<Edge>,
    /// Per face, the part of the mesh it came from (`Mesh::parts`; all 0
    /// for a mesh of one part).
    pub face_parts: Vec<u32>,
    /// Per edge, whether the file marks it (`Mesh::edge_marks`, decision
    /// 0063): every face of the edge marks it from its side.
    pub marked: Vec<bool>,
}

/// Relative size under which two vertices weld and a face counts as
/// degenerate: f32 positions carry ~1e-7 relative error, so anything under
/// 1e-6 of the mesh's extent is the same point.
const WELD_RELATIVE: f64 = 1e-6;

impl EdgeMesh {
    /// Welds `mesh` by position and builds the edge-face adjacency.
    pub fn new(mesh: &Mesh) -> EdgeMesh {
        let extent = mesh
            .bounds()
            .map(|(lo, hi)| (0..3).map(|i| f64::from(hi[i] - lo[i])).fold(0.0, f64::max))
            .unwrap_or(0.0);
        let cell = (extent * WELD_RELATIVE).max(f64::MIN_POSITIVE);
        let mut welded: HashMap<[i64; 3], u32> = HashMap::new();
        let mut positions: Vec<DVec3> = Vec::new();
        let remap: Vec<u32> = mesh
            .positions
            .iter()
            .map(|p| {
                let p = DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
                let key = [
                    (p.x / cell).floor() as i64,
                    (p.y / cell).floor() as i64,
                    (p.z / cell).floor() as i64,
                ];
                // Two points a rounding error apart can straddle a cell
                // boundary: look in the neighbouring cells too.
                for dx in -1..=1 {
                    for dy in -1..=1 {
                        for dz in -1..=1 {
                            let near = [key[0] + dx, key[1] + dy, key[2] + dz];
                            if let Some(&v) = welded.get(&near) {
                                if (positions[v as usize] - p).length() <= cell {
                                    return v;
                                }
                            }
                        }
                    }
                }
                positions.push(p);
                let v = (positions.len() - 1) as u32;
                welded.entry(key).or_insert(v);
                v
            })
            .collect();
        let mut faces = Vec::new();
        let mut normals = Vec::new();
        let mut by_pair: HashMap<(u32, u32), usize> = HashMap::new();
        let mut edges: Vec<Edge> = Vec::new();
        let mut face_parts = Vec::new();
        // Per edge, how many of its faces mark it.
        let mut marked_by: Vec<u32> = Vec::new();
        for (t, tri) in mesh.indices.chunks_exact(3).enumerate() {
            let [a, b, c] = [remap[tri[0] as usize], remap[tri[1] as usize], remap[tri[2] as usize]];
            // A welded-away edge (two corners at one point) makes the face
            // a zero-area sliver: it has no normal, so no facing, and its
            // zero-length edges are no lines.
            if a == b || b == c || a == c {
                continue;
            }
            let cross =
                (positions[b as usize] - positions[a as usize]).cross(positions[c as usize] - positions[a as usize]);
            let length = cross.length();
            if length.is_nan() || length <= cell * extent.max(cell) {
                continue; // collinear corners: zero area, no normal
            }
            let face = faces.len() as u32;
            faces.push([a, b, c]);
            normals.push(cross / length);
            face_parts.push(mesh.parts.as_ref().and_then(|p| p.get(t).copied()).unwrap_or(0));
            let marks = mesh.edge_marks.as_ref().and_then(|m| m.get(t).copied()).unwrap_or(0);
            for (k, (p, q)) in [(a, b), (b, c), (c, a)].into_iter().enumerate() {
                let key = (p.min(q), p.max(q));
                let index = *by_pair.entry(key).or_insert_with(|| {
                    edges.push(Edge {
                        a: key.0,
                        b: key.1,
                        faces: Vec::new(),
                    });
                    marked_by.push(0);
                    edges.len() - 1
                });
                edges[index].faces.push(face);
                marked_by[index] += u32::from(marks >> k & 1);
            }
        }
        // A mark on one side only is a diagonal of a polygon whose outer
        // edge was marked (an untriangulated source), not a marked edge.
        let marked = edges
            .iter()
            .zip(&marked_by)
            .map(|(e, &n)| n > 0 && n as usize == e.faces.len())
            .collect();
        EdgeMesh {
            positions,
            faces,
            normals,
            edges,
            face_parts,
            marked,
        }
    }

    /// Border edges: those with one face, the rim of an open mesh (a
    /// plane's outline, a box without its lid). Indices into `edges`.
    pub fn borders(&self) -> Vec<u32> {
        self.edges_where(|_, e| e.faces.len() == 1)
    }

    /// Crease edges alone: two faces whose dihedral angle exceeds
    /// `threshold_deg` (unlike [`EdgeMesh::creases`], no border or
    /// non-manifold edge). Indices into `edges`.
    pub fn creases_over(&self, threshold_deg: f64) -> Vec<u32> {
        self.edges_where(|mesh, e| e.faces.len() == 2 && mesh.dihedral_deg(e).is_some_and(|a| a > threshold_deg))
    }

    /// Material (part) boundaries: edges whose faces are not all in one
    /// part (`Mesh::parts`). Indices into `edges`.
    pub fn part_boundaries(&self) -> Vec<u32> {
        self.edges_where(|mesh, e| {
            let part = mesh.face_parts[e.faces[0] as usize];
            e.faces.iter().any(|&f| mesh.face_parts[f as usize] != part)
        })
    }

    /// Edges marked in the mesh's file (Freestyle's edge marks, decision
    /// 0063). Indices into `edges`.
    pub fn marked(&self) -> Vec<u32> {
        (0..self.edges.len() as u32)
            .filter(|&e| self.marked[e as usize])
            .collect()
    }

    fn edges_where(&self, keep: impl Fn(&EdgeMesh, &Edge) -> bool) -> Vec<u32> {
        self.edges
            .iter()
            .enumerate()
            .filter(|(_, e)| keep(self, e))
            .map(|(i, _)| i as u32)
            .collect()
    }

    /// The dihedral angle of a two-face edge in degrees: the angle between
    /// the face normals (0 for coplanar faces, 90 on a cube's edge). `None`
    /// for boundary and non-manifold edges.
    pub fn dihedral_deg(&self, edge: &Edge) -> Option<f64> {
        match edge.faces[..] {
            [f, g] => {
                let (n, m) = (self.normals[f as usize], self.normals[g as usize]);
                // atan2 of |n×m| and n·m keeps precision near 0° and 180°,
                // where acos of the dot product does not.
                Some(n.cross(m).length().atan2(n.dot(m)).to_degrees())
            }
            _ => None,
        }
    }

    /// Static feature edges (§5 "creases at the intersections of
    /// non-coplanar polygons"): a dihedral angle over `threshold_deg`, and
    /// every boundary and non-manifold edge. Indices into `edges`.
    pub fn creases(&self, threshold_deg: f64) -> Vec<(u32, EdgeKind)> {
        self.edges
            .iter()
            .enumerate()
            .filter_map(|(i, edge)| {
                let kind = match edge.faces.len() {
                    1 => EdgeKind::Boundary,
                    2 if self.dihedral_deg(edge)? > threshold_deg => EdgeKind::Crease,
                    2 => return None,
                    _ => EdgeKind::NonManifold,
                };
                Some((i as u32, kind))
            })
            .collect()
    }

    /// Whether face `f` faces the eye at `eye` (object space: a point, or
    /// an orthographic eye's direction, [`Viewpoint`]). A face whose
    /// plane holds the eye (edge-on) counts as back-facing, so every face
    /// has exactly one answer and edge-on faces cannot make a silhouette
    /// with each other.
    pub fn is_front(&self, f: u32, eye: impl Into<Viewpoint>) -> bool {
        let corner = self.positions[self.faces[f as usize][0] as usize];
        self.normals[f as usize].dot(eye.into().towards_from(corner)) > 0.0
    }

    /// Silhouette edges from the eye at `eye` in object space (per frame,
    /// per eye): two-face edges whose faces differ in facing. Indices into
    /// `edges`.
    pub fn silhouettes(&self, eye: impl Into<Viewpoint>) -> Vec<u32> {
        let eye = eye.into();
        let front: Vec<bool> = (0..self.faces.len() as u32).map(|f| self.is_front(f, eye)).collect();
        self.edges
            .iter()
            .enumerate()
            .filter(|(_, e)| matches!(e.faces[..], [f, g] if front[f as usize] != front[g as usize]))
            .map(|(i, _)| i as u32)
            .collect()
    }

    /// The polylines through the given edges (see [`chain`]).
    pub fn chain(&self, edge_indices: &[u32]) -> Vec<Polyline> {
        let pairs: Vec<(u32, u32)> = edge_indices
            .iter()
            .map(|&i| (self.edges[i as usize].a, self.edges[i as usize].b))
            .collect();
        chain(&pairs)
    }
}

/// A chain of welded vertices; a closed one repeats no vertex (its last
/// vertex joins its first).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Polyline {
    pub vertices: Vec<u32>,
    pub closed: bool,
}

/// Joins undirected edges into maximal polylines. A chain runs through
/// vertices where exactly two of the edges meet and ends where one or three
/// or more meet (a cube's corner ends three chains: there is no single
/// continuation, and picking one would make the phase depend on edge
/// order). What is left after the open chains are cycles: closed polylines.
/// Every edge is in exactly one polyline. Deterministic: chains start at the
/// lowest-numbered end vertex and follow edges in input order.
pub fn chain(edges: &[(u32, u32)]) -> Vec<Polyline> {
    let mut incident: HashMap<u32, Vec<usize>> = HashMap::new();
    for (i, &(a, b)) in edges.iter().enumerate() {
        if a == b {
            continue; // zero-length: nothing to draw
        }
        incident.entry(a).or_default().push(i);
        incident.entry(b).or_default().push(i);
    }
    let mut used: Vec<bool> = edges.iter().map(|&(a, b)| a == b).collect();
    let mut starts: Vec<u32> = incident.iter().filter(|(_, e)| e.len() != 2).map(|(&v, _)| v).collect();
    starts.sort_unstable();
    let mut lines = Vec::new();
    let walk = |start: u32, first: usize, used: &mut [bool]| -> Polyline {
        let mut vertices = vec![start];
        let (mut at, mut edge) = (start, first);
        loop {
            used[edge] = true;
            let (a, b) = edges[edge];
            let next = if a == at { b } else { a };
            let around = &incident[&next];
            if next == start {
                return Polyline { vertices, closed: true };
            }
            vertices.push(next);
            at = next;
            match around.iter().find(|&&e| !used[e]) {
                Some(&e) if around.len() == 2 => edge = e,
                _ => {
                    return Polyline {
                        vertices,
                        closed: false,
                    }
                }
            }
        }
    };
    for &start in &starts {
        for &first in &incident[&start] {
            if !used[first] {
                lines.push(walk(start, first, &mut used));
            }
        }
    }
    // Only cycles through degree-2 vertices are left.
    for i in 0..edges.len() {
        if !used[i] {
            let start = edges[i].0.min(edges[i].1);
            let first = incident[&start].iter().copied().find(|&e| !used[e]).unwrap_or(i);
            lines.push(walk(start, first, &mut used));
        }
    }
    lines
}
