//! Test meshes the patch tests share: an n × n grid of unit squares and
//! its split into a left and a right patch.

use super::Mesh;

/// An n × n grid of unit squares in the xy plane, two triangles each.
pub(crate) fn grid(n: u32) -> Mesh {
    let mut positions = Vec::new();
    for y in 0..=n {
        for x in 0..=n {
            positions.push([x as f32, y as f32, 0.0]);
        }
    }
    let at = |x: u32, y: u32| y * (n + 1) + x;
    let mut indices = Vec::new();
    for y in 0..n {
        for x in 0..n {
            indices.extend([
                at(x, y),
                at(x + 1, y),
                at(x + 1, y + 1),
                at(x, y),
                at(x + 1, y + 1),
                at(x, y + 1),
            ]);
        }
    }
    Mesh::from_parts(positions, None, None, None, indices, "grid".into())
}

/// The left half (x < n/2) is patch 0, the right half patch 1.
pub(crate) fn halves(mesh: &Mesh, n: u32) -> Vec<u32> {
    mesh.indices
        .chunks_exact(3)
        .map(|t| {
            let cx: f32 = t.iter().map(|&i| mesh.positions[i as usize][0]).sum::<f32>() / 3.0;
            u32::from(cx > n as f32 / 2.0)
        })
        .collect()
}
