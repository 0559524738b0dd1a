// Shared MetaTexture helpers (Harvill et al., "Age of Sail", journal version §3),
// used by the 4-tap and 8-tap operators. Gradients are in UV per px.
//
// Erratum applied: eqs. 4–5 as printed swap U1 and U2, which contradicts
// eq. 8 (the weight B_u must go to the copy whose u is scaled up). Here
// U1 scales v and U2 scales u, so M is continuous as E_u, E_v cross integers.
// `base` generalizes the powers of two (the paper's future-work suggestion).
// Exponents are clamped so that base^E ≤ 4096: then
// k·uv keeps at least 12 fractional bits in f32 (tileable T: only fract matters).
// Downwards (far away, grazing) scales go to 2^-40: k·uv only shrinks there.

const npr_meta__MAX_SCALE: f32 = 4096.0;
const npr_meta__MIN_LOG2_SCALE: f32 = -40.0;

// β of eq. 7: 0 = linear, 1 = cubic −2x³+3x², 2 = quintic 6x⁵−15x⁴+10x³.
fn npr_meta__beta(x: f32, kind: i32) -> f32 {
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
fn npr_meta__k(t: f32) -> f32 {
    return 2.0 * t * t - 2.0 * t + 1.0;
}

struct npr_meta__Level {
    scale: vec2<f32>,   // base^floor(E), per axis (eq. 3)
    blend: vec2<f32>,   // B (eq. 7)
}

// Eqs. 1–2 and 7 for one pair of gradients: the quantized scales and blend weights.
fn npr_meta__level(du: vec2<f32>, dv: vec2<f32>, width: f32, base: f32, beta: i32) -> npr_meta__Level {
    let lb = log2(max(base, 1.0001));
    let max_e = log2(npr_meta__MAX_SCALE) / lb;
    // Eq. 1 (S = 1 / (w |∇u|)) and eq. 2 (E = log_base S), guarded against |∇u| → 0 and ∞.
    let len_u = clamp(length(du), 1e-30, 1e30);
    let len_v = clamp(length(dv), 1e-30, 1e30);
    let min_e = npr_meta__MIN_LOG2_SCALE / lb;
    let e = clamp(vec2<f32>(-log2(max(width, 1e-6) * len_u), -log2(max(width, 1e-6) * len_v)) / lb, vec2<f32>(min_e), vec2<f32>(max_e));
    let fe = floor(e);
    var out: npr_meta__Level;
    out.scale = exp2(fe * lb);
    out.blend = vec2<f32>(npr_meta__beta(e.x - fe.x, beta), npr_meta__beta(e.y - fe.y, beta));
    return out;
}

fn npr_meta__tap(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, k: vec2<f32>, du: vec2<f32>, dv: vec2<f32>) -> vec4<f32> {
    // fract keeps the coordinate small (T is tileable); the gradients are exact: d(k·u) = k·du.
    let p = fract(k * uv);
    let ddx = vec2<f32>(k.x * du.x, k.y * dv.x);
    let ddy = vec2<f32>(k.x * du.y, k.y * dv.y);
    return textureSampleGrad(tex, samp, p, ddx, ddy);
}

// Eq. 8 with the corrected U1/U2: four taps at scales (1,1), (1,b), (b,1), (b,b) of U0.
fn npr_meta__four(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, du: vec2<f32>, dv: vec2<f32>, lv: npr_meta__Level, base: f32) -> vec4<f32> {
    let k0 = lv.scale;
    let t0 = npr_meta__tap(tex, samp, uv, k0, du, dv);
    let t1 = npr_meta__tap(tex, samp, uv, k0 * vec2<f32>(1.0, base), du, dv);
    let t2 = npr_meta__tap(tex, samp, uv, k0 * vec2<f32>(base, 1.0), du, dv);
    let t3 = npr_meta__tap(tex, samp, uv, k0 * vec2<f32>(base, base), du, dv);
    let bu = lv.blend.x;
    let bv = lv.blend.y;
    return (1.0 - bv) * ((1.0 - bu) * t0 + bu * t2) + bv * ((1.0 - bu) * t1 + bu * t3);
}

// Contrast compensation of eqs. 24–25 around the example's mean: 0 none,
// 1 as printed (deviation × c), 2 variance-preserving (deviation ÷ √c, as in
// Heitz & Neyret's histogram-preserving blend).
fn npr_meta__contrast(m: vec4<f32>, c: f32, mode: i32, mean: vec4<f32>) -> vec4<f32> {
    if (mode == 1) {
        return mean + (m - mean) * c;
    }
    if (mode == 2) {
        return mean + (m - mean) * inverseSqrt(max(c, 1e-6));
    }
    return m;
}
