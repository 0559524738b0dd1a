// A trilinear read of a mip-mapped texture (an art-map) with its level of
// detail moved by `bias` levels: stroke size per surface, as Klein et al.
// 2000 §4.2 suggest ("control the sizes of rendered strokes on a
// per-surface basis using ... LOD bias"). WebGPU samplers have no LOD bias
// and textureSampleBias needs uniform control flow, so the screen
// derivatives of uv are scaled by 2^bias: the hardware's level is log2 of
// the footprint, so the footprint × 2^bias is the level + bias.
fn npr_sample_biased(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>, bias: f32) -> vec4<f32> {
    let s = exp2(bias);
    return textureSampleGrad(tex, samp, uv, dpdx(uv) * s, dpdy(uv) * s);
}
