//! Stratified sample points on a mesh's surface, for compute passes over
//! `samples` (Breslav et al. 2007 §3.1, after Nehab and Shilane 2004).
//!
//! Nehab and Shilane stratify points drawn uniformly on the surface by a
//! voxel grid: one point per voxel that the surface crosses, so the points
//! cover the surface evenly whatever its triangulation. jot-lib
//! (`src/sps/sps.cpp`) does the same with an octree; a flat grid of the
//! target spacing gives the same stratification for one level. Here:
//! 1. candidates are drawn uniformly by area (a triangle by its share of the
//!    area, then a uniform point in it), 8 per wanted sample;
//! 2. the grid's cell size h starts at √(area / count) and is searched (by
//!    bisection of its scale) so that the number of occupied cells comes
//!    closest to the wanted count;
//! 3. each occupied cell keeps its candidate of lowest random priority;
//!    past the wanted count, a random subset of the cells stays (never more
//!    samples than asked for).
//!
//! Every random number comes from a SplitMix64 stream of the seed, so the
//! samples are the same in every run. A sample is stored as its triangle
//! (the three vertex indices) and barycentric coordinates, as in the paper
//! and jot-lib, so it stays on the surface when the object moves or its
//! vertices are animated.

use super::Mesh;
use std::collections::HashMap;

/// One sample: `position = (1 − b1 − b2)·v[i0] + b1·v[i1] + b2·v[i2]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub triangle: [u32; 3],
    pub b1: f32,
    pub b2: f32,
}

/// The samples of one mesh and their spacing (object-space units): the
/// grid's cell size, the diameter of the surface each sample stands for.
#[derive(Debug, Clone, PartialEq)]
pub struct Samples {
    pub samples: Vec<Sample>,
    pub spacing: f32,
}

