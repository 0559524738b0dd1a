// LSA contours, full monoscopic method (Zaidi et al. §3–4.1): e_sum
// (eq. 7) when `plane`, eq. 8 with the pixels two steps away when `aa`,
// both halves of each direction merged (e_max). With a constant false flag
// the compiler calls `lsa_sum`, `lsa_curv_aa` or `lsa_curv` instead, so
// the disabled code is not emitted.
fn npr_lsa(pos: texture_2d<f32>, normals: texture_2d<f32>, uv: vec2<f32>, plane: bool, aa: bool, eta_min: f32, eta_max: f32, normal_encoding: i32) -> vec4<f32> {
    let px = npr_lsa_core__pixel(pos, uv);
    let p = npr_lsa_core__fetch(pos, normals, normal_encoding, px);
    var out = vec4<f32>(0.0);
    for (var i = 0; i < 4; i = i + 1) {
        let m = npr_lsa_core__dir(i);
        let b = npr_lsa_core__fetch(pos, normals, normal_encoding, px - m);
        let d = npr_lsa_core__fetch(pos, normals, normal_encoding, px + m);
        // Both halves of the pair (e_max, §4.1): d tested against S(p, ·)
        // fitted to b, and b against the sphere fitted to d.
        var vd = max(npr_lsa_plane__error(b, p, d, 1.0, 1.0, plane, eta_min, eta_max), 0.0);
        var vb = max(npr_lsa_plane__error(d, p, b, 1.0, 1.0, plane, eta_min, eta_max), 0.0);
        if (aa) {
            // Eq. 8 with the pixels two steps away: for q = d, q̂ = f and the
            // control of S(p, q̂) is a; offsets over two steps are halved.
            let a = npr_lsa_core__fetch(pos, normals, normal_encoding, px - 2 * m);
            let f = npr_lsa_core__fetch(pos, normals, normal_encoding, px + 2 * m);
            vd = npr_lsa_aa__mix(npr_lsa_plane__error(b, p, f, 1.0, 0.5, plane, eta_min, eta_max), npr_lsa_plane__error(a, p, d, 0.5, 1.0, plane, eta_min, eta_max), vd);
            vb = npr_lsa_aa__mix(npr_lsa_plane__error(d, p, a, 1.0, 0.5, plane, eta_min, eta_max), npr_lsa_plane__error(f, p, b, 0.5, 1.0, plane, eta_min, eta_max), vb);
        }
        out[i] = max(vd, vb);
    }
    return out;
}
