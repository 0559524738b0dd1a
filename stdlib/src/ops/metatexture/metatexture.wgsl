// MetaTexture with screen-space UV gradients from fragment derivatives
// (Age of Sail §3.1, eq. 1 with ∇u = (∂u/∂x, ∂u/∂y)). Fragment stage only.
fn npr_metatexture(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, width: f32, beta: i32, base: f32, skew: i32, contrast: i32, mean: vec4<f32>) -> vec4<f32> {
    let grad_u = vec2<f32>(dpdx(uv.x), dpdy(uv.x));
    let grad_v = vec2<f32>(dpdx(uv.y), dpdy(uv.y));
    return npr_metatexture_grad(tex, samp, uv, grad_u, grad_v, width, beta, base, skew, contrast, mean);
}
