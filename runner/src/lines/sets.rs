//! The line sets of a `lines` pass (decision 0056): each set selects its
//! surfaces (the pass's objects, narrowed by the set's tag) and a union of
//! edge types, and draws them in its own style. An edge two sets select is
//! drawn once, by the set listed first (the manifest lists sets highest
//! priority first), so two sets never stack two strips with different
//! phases on one edge (issue 35 item 8, now between sets).
//!
//! Edge identity: a mesh edge is (surface, edge index), the surface being
//! its index in the pass's surfaces (the same object selected by two sets
//! is the same surface, whatever its place in each set); an intersection segment is its two end points'
//! bits, which are computed from the same triangles by the same arithmetic
//! in every set that finds them, so equal bit for bit.
//!
//! Within a set, as in a pass without sets, the silhouettes are chained
//! first (a silhouette loop keeps one phase all round it) and the set's
//! other mesh edges are chained together after them; the intersection lines
//! are chained on their own.

use std::collections::HashSet;

use glam::{DMat4, DVec2, DVec3};
use npr_abi::lines::EdgeTypes;

use super::edges::EdgeMesh;
use super::intersections::{intersection_segments, weld_and_chain, PlacedMesh};
use super::strip::{self, LineStyle, Strips};
use super::viewpoint::Viewpoint;

/// A surface's identity across sets: its index among the pass's surfaces.
pub type SurfaceKey = usize;

/// One surface a set draws: its edge mesh, placement and identity.
pub struct SetSurface<'a> {
    pub edges: &'a EdgeMesh,
    pub model: DMat4,
    pub key: SurfaceKey,
}

/// One set, ready to build: its surfaces, edge types and style.
pub struct SetInput<'a> {
    pub surfaces: Vec<SetSurface<'a>>,
    pub edges: EdgeTypes,
    pub style: LineStyle,
}

/// World-space polylines (closed or not).
pub type Polylines = Vec<(Vec<DVec3>, bool)>;

/// Per set (in the order given, highest priority first), the world-space
/// polylines it draws from the eye at `eye_position`: each edge in exactly
/// one set, the first that selects it.
pub fn select(sets: &[SetInput<'_>], eye_position: impl Into<Viewpoint>) -> Vec<Polylines> {
    let eye_position = eye_position.into();
    let mut taken_edges: HashSet<(SurfaceKey, u32)> = HashSet::new();
    let mut taken_segments: HashSet<[u64; 6]> = HashSet::new();
    sets.iter()
        .map(|set| {
            let mut polylines: Polylines = Vec::new();
            for surface in &set.surfaces {
                let mesh = surface.edges;
                let world = |vertices: &[u32], closed: bool| -> (Vec<DVec3>, bool) {
                    let points = vertices
                        .iter()
                        .map(|&v| surface.model.transform_point3(mesh.positions[v as usize]));
                    (points.collect(), closed)
                };
                let local_eye = eye_position.transformed(surface.model.inverse());
                let mut claim = |indices: Vec<u32>| -> Vec<u32> {
                    indices
                        .into_iter()
                        .filter(|&e| taken_edges.insert((surface.key, e)))
                        .collect()
                };
                if set.edges.silhouette && local_eye.is_finite() {
                    let silhouettes = claim(mesh.silhouettes(local_eye));
                    polylines.extend(mesh.chain(&silhouettes).iter().map(|l| world(&l.vertices, l.closed)));
                }
                let mut others: Vec<u32> = Vec::new();
                if set.edges.border {
                    others.extend(mesh.borders());
                }
                if let Some(threshold) = set.edges.crease_deg {
                    others.extend(mesh.creases_over(threshold));
                }
                if set.edges.material_boundary {
                    others.extend(mesh.part_boundaries());
                }
                others.sort_unstable();
                others.dedup();
                let others = claim(others);
                polylines.extend(mesh.chain(&others).iter().map(|l| world(&l.vertices, l.closed)));
            }
            if set.edges.intersection {
                let placed: Vec<PlacedMesh<'_>> = set
                    .surfaces
                    .iter()
                    .map(|s| PlacedMesh {
                        edges: s.edges,
                        model: s.model,
                    })
                    .collect();
                let (segments, tolerance) = intersection_segments(&placed);
                let mine: Vec<(DVec3, DVec3)> = segments
                    .into_iter()
                    .filter(|&(a, b)| taken_segments.insert(segment_key(a, b)))
                    .collect();
                polylines.extend(weld_and_chain(&mine, tolerance));
            }
            polylines
        })
        .collect()
}

/// A segment's identity whichever way round it was found.
fn segment_key(a: DVec3, b: DVec3) -> [u64; 6] {
    let (a, b) = (a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits));
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]
}

/// The strips of every set from one eye, each vertex marked with its set's
/// index (`LineVertex::line.w`, which the shader's `line.color` reads).
pub fn build(sets: &[SetInput<'_>], eye_position: impl Into<Viewpoint>, view_proj: DMat4, size: DVec2) -> Strips {
    let mut strips = Strips::default();
    for (index, (set, polylines)) in sets.iter().zip(select(sets, eye_position)).enumerate() {
        strips.append(strip::build(&polylines, view_proj, size, &set.style), index as u32);
    }
    strips
}
