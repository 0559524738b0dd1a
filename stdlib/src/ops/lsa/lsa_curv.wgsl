// LSA contours, base method (Zaidi et al., eqs. 1–5): per direction of the
// half neighbourhood, the larger remapped e_curv of the two neighbours, each
// tested against the sphere fitted to p and the opposite neighbour. The four
// channels are the directions (1,0), (1,1), (0,1), (−1,1); their maximum is
// E(p) of eq. 1.
fn npr_lsa_curv(pos: texture_2d<f32>, normals: texture_2d<f32>, uv: vec2<f32>, eta_min: f32, eta_max: f32, normal_encoding: i32) -> vec4<f32> {
    let px = npr_lsa_core__pixel(pos, uv);
    let p = npr_lsa_core__fetch(pos, normals, normal_encoding, px);
    var out = vec4<f32>(0.0);
    for (var i = 0; i < 4; i = i + 1) {
        let m = npr_lsa_core__dir(i);
        let b = npr_lsa_core__fetch(pos, normals, normal_encoding, px - m);
        let d = npr_lsa_core__fetch(pos, normals, normal_encoding, px + m);
        // Both halves of the pair (e_max, §4.1): d tested against S(p, ·)
        // fitted to b, and b against the sphere fitted to d.
        var vd = max(npr_lsa_core__error(b, p, d, 0.0, eta_min, eta_max), 0.0);
        var vb = max(npr_lsa_core__error(d, p, b, 0.0, eta_min, eta_max), 0.0);
        out[i] = max(vd, vb);
    }
    return out;
}
