//! Patches (Breslav et al. 2007 §3.6): an object divided into pieces that
//! each get their own samples and their own 2D similarity, which reduces
//! sliding where one similarity cannot follow the whole object (an
//! elongated object in depth, Fig. 4). A scene asks for them per object:
//! `patches = "parts"` takes the mesh file's parts (OBJ `o`/`g`, glTF
//! primitives); `patches = 6` splits the surface into 6 compact pieces by
//! area-weighted k-means of the triangles' centroids (the paper's patches
//! are drawn by hand; any division will do for the method).
//!
//! Each patch becomes an object of its own at load
//! (`parse_patches::expand`), with the object's transform, tags and
//! bindings, so every per-object pass (samples, the ID image, the tracker)
//! works per patch unchanged. What is of the surface as a whole (its feature
//! edges: a seam between two patches is no edge of the surface) is found on
//! the whole mesh, which each patch keeps ([`PatchOf`]).
//!
//! Blending across patch boundaries (§3.6) is in [`super::patch_weights`]
//! (the weights) and [`super::patch_blend`] (each patch with its n-ring, as
//! render passes reading `patch.weight` draw it).

use super::mesh::Mesh;
use std::collections::HashMap;

/// How a scene object is divided into patches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PatchSpec {
    /// The mesh file's parts.
    Parts,
    /// This many pieces, by k-means of the triangles.
    Split(u32),
}

/// Where a patch object came from: the object it is a piece of. Feature
/// edges for `lines` passes are found on `whole` (`crate::lines::objects`),
/// so that a seam between two patches is a crease only where the surface
/// bends there, never a boundary.
#[derive(Debug, Clone)]
pub struct PatchOf {
    /// The patched object's name as the scene wrote it (unique in the
    /// scene; its patches are `<source>.<index>`).
    pub source: String,
    /// The object's whole mesh, every patch's faces together.
    pub whole: std::sync::Arc<Mesh>,
    /// This patch, in `0..count`.
    pub index: u32,
    pub count: u32,
}

/// The most patches an object may be split into.
pub const MAX_PATCHES: u32 = 64;

/// Lloyd iterations of the k-means split (it converges well before).
const KMEANS_ITERATIONS: usize = 24;

/// Per triangle, its patch in `0..count`, every patch non-empty; `None` when
/// the mesh cannot be divided so (no parts, or fewer triangles than
/// patches, or a split that left a patch empty).
pub fn assign(mesh: &Mesh, spec: PatchSpec) -> Option<(Vec<u32>, u32)> {
    let labels = match spec {
        PatchSpec::Parts => mesh.parts.clone()?,
        PatchSpec::Split(k) => kmeans(mesh, k)?,
    };
    compact(labels)
}

/// Renumbers labels to 0..count in order of first use; `None` for fewer
/// than two patches.
fn compact(labels: Vec<u32>) -> Option<(Vec<u32>, u32)> {
    let mut renumbered: HashMap<u32, u32> = HashMap::new();
    let out: Vec<u32> = labels
        .iter()
        .map(|l| {
            let next = renumbered.len() as u32;
            *renumbered.entry(*l).or_insert(next)
        })
        .collect();
    let count = renumbered.len() as u32;
    (count >= 2).then_some((out, count))
}

fn centroid_and_area(mesh: &Mesh, t: usize) -> ([f64; 3], f64) {
    let at = |i: usize| mesh.positions[mesh.indices[3 * t + i] as usize].map(f64::from);
    let (a, b, c) = (at(0), at(1), at(2));
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let area = 0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (std::array::from_fn(|i| (a[i] + b[i] + c[i]) / 3.0), area)
}

fn distance2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}

/// Area-weighted k-means of the triangle centroids, seeded by farthest-point
/// selection from the triangle nearest the centroid of the whole surface, so
/// the split is deterministic and spreads its seeds over the surface.
fn kmeans(mesh: &Mesh, k: u32) -> Option<Vec<u32>> {
    let triangles = mesh.indices.len() / 3;
    let k = k as usize;
    if k < 2 || triangles < k {
        return None;
    }
    let (centroids, areas): (Vec<[f64; 3]>, Vec<f64>) = (0..triangles).map(|t| centroid_and_area(mesh, t)).unzip();
    let total: f64 = areas.iter().sum();
    if total <= 0.0 || !total.is_finite() {
        return None;
    }
    let mean: [f64; 3] =
        std::array::from_fn(|i| centroids.iter().zip(&areas).map(|(c, a)| c[i] * a).sum::<f64>() / total);
    let nearest = |p: [f64; 3]| {
        (0..triangles)
            .min_by(|&a, &b| distance2(centroids[a], p).total_cmp(&distance2(centroids[b], p)))
            .expect("triangles")
    };
    let mut centres = vec![centroids[nearest(mean)]];
    while centres.len() < k {
        let farthest = (0..triangles)
            .max_by(|&a, &b| {
                let d = |t: usize| {
                    centres
                        .iter()
                        .map(|c| distance2(centroids[t], *c))
                        .fold(f64::INFINITY, f64::min)
                };
                d(a).total_cmp(&d(b))
            })
            .expect("triangles");
        centres.push(centroids[farthest]);
    }
    let mut labels = vec![0u32; triangles];
    for _ in 0..KMEANS_ITERATIONS {
        for (t, label) in labels.iter_mut().enumerate() {
            *label = (0..k)
                .min_by(|&a, &b| distance2(centroids[t], centres[a]).total_cmp(&distance2(centroids[t], centres[b])))
                .expect("k ≥ 2") as u32;
        }
        let mut sums = vec![([0.0f64; 3], 0.0f64); k];
        for t in 0..triangles {
            let (s, w) = &mut sums[labels[t] as usize];
            for i in 0..3 {
                s[i] += centroids[t][i] * areas[t];
            }
            *w += areas[t];
        }
        for (c, (s, w)) in centres.iter_mut().zip(&sums) {
            if *w > 0.0 {
                *c = s.map(|x| x / w);
            }
        }
    }
    let mut used = vec![false; k];
    for &l in &labels {
        used[l as usize] = true;
    }
    used.iter().all(|&u| u).then_some(labels)
}

