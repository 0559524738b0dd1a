// Line-density filter of the LSA contours (§4.1, Fig. 4): per direction
// channel i, a local-maximum filter along the 5-pixel line through p in
// direction i: e_i − 2·strength·min(e_i at p ± m, p ± 2m), clamped to [0, 1].
// Texels outside the image take no part (so the border keeps its lines); a
// line with no neighbour inside leaves the value as it is.
fn npr_lsa_density(src: texture_2d<f32>, uv: vec2<f32>, strength: f32) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(src));
    let px = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    let c = textureLoad(src, px, 0);
    var out = c;
    for (var i = 0; i < 4; i = i + 1) {
        let m = select(select(select(vec2<i32>(-1, 1), vec2<i32>(0, 1), i == 2), vec2<i32>(1, 1), i == 1), vec2<i32>(1, 0), i == 0);
        var lo = 2.0;
        for (var k = -2; k <= 2; k = k + 1) {
            let q = px + k * m;
            if (k != 0 && all(q >= vec2<i32>(0)) && all(q < dims)) {
                lo = min(lo, textureLoad(src, q, 0)[i]);
            }
        }
        lo = select(lo, 0.0, lo > 1.5);
        out[i] = clamp(c[i] - 2.0 * strength * lo, 0.0, 1.0);
    }
    return out;
}
