// 2×2 box filter of the source texels under a half-resolution pixel: the
// source texel pair starting at floor(uv·dims − 0.5) in each axis.
fn npr_downsample(src: texture_2d<f32>, uv: vec2<f32>) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(src));
    let base = vec2<i32>(floor(uv * vec2<f32>(dims) - vec2<f32>(0.5)));
    var acc = vec4<f32>(0.0);
    for (var dy = 0; dy < 2; dy = dy + 1) {
        for (var dx = 0; dx < 2; dx = dx + 1) {
            let q = clamp(base + vec2<i32>(dx, dy), vec2<i32>(0), dims - vec2<i32>(1));
            acc = acc + textureLoad(src, q, 0);
        }
    }
    return acc * 0.25;
}
