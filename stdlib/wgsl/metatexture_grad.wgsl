// MetaTexture (Harvill et al., "Age of Sail", journal version §3) with the
// screen-space UV gradients given explicitly (du = ∇u, dv = ∇v, in UV per px).
//
// Erratum applied: eqs. 4–5 as printed swap U1 and U2, which contradicts
// eq. 8 (the weight B_u must go to the copy whose u is scaled up). Here
// U1 scales v and U2 scales u, so M is continuous as E_u, E_v cross integers.
// `base` generalizes the powers of two (the paper's future-work suggestion).
// Exponents are clamped so that base^E ≤ 4096: then
// k·uv keeps at least 12 fractional bits in f32 (tileable T: only fract matters).

const npr_metatexture_grad__MAX_SCALE: f32 = 4096.0;

// β of eq. 7: 0 = linear, 1 = cubic −2x³+3x², 2 = quintic 6x⁵−15x⁴+10x³.
fn npr_metatexture_grad__beta(x: f32, kind: i32) -> f32 {
    let t = clamp(x, 0.0, 1.0);
    if (kind == 0) {
        return t;
    }
    if (kind == 1) {
        return t * t * (3.0 - 2.0 * t);
    }
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// k(t) = 2t² − 2t + 1 (eq. 25): the sum of the squared weights of a two-way blend.
fn npr_metatexture_grad__k(t: f32) -> f32 {
    return 2.0 * t * t - 2.0 * t + 1.0;
}

struct npr_metatexture_grad__Level {
    scale: vec2<f32>,   // base^floor(E), per axis (eq. 3)
    blend: vec2<f32>,   // B (eq. 7)
}

// Eqs. 1–2 and 7 for one pair of gradients: the quantized scales and blend weights.
fn npr_metatexture_grad__level(du: vec2<f32>, dv: vec2<f32>, width: f32, base: f32, beta: i32) -> npr_metatexture_grad__Level {
    let lb = log2(max(base, 1.0001));
    let max_e = log2(npr_metatexture_grad__MAX_SCALE) / lb;
    // Eq. 1 (S = 1 / (w |∇u|)) and eq. 2 (E = log_base S), guarded against |∇u| → 0 and ∞.
    let len_u = clamp(length(du), 1e-30, 1e30);
    let len_v = clamp(length(dv), 1e-30, 1e30);
    let e = clamp(vec2<f32>(-log2(max(width, 1e-6) * len_u), -log2(max(width, 1e-6) * len_v)) / lb, vec2<f32>(-max_e), vec2<f32>(max_e));
    let fe = floor(e);
    var out: npr_metatexture_grad__Level;
    out.scale = exp2(fe * lb);
    out.blend = vec2<f32>(npr_metatexture_grad__beta(e.x - fe.x, beta), npr_metatexture_grad__beta(e.y - fe.y, beta));
    return out;
}

fn npr_metatexture_grad__tap(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, k: vec2<f32>, du: vec2<f32>, dv: vec2<f32>) -> vec4<f32> {
    // fract keeps the coordinate small (T is tileable); the gradients are exact: d(k·u) = k·du.
    let p = fract(k * uv);
    let ddx = vec2<f32>(k.x * du.x, k.y * dv.x);
    let ddy = vec2<f32>(k.x * du.y, k.y * dv.y);
    return textureSampleGrad(tex, samp, p, ddx, ddy);
}

// Eq. 8 with the corrected U1/U2: four taps at scales (1,1), (1,b), (b,1), (b,b) of U0.
fn npr_metatexture_grad__four(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, du: vec2<f32>, dv: vec2<f32>, lv: npr_metatexture_grad__Level, base: f32) -> vec4<f32> {
    let k0 = lv.scale;
    let t0 = npr_metatexture_grad__tap(tex, samp, uv, k0, du, dv);
    let t1 = npr_metatexture_grad__tap(tex, samp, uv, k0 * vec2<f32>(1.0, base), du, dv);
    let t2 = npr_metatexture_grad__tap(tex, samp, uv, k0 * vec2<f32>(base, 1.0), du, dv);
    let t3 = npr_metatexture_grad__tap(tex, samp, uv, k0 * vec2<f32>(base, base), du, dv);
    let bu = lv.blend.x;
    let bv = lv.blend.y;
    return (1.0 - bv) * ((1.0 - bu) * t0 + bu * t2) + bv * ((1.0 - bu) * t1 + bu * t3);
}

// MetaTexture M (eq. 8, or eq. 23 when skew > 0) with optional contrast
// compensation (0 none, 1 printed: deviation × c (eq. 24), 2 variance-preserving:
// deviation / √c, as in Heitz & Neyret's histogram-preserving blend).
// `mean` is the example texture's mean, the pivot of the contrast change.
fn npr_metatexture_grad(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, grad_u: vec2<f32>, grad_v: vec2<f32>, width: f32, beta: i32, base: f32, skew: i32, contrast: i32, mean: vec4<f32>) -> vec4<f32> {
    var m: vec4<f32>;
    var c: f32;
    if (skew <= 0) {
        let lv = npr_metatexture_grad__level(grad_u, grad_v, width, base, beta);
        m = npr_metatexture_grad__four(tex, samp, uv, grad_u, grad_v, lv, base);
        c = npr_metatexture_grad__k(lv.blend.x) * npr_metatexture_grad__k(lv.blend.y);
    } else {
        // Eqs. 14–15: skew σ = atan(ε) · cos(angle between ∇u and ∇v).
        let lu = max(length(grad_u), 1e-30);
        let lv_ = max(length(grad_v), 1e-30);
        let eps = min(lu, lv_) / max(lu, lv_);
        let sigma = atan(eps) * dot(grad_u / lu, grad_v / lv_);
        // Eqs. 16–19, 22.
        let n = f32(skew);
        let fl = floor(n * sigma);
        let psi0 = atan((fl / n) / 2.0);
        let psi1 = atan(((fl + 1.0) / n) / 2.0);
        let bw = npr_metatexture_grad__beta(n * sigma - fl, beta);
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
        let l0 = npr_metatexture_grad__level(du0, dv0, width, base, beta);
        let l1 = npr_metatexture_grad__level(du1, dv1, width, base, beta);
        let m0 = npr_metatexture_grad__four(tex, samp, uv0, du0, dv0, l0, base);
        let m1 = npr_metatexture_grad__four(tex, samp, uv1, du1, dv1, l1, base);
        // Eq. 23.
        m = (1.0 - bw) * m0 + bw * m1;
        // Eq. 24, with k(B_u), k(B_v) taken from the blend of the two skew sets.
        let bu = mix(l0.blend.x, l1.blend.x, bw);
        let bv = mix(l0.blend.y, l1.blend.y, bw);
        c = npr_metatexture_grad__k(bu) * npr_metatexture_grad__k(bv) * npr_metatexture_grad__k(bw);
    }
    if (contrast == 1) {
        return mean + (m - mean) * c;
    }
    if (contrast == 2) {
        return mean + (m - mean) * inverseSqrt(max(c, 1e-6));
    }
    return m;
}
