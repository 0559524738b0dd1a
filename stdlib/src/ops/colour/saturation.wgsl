// Saturation: lerp from Rec. 709 grey (amount 0) through the colour (1)
// and beyond (> 1 oversaturates); alpha is kept.
fn npr_saturation(c: vec4<f32>, amount: f32) -> vec4<f32> {
    let grey = vec3<f32>(npr_luminance(c));
    return vec4<f32>(mix(grey, c.rgb, amount), c.a);
}
