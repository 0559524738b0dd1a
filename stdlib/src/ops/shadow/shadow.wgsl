// Cast-shadow visibility from a light-view depth map (Age of Sail §5: the
// depth pass of the shadow casters, read by the shadow pass's red channel).
// `p_light` is the surface point in light NDC (`position.light`); `warp` is the
// sigmoid strength the depth pass used in `vertex { shadow_warp: k }`, applied
// here the same way: x' = tanh(k·x) / tanh(k). A (2r+1)² percentage-closer
// filter softens the edge; points outside the map, or behind the light's far
// plane, are lit. Returns the lit fraction in [0, 1].
fn npr_shadow(depth_map: texture_2d<f32>, p_light: vec3<f32>, bias: f32, warp: f32, radius: i32) -> f32 {
    // NaN test on the bits: shader compilers may fold `x != x` to false.
    let nan = (bitcast<vec3<u32>>(p_light) & vec3<u32>(0x7fffffffu)) > vec3<u32>(0x7f800000u);
    if (any(abs(p_light.xy) > vec2<f32>(1.0)) || p_light.z > 1.0 || any(nan)) {
        return 1.0;
    }
    let k = clamp(warp, 0.0, 16.0);
    var xy = p_light.xy;
    if (k > 1e-4) {
        xy = tanh(k * xy) / tanh(k);
    }
    let uv = xy * vec2<f32>(0.5, -0.5) + vec2<f32>(0.5);
    let dims = vec2<i32>(textureDimensions(depth_map));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    let r = clamp(radius, 0, 3);
    var lit = 0.0;
    for (var j = -r; j <= r; j = j + 1) {
        for (var i = -r; i <= r; i = i + 1) {
            let q = clamp(p + vec2<i32>(i, j), vec2<i32>(0), dims - vec2<i32>(1));
            let occluder = textureLoad(depth_map, q, 0).r;
            lit = lit + select(0.0, 1.0, p_light.z - bias <= occluder);
        }
    }
    let n = f32(2 * r + 1);
    return lit / (n * n);
}
