//! Derived vertex attributes: smooth normals and UV tangent frames.
//!
//! Every function here is total: out-of-range indices, zero-area triangles,
//! degenerate UVs and NaNs in the input never panic and never produce NaN
//! output. Loaders call them before [`super::Mesh::validate`], so they cannot
//! assume valid input.

use glam::{Vec2, Vec3};
use std::collections::HashMap;

/// Area-weighted smooth vertex normals.
///
/// Vertices at the same position share one normal even when they are separate
/// vertices (an OBJ with `vt` is split along its UV seams by single indexing):
/// otherwise the seams would show up as false creases in shading and in
/// normal-based contour detection. Zero-area triangles are skipped; a vertex
/// that touches no usable triangle gets +Y.
pub fn smooth_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let (group_of_vertex, group_count) = weld_by_position(positions);
    let mut group_sums = vec![Vec3::ZERO; group_count];
    for_each_triangle(positions, indices, |corners, p| {
        // The cross product's length is twice the area: this is the weighting.
        let face = (p[1] - p[0]).cross(p[2] - p[0]);
        if face.length_squared() > 0.0 && face.is_finite() {
            for &vertex in &corners {
                group_sums[group_of_vertex[vertex]] += face;
            }
        }
    });
    group_of_vertex
        .iter()
        .map(|&group| group_sums[group].try_normalize().unwrap_or(Vec3::Y).to_array())
        .collect()
}

/// Normals split at creases, for CAD meshes with sharp edges (fandisk):
/// each triangle corner gets the area-weighted sum of the face normals of
/// the triangles around its vertex (welded by position, as in
/// [`smooth_normals`]) that lie within `crease_deg` of its own face normal,
/// so faces meeting at a sharper angle keep separate normals, while a
/// smooth surface tessellated finer than `crease_deg` stays smooth.
///
/// Returns new arrays: a vertex is duplicated once per distinct normal its
/// corners get (`source[i]` is the input vertex the new vertex `i` copies,
/// for its other attributes), and the new indices. Corners of zero-area
/// triangles keep the vertex's smooth normal.
pub fn crease_normals(positions: &[[f32; 3]], indices: &[u32], crease_deg: f32) -> CreaseSplit {
    let (group_of_vertex, group_count) = weld_by_position(positions);
    let smooth = smooth_normals(positions, indices);
    // Each triangle's area-weighted normal, and the triangles around each group.
    let mut faces: Vec<([usize; 3], Vec3)> = Vec::with_capacity(indices.len() / 3);
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); group_count];
    for_each_triangle(positions, indices, |corners, p| {
        let face = (p[1] - p[0]).cross(p[2] - p[0]);
        let face = if face.is_finite() { face } else { Vec3::ZERO };
        for &vertex in &corners {
            around[group_of_vertex[vertex]].push(faces.len());
        }
        faces.push((corners, face));
    });
    let cos_limit = crease_deg.to_radians().cos();
    let mut vertex_of: HashMap<(usize, [u32; 3]), u32> = HashMap::new();
    let mut split = CreaseSplit::default();
    for &(corners, face) in &faces {
        let unit = face.try_normalize();
        for vertex in corners {
            let normal = match unit {
                Some(own) => around[group_of_vertex[vertex]]
                    .iter()
                    .map(|&t| faces[t].1)
                    .filter(|other| other.try_normalize().is_some_and(|o| o.dot(own) >= cos_limit))
                    .sum::<Vec3>()
                    .try_normalize()
                    .unwrap_or(own),
                None => Vec3::from_array(smooth[vertex]),
            };
            let key = (vertex, normal.to_array().map(f32::to_bits));
            let next = split.source.len() as u32;
            let index = *vertex_of.entry(key).or_insert_with(|| {
                split.positions.push(positions[vertex]);
                split.normals.push(normal.to_array());
                split.source.push(vertex);
                next
            });
            split.indices.push(index);
        }
    }
    split
}

