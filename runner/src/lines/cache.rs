//! The per-renderer state of a `lines` pass: what is static per mesh (the
//! welded edge mesh, its creases and their chains, §5 "creases at the
//! intersections of non-coplanar polygons") is built once per mesh content
//! and crease threshold; the strips of one eye are rebuilt only when that
//! eye's view, an object's placement, the viewport, the line style or a
//! mesh changes (issue 10: "geometry is rebuilt only when the view or the
//! mesh changes"). Silhouettes depend on the eye, so they are found with
//! the strips, per eye in stereo.
//!
//! An edge is drawn once, whatever it is (issue 35 item 8): with both
//! silhouettes and creases on, a cube's outer edges are silhouettes and
//! creases at once, and drawn from both lists they made two strips whose
//! sines had different phases (a doubled line up to 2·amplitude wider, or a
//! wave that cancelled). The silhouettes are chained first, so a
//! silhouette loop keeps one phase all round it (the outline is the line
//! that must read as one stroke, §5); the creases are then chained from the
//! crease edges that are not silhouettes from this eye. Without silhouettes
//! the crease chains are static and cached.
//!
//! A pass with line sets (decision 0056) shares the edge meshes; its strips
//! are rebuilt as a whole (`sets::build`) when its view key changes.

use std::collections::HashMap;

use glam::{DMat4, DVec2, DVec3};

use super::edges::{EdgeMesh, Polyline};
use super::sets::{self, SetInput, SetSurface};
use super::strip::{self, LineStyle, Strips};
use super::viewpoint::Viewpoint;
use crate::scene::Mesh;

/// Which feature edges a pass draws.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeSelection {
    pub silhouettes: bool,
    /// The dihedral threshold in degrees; `None` draws no creases.
    pub crease_deg: Option<f64>,
}

/// One object as the lines see it: its mesh and object-to-world matrix.
pub struct LineObject<'a> {
    pub mesh: &'a Mesh,
    pub model: DMat4,
}

/// The static part of one mesh.
struct MeshEdges {
    edges: EdgeMesh,
    /// Crease edges and their chains per threshold (bit pattern of the
    /// f64), found once.
    creases: HashMap<u64, Creases>,
}

/// The crease edges at one threshold (indices into the edge mesh's edges)
/// and their chains when no silhouette takes any of them.
struct Creases {
    indices: Vec<u32>,
    chains: Vec<Polyline>,
}

/// Everything that decides an eye's strips, compared bit for bit.
#[derive(Debug, Clone, PartialEq)]
struct ViewKey {
    view_proj: [u64; 16],
    models: Vec<[u64; 16]>,
    meshes: Vec<blake3::Hash>,
    size: [u64; 2],
    style: [u64; 5],
    selection: (bool, Option<u64>),
    /// With line sets: per set, its surfaces, style and edge types.
    sets: Vec<(Vec<usize>, [u64; 5], String)>,
}

/// One line set as the cache takes it: the indices of its surfaces among
/// the pass's objects, its edge types and its style.
pub struct SetRequest {
    pub surfaces: Vec<usize>,
    pub edges: npr_abi::lines::EdgeTypes,
    pub style: LineStyle,
    /// Which lines by QI (decision 0063); `None` draws all.
    pub visibility: Option<npr_abi::lines::LineVisibility>,
    /// Dashes `(on, off)` in px.
    pub dash: Option<[f64; 2]>,
}

fn style_bits(style: &LineStyle) -> [u64; 5] {
    [
        style.width_px,
        style.amplitude_px,
        style.wavelength_px,
        style.phase,
        style.taper,
    ]
    .map(f64::to_bits)
}

/// Edge meshes by content, and each eye's strips with the key they were
/// built for.
#[derive(Default)]
pub struct LinesCache {
    meshes: HashMap<blake3::Hash, MeshEdges>,
    eyes: HashMap<u32, (ViewKey, Strips)>,
    /// How many times strips were built (for tests and `npr bench lines`).
    pub rebuilds: u64,
    /// How many edge meshes were built.
    pub mesh_builds: u64,
}

impl LinesCache {
    /// How many edge meshes the cache holds now (bounded: see `strips`).
    pub fn edge_meshes(&self) -> usize {
        self.meshes.len()
    }
}

fn mesh_hash(mesh: &Mesh) -> blake3::Hash {
    let mut hasher = blake3::Hasher::new();
    hasher.update(bytemuck::cast_slice(&mesh.positions));
    hasher.update(bytemuck::cast_slice(&mesh.indices));
    // Two meshes of one shape with different marks have different edges.
    if let Some(marks) = &mesh.edge_marks {
        hasher.update(marks);
    }
    hasher.finalize()
}

fn bits(m: DMat4) -> [u64; 16] {
    m.to_cols_array().map(f64::to_bits)
}

