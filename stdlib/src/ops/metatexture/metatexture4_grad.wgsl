// MetaTexture without skew compensation: 4 taps (eq. 8). The compiler calls
// this instead of `metatexture_grad` when `skew` is the constant 0, so a style
// without skew compensation emits no 8-tap code.
fn npr_metatexture4_grad(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, grad_u: vec2<f32>, grad_v: vec2<f32>, width: f32, beta: i32, base: f32, contrast: i32, mean: vec4<f32>) -> vec4<f32> {
    let lv = npr_meta__level(grad_u, grad_v, width, base, beta);
    let m = npr_meta__four(tex, samp, uv, grad_u, grad_v, lv, base);
    return npr_meta__contrast(m, npr_meta__k(lv.blend.x) * npr_meta__k(lv.blend.y), contrast, mean);
}
