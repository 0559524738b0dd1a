//! What a patch is drawn with where patterns cross-fade across patch
//! boundaries (Breslav et al. 2007 §3.6): "to render a patch, we render all
//! of its triangles plus those in the 1-ring outside the patch", with the
//! pattern's strength from the patch's blending weight at each vertex.
//!
//! With n rings ([`blend_weights`] with n − 1 smoothing passes) a patch's
//! weight reaches n rings of faces outside it, so it is drawn over those:
//! its own faces, then every face outside it with a vertex where its weight
//! is above 0. That is jot-lib's `Patch::draw_n_ring_triangles(passes + 1)`
//! (`src/gtex/hatching_tx.cpp`, `HatchingTX::draw_triangles`), except that
//! the faces are chosen from the weights rather than by ring distance: the
//! two are the same set (a unit test checks it), and choosing by weight is
//! what guarantees that every patch with a weight on a face draws that face,
//! so that the weights drawn sum to 1 at every point of the surface (they
//! sum to 1 at each vertex and are interpolated linearly over each face).
//!
//! `blend_rings = 0` in a scene is no blending: each patch is drawn over its
//! own faces with weight 1 (the hard seams of separately drawn patches).

use super::mesh::Mesh;
use super::patch_weights::{blend_weights, PatchWeights};
use std::collections::HashMap;

/// The most rings a scene may blend patches over.
pub const MAX_BLEND_RINGS: u32 = 16;

/// The rings a patched object blends over when the scene does not say: the
/// paper's 1-ring (jot-lib's default of 0 smoothing passes).
pub const DEFAULT_BLEND_RINGS: u32 = 1;

/// One patch as a render pass that reads `patch.weight` draws it.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchBlend {
    /// The patch's own faces first (in the order of its own mesh, with its
    /// own vertices first in the same order), then the faces of its n-ring.
    pub mesh: Mesh,
    /// Per vertex of `mesh`: the patch's blending weight there, in 0..=1.
    pub weights: Vec<f32>,
    /// How many of `mesh`'s indices are the patch's own faces.
    pub own_indices: usize,
    /// n: the rings the weights reach outside the patch.
    pub rings: u32,
}

/// Per patch, its [`PatchBlend`] over `rings` rings (≥ 1), for the
/// per-triangle `labels` of `mesh` with `count` patches.
pub fn blends(mesh: &Mesh, labels: &[u32], count: u32, rings: u32) -> Vec<PatchBlend> {
    debug_assert!(rings >= 1);
    let weights = blend_weights(mesh, labels, rings - 1);
    (0..count).map(|p| blend_of(mesh, labels, p, &weights, rings)).collect()
}

/// Patch `patch`'s faces and n-ring, with its weights.
fn blend_of(mesh: &Mesh, labels: &[u32], patch: u32, weights: &PatchWeights, rings: u32) -> PatchBlend {
    let triangles = mesh.indices.len() / 3;
    let corners = |t: usize| &mesh.indices[3 * t..3 * t + 3];
    let own = (0..triangles).filter(|&t| labels[t] == patch);
    let ring = (0..triangles)
        .filter(|&t| labels[t] != patch && corners(t).iter().any(|&v| weights.weight(v as usize, patch) > 0.0));
    let faces: Vec<usize> = own.chain(ring).collect();
    let own_indices = 3 * labels.iter().filter(|&&l| l == patch).count();
    let (sub, used) = sub_mesh(mesh, &faces, format!("{} (patch {patch}, {rings}-ring)", mesh.source));
    let weights = used.iter().map(|&v| weights.weight(v as usize, patch) as f32).collect();
    PatchBlend {
        mesh: sub,
        weights,
        own_indices,
        rings,
    }
}