/// The triangles of `patch` as a mesh of their own: the vertices they use,
/// with the object's normals, UVs and tangents (so shading is continuous
/// across a seam).
pub fn patch_mesh(mesh: &Mesh, labels: &[u32], patch: u32) -> Mesh {
    let faces: Vec<usize> = (0..labels.len()).filter(|&t| labels[t] == patch).collect();
    super::patch_blend::sub_mesh(mesh, &faces, format!("{} (patch {patch})", mesh.source)).0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of `n` × 1 unit squares along x, two triangles each.
    fn strip(n: u32) -> Mesh {
        let mut positions = Vec::new();
        for i in 0..=n {
            positions.push([i as f32, 0.0, 0.0]);
            positions.push([i as f32, 1.0, 0.0]);
        }
        let mut indices = Vec::new();
        for i in 0..n {
            let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
            indices.extend([a, b, c, a, c, d]);
        }
        Mesh::from_parts(positions, None, None, None, indices, "strip".into())
    }

    fn area(mesh: &Mesh) -> f64 {
        (0..mesh.indices.len() / 3).map(|t| centroid_and_area(mesh, t).1).sum()
    }

    #[test]
    fn a_split_covers_every_triangle_once_in_compact_pieces() {
        let mesh = strip(40);
        let (labels, count) = assign(&mesh, PatchSpec::Split(4)).expect("split");
        assert_eq!(count, 4);
        assert_eq!(labels.len(), 80);
        // On a strip, compact pieces are runs along x: each patch's x range
        // is about a quarter of the strip, and the ranges do not overlap.
        let mut ranges: Vec<(f64, f64)> = (0..4)
            .map(|p| {
                let xs: Vec<f64> = (0..80)
                    .filter(|&t| labels[t] == p)
                    .map(|t| centroid_and_area(&mesh, t).0[0])
                    .collect();
                (
                    xs.iter().copied().fold(f64::MAX, f64::min),
                    xs.iter().copied().fold(f64::MIN, f64::max),
                )
            })
            .collect();
        ranges.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in ranges.windows(2) {
            assert!(w[0].1 < w[1].0, "patches overlap: {ranges:?}");
        }
        for r in &ranges {
            assert!((r.1 - r.0 - 9.0).abs() <= 3.0, "uneven patch {r:?} in {ranges:?}");
        }
        // The pieces together are the whole surface.
        let total: f64 = (0..count).map(|p| area(&patch_mesh(&mesh, &labels, p))).sum();
        assert!((total - area(&mesh)).abs() < 1e-9, "{total} against {}", area(&mesh));
        // And the same split every time.
        assert_eq!(assign(&mesh, PatchSpec::Split(4)), Some((labels, count)));
    }

    #[test]
    fn a_patch_mesh_keeps_only_the_vertices_it_uses() {
        let mesh = strip(4);
        let labels = vec![0, 0, 1, 1, 1, 1, 0, 0];
        let a = patch_mesh(&mesh, &labels, 0);
        let b = patch_mesh(&mesh, &labels, 1);
        assert_eq!((a.indices.len(), b.indices.len()), (12, 12));
        assert_eq!((a.positions.len(), b.positions.len()), (8, 6));
        assert!(a.validate().is_ok() && b.validate().is_ok());
    }

    #[test]
    fn too_few_triangles_or_one_part_is_no_division() {
        let mesh = strip(1);
        assert_eq!(assign(&mesh, PatchSpec::Split(3)), None);
        assert_eq!(assign(&mesh, PatchSpec::Parts), None);
        let two = strip(2).with_parts(vec![7, 7, 3, 3]);
        assert_eq!(assign(&two, PatchSpec::Parts), Some((vec![0, 0, 1, 1], 2)));
    }
}
