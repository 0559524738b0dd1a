// Rec. 709 luma of the colour's rgb.
fn npr_luminance(c: vec4<f32>) -> f32 {
    return dot(c.rgb, vec3<f32>(0.2126, 0.7152, 0.0722));
}