/// The triangles `faces` of `mesh` as a mesh of their own, with the
/// vertices they use in order of first use (and the object's normals, UVs
/// and tangents, so shading is continuous across a seam), and per new
/// vertex its index in `mesh`.
pub fn sub_mesh(mesh: &Mesh, faces: &[usize], source: String) -> (Mesh, Vec<u32>) {
    let mut index_of: HashMap<u32, u32> = HashMap::new();
    let mut used: Vec<u32> = Vec::new();
    let mut indices = Vec::with_capacity(3 * faces.len());
    for &t in faces {
        for &v in &mesh.indices[3 * t..3 * t + 3] {
            let next = used.len() as u32;
            let i = *index_of.entry(v).or_insert_with(|| {
                used.push(v);
                next
            });
            indices.push(i);
        }
    }
    let pick = |v: &[[f32; 3]]| used.iter().map(|&i| v[i as usize]).collect::<Vec<_>>();
    let sub = Mesh {
        positions: pick(&mesh.positions),
        normals: pick(&mesh.normals),
        uvs: mesh
            .uvs
            .as_ref()
            .map(|uvs| used.iter().map(|&i| uvs[i as usize]).collect()),
        tangents: mesh
            .tangents
            .as_ref()
            .map(|ts| used.iter().map(|&i| ts[i as usize]).collect()),
        indices,
        source,
        parts: None,
        edge_marks: None,
    };
    (sub, used)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::test_grid::{grid, halves as split};
    use std::collections::BTreeSet;

    /// An n × n grid split at x = n/2 into patch 0 (left) and 1 (right).
    fn halves(n: u32) -> (Mesh, Vec<u32>) {
        let mesh = grid(n);
        let labels = split(&mesh, n);
        (mesh, labels)
    }

    /// The faces within `rings` rings of `patch`'s faces, by shared vertices
    /// (the paper's n-ring, computed independently of the weights).
    fn n_ring(mesh: &Mesh, labels: &[u32], patch: u32, rings: u32) -> BTreeSet<usize> {
        let triangles = mesh.indices.len() / 3;
        let mut faces: BTreeSet<usize> = (0..triangles).filter(|&t| labels[t] == patch).collect();
        for _ in 0..rings {
            let verts: BTreeSet<u32> = faces
                .iter()
                .flat_map(|&t| mesh.indices[3 * t..3 * t + 3].to_vec())
                .collect();
            faces = (0..triangles)
                .filter(|&t| mesh.indices[3 * t..3 * t + 3].iter().any(|v| verts.contains(v)))
                .collect();
        }
        faces
    }

    /// The faces of a blend mesh, as triangles of the original mesh (by
    /// their sorted vertex positions).
    fn face_keys(mesh: &Mesh, faces: impl Iterator<Item = usize>) -> BTreeSet<[[u32; 3]; 3]> {
        faces
            .map(|t| {
                let mut k: Vec<[u32; 3]> = mesh.indices[3 * t..3 * t + 3]
                    .iter()
                    .map(|&v| mesh.positions[v as usize].map(f32::to_bits))
                    .collect();
                k.sort();
                [k[0], k[1], k[2]]
            })
            .collect()
    }

    #[test]
    fn each_patch_is_drawn_over_its_faces_and_exactly_its_n_ring() {
        let (mesh, labels) = halves(12);
        for rings in [1, 2, 4] {
            let blends = blends(&mesh, &labels, 2, rings);
            for (p, blend) in blends.iter().enumerate() {
                let drawn = face_keys(&blend.mesh, 0..blend.mesh.indices.len() / 3);
                let expected = face_keys(&mesh, n_ring(&mesh, &labels, p as u32, rings).into_iter());
                assert_eq!(drawn, expected, "patch {p}, {rings} rings");
                // Its own faces first.
                let own = face_keys(&blend.mesh, 0..blend.own_indices / 3);
                let own_expected = face_keys(&mesh, (0..labels.len()).filter(|&t| labels[t] == p as u32));
                assert_eq!(own, own_expected, "patch {p}, {rings} rings: own faces first");
                assert!(blend.mesh.validate().is_ok());
                assert_eq!(blend.weights.len(), blend.mesh.positions.len());
            }
        }
    }

    #[test]
    fn the_weights_drawn_sum_to_one_wherever_a_patch_is_drawn() {
        // At every vertex position of any blend mesh, the weights of every
        // patch drawn there sum to 1; and a vertex where a patch has weight
        // is in that patch's blend mesh (nothing is left out of the sum).
        let (mesh, labels) = halves(10);
        let weights = blend_weights(&mesh, &labels, 2);
        let blends = blends(&mesh, &labels, 2, 3);
        let mut sums: HashMap<[u32; 3], f64> = HashMap::new();
        for blend in &blends {
            let mut seen = BTreeSet::new();
            for (p, w) in blend.mesh.positions.iter().zip(&blend.weights) {
                if seen.insert(p.map(f32::to_bits)) {
                    *sums.entry(p.map(f32::to_bits)).or_default() += f64::from(*w);
                }
            }
        }
        for (v, p) in mesh.positions.iter().enumerate() {
            let total = sums.get(&p.map(f32::to_bits)).copied().unwrap_or(0.0);
            assert!((total - 1.0).abs() < 1e-6, "vertex {v} at {p:?}: {total}");
            for patch in 0..2 {
                if weights.weight(v, patch) > 0.0 {
                    assert!(blends[patch as usize].mesh.positions.contains(p));
                }
            }
        }
    }
}