/// The seed of object `object`'s samples in a pass seeded `seed`: objects
/// that share a mesh get different samples.
pub fn object_seed(seed: u32, object: usize) -> u64 {
    u64::from(seed) ^ (object as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
}

/// Candidates drawn per wanted sample.
const CANDIDATES_PER_SAMPLE: usize = 8;
/// Bisection steps for the cell size.
const SEARCH_STEPS: usize = 24;

/// SplitMix64: a small, well-mixed, seedable generator.
struct Stream(u64);

impl Stream {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

struct Candidate {
    triangle: usize,
    b1: f64,
    b2: f64,
    position: [f64; 3],
    priority: u64,
}

fn vertex(mesh: &Mesh, i: u32) -> [f64; 3] {
    let p = mesh.positions[i as usize];
    [p[0] as f64, p[1] as f64, p[2] as f64]
}

fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
}

/// About `count` stratified samples on `mesh` (none for a mesh without
/// triangles or area), the same for the same mesh, count and seed.
pub fn stratified(mesh: &Mesh, count: usize, seed: u64) -> Samples {
    let triangles: Vec<[u32; 3]> = mesh.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    let areas: Vec<f64> = triangles
        .iter()
        .map(|t| triangle_area(vertex(mesh, t[0]), vertex(mesh, t[1]), vertex(mesh, t[2])))
        .collect();
    let total: f64 = areas.iter().sum();
    if count == 0 || total.is_nan() || total <= 0.0 || !total.is_finite() {
        return Samples {
            samples: Vec::new(),
            spacing: 0.0,
        };
    }
    // The area's cumulative distribution over the triangles.
    let mut cdf = Vec::with_capacity(areas.len());
    let mut running = 0.0;
    for a in &areas {
        running += a;
        cdf.push(running / total);
    }
    let mut rng = Stream(seed ^ 0x6E70_725F_7361_6D70);
    let candidates: Vec<Candidate> = (0..count * CANDIDATES_PER_SAMPLE)
        .map(|_| {
            let pick = rng.next_f64();
            let triangle = cdf.partition_point(|c| *c <= pick).min(triangles.len() - 1);
            // A uniform point in the triangle (Osada et al.'s square-root map).
            let (r1, r2) = (rng.next_f64().sqrt(), rng.next_f64());
            let (b1, b2) = (r1 * (1.0 - r2), r1 * r2);
            let [a, b, c] = triangles[triangle].map(|i| vertex(mesh, i));
            let b0 = 1.0 - b1 - b2;
            let position = [0, 1, 2].map(|k| b0 * a[k] + b1 * b[k] + b2 * c[k]);
            Candidate {
                triangle,
                b1,
                b2,
                position,
                priority: rng.next_u64(),
            }
        })
        .collect();
    // One candidate per occupied cell of size h: the lowest priority.
    let stratify = |h: f64| -> HashMap<[i64; 3], usize> {
        let mut cells: HashMap<[i64; 3], usize> = HashMap::new();
        for (i, c) in candidates.iter().enumerate() {
            let key = c.position.map(|x| (x / h).floor() as i64);
            let keep = cells.get(&key).is_none_or(|j| candidates[*j].priority > c.priority);
            if keep {
                cells.insert(key, i);
            }
        }
        cells
    };
    let base = (total / count as f64).sqrt();
    // Occupied cells fall as the cells grow: bisect the scale of h for the
    // count closest to the wanted one.
    let (mut lo, mut hi) = (0.25f64, 4.0f64);
    let mut best = (usize::MAX, base);
    for _ in 0..SEARCH_STEPS {
        let mid = (lo * hi).sqrt();
        let n = stratify(base * mid).len();
        if n.abs_diff(count) < best.0 {
            best = (n.abs_diff(count), base * mid);
        }
        if n > count {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let h = best.1;
    let mut kept: Vec<usize> = stratify(h).into_values().collect();
    // Never more than asked for: past the count, the cells whose candidates
    // have the lowest priorities (a random subset of the cells) stay.
    if kept.len() > count {
        kept.sort_unstable_by_key(|i| candidates[*i].priority);
        kept.truncate(count);
    }
    // Cells come out of the map in no fixed order: order by candidate.
    kept.sort_unstable();
    Samples {
        samples: kept
            .into_iter()
            .map(|i| {
                let c = &candidates[i];
                Sample {
                    triangle: triangles[c.triangle],
                    b1: c.b1 as f32,
                    b2: c.b2 as f32,
                }
            })
            .collect(),
        spacing: h as f32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square in z = 0 split into `n × n` quads (2n² triangles).
    fn square(n: u32) -> Mesh {
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                positions.push([i as f32 / n as f32, j as f32 / n as f32, 0.0]);
            }
        }
        let mut indices = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let a = j * (n + 1) + i;
                indices.extend_from_slice(&[a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]);
            }
        }
        Mesh {
            normals: vec![[0.0, 0.0, 1.0]; positions.len()],
            positions,
            uvs: None,
            tangents: None,
            indices,
            source: "square".into(),
            parts: None,
        }
    }

    fn position(mesh: &Mesh, s: &Sample) -> [f64; 3] {
        let [a, b, c] = s.triangle.map(|i| vertex(mesh, i));
        let (b1, b2) = (s.b1 as f64, s.b2 as f64);
        [0, 1, 2].map(|k| (1.0 - b1 - b2) * a[k] + b1 * b[k] + b2 * c[k])
    }

    #[test]
    fn the_same_seed_gives_the_same_samples_and_another_seed_others() {
        let m = square(4);
        assert_eq!(stratified(&m, 300, 1), stratified(&m, 300, 1));
        assert_ne!(stratified(&m, 300, 1).samples, stratified(&m, 300, 2).samples);
    }

    #[test]
    fn about_the_wanted_count_on_the_surface() {
        let m = square(3);
        for count in [10, 100, 400, 2000] {
            let s = stratified(&m, count, 7);
            let n = s.samples.len();
            assert!(
                n <= count && n.abs_diff(count) * 10 <= count.max(10),
                "{n} samples for {count}"
            );
            for x in &s.samples {
                assert!(x.b1 >= 0.0 && x.b2 >= 0.0 && x.b1 + x.b2 <= 1.0 + 1e-6, "{x:?}");
            }
            // Each sample stands for about spacing² of the unit area.
            let covered = n as f64 * (s.spacing as f64).powi(2);
            assert!((0.5..2.0).contains(&covered), "{n} × {}² = {covered}", s.spacing);
        }
    }

    /// Even coverage whatever the triangulation: 2 or 2048 triangles give
    /// the same share of samples in every 4 × 4 block of the square.
    #[test]
    fn coverage_does_not_depend_on_the_triangulation() {
        for n in [1, 32] {
            let m = square(n);
            let s = stratified(&m, 800, 3);
            let mut blocks = [0usize; 16];
            for x in &s.samples {
                let p = position(&m, x);
                let (i, j) = (((p[0] * 4.0) as usize).min(3), ((p[1] * 4.0) as usize).min(3));
                blocks[j * 4 + i] += 1;
            }
            let mean = s.samples.len() as f64 / 16.0;
            for (b, k) in blocks.iter().enumerate() {
                assert!(
                    (*k as f64 - mean).abs() <= 0.3 * mean,
                    "{n}×{n} quads: block {b} has {k} samples, mean {mean}: {blocks:?}"
                );
            }
        }
    }

    #[test]
    fn one_sample_when_one_is_asked_for() {
        assert_eq!(stratified(&square(2), 1, 9).samples.len(), 1);
    }

    #[test]
    fn no_area_no_samples() {
        let mut m = square(1);
        m.indices.clear();
        assert!(stratified(&m, 100, 1).samples.is_empty());
        let m = square(1);
        assert!(stratified(&m, 0, 1).samples.is_empty());
    }
}
