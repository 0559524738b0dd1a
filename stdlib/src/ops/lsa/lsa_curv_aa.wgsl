// LSA contours with the anti-aliasing extension (eq. 8) on e_curv alone;
// what `lsa` compiles to with plane = false.

// One direction m: b = p − m and d = p + m as in the base method; with `aa`,
// eq. 8 with the texels two steps away, a = p − 2m and f = p + 2m. κ of a
// control is computed once and reused for both checks against it.
fn npr_lsa_curv_aa__direction(pos: texture_2d<f32>, normals: texture_2d<f32>, encoding: i32, px: vec2<i32>, p: npr_lsa_core__Texel, m: vec2<i32>, aa: bool, lo: f32, hi: f32) -> f32 {
    let b = npr_lsa_core__fetch(pos, normals, encoding, px - m);
    let d = npr_lsa_core__fetch(pos, normals, encoding, px + m);
    let kb = npr_lsa_core__kappa(b, p);
    let kd = npr_lsa_core__kappa(d, p);
    var vd = max(npr_lsa_core__error(b, p, d, kb, 0.0, lo, hi), 0.0);
    var vb = max(npr_lsa_core__error(d, p, b, kd, 0.0, lo, hi), 0.0);
    if (aa) {
        // For q = d, q̂ = f and the control of S(p, q̂) is a (eq. 8).
        let a = npr_lsa_core__fetch(pos, normals, encoding, px - 2 * m);
        let f = npr_lsa_core__fetch(pos, normals, encoding, px + 2 * m);
        vd = npr_lsa_aa__mix(npr_lsa_core__error(b, p, f, kb, 0.0, lo, hi), npr_lsa_core__error(a, p, d, npr_lsa_core__kappa(a, p), 0.0, lo, hi), vd);
        vb = npr_lsa_aa__mix(npr_lsa_core__error(d, p, a, kd, 0.0, lo, hi), npr_lsa_core__error(f, p, b, npr_lsa_core__kappa(f, p), 0.0, lo, hi), vb);
    }
    return max(vd, vb);
}

// The directions are written out (see `npr_lsa_curv`).
fn npr_lsa_curv_aa(pos: texture_2d<f32>, normals: texture_2d<f32>, uv: vec2<f32>, aa: bool, eta_min: f32, eta_max: f32, normal_encoding: i32) -> vec4<f32> {
    let px = npr_lsa_core__pixel(pos, uv);
    let p = npr_lsa_core__fetch(pos, normals, normal_encoding, px);
    return vec4<f32>(
        npr_lsa_curv_aa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 0), aa, eta_min, eta_max),
        npr_lsa_curv_aa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(1, 1), aa, eta_min, eta_max),
        npr_lsa_curv_aa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(0, 1), aa, eta_min, eta_max),
        npr_lsa_curv_aa__direction(pos, normals, normal_encoding, px, p, vec2<i32>(-1, 1), aa, eta_min, eta_max),
    );
}
