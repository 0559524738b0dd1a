// Sobel gradient magnitude of channel r, each axis normalized by 1/8 so a
// unit step per texel gives magnitude 1 (Sobel & Feldman 1968), clamp-to-edge.
fn npr_sobel(src: texture_2d<f32>, uv: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(src));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    var v: array<f32, 9>;
    for (var j = 0; j < 3; j = j + 1) {
        for (var i = 0; i < 3; i = i + 1) {
            let q = clamp(p + vec2<i32>(i - 1, j - 1), vec2<i32>(0), dims - vec2<i32>(1));
            v[j * 3 + i] = textureLoad(src, q, 0).r;
        }
    }
    let gx = (v[2] + 2.0 * v[5] + v[8]) - (v[0] + 2.0 * v[3] + v[6]);
    let gy = (v[6] + 2.0 * v[7] + v[8]) - (v[0] + 2.0 * v[1] + v[2]);
    return length(vec2<f32>(gx, gy)) / 8.0;
}
