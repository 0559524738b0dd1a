// Shared helpers of the LSA contour operators (Zaidi et al., "Local Surface
// Approximation Contours for Virtual Reality Stylisation"; equation numbers
// are the paper's). The G-buffer holds positions (alpha 1 on geometry, 0 on
// the cleared background) and normals in one space, world or view: LSA only
// compares them with each other. Normals are xyz, or octahedral codes in a
// 2-channel target (the packed G-buffer; see `npr_lsa_core__fetch`).
//
// The 8-neighbourhood W(p) of eq. 1 is walked as 4 directions m (E, SE, S,
// SW in image coordinates); the pair p − m, p + m serves both neighbours: the
// sphere S(p, q) is fitted to the opposite pixel q̌ (§3.1), so each pair
// gives e(p + m, S from p − m) and e(p − m, S from p + m). Grouping the two
// halves per direction is the e_max acceleration of §4.1, and the four
// per-direction values feed the line-density filter of §4.1 separately.

// One G-buffer texel. `inside`: within the image; `geo`: holds geometry
// (inside, finite, position alpha > 0.5). Outside texels are never clamped
// onto the border, so the border draws no lines.
struct npr_lsa_core__Texel {
    p: vec3<f32>,
    n: vec3<f32>,
    geo: bool,
    inside: bool,
}

// The texel of `tex` under `uv` (as `npr_load` picks it).
fn npr_lsa_core__pixel(tex: texture_2d<f32>, uv: vec2<f32>) -> vec2<i32> {
    let dims = vec2<i32>(textureDimensions(tex));
    return clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
}

// `encoding` is the operators' `normal_encoding`: 0 (xyz) reads the normal
// from rgb, 1 (octahedral) decodes it from rg (`oct_encode`, Cigolle et al.
// 2014 §3.1), the packed G-buffer of docs/PERFORMANCE.md. Only this read
// differs: the LSA math below is the same for both layouts. A constant
// encoding is a literal argument (`0i` or `1i`), a branch a driver that
// inlines can fold; no variant operators, so no second copy of the loops.
fn npr_lsa_core__fetch(pos: texture_2d<f32>, normals: texture_2d<f32>, encoding: i32, q: vec2<i32>) -> npr_lsa_core__Texel {
    let dims = vec2<i32>(textureDimensions(pos));
    let ndims = vec2<i32>(textureDimensions(normals));
    var t: npr_lsa_core__Texel;
    t.inside = all(q >= vec2<i32>(0)) && all(q < dims);
    let pw = textureLoad(pos, clamp(q, vec2<i32>(0), dims - vec2<i32>(1)), 0);
    let nw = textureLoad(normals, clamp(q, vec2<i32>(0), ndims - vec2<i32>(1)), 0);
    var n = nw.xyz;
    if (encoding == 1) {
        n = npr_oct__decode(nw.xy);
    }
    // A non-finite texel (an f16 overflow, say) counts as background: the
    // comparisons are false for NaN and ±Inf, so no NaN spreads.
    let big = vec3<f32>(1.0e37);
    let finite = all(abs(pw.xyz) < big) && all(abs(n) < big) && abs(pw.w) < 1.0e37;
    t.geo = t.inside && finite && pw.w > 0.5;
    t.p = select(vec3<f32>(0.0), pw.xyz, t.geo);
    let nn = select(vec3<f32>(0.0), n, t.geo);
    t.n = nn * inverseSqrt(max(dot(nn, nn), 1e-30));
    return t;
}

// What a triple (control c, centre p, check q) gives before any fitting:
// −2 when c or q lies outside the image (the pair is skipped, so no line at
// the border); 1e6 (a sure line) where geometry meets background; 0 inside
// the background; −1 when all three hold geometry and the LSA is evaluated.
fn npr_lsa_core__guard(c: npr_lsa_core__Texel, p: npr_lsa_core__Texel, q: npr_lsa_core__Texel) -> f32 {
    if (!(c.inside && q.inside)) {
        return -2.0;
    }
    if (c.geo && p.geo && q.geo) {
        return -1.0;
    }
    return select(0.0, 1.0e6, c.geo || p.geo || q.geo);
}

// Signed curvature κ = 1/r of the sphere through P_p and P_c tangent to both
// normals (eqs. 2–3): |r| = |P_c − P_p| / |N_c − N_p|, sign
// sgn((N_c − N_p)·(P_c − P_p)). Equal normals give exactly κ = 0 (a plane),
// and coincident positions are floored at 1e-5 m, so κ is always finite.
// It depends on the control texel only, so each operator computes it once
// per control and reuses it for every check texel tested against S(p, c).
fn npr_lsa_core__kappa(c: npr_lsa_core__Texel, p: npr_lsa_core__Texel) -> f32 {
    let dn = c.n - p.n;
    let dp = c.p - p.p;
    return sign(dot(dn, dp)) * length(dn) / max(1e-5, length(dp));
}

// The remap of §3.2: [η_min, η_max] → [0, 1], clamped (a step when η_max ≤ η_min).
fn npr_lsa_core__remap(e: f32, lo: f32, hi: f32) -> f32 {
    if (hi <= lo) {
        return select(0.0, 1.0, e >= lo);
    }
    return clamp((e - lo) / (hi - lo), 0.0, 1.0);
}

// The remapped error of check q against the sphere S(p, c) of curvature k
// (κ of control c): e_curv (eq. 5), |κ(P_q − P_p) − (N_q − N_p)|, plus
// `extra` (e_plane for e_sum, eq. 7, or 0). −1 when c or q lies outside the
// image; the background/geometry value of `guard` when they mix.
//
// Branch-free on purpose: e_curv is computed for every texel (background
// texels hold zeros, so it stays finite) and the guard picks the result.
// A driver that runs pixels in SIMD lanes (lavapipe) executes both sides of
// a divergent branch anyway; the selects save the masking.
fn npr_lsa_core__error(c: npr_lsa_core__Texel, p: npr_lsa_core__Texel, q: npr_lsa_core__Texel, k: f32, extra: f32, lo: f32, hi: f32) -> f32 {
    let g = npr_lsa_core__guard(c, p, q);
    let e = select(g, length(k * (q.p - p.p) - (q.n - p.n)) + extra, g == -1.0);
    return select(npr_lsa_core__remap(e, lo, hi), -1.0, g < -1.5);
}

// One direction m of the base method (eqs. 1–5 with e_max, §4.1): the
// larger remapped e_curv of the two neighbours b = p − m and d = p + m,
// each tested against the sphere fitted to p and the opposite neighbour.
fn npr_lsa_core__direction(pos: texture_2d<f32>, normals: texture_2d<f32>, encoding: i32, px: vec2<i32>, p: npr_lsa_core__Texel, m: vec2<i32>, lo: f32, hi: f32) -> f32 {
    let b = npr_lsa_core__fetch(pos, normals, encoding, px - m);
    let d = npr_lsa_core__fetch(pos, normals, encoding, px + m);
    let vd = npr_lsa_core__error(b, p, d, npr_lsa_core__kappa(b, p), 0.0, lo, hi);
    let vb = npr_lsa_core__error(d, p, b, npr_lsa_core__kappa(d, p), 0.0, lo, hi);
    return max(max(vd, vb), 0.0);
}
