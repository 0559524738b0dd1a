// Filtered texture read at level 0 (uses textureSampleLevel so it is valid
// in any control flow and any stage).
fn npr_sample(tex: texture_2d<f32>, samp: sampler, uv: vec2<f32>) -> vec4<f32> {
    return textureSampleLevel(tex, samp, uv, 0.0);
}
