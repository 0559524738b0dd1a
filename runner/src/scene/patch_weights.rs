//! Blending weights per vertex per patch (Breslav et al. 2007 §3.6), as
//! jot-lib computes them (`src/mesh/patch_blend_weight.cpp`,
//! `PatchBlendWeight::compute_all`):
//!
//! 1. at each vertex, a patch's weight is the share of the vertex's faces
//!    that belong to it (jot-lib's face share: 1 inside a patch, and at a
//!    boundary between k patches 1/k when they share the faces evenly, which
//!    is the paper's 1/k);
//! 2. then `passes` smoothing passes: in pass i, every vertex within the
//!    i-ring of a patch's faces takes, for that patch, the mean of its
//!    neighbours' weights (jot-lib averages the neighbours only, without the
//!    vertex itself), and every vertex's weights are renormalized to sum to 1.
//!
//! With n − 1 passes a patch reaches n rings outside its own faces: the
//! paper's n-ring over which patterns cross-fade. Vertices are welded by
//! position first, so seams where a mesh file splits vertices (UV or normal
//! seams) do not cut the smoothing.
//!
//! Render passes that read `patch.weight` draw with them: each patch over
//! its faces and n-ring ([`super::patch_blend`]), the style raising the
//! weight to a power for the pattern's strength.

use super::mesh::Mesh;
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// Per welded vertex, the patches with a weight there and their weights.
pub struct PatchWeights {
    /// Per mesh vertex, its welded vertex.
    pub welded: Vec<usize>,
    /// Per welded vertex: patch → weight, summing to 1.
    pub weights: Vec<BTreeMap<u32, f64>>,
}

impl PatchWeights {
    /// Patch `patch`'s weight at mesh vertex `v`.
    pub fn weight(&self, v: usize, patch: u32) -> f64 {
        self.weights[self.welded[v]].get(&patch).copied().unwrap_or(0.0)
    }
}