/// The result of [`crease_normals`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CreaseSplit {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    /// For each new vertex, the input vertex it was copied from.
    pub source: Vec<usize>,
    pub indices: Vec<u32>,
}

/// Normals read from a file, made unit length. Zero or non-finite ones (and
/// the whole array if its length is wrong) are replaced by smooth normals.
pub fn repair_normals(positions: &[[f32; 3]], indices: &[u32], given: Vec<[f32; 3]>) -> Vec<[f32; 3]> {
    if given.len() != positions.len() {
        return smooth_normals(positions, indices);
    }
    let mut smooth: Option<Vec<[f32; 3]>> = None;
    given
        .iter()
        .enumerate()
        .map(|(vertex, n)| match Vec3::from_array(*n).try_normalize() {
            Some(unit) => unit.to_array(),
            None => smooth.get_or_insert_with(|| smooth_normals(positions, indices))[vertex],
        })
        .collect()
}

/// Per-vertex tangents from UVs: each triangle's dP/du and dP/dv, normalized
/// and weighted by triangle area, summed per vertex, then Gram-Schmidt
/// orthogonalized against the normal. `w` is the handedness (±1) such that
/// `w · cross(n, t)` points along -v, towards the top of the image (the glTF
/// convention, so glTF tangents pass through unchanged and normal maps with
/// "green up" work). Triangles with degenerate UVs add
/// nothing; a vertex left without a usable direction gets an arbitrary unit
/// vector orthogonal to its normal.
pub fn uv_tangents(positions: &[[f32; 3]], normals: &[[f32; 3]], uvs: &[[f32; 2]], indices: &[u32]) -> Vec<[f32; 4]> {
    let mut along_u = vec![Vec3::ZERO; positions.len()];
    let mut towards_image_top = vec![Vec3::ZERO; positions.len()];
    for_each_triangle(positions, indices, |corners, p| {
        let Some(uv) = corner_uvs(uvs, corners) else {
            return;
        };
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let (d1, d2) = (uv[1] - uv[0], uv[2] - uv[0]);
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() <= f32::EPSILON * 1e-3 || !det.is_finite() {
            return;
        }
        let area = 0.5 * e1.cross(e2).length();
        let dp_du = ((e1 * d2.y - e2 * d1.y) / det).normalize_or_zero() * area;
        let dp_dv = ((e2 * d1.x - e1 * d2.x) / det).normalize_or_zero() * area;
        if !(dp_du.is_finite() && dp_dv.is_finite()) {
            return;
        }
        for &vertex in &corners {
            along_u[vertex] += dp_du;
            towards_image_top[vertex] -= dp_dv;
        }
    });
    (0..positions.len())
        .map(|vertex| {
            let normal = normal_at(normals, vertex);
            orthonormal_tangent(normal, along_u[vertex], towards_image_top[vertex])
        })
        .collect()
}

/// Tangents read from a file, orthogonalized against the (possibly repaired)
/// normals, with `w` snapped to ±1.
pub fn repair_tangents(normals: &[[f32; 3]], given: Vec<[f32; 4]>) -> Vec<[f32; 4]> {
    given
        .iter()
        .enumerate()
        .map(|(vertex, t)| {
            let normal = normal_at(normals, vertex);
            let tangent = Vec3::new(t[0], t[1], t[2]);
            let handedness = if t[3] < 0.0 { -1.0 } else { 1.0 };
            // The image-top direction the stored handedness implies, so that
            // `orthonormal_tangent` keeps it.
            let image_top = normal.cross(tangent) * handedness;
            orthonormal_tangent(normal, tangent, image_top)
        })
        .collect()
}

/// Any unit vector orthogonal to `normal` (which must be unit length).
pub fn any_orthogonal(normal: Vec3) -> Vec3 {
    // Project out the normal from the axis least aligned with it: always far
    // from parallel, so the result is well conditioned.
    let axis = if normal.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    (axis - normal * normal.dot(axis)).try_normalize().unwrap_or(Vec3::Z)
}

