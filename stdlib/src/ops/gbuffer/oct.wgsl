// Octahedral unit-vector encoding (Cigolle et al. 2014, "A Survey of
// Efficient Representations for Independent Unit Vectors", JCGT 3(2):
// §3.1 and the float32x3_to_oct / oct_to_float32x3 listing). The signed
// variant: n is projected onto the octahedron |x| + |y| + |z| = 1 and the
// lower hemisphere (z < 0) is folded over the diagonals onto the outer
// triangles of the square, so e ∈ [−1, 1]². An `rg16float` target stores e
// as it is (no remap to [0, 1]): its spacing is 2^-11 at |e| ≥ ½ and finer
// towards 0; decoded, the round trip is within 0.06° (stores rounded to
// nearest) or 0.12° (truncated, as lavapipe does), measured in
// stdlib/tests/gpu_gbuffer.rs.

// ±1 per component, +1 at 0 (the paper's signNotZero): the folds at x = 0
// or y = 0 of the lower hemisphere must pick a side.
fn npr_oct__sign_not_zero(v: vec2<f32>) -> vec2<f32> {
    return select(vec2<f32>(-1.0), vec2<f32>(1.0), v >= vec2<f32>(0.0));
}

// n need not be unit length (the L1 projection divides it out); the zero
// vector encodes to (0, 0), which decodes to +z.
fn npr_oct__encode(n: vec3<f32>) -> vec2<f32> {
    let l1 = abs(n.x) + abs(n.y) + abs(n.z);
    let p = n.xy / max(l1, 1e-30);
    if (n.z < 0.0) {
        return (vec2<f32>(1.0) - abs(p.yx)) * npr_oct__sign_not_zero(p);
    }
    return p;
}

// The inverse: unfold the outer triangles (|e.x| + |e.y| > 1, i.e. z < 0),
// then normalize (the octahedron's point has L1 norm 1, not L2).
fn npr_oct__decode(e: vec2<f32>) -> vec3<f32> {
    let z = 1.0 - abs(e.x) - abs(e.y);
    var xy = e;
    if (z < 0.0) {
        xy = (vec2<f32>(1.0) - abs(e.yx)) * npr_oct__sign_not_zero(e);
    }
    return normalize(vec3<f32>(xy, z));
}