/// Computes the weights for the per-triangle `labels` with `passes`
/// smoothing passes.
pub fn blend_weights(mesh: &Mesh, labels: &[u32], passes: u32) -> PatchWeights {
    let mut welded = Vec::with_capacity(mesh.positions.len());
    let mut index_of: HashMap<[u32; 3], usize> = HashMap::new();
    for p in &mesh.positions {
        let next = index_of.len();
        welded.push(*index_of.entry(p.map(f32::to_bits)).or_insert(next));
    }
    let count = index_of.len();
    let triangles: Vec<[usize; 3]> = mesh
        .indices
        .chunks_exact(3)
        .map(|t| [welded[t[0] as usize], welded[t[1] as usize], welded[t[2] as usize]])
        .collect();
    let mut star: Vec<Vec<usize>> = vec![Vec::new(); count];
    let mut neighbours: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); count];
    for (f, t) in triangles.iter().enumerate() {
        for i in 0..3 {
            star[t[i]].push(f);
            for j in 0..3 {
                if i != j && t[i] != t[j] {
                    neighbours[t[i]].insert(t[j]);
                }
            }
        }
    }
    // 1. The face share.
    let mut weights: Vec<BTreeMap<u32, f64>> = star
        .iter()
        .map(|faces| {
            let mut w = BTreeMap::new();
            for &f in faces {
                *w.entry(labels[f]).or_insert(0.0) += 1.0;
            }
            // Counts over the star's size (so a patch's interior is exactly 1).
            w.values_mut().for_each(|x: &mut f64| *x /= faces.len() as f64);
            w
        })
        .collect();
    let patches: BTreeSet<u32> = labels.iter().copied().collect();
    // The vertices of each patch's faces (its 0-ring), grown by one ring per pass.
    let mut rings: BTreeMap<u32, BTreeSet<usize>> = patches.iter().map(|&p| (p, BTreeSet::new())).collect();
    for (f, t) in triangles.iter().enumerate() {
        rings
            .get_mut(&labels[f])
            .expect("a patch of the labels")
            .extend(t.iter().copied());
    }
    for _ in 0..passes {
        for (&patch, ring) in rings.iter_mut() {
            // The i-ring of faces: every face touching the vertices so far.
            let grown: BTreeSet<usize> = ring
                .iter()
                .flat_map(|&v| star[v].iter().flat_map(|&f| triangles[f]))
                .collect();
            *ring = grown;
            let smoothed: Vec<(usize, f64)> = ring
                .iter()
                .map(|&v| {
                    let n = &neighbours[v];
                    let w = if n.is_empty() {
                        weights[v].get(&patch).copied().unwrap_or(0.0)
                    } else {
                        n.iter()
                            .map(|&u| weights[u].get(&patch).copied().unwrap_or(0.0))
                            .sum::<f64>()
                            / n.len() as f64
                    };
                    (v, w)
                })
                .collect();
            for (v, w) in smoothed {
                if w > 0.0 {
                    weights[v].insert(patch, w);
                } else {
                    weights[v].remove(&patch);
                }
            }
        }
        for w in &mut weights {
            let total: f64 = w.values().sum();
            // Every vertex of a face keeps a weight for that face's patch
            // through a pass (its neighbours include the face's other
            // vertices), so the total is positive.
            debug_assert!(total > 0.0);
            for x in w.values_mut() {
                *x /= total;
            }
        }
    }
    PatchWeights { welded, weights }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::test_grid::{grid, halves};

    #[test]
    fn the_weights_sum_to_one_and_fade_over_the_n_ring() {
        let n = 16;
        let mesh = grid(n);
        let labels = halves(&mesh, n);
        for passes in [0, 1, 3] {
            let w = blend_weights(&mesh, &labels, passes);
            for v in 0..mesh.positions.len() {
                let total: f64 = w.weights[w.welded[v]].values().sum();
                assert!(
                    (total - 1.0).abs() < 1e-12,
                    "passes {passes}: vertex {v} sums to {total}"
                );
            }
            // Along a row across the boundary at x = 8: patch 0's weight
            // falls from 1 to 0, monotonically, within `passes + 1` columns
            // of the boundary on either side.
            let row = |x: u32| (8 * (n + 1) + x) as usize;
            let mut last = f64::INFINITY;
            for x in 0..=n {
                let w0 = w.weight(row(x), 0);
                assert!(w0 <= last + 1e-12, "passes {passes}: weight rises at x = {x}");
                last = w0;
                let distance = x as i64 - 8;
                if distance < -(passes as i64 + 1) {
                    assert_eq!(w0, 1.0, "passes {passes}: x = {x} is inside patch 0");
                }
                if distance > passes as i64 + 1 {
                    assert_eq!(w0, 0.0, "passes {passes}: x = {x} is beyond the n-ring");
                }
            }
            // On the boundary itself the two patches share evenly.
            assert!(
                (w.weight(row(8), 0) - 0.5).abs() < 1e-12,
                "passes {passes}: {}",
                w.weight(row(8), 0)
            );
        }
        // More passes widen the fade: at two columns from the boundary,
        // patch 1 reaches with 3 passes and not with none.
        let row = |x: u32| (8 * (n + 1) + x) as usize;
        assert_eq!(blend_weights(&mesh, &labels, 0).weight(row(6), 1), 0.0);
        assert!(blend_weights(&mesh, &labels, 3).weight(row(6), 1) > 0.0);
    }

    #[test]
    fn split_vertices_are_welded() {
        // Two separate triangles sharing an edge by position only.
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let mesh = Mesh::from_parts(positions, None, None, None, vec![0, 1, 2, 3, 4, 5], "seam".into());
        let w = blend_weights(&mesh, &[0, 1], 0);
        assert_eq!(w.welded[1], w.welded[3]);
        assert!((w.weight(1, 0) - 0.5).abs() < 1e-12 && (w.weight(3, 1) - 0.5).abs() < 1e-12);
        assert_eq!(w.weight(0, 1), 0.0);
    }
}