/// Gram-Schmidt: `direction` made orthogonal to `normal` and unit length,
/// with the handedness that makes `w · cross(n, t)` agree with `image_top`
/// (the direction of decreasing v).
pub fn orthonormal_tangent(normal: Vec3, direction: Vec3, image_top: Vec3) -> [f32; 4] {
    let tangent = (direction - normal * normal.dot(direction))
        .try_normalize()
        .unwrap_or_else(|| any_orthogonal(normal));
    let handedness = if normal.cross(tangent).dot(image_top) < 0.0 {
        -1.0
    } else {
        1.0
    };
    [tangent.x, tangent.y, tangent.z, handedness]
}

fn normal_at(normals: &[[f32; 3]], vertex: usize) -> Vec3 {
    normals
        .get(vertex)
        .and_then(|n| Vec3::from_array(*n).try_normalize())
        .unwrap_or(Vec3::Y)
}

fn corner_uvs(uvs: &[[f32; 2]], corners: [usize; 3]) -> Option<[Vec2; 3]> {
    let uv = |vertex: usize| uvs.get(vertex).map(|c| Vec2::from_array(*c));
    Some([uv(corners[0])?, uv(corners[1])?, uv(corners[2])?])
}

/// Calls `visit` with the vertex indices and positions of every triangle
/// whose indices are all in range (others are skipped, not a panic).
fn for_each_triangle(positions: &[[f32; 3]], indices: &[u32], mut visit: impl FnMut([usize; 3], [Vec3; 3])) {
    for triangle in indices.chunks_exact(3) {
        let corners = [triangle[0] as usize, triangle[1] as usize, triangle[2] as usize];
        let position = |vertex: usize| positions.get(vertex).map(|p| Vec3::from_array(*p));
        if let (Some(a), Some(b), Some(c)) = (position(corners[0]), position(corners[1]), position(corners[2])) {
            visit(corners, [a, b, c]);
        }
    }
}

