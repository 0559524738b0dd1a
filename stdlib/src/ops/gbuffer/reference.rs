//! CPU f64 references of the G-buffer packing operators: the signed
//! octahedral encoding (Cigolle et al. 2014 §3.1), line by line in meaning
//! with `oct.wgsl` beside it, and the 16-bit float stores a target of
//! codes rounds through (to nearest, or truncating, as lavapipe does).

/// ±1, +1 at 0 (`npr_oct__sign_not_zero`).
fn sign_not_zero(v: f64) -> f64 {
    if v >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// `oct_encode`: the L1 projection onto the octahedron, the lower
/// hemisphere folded over the diagonals; e ∈ [−1, 1]².
pub fn oct_encode(n: [f64; 3]) -> [f64; 2] {
    let l1 = (n[0].abs() + n[1].abs() + n[2].abs()).max(1e-30);
    let p = [n[0] / l1, n[1] / l1];
    if n[2] < 0.0 {
        [
            (1.0 - p[1].abs()) * sign_not_zero(p[0]),
            (1.0 - p[0].abs()) * sign_not_zero(p[1]),
        ]
    } else {
        p
    }
}

/// `oct_decode`: the outer triangles unfolded, then normalized.
pub fn oct_decode(e: [f64; 2]) -> [f64; 3] {
    let z = 1.0 - e[0].abs() - e[1].abs();
    let xy = if z < 0.0 {
        [
            (1.0 - e[1].abs()) * sign_not_zero(e[0]),
            (1.0 - e[0].abs()) * sign_not_zero(e[1]),
        ]
    } else {
        e
    };
    let l = (xy[0] * xy[0] + xy[1] * xy[1] + z * z).sqrt();
    [xy[0] / l, xy[1] / l, z / l]
}