impl LinesCache {
    /// The strips of eye `eye_index` at `eye_position` (world space) through
    /// `view_proj` on a `size` px viewport: the cached ones when nothing
    /// they depend on changed.
    #[allow(clippy::too_many_arguments)]
    pub fn strips(
        &mut self,
        eye_index: u32,
        objects: &[LineObject<'_>],
        eye_position: impl Into<Viewpoint>,
        view_proj: DMat4,
        size: DVec2,
        style: &LineStyle,
        selection: EdgeSelection,
    ) -> &Strips {
        let eye_position: Viewpoint = eye_position.into();
        let hashes: Vec<blake3::Hash> = objects.iter().map(|o| mesh_hash(o.mesh)).collect();
        let key = ViewKey {
            view_proj: bits(view_proj),
            models: objects.iter().map(|o| bits(o.model)).collect(),
            meshes: hashes.clone(),
            size: [size.x.to_bits(), size.y.to_bits()],
            style: style_bits(style),
            selection: (selection.silhouettes, selection.crease_deg.map(f64::to_bits)),
            sets: Vec::new(),
        };
        let fresh = matches!(self.eyes.get(&eye_index), Some((k, _)) if *k == key);
        if !fresh {
            let mut polylines: Vec<(Vec<DVec3>, bool)> = Vec::new();
            for (object, hash) in objects.iter().zip(&hashes) {
                let entry = self.meshes.entry(*hash).or_insert_with(|| {
                    self.mesh_builds += 1;
                    MeshEdges {
                        edges: EdgeMesh::new(object.mesh),
                        creases: HashMap::new(),
                    }
                });
                let world = |line: &Polyline, edges: &EdgeMesh| -> (Vec<DVec3>, bool) {
                    let points = line
                        .vertices
                        .iter()
                        .map(|&v| object.model.transform_point3(edges.positions[v as usize]));
                    (points.collect(), line.closed)
                };
                let edges = &entry.edges;
                let creases = selection.crease_deg.map(|threshold| {
                    &*entry.creases.entry(threshold.to_bits()).or_insert_with(|| {
                        let indices: Vec<u32> = edges.creases(threshold).iter().map(|c| c.0).collect();
                        let chains = edges.chain(&indices);
                        Creases { indices, chains }
                    })
                });
                // The eye in the object's own space: facing is decided
                // against the object-space face normals.
                let local_eye = eye_position.transformed(object.model.inverse());
                let silhouettes = if selection.silhouettes && local_eye.is_finite() {
                    edges.silhouettes(local_eye)
                } else {
                    Vec::new()
                };
                polylines.extend(edges.chain(&silhouettes).iter().map(|l| world(l, edges)));
                if let Some(creases) = creases {
                    if silhouettes.is_empty() {
                        polylines.extend(creases.chains.iter().map(|l| world(l, edges)));
                    } else {
                        // Each edge once: a crease that is a silhouette from
                        // this eye is already in a silhouette chain.
                        let mut taken = vec![false; edges.edges.len()];
                        for &i in &silhouettes {
                            taken[i as usize] = true;
                        }
                        let rest: Vec<u32> = creases
                            .indices
                            .iter()
                            .copied()
                            .filter(|&i| !taken[i as usize])
                            .collect();
                        polylines.extend(edges.chain(&rest).iter().map(|l| world(l, edges)));
                    }
                }
            }
            let strips = strip::build(&polylines, view_proj, size, style);
            self.store(eye_index, key, strips);
        }
        &self.eyes[&eye_index].1
    }

    /// The strips of a pass's line sets (decision 0056; highest priority
    /// first) for eye `eye_index`, as [`LinesCache::strips`] without sets:
    /// the cached ones when nothing they depend on changed.
    pub fn set_strips(
        &mut self,
        eye_index: u32,
        objects: &[LineObject<'_>],
        sets: &[SetRequest],
        eye_position: impl Into<Viewpoint>,
        view_proj: DMat4,
        size: DVec2,
    ) -> &Strips {
        let eye_position: Viewpoint = eye_position.into();
        let hashes: Vec<blake3::Hash> = objects.iter().map(|o| mesh_hash(o.mesh)).collect();
        let key = ViewKey {
            view_proj: bits(view_proj),
            models: objects.iter().map(|o| bits(o.model)).collect(),
            meshes: hashes.clone(),
            size: [size.x.to_bits(), size.y.to_bits()],
            style: [0; 5],
            selection: (false, None),
            sets: sets
                .iter()
                .map(|s| {
                    let how = format!(
                        "{:?} {:?} {:?}",
                        s.edges,
                        s.visibility,
                        s.dash.map(|d| d.map(f64::to_bits))
                    );
                    (s.surfaces.clone(), style_bits(&s.style), how)
                })
                .collect(),
        };
        let fresh = matches!(self.eyes.get(&eye_index), Some((k, _)) if *k == key);
        if !fresh {
            for (object, hash) in objects.iter().zip(&hashes) {
                self.meshes.entry(*hash).or_insert_with(|| {
                    self.mesh_builds += 1;
                    MeshEdges {
                        edges: EdgeMesh::new(object.mesh),
                        creases: HashMap::new(),
                    }
                });
            }
            let inputs: Vec<SetInput<'_>> = sets
                .iter()
                .map(|set| SetInput {
                    surfaces: set
                        .surfaces
                        .iter()
                        .map(|&i| SetSurface {
                            edges: &self.meshes[&hashes[i]].edges,
                            model: objects[i].model,
                            key: i,
                        })
                        .collect(),
                    edges: set.edges,
                    style: set.style,
                    visibility: set.visibility,
                    dash: set.dash,
                })
                .collect();
            let strips = sets::build(&inputs, eye_position, view_proj, size);
            self.store(eye_index, key, strips);
        }
        &self.eyes[&eye_index].1
    }

    fn store(&mut self, eye_index: u32, key: ViewKey, strips: Strips) {
        let drawn = key.meshes.len();
        self.rebuilds += 1;
        self.eyes.insert(eye_index, (key, strips));
        // A mesh whose vertices change (the ocean, a host's deforming
        // mesh) is a new content every frame: edge meshes no eye draws
        // now go once they outnumber the drawn ones, so the cache stays
        // bounded.
        if self.meshes.len() > 2 * drawn + 8 {
            let eyes = &self.eyes;
            self.meshes
                .retain(|hash, _| eyes.values().any(|(key, _)| key.meshes.contains(hash)));
        }
    }
}