/// Groups vertices with bit-identical positions; returns each vertex's group
/// and the number of groups.
fn weld_by_position(positions: &[[f32; 3]]) -> (Vec<usize>, usize) {
    let mut group_of_position: HashMap<[u32; 3], usize> = HashMap::with_capacity(positions.len());
    let group_of_vertex = positions
        .iter()
        .map(|p| {
            // `+ 0.0` turns -0.0 into 0.0 so the two weld together.
            let key = [(p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits(), (p[2] + 0.0).to_bits()];
            let next = group_of_position.len();
            *group_of_position.entry(key).or_insert(next)
        })
        .collect();
    (group_of_vertex, group_of_position.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_unit(v: [f32; 3]) {
        let len = Vec3::from_array(v).length();
        assert!((len - 1.0).abs() < 1e-5, "length {len} of {v:?}");
    }

    #[test]
    fn crease_normals_split_a_cube_corner_and_keep_a_shallow_fold_smooth() {
        // Two triangles folded 90° along the x axis (sharing vertices 0, 1).
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let indices = [0, 1, 2, 1, 0, 3];
        let sharp = crease_normals(&positions, &indices, 30.0);
        // The shared edge's vertices are duplicated: 6 vertices, each with its face's normal.
        assert_eq!(sharp.positions.len(), 6);
        assert_eq!(&sharp.normals[..3], &[[0.0, 0.0, 1.0]; 3]);
        assert_eq!(&sharp.normals[3..], &[[0.0, 1.0, 0.0]; 3]);
        assert_eq!(sharp.source, vec![0, 1, 2, 1, 0, 3]);
        // Above the fold angle it is the smooth mesh again: 4 vertices and
        // the shared ones averaged.
        let smooth = crease_normals(&positions, &indices, 100.0);
        assert_eq!(smooth.positions.len(), 4);
        let diagonal = Vec3::new(0.0, 1.0, 1.0).normalize().to_array();
        assert_eq!(smooth.normals[0], diagonal);
        assert_eq!(smooth.normals, {
            let n = smooth_normals(&positions, &indices);
            smooth.source.iter().map(|&v| n[v]).collect::<Vec<_>>()
        });
    }

    #[test]
    fn smooth_normals_of_a_ccw_triangle_point_up_the_right_hand_rule() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let normals = smooth_normals(&positions, &[0, 1, 2]);
        for n in normals {
            assert_eq!(n, [0.0, 0.0, 1.0]);
        }
    }

    #[test]
    fn degenerate_and_isolated_vertices_get_plus_y_not_nan() {
        // Triangle 0-1-2 has zero area; vertex 3 is used by nothing.
        let positions = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [5.0, 5.0, 5.0]];
        let normals = smooth_normals(&positions, &[0, 1, 2]);
        assert!(normals.iter().all(|n| *n == [0.0, 1.0, 0.0]));
    }

    #[test]
    fn out_of_range_indices_and_nan_positions_do_not_panic() {
        let positions = [[f32::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let normals = smooth_normals(&positions, &[0, 1, 2, 7, 8, 9, 1]);
        assert!(normals.iter().flatten().all(|c| c.is_finite()));
        let tangents = uv_tangents(&positions, &normals, &[[0.0, 0.0]], &[0, 1, 2]);
        assert!(tangents.iter().flatten().all(|c| c.is_finite()));
    }

    #[test]
    fn coincident_vertices_share_a_normal_across_a_seam() {
        // Two triangles folded at the x axis, with the shared edge's vertices
        // duplicated (as a UV seam would split them).
        let positions = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let normals = smooth_normals(&positions, &[0, 1, 2, 3, 4, 5]);
        assert_eq!(normals[0], normals[4]);
        assert_eq!(normals[1], normals[3]);
        assert_ne!(normals[0], normals[2]);
    }

    #[test]
    fn tangents_follow_u_and_handedness_follows_the_image_top() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let normals = smooth_normals(&positions, &[0, 1, 2]);
        // u along +x, v down along -y (an unmirrored image): the image top is
        // +y = +cross(z, x), so w = +1.
        let tangents = uv_tangents(&positions, &normals, &[[0.0, 1.0], [1.0, 1.0], [0.0, 0.0]], &[0, 1, 2]);
        assert_eq!(tangents[0], [1.0, 0.0, 0.0, 1.0]);
        // v mirrored: handedness flips.
        let tangents = uv_tangents(&positions, &normals, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], &[0, 1, 2]);
        assert_eq!(tangents[0], [1.0, 0.0, 0.0, -1.0]);
    }

    #[test]
    fn degenerate_uvs_fall_back_to_a_vector_orthogonal_to_the_normal() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let normals = smooth_normals(&positions, &[0, 1, 2]);
        let tangents = uv_tangents(&positions, &normals, &[[0.5, 0.5]; 3], &[0, 1, 2]);
        for (t, n) in tangents.iter().zip(&normals) {
            let t3 = [t[0], t[1], t[2]];
            assert_unit(t3);
            assert!(Vec3::from_array(t3).dot(Vec3::from_array(*n)).abs() < 1e-6);
        }
    }

    #[test]
    fn any_orthogonal_is_unit_and_orthogonal_for_every_axis() {
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            -Vec3::X,
            Vec3::new(1.0, 1.0, 1.0).normalize(),
        ] {
            let t = any_orthogonal(n);
            assert_unit(t.to_array());
            assert!(t.dot(n).abs() < 1e-6);
        }
    }

    #[test]
    fn repaired_normals_are_unit_and_zero_ones_are_recomputed() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let normals = repair_normals(&positions, &[0, 1, 2], vec![[0.0, 0.0, 2.0], [0.0; 3], [f32::NAN; 3]]);
        assert_eq!(normals, vec![[0.0, 0.0, 1.0]; 3]);
    }
}
