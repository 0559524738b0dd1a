// MetaTexture with explicit screen-space UV gradients (∇u, ∇v in UV per px),
// 4 taps (eq. 8) when skew = 0, 8 taps (eq. 23) when skew ≥ 1.
// MetaTexture M (eq. 8, or eq. 23 when skew > 0) with optional contrast
// compensation (0 none, 1 printed: deviation × c (eq. 24), 2 variance-preserving:
// deviation / √c, as in Heitz & Neyret's histogram-preserving blend).
// `mean` is the example texture's mean, the pivot of the contrast change.
fn npr_metatexture_grad(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, grad_u: vec2<f32>, grad_v: vec2<f32>, width: f32, beta: i32, base: f32, skew: i32, contrast: i32, mean: vec4<f32>) -> vec4<f32> {
    var m: vec4<f32>;
    var c: f32;
    if (skew <= 0) {
        let lv = npr_meta__level(grad_u, grad_v, width, base, beta);
        m = npr_meta__four(tex, samp, uv, grad_u, grad_v, lv, base);
        c = npr_meta__k(lv.blend.x) * npr_meta__k(lv.blend.y);
    } else {
        // Eqs. 14–15: skew σ = atan(ε) · cos(angle between ∇u and ∇v), with the
        // sign flipped: ∇u'·∇v' = ∇u·∇v + ½ sin 2ψ (|∇u|² + |∇v|²) for the shear of
        // eqs. 20–21, so ψ must have the opposite sign of ∇u·∇v to straighten the
        // axes. The printed sign increases anisotropy (npr_stdlib::metrics measures it).
        let lu = max(length(grad_u), 1e-30);
        let lv_ = max(length(grad_v), 1e-30);
        let eps = min(lu, lv_) / max(lu, lv_);
        let sigma = -atan(eps) * dot(grad_u / lu, grad_v / lv_);
        // Eqs. 16–19, 22.
        let n = f32(skew);
        let fl = floor(n * sigma);
        let psi0 = atan((fl / n) / 2.0);
        let psi1 = atan(((fl + 1.0) / n) / 2.0);
        let bw = npr_meta__beta(n * sigma - fl, beta);
        // Eqs. 20–21 as printed: a symmetric shear ⟨u cosψ + v sinψ, v cosψ + u sinψ⟩, not a rotation.
        let c0 = cos(psi0);
        let s0 = sin(psi0);
        let c1 = cos(psi1);
        let s1 = sin(psi1);
        let uv0 = vec2<f32>(uv.x * c0 + uv.y * s0, uv.y * c0 + uv.x * s0);
        let uv1 = vec2<f32>(uv.x * c1 + uv.y * s1, uv.y * c1 + uv.x * s1);
        // The sheared coordinates' own gradients give their scale levels (eqs. 1–7 on U', U'').
        let du0 = c0 * grad_u + s0 * grad_v;
        let dv0 = c0 * grad_v + s0 * grad_u;
        let du1 = c1 * grad_u + s1 * grad_v;
        let dv1 = c1 * grad_v + s1 * grad_u;
        let l0 = npr_meta__level(du0, dv0, width, base, beta);
        let l1 = npr_meta__level(du1, dv1, width, base, beta);
        let m0 = npr_meta__four(tex, samp, uv0, du0, dv0, l0, base);
        let m1 = npr_meta__four(tex, samp, uv1, du1, dv1, l1, base);
        // Eq. 23.
        m = (1.0 - bw) * m0 + bw * m1;
        // Eq. 24 for eight taps: the sum of the squared weights, each skew set
        // with its own B_u, B_v: (1 − B_w)² k(B_u')k(B_v') + B_w² k(B_u'')k(B_v'')
        // (= k(B_u)k(B_v)k(B_w) when both sets share their blend weights).
        c = (1.0 - bw) * (1.0 - bw) * npr_meta__k(l0.blend.x) * npr_meta__k(l0.blend.y)
            + bw * bw * npr_meta__k(l1.blend.x) * npr_meta__k(l1.blend.y);
    }
    return npr_meta__contrast(m, c, contrast, mean);
}
