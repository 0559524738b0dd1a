//! Intersection lines (decision 0056): where the surfaces of a `lines` set
//! pass through each other, in world space, in f64 on the CPU. They are not
//! mesh edges, so they are found from the triangles themselves:
//!
//! 1. every welded face is placed in world space by its object's model;
//! 2. a uniform grid over the faces' bounding boxes (cell = the mean face
//!    extent) gives the candidate pairs: faces of two different surfaces,
//!    or of one surface when they share no welded vertex (a
//!    self-intersection: neighbours meet along their shared edge or corner,
//!    which is no intersection line);
//! 3. each pair's segment is the classic triangle–triangle test (Möller
//!    1997): each triangle cut by the other's plane gives a segment on the
//!    planes' common line, and their overlap along that line is the
//!    intersection. Coplanar pairs give no line (their overlap is an area,
//!    not a curve: Freestyle and Blender's Line Art skip them too);
//! 4. the segments' ends are welded by position and chained ([`chain`]) so
//!    a sphere through a plane gives one closed loop.
//!
//! Cost: O(faces + candidate pairs). The lines depend only on the
//! placements, but they are found again with every rebuild of the set's
//! strips (`sets::build`, on a change of view): keeping them per placement
//! is not done yet.

use std::collections::HashMap;

use glam::{DMat4, DVec3};

use super::edges::{chain, EdgeMesh};

/// One surface as the intersection finder sees it.
pub struct PlacedMesh<'a> {
    pub edges: &'a EdgeMesh,
    pub model: DMat4,
}

/// Relative size (of the scene's extent) under which a distance is zero:
/// as `edges::WELD_RELATIVE`, f32 input carries ~1e-7 relative error.
const ZERO_RELATIVE: f64 = 1e-9;
/// Segment ends closer than this share of the extent are one point.
const WELD_RELATIVE: f64 = 1e-7;
/// The most cells a face may span in the grid, so one huge face among
/// small ones cannot make the grid walk quadratic.
const MAX_CELLS_PER_FACE: i64 = 4096;

