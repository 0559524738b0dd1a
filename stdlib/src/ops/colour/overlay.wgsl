// The overlay blend mode per channel (multiply below 0.5, screen above, on
// the base), mixed in by `opacity`; the base's alpha is kept.
fn npr_overlay(base: vec4<f32>, blend: vec4<f32>, opacity: f32) -> vec4<f32> {
    let b = base.rgb;
    let s = blend.rgb;
    let low = 2.0 * b * s;
    let high = vec3<f32>(1.0) - 2.0 * (vec3<f32>(1.0) - b) * (vec3<f32>(1.0) - s);
    let o = select(high, low, b < vec3<f32>(0.5));
    return vec4<f32>(mix(b, o, opacity), base.a);
}
