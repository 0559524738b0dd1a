// One separable 1D Gaussian pass (axis 0 = x, 1 = y) with taps at texel
// centres, weights exp(-d²/2σ²) normalized to sum 1, clamp-to-edge. The
// radius is ceil(3σ), capped at 48 texels (σ ≤ 16 px keeps 99.7% of the mass).
fn npr_gaussian(src: texture_2d<f32>, uv: vec2<f32>, sigma: f32, axis: i32) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(src));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    let s = max(sigma, 1e-3);
    let radius = min(i32(ceil(3.0 * s)), 48);
    let dir = select(vec2<i32>(0, 1), vec2<i32>(1, 0), axis == 0);
    var acc = vec4<f32>(0.0);
    var total = 0.0;
    for (var i = -radius; i <= radius; i = i + 1) {
        let w = exp(-f32(i * i) / (2.0 * s * s));
        let q = clamp(p + dir * i, vec2<i32>(0), dims - vec2<i32>(1));
        acc = acc + w * textureLoad(src, q, 0);
        total = total + w;
    }
    return acc / total;
}
