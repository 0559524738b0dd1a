//! Quantitative invisibility (Appel 1967; decision 0063): how many surfaces
//! lie between the eye and each point of a line, so that a line set can
//! draw the visible lines (QI 0), the hidden ones (QI ≥ 1), those behind
//! exactly n surfaces, or all of them, each piece with its own QI.
//!
//! The method: a ray cast per sample on the CPU in f64 through a bounding
//! volume hierarchy of the pass's triangles ([`Occluders`]), not Appel's
//! propagation along chains. Appel's method is faster (one ray per chain,
//! then QI changes only where the line passes behind a contour), but it
//! needs the contours' projected crossings found exactly and breaks down
//! wherever the propagation meets a degenerate crossing (a cusp, a vertex on
//! a contour); a miscounted crossing then corrupts the rest of the chain. A
//! ray per sample cannot propagate an error. Cost: each world-space segment
//! is sampled [`SAMPLES_PER_SEGMENT`] times plus every [`MAX_STEP_SHARE`] of
//! the surfaces' extent, one ray each (O(log triangles) with the hierarchy),
//! and where two neighbouring samples differ the change is found by
//! [`BISECTIONS`] more rays, so the boundary sits within 2⁻¹⁶ of the sample
//! spacing of the true one. A change between the last sample of one
//! segment and the first of the next is placed at their shared vertex
//! (within half a sample spacing).
//!
//! Counting: a triangle counts when the open segment from the eye to the
//! point crosses it, at a ray parameter under 1 − [`NEAR_POINT`] (the faces
//! the line lies on meet the ray at the point itself, parameter 1). Hits at
//! one parameter (a ray through an edge two triangles share) count once.

use glam::{DMat4, DVec3};

use super::edges::EdgeMesh;
use super::viewpoint::Viewpoint;

/// Samples per segment at least, whatever its length.
pub const SAMPLES_PER_SEGMENT: usize = 4;
/// The longest step between samples, as a share of the occluders' extent.
pub const MAX_STEP_SHARE: f64 = 1.0 / 256.0;
/// Bisection steps that place a change of QI between two samples.
pub const BISECTIONS: u32 = 16;
/// Ray parameters within this of 1 are the point's own surface.
pub const NEAR_POINT: f64 = 1e-7;
/// Hits whose parameters differ by less than this are one crossing.
const SAME_HIT: f64 = 1e-10;
const LEAF_TRIANGLES: usize = 4;

/// Which lines a set draws by their quantitative invisibility.
pub use npr_abi::lines::LineVisibility;

/// The triangles of every surface of a pass in world space, in a bounding
/// volume hierarchy (median split on the longest axis).
pub struct Occluders {
    triangles: Vec<[DVec3; 3]>,
    nodes: Vec<Node>,
    extent: f64,
}

struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: triangles `first..first + count`; inner: children `first`,
    /// `first + 1`... as indices into `nodes` (`count` 0).
    first: usize,
    count: usize,
    right: usize,
}

