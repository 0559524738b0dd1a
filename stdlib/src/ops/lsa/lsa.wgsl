// LSA contours, full monoscopic method (Zaidi et al. §3–4.1): e_sum
// (eq. 7) when `plane`, eq. 8 with the pixels two steps away when `aa`,
// both halves of each direction merged (e_max). With a constant false flag
// the compiler calls `lsa_sum`, `lsa_curv_aa` or `lsa_curv` instead, so
// the disabled code is not emitted.

// One direction m: b = p − m, d = p + m and, with `aa`, a = p − 2m,
// f = p + 2m. Six errors are tested per direction (eq. 8: c, a and b for
// each half), but κ and eq. 6's denominator depend only on the control and
// eq. 6's numerator only on the check, so each is computed once per texel:
// four of each instead of six.
fn npr_lsa__direction(pos: texture_2d<f32>, normals: texture_2d<f32>, encoding: i32, px: vec2<i32>, p: npr_lsa_core__Texel, m: vec2<i32>, plane: bool, aa: bool, lo: f32, hi: f32) -> f32 {
    let b = npr_lsa_core__fetch(pos, normals, encoding, px - m);
    let d = npr_lsa_core__fetch(pos, normals, encoding, px + m);
    let kb = npr_lsa_core__kappa(b, p);
    let kd = npr_lsa_core__kappa(d, p);
    let one = npr_lsa_plane__pair(b, d, p, 1.0, plane);
    var vd = max(npr_lsa_core__error(b, p, d, kb, npr_lsa_plane__term(plane, one.num_ahead, one.den_back), lo, hi), 0.0);
    var vb = max(npr_lsa_core__error(d, p, b, kd, npr_lsa_plane__term(plane, one.num_back, one.den_ahead), lo, hi), 0.0);
    if (aa) {
        // For q = d, q̂ = f and the control of S(p, q̂) is a; offsets over
        // two steps are halved in eq. 6.
        let a = npr_lsa_core__fetch(pos, normals, encoding, px - 2 * m);
        let f = npr_lsa_core__fetch(pos, normals, encoding, px + 2 * m);
        let two = npr_lsa_plane__pair(a, f, p, 0.5, plane);
        let ka = npr_lsa_core__kappa(a, p);
        let kf = npr_lsa_core__kappa(f, p);
        vd = npr_lsa_aa__mix(npr_lsa_core__error(b, p, f, kb, npr_lsa_plane__term(plane, two.num_ahead, one.den_back), lo, hi), npr_lsa_core__error(a, p, d, ka, npr_lsa_plane__term(plane, one.num_ahead, two.den_back), lo, hi), vd);
        vb = npr_lsa_aa__mix(npr_lsa_core__error(d, p, a, kd, npr_lsa_plane__term(plane, two.num_back, one.den_ahead), lo, hi), npr_lsa_core__error(f, p, b, kf, npr_lsa_plane__term(plane, one.num_back, two.den_ahead), lo, hi), vb);
    }
    return max(vd, vb);
}

// The directions are written out (see `npr_lsa_curv`).
fn npr_lsa(pos: texture_2d<f32>, normals: texture_2d<f32>, uv: vec2<f32>, plane: bool, aa: bool, eta_min: f32, eta_max: f32, normal_encoding: i32) -> vec4<f32> {
    let px = npr_lsa_core__pixel(pos, uv);
    let p = npr_lsa_core__fetch(pos, normals, normal_encoding, px);
    return vec4<f32>(
        npr_lsa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 0), plane, aa, eta_min, eta_max),
        npr_lsa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 1), plane, aa, eta_min, eta_max),
        npr_lsa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(0, 1), plane, aa, eta_min, eta_max),
        npr_lsa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(-1, 1), plane, aa, eta_min, eta_max),
    );
}
