// Edge breakup warp (Age of Sail §4, Fig. 10d): read `src` displaced by the warp
// field, uv + vec · strength / size(src): `vec` is the warp vector (|vec| ≤ 1
// for a remapped noise texture), `strength` its length in px of `src`. Nearest
// texel, like every target read, so edges stay crisp; clamped at the border.
fn npr_warp(src: texture_2d<f32>, offset: vec2<f32>, strength: f32, uv: vec2<f32>) -> vec4<f32> {
    let dims = vec2<f32>(textureDimensions(src));
    let d = clamp(offset * strength, vec2<f32>(-1e6), vec2<f32>(1e6));
    let p = uv * dims + select(d, vec2<f32>(0.0), d != d);
    let ip = clamp(vec2<i32>(floor(p)), vec2<i32>(0), vec2<i32>(dims) - vec2<i32>(1));
    return textureLoad(src, ip, 0);
}
