// LSA contours, base method (Zaidi et al., eqs. 1–5): per direction of the
// half neighbourhood, the larger remapped e_curv of the two neighbours, each
// tested against the sphere fitted to p and the opposite neighbour. The four
// channels are the directions (1,0), (1,1), (0,1), (−1,1); their maximum is
// E(p) of eq. 1. The directions are written out, not looped: with constant
// offsets every texel address folds, and no driver has to unroll the loop.
fn npr_lsa_curv(pos: texture_2d<f32>, normals: texture_2d<f32>, uv: vec2<f32>, eta_min: f32, eta_max: f32, normal_encoding: i32) -> vec4<f32> {
    let px = npr_lsa_core__pixel(pos, uv);
    let p = npr_lsa_core__fetch(pos, normals, normal_encoding, px);
    return vec4<f32>(
        npr_lsa_core__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 0), eta_min, eta_max),
        npr_lsa_core__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 1), eta_min, eta_max),
        npr_lsa_core__direction(pos, normals, normal_encoding, px, p, vec2<i32>(0, 1), eta_min, eta_max),
        npr_lsa_core__direction(pos, normals, normal_encoding, px, p, vec2<i32>(-1, 1), eta_min, eta_max),
    );
}