impl Occluders {
    /// The occluders of surfaces (an edge mesh and its model matrix each).
    pub fn new<'a>(surfaces: impl IntoIterator<Item = (&'a EdgeMesh, DMat4)>) -> Occluders {
        let mut triangles: Vec<[DVec3; 3]> = Vec::new();
        for (mesh, model) in surfaces {
            triangles.extend(
                mesh.faces
                    .iter()
                    .map(|f| f.map(|v| model.transform_point3(mesh.positions[v as usize]))),
            );
        }
        let mut occluders = Occluders {
            triangles,
            nodes: Vec::new(),
            extent: 0.0,
        };
        if !occluders.triangles.is_empty() {
            let n = occluders.triangles.len();
            occluders.build(0, n);
            let root = &occluders.nodes[0];
            occluders.extent = (root.hi - root.lo).max_element();
        }
        occluders
    }

    /// The largest side of the box around every triangle (0 when none).
    pub fn extent(&self) -> f64 {
        self.extent
    }

    fn build(&mut self, first: usize, end: usize) -> usize {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for t in &self.triangles[first..end] {
            for p in t {
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
        }
        let index = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            first,
            count: end - first,
            right: 0,
        });
        if end - first <= LEAF_TRIANGLES {
            return index;
        }
        let size = hi - lo;
        let axis = if size.x >= size.y && size.x >= size.z {
            0
        } else if size.y >= size.z {
            1
        } else {
            2
        };
        let centre = |t: &[DVec3; 3]| (t[0][axis] + t[1][axis] + t[2][axis]) / 3.0;
        let mid = (first + end) / 2;
        self.triangles[first..end].select_nth_unstable_by(mid - first, |a, b| centre(a).total_cmp(&centre(b)));
        let left = self.build(first, mid);
        let right = self.build(mid, end);
        self.nodes[index] = Node {
            lo,
            hi,
            first: left,
            count: 0,
            right,
        };
        index
    }

    /// The number of surfaces between `viewpoint` and `point` (see the
    /// module header for what counts). An orthographic viewpoint (a
    /// direction, decision 0062) is taken as a point that far along it
    /// from `point` which lies past every occluder.
    pub fn qi(&self, viewpoint: impl Into<Viewpoint>, point: DVec3) -> u32 {
        let viewpoint = viewpoint.into();
        if self.nodes.is_empty() {
            return 0;
        }
        let eye = if viewpoint.0.w != 0.0 {
            viewpoint.0.truncate() / viewpoint.0.w
        } else {
            let root = &self.nodes[0];
            let reach = (point - root.lo).abs().max((point - root.hi).abs()).length() + 1.0;
            point + viewpoint.0.truncate().normalize() * reach
        };
        let direction = point - eye;
        let inverse = direction.recip();
        let mut hits: Vec<f64> = Vec::new();
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if !segment_meets_box(eye, inverse, node.lo, node.hi) {
                continue;
            }
            if node.count == 0 {
                stack.push(node.first);
                stack.push(node.right);
                continue;
            }
            for t in &self.triangles[node.first..node.first + node.count] {
                if let Some(at) = crossing(eye, direction, t) {
                    if at > 0.0 && at < 1.0 - NEAR_POINT {
                        hits.push(at);
                    }
                }
            }
        }
        hits.sort_by(f64::total_cmp);
        hits.dedup_by(|a, b| (*a - *b).abs() < SAME_HIT);
        hits.len() as u32
    }

    /// `polyline` (world space, closed or not) cut into runs of one QI seen
    /// from `eye`: each run's points and QI, in order along the line. A
    /// closed line of one QI all round is one closed run.
    pub fn runs(&self, points: &[DVec3], closed: bool, eye: impl Into<Viewpoint>) -> Vec<(Vec<DVec3>, bool, u32)> {
        let eye = eye.into();
        if points.len() < 2 {
            return Vec::new();
        }
        let mut segments: Vec<(DVec3, DVec3)> = points.windows(2).map(|w| (w[0], w[1])).collect();
        if closed {
            segments.push((points[points.len() - 1], points[0]));
        }
        let step = (self.extent * MAX_STEP_SHARE).max(f64::MIN_POSITIVE);
        // Runs as (points, qi); a new run starts where the QI changes.
        let mut runs: Vec<(Vec<DVec3>, u32)> = Vec::new();
        for (a, b) in segments {
            let samples = SAMPLES_PER_SEGMENT
                .max(((b - a).length() / step).ceil() as usize)
                .min(1 << 16);
            // Sample centres, so no sample sits on a vertex (where the
            // line's own faces meet the ray edge-on).
            let at = |u: f64| a + (b - a) * u;
            let mut previous: Option<(f64, u32)> = None;
            for k in 0..samples {
                let u = (k as f64 + 0.5) / samples as f64;
                let qi = self.qi(eye, at(u));
                match (previous, runs.last_mut()) {
                    (None, Some((run, last))) if *last == qi => {
                        run.push(a);
                    }
                    (None, _) => {
                        if let Some((run, _)) = runs.last_mut() {
                            run.push(a);
                        }
                        runs.push((vec![a], qi));
                    }
                    (Some((_, q)), _) if q == qi => {}
                    (Some((u0, q)), _) => {
                        let change = at(self.change(eye, &at, u0, q, u));
                        if let Some((run, _)) = runs.last_mut() {
                            run.push(change);
                        }
                        runs.push((vec![change], qi));
                    }
                }
                previous = Some((u, qi));
            }
            if let Some((run, _)) = runs.last_mut() {
                run.push(b);
            }
        }
        // Consecutive points can repeat where a segment's start joined the
        // run before; keep one.
        for (run, _) in &mut runs {
            run.dedup();
        }
        let whole_loop = closed && runs.len() == 1;
        if closed && runs.len() > 1 && runs[0].1 == runs[runs.len() - 1].1 {
            // The run across the loop's start is one run.
            let (first, _) = runs.remove(0);
            let last = runs.last_mut().map(|(run, _)| run);
            if let Some(last) = last {
                last.extend(first.into_iter().skip(1));
            }
        }
        runs.into_iter()
            .filter(|(run, _)| run.len() >= 2)
            .map(|(mut run, qi)| {
                if whole_loop {
                    run.pop(); // the closing point repeats the first
                }
                (run, whole_loop, qi)
            })
            .collect()
    }

    /// Where along `at` between `u0` (QI `q0`) and `u1` the QI changes, by
    /// bisection.
    fn change(&self, eye: Viewpoint, at: &impl Fn(f64) -> DVec3, mut u0: f64, q0: u32, mut u1: f64) -> f64 {
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (u0 + u1);
            if self.qi(eye, at(mid)) == q0 {
                u0 = mid;
            } else {
                u1 = mid;
            }
        }
        0.5 * (u0 + u1)
    }
}

/// Whether the segment `origin + t·direction`, t in 0..1, meets the box
/// (slab test; `inverse` is 1 / direction).
fn segment_meets_box(origin: DVec3, inverse: DVec3, lo: DVec3, hi: DVec3) -> bool {
    let (mut near, mut far) = (0.0f64, 1.0f64);
    for axis in 0..3 {
        let (o, inv) = (origin[axis], inverse[axis]);
        if inv.is_infinite() {
            if o < lo[axis] || o > hi[axis] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[axis] - o) * inv, (hi[axis] - o) * inv);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
        if near > far {
            return false;
        }
    }
    true
}

/// The ray parameter where `origin + t·direction` crosses triangle `t`
/// (Möller and Trumbore 1997), or `None` when it misses it or runs in its
/// plane. Hits on the triangle's border count.
fn crossing(origin: DVec3, direction: DVec3, t: &[DVec3; 3]) -> Option<f64> {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = direction.cross(e2);
    let det = e1.dot(p);
    let scale = e1.length() * e2.length() * direction.length();
    if det.abs() <= 1e-12 * scale {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - t[0];
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = direction.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    Some(e2.dot(q) * inv)
}