/// The world-space polylines (closed or not) where `surfaces` meet each
/// other or themselves.
pub fn intersection_lines(surfaces: &[PlacedMesh<'_>]) -> Vec<(Vec<DVec3>, bool)> {
    let (segments, tolerance) = intersection_segments(surfaces);
    weld_and_chain(&segments, tolerance)
}

/// The segments where `surfaces` meet each other or themselves, one per
/// crossing triangle pair, and the distance under which two segment ends
/// are one point (for [`weld_and_chain`]).
pub fn intersection_segments(surfaces: &[PlacedMesh<'_>]) -> (Vec<(DVec3, DVec3)>, f64) {
    let mut triangles: Vec<[DVec3; 3]> = Vec::new();
    // (surface, welded vertex ids) per triangle, for the adjacency rule.
    let mut owners: Vec<(usize, [u32; 3])> = Vec::new();
    for (s, surface) in surfaces.iter().enumerate() {
        let world: Vec<DVec3> = surface
            .edges
            .positions
            .iter()
            .map(|&p| surface.model.transform_point3(p))
            .collect();
        if world.iter().any(|p| !p.is_finite()) {
            continue;
        }
        for face in &surface.edges.faces {
            triangles.push(face.map(|v| world[v as usize]));
            owners.push((s, *face));
        }
    }
    if triangles.len() < 2 {
        return (Vec::new(), 0.0);
    }
    let (lo, hi) = triangles
        .iter()
        .flatten()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let mean_face = triangles
        .iter()
        .map(|t| (t[0].max(t[1]).max(t[2]) - t[0].min(t[1]).min(t[2])).max_element())
        .sum::<f64>()
        / triangles.len() as f64;
    let cell = mean_face.max(extent * 1e-6);
    let cell_of = |p: DVec3| ((p - lo) / cell).floor().as_i64vec3();
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut huge: Vec<u32> = Vec::new();
    for (i, t) in triangles.iter().enumerate() {
        let (a, b) = (cell_of(t[0].min(t[1]).min(t[2])), cell_of(t[0].max(t[1]).max(t[2])));
        let span = (b - a + 1).as_dvec3();
        if span.x * span.y * span.z > MAX_CELLS_PER_FACE as f64 {
            // A face far larger than the mean (a ground plane of two
            // triangles under a fine mesh) is tested against every face.
            huge.push(i as u32);
            continue;
        }
        for x in a.x..=b.x {
            for y in a.y..=b.y {
                for z in a.z..=b.z {
                    grid.entry([x, y, z]).or_default().push(i as u32);
                }
            }
        }
    }
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for bucket in grid.values() {
        for (k, &i) in bucket.iter().enumerate() {
            for &j in &bucket[k + 1..] {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    for &h in &huge {
        for j in 0..triangles.len() as u32 {
            if j != h {
                pairs.push((h.min(j), h.max(j)));
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let zero = extent * ZERO_RELATIVE;
    let mut segments: Vec<(DVec3, DVec3)> = Vec::new();
    for (i, j) in pairs {
        let ((si, vi), (sj, vj)) = (owners[i as usize], owners[j as usize]);
        if si == sj && vi.iter().any(|v| vj.contains(v)) {
            continue; // neighbours on one surface
        }
        if let Some(segment) = triangle_pair_segment(&triangles[i as usize], &triangles[j as usize], zero) {
            segments.push(segment);
        }
    }
    (segments, extent * WELD_RELATIVE)
}

/// The segment where triangles `t` and `u` meet, `None` when they do not
/// cross (or only touch at a point, or are coplanar). `zero`: the distance
/// under which a vertex is on the other's plane.
pub fn triangle_pair_segment(t: &[DVec3; 3], u: &[DVec3; 3], zero: f64) -> Option<(DVec3, DVec3)> {
    let nt = (t[1] - t[0]).cross(t[2] - t[0]);
    let nu = (u[1] - u[0]).cross(u[2] - u[0]);
    let (nt, nu) = (nt.try_normalize()?, nu.try_normalize()?);
    let snap = |d: f64| if d.abs() <= zero { 0.0 } else { d };
    let du = u.map(|p| snap(nt.dot(p - t[0])));
    let dt = t.map(|p| snap(nu.dot(p - u[0])));
    let one_side = |d: &[f64; 3]| d.iter().all(|&x| x > 0.0) || d.iter().all(|&x| x < 0.0);
    if one_side(&du) || one_side(&dt) || du.iter().all(|&x| x == 0.0) {
        return None;
    }
    let direction = nt.cross(nu).try_normalize()?;
    let (a0, a1) = plane_cut(t, &dt, direction)?;
    let (b0, b1) = plane_cut(u, &du, direction)?;
    // The overlap of the two intervals along the common line.
    let start = if a0.0 >= b0.0 { a0 } else { b0 };
    let stop = if a1.0 <= b1.0 { a1 } else { b1 };
    if stop.0 - start.0 <= zero {
        return None;
    }
    Some((start.1, stop.1))
}

/// The points of triangle `t` on the other's plane (signed distances `d`),
/// as (position along `direction`, point), lowest and highest.
fn plane_cut(t: &[DVec3; 3], d: &[f64; 3], direction: DVec3) -> Option<((f64, DVec3), (f64, DVec3))> {
    let mut points: Vec<DVec3> = Vec::with_capacity(3);
    for i in 0..3 {
        let j = (i + 1) % 3;
        if d[i] == 0.0 {
            points.push(t[i]);
        }
        if d[i] * d[j] < 0.0 {
            points.push(t[i] + (t[j] - t[i]) * (d[i] / (d[i] - d[j])));
        }
    }
    let along = |p: DVec3| (direction.dot(p), p);
    let first = along(*points.first()?);
    Some(points.iter().map(|&p| along(p)).fold((first, first), |(lo, hi), x| {
        (if x.0 < lo.0 { x } else { lo }, if x.0 > hi.0 { x } else { hi })
    }))
}

/// Segments joined at shared ends (welded within `tolerance`) into
/// polylines.
pub fn weld_and_chain(segments: &[(DVec3, DVec3)], tolerance: f64) -> Vec<(Vec<DVec3>, bool)> {
    let tolerance = tolerance.max(f64::MIN_POSITIVE);
    let mut points: Vec<DVec3> = Vec::new();
    let mut by_cell: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut id = |p: DVec3| -> u32 {
        let key = (p / tolerance).floor().as_i64vec3();
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let near = [key.x + dx, key.y + dy, key.z + dz];
                    if let Some(found) = by_cell.get(&near) {
                        if let Some(&v) = found.iter().find(|&&v| (points[v as usize] - p).length() <= tolerance) {
                            return v;
                        }
                    }
                }
            }
        }
        points.push(p);
        let v = (points.len() - 1) as u32;
        by_cell.entry(key.to_array()).or_default().push(v);
        v
    };
    let mut pairs: Vec<(u32, u32)> = segments.iter().map(|&(a, b)| (id(a), id(b))).collect();
    // A segment found twice (a pair of faces on a shared edge of a third
    // surface's cut) is one line.
    for p in &mut pairs {
        *p = (p.0.min(p.1), p.0.max(p.1));
    }
    pairs.sort_unstable();
    pairs.dedup();
    chain(&pairs)
        .into_iter()
        .map(|line| (line.vertices.iter().map(|&v| points[v as usize]).collect(), line.closed))
        .collect()
}
