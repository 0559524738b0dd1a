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
//! The search is what drawing costs (24 steps over 8 candidates a sample):
//! each step only counts the occupied cells, in a set reused across steps,
//! with small keys and a fast hash (`CellCounter`), and it stops at a step
//! that hits the count exactly, after which no step could change h.
//!
//! Every random number comes from a SplitMix64 stream of the seed, so the
//! samples are the same in every run. A sample is stored as its triangle
//! (the three vertex indices) and barycentric coordinates, as in the paper
//! and jot-lib, so it stays on the surface when the object moves or its
//! vertices are animated.

use super::Mesh;
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

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

/// Grid cells by their integer coordinates, hashed with [`CellHasher`].
type CellMap<V> = HashMap<[i64; 3], V, BuildHasherDefault<CellHasher>>;

/// FxHash (rustc's hasher: rotate, xor, multiply per word) for the cell
/// keys. The search hashes every candidate at every step, 8 × 24 times a
/// sample, where the default SipHash cost most of the time; the keys are
/// the mesh's own grid cells, not chosen by anyone to collide. Which cells
/// come out is the same with any hasher: only their count is used, and the
/// kept cells are ordered by candidate afterwards.
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }

    /// The words mixed so that every bit of every word reaches the low
    /// bits (SplitMix64's finalizer): the table picks a bucket by the low
    /// bits, and FxHash's last multiply leaves those depending on the low
    /// bits of the last word alone, so cells in one column shared buckets.
    fn finish(&self) -> u64 {
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// The grid cell of size `h` holding a candidate.
fn cell(c: &Candidate, h: f64) -> [i64; 3] {
    c.position.map(|x| (x / h).floor() as i64)
}

/// Counts the cells of size h that candidates occupy, for the search,
/// which needs only the count. Where the candidates span fewer than 2^21
/// cells along every axis (any mesh at the sizes the search tries, a
/// sample's cell being about √(area / count), short of a sliver a million
/// times longer than wide), each cell is one u64 of three 21-bit offsets
/// from the lowest cell; else its three i64 coordinates. The search spends
/// its time in the set's cache misses, and the packed key is a third the
/// size: 2× faster at 10⁵ samples. Both sets are reused across steps.
struct CellCounter {
    low: [f64; 3],
    high: [f64; 3],
    packed: HashSet<u64, BuildHasherDefault<CellHasher>>,
    wide: CellMap<()>,
}

/// Bits per axis of a packed cell key.
const PACKED_BITS: u32 = 21;

impl CellCounter {
    fn new(candidates: &[Candidate]) -> CellCounter {
        let (mut low, mut high) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for c in candidates {
            for k in 0..3 {
                low[k] = low[k].min(c.position[k]);
                high[k] = high[k].max(c.position[k]);
            }
        }
        CellCounter {
            low,
            high,
            packed: HashSet::with_capacity_and_hasher(candidates.len(), Default::default()),
            wide: CellMap::default(),
        }
    }

    /// Whether the candidates' cells of size `h` fit packed keys: floor(x/h)
    /// is monotone in x, so every cell lies between the bounds' cells.
    fn packs(&self, h: f64) -> bool {
        (0..3).all(|k| (self.high[k] / h).floor() - (self.low[k] / h).floor() < f64::from(1u32 << PACKED_BITS))
    }

    fn count(&mut self, candidates: &[Candidate], h: f64) -> usize {
        if self.packs(h) {
            self.count_packed(candidates, h)
        } else {
            self.count_wide(candidates, h)
        }
    }

    fn count_packed(&mut self, candidates: &[Candidate], h: f64) -> usize {
        let origin = self.low.map(|x| (x / h).floor() as i64);
        self.packed.clear();
        self.packed.extend(candidates.iter().map(|c| {
            let k = cell(c, h);
            (0..3).fold(0u64, |key, a| {
                key | ((k[a] - origin[a]) as u64) << (a as u32 * PACKED_BITS)
            })
        }));
        self.packed.len()
    }

    fn count_wide(&mut self, candidates: &[Candidate], h: f64) -> usize {
        self.wide.clear();
        self.wide.extend(candidates.iter().map(|c| (cell(c, h), ())));
        self.wide.len()
    }
}

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
    let stratify = |h: f64| -> CellMap<usize> {
        let mut cells: CellMap<usize> = CellMap::with_capacity_and_hasher(candidates.len(), Default::default());
        for (i, c) in candidates.iter().enumerate() {
            cells
                .entry(cell(c, h))
                .and_modify(|j| {
                    if candidates[*j].priority > c.priority {
                        *j = i;
                    }
                })
                .or_insert(i);
        }
        cells
    };
    let base = (total / count as f64).sqrt();
    // Occupied cells fall as the cells grow: bisect the scale of h for the
    // count closest to the wanted one.
    let mut counter = CellCounter::new(&candidates);
    let (mut lo, mut hi) = (0.25f64, 4.0f64);
    let mut best = (usize::MAX, base);
    for _ in 0..SEARCH_STEPS {
        let mid = (lo * hi).sqrt();
        let n = counter.count(&candidates, base * mid);
        if n.abs_diff(count) < best.0 {
            best = (n.abs_diff(count), base * mid);
        }
        if n == count {
            // No later step can come closer (`best` only takes a strictly
            // smaller difference), so they would not change h.
            break;
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
        kept.sort_unstable_by_key(|i| (candidates[*i].priority, *i));
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
            edge_marks: None,
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

    /// The samples as bits: triangle, barycentrics, spacing.
    fn digest(s: &Samples) -> String {
        let mut hasher = blake3::Hasher::new();
        for x in &s.samples {
            hasher.update(bytemuck::cast_slice(&x.triangle));
            hasher.update(&x.b1.to_bits().to_le_bytes());
            hasher.update(&x.b2.to_bits().to_le_bytes());
        }
        hasher.update(&s.spacing.to_bits().to_le_bytes());
        hasher.finalize().to_hex()[..16].to_string()
    }

    /// The samples are exactly those of the first implementation (a SipHash
    /// map per step and all 24 steps of the search, whose digests these
    /// are): the faster search (FxHash, one set reused, stopping at an exact
    /// count) changed the time, not the samples that every tracker style,
    /// test and benchmark draws.
    #[test]
    fn the_samples_are_those_of_the_first_implementation() {
        let sphere = crate::scene::primitives::sphere(0.4, 48, 24);
        let cases: [(&Mesh, usize, u64, &str); 6] = [
            (&sphere, 1, 1, "32b09363d1244370"),
            (&sphere, 100, 1, "ba9c975b6407fc20"),
            (&sphere, 1000, 7, "f72af83dc9f535cf"),
            (&sphere, 20_000, 3, "141de52d22e6b061"),
            (&square(3), 400, 9, "e86581e643736212"),
            (&square(32), 2000, 5, "54d9b5f9fc1d476c"),
        ];
        let got: Vec<String> = cases
            .iter()
            .map(|(m, n, seed, _)| digest(&stratified(m, *n, *seed)))
            .collect();
        for ((_, n, seed, want), got) in cases.iter().zip(&got) {
            assert_eq!(got, want, "{n} samples, seed {seed}");
        }
    }

    /// The search's cell counts, packed or wide, against a plain ordered
    /// set of the cells: from sizes where the points span a few cells, to
    /// past 2^21 cells along x (1e-6 over 3 units), where the packed keys
    /// would not fit and the wide set counts.
    #[test]
    fn the_cell_counts_are_the_number_of_distinct_cells() {
        let mut rng = Stream(5);
        let candidates: Vec<Candidate> = (0..4000)
            .map(|_| Candidate {
                triangle: 0,
                b1: 0.0,
                b2: 0.0,
                position: [
                    rng.next_f64() * 3.0 - 1.0,
                    rng.next_f64() * 0.5,
                    rng.next_f64() * 2.0 - 7.0,
                ],
                priority: rng.next_u64(),
            })
            .collect();
        let mut counter = CellCounter::new(&candidates);
        let mut paths = [0, 0];
        for h in [2.0, 1.0, 0.3, 0.1, 0.03, 0.01, 3e-3, 1e-4, 1e-6, 1e-9] {
            let cells: std::collections::BTreeSet<[i64; 3]> = candidates.iter().map(|c| cell(c, h)).collect();
            assert_eq!(counter.count(&candidates, h), cells.len(), "h = {h}");
            paths[usize::from(counter.packs(h))] += 1;
            if counter.packs(h) {
                assert_eq!(counter.count_wide(&candidates, h), cells.len(), "h = {h}");
            }
        }
        assert_eq!(paths, [2, 8], "1e-6 and 1e-9 do not pack");
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
