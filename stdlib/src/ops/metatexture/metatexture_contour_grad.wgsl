// MetaTexture re-oriented to indicate contour (Age of Sail §3.5). A directional
// example texture keeps its x axis along u where v is the foreshortened axis
// (|∇v| > |∇u|) and turns by 90° (x along v) where u is; across
// r = log₂(|∇u|/|∇v|) ∈ [−band/2, band/2] the two orientations are blended with
// β, so there is no seam. Each orientation is a full `metatexture_grad`; only
// pixels inside the band pay for both. `orient` = 0 (off) compiles to
// `metatexture_grad` (see the operator's specialization).
fn npr_metatexture_contour_grad(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, grad_u: vec2<f32>, grad_v: vec2<f32>, width: f32, beta: i32, base: f32, skew: i32, contrast: i32, mean: vec4<f32>, orient: i32, band: f32) -> vec4<f32> {
    if (orient == 0) {
        return npr_metatexture_grad(tex, samp, uv, grad_u, grad_v, width, beta, base, skew, contrast, mean);
    }
    let r = log2(clamp(length(grad_u), 1e-30, 1e30)) - log2(clamp(length(grad_v), 1e-30, 1e30));
    let w = npr_meta__beta(0.5 + r / max(band, 1e-3), beta);
    var m0 = vec4<f32>(0.0);
    var m1 = vec4<f32>(0.0);
    // textureSampleGrad has explicit gradients, so it is valid in these branches.
    if (w < 1.0) {
        m0 = npr_metatexture_grad(tex, samp, uv, grad_u, grad_v, width, beta, base, skew, contrast, mean);
    }
    if (w > 0.0) {
        // Rotated by 90° in UV: U_r = (v, −u), so ∇U_r = (∇v, −∇u).
        m1 = npr_metatexture_grad(tex, samp, vec2<f32>(uv.y, -uv.x), grad_v, -grad_u, width, beta, base, skew, contrast, mean);
    }
    let m = mix(m0, m1, w);
    // The orientation blend is one more two-way blend: eq. 24 gains a factor k(w).
    return npr_meta__contrast(m, npr_meta__k(w), contrast, mean);
}
