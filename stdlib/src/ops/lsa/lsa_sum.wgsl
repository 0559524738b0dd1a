// LSA contours with the planarity extension: e_sum = e_curv + e_plane
// (eqs. 5–7) per neighbour, remapped; what `lsa` compiles to with aa = false.

// One direction m: b = p − m and d = p + m, each checked against the sphere
// fitted to p and the other (e_max, §4.1).
fn npr_lsa_sum__direction(pos: texture_2d<f32>, normals: texture_2d<f32>, encoding: i32, px: vec2<i32>, p: npr_lsa_core__Texel, m: vec2<i32>, plane: bool, lo: f32, hi: f32) -> f32 {
    let b = npr_lsa_core__fetch(pos, normals, encoding, px - m);
    let d = npr_lsa_core__fetch(pos, normals, encoding, px + m);
    let one = npr_lsa_plane__pair(b, d, p, 1.0, plane);
    let vd = npr_lsa_core__error(b, p, d, npr_lsa_core__kappa(b, p), npr_lsa_plane__term(plane, one.num_ahead, one.den_back), lo, hi);
    let vb = npr_lsa_core__error(d, p, b, npr_lsa_core__kappa(d, p), npr_lsa_plane__term(plane, one.num_back, one.den_ahead), lo, hi);
    return max(max(vd, vb), 0.0);
}

// The directions are written out (see `npr_lsa_curv`).
fn npr_lsa_sum(pos: texture_2d<f32>, normals: texture_2d<f32>, uv: vec2<f32>, plane: bool, eta_min: f32, eta_max: f32, normal_encoding: i32) -> vec4<f32> {
    let px = npr_lsa_core__pixel(pos, uv);
    let p = npr_lsa_core__fetch(pos, normals, normal_encoding, px);
    return vec4<f32>(
        npr_lsa_sum__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 0), plane, eta_min, eta_max),
        npr_lsa_sum__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 1), plane, eta_min, eta_max),
        npr_lsa_sum__direction(pos, normals, normal_encoding, px, p, vec2<i32>(0, 1), plane, eta_min, eta_max),
        npr_lsa_sum__direction(pos, normals, normal_encoding, px, p, vec2<i32>(-1, 1), plane, eta_min, eta_max),
    );
}
