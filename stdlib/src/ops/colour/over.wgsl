// Porter-Duff "over" with straight (not premultiplied) alpha; a fully
// transparent result is transparent black instead of NaN.
fn npr_over(fg: vec4<f32>, bg: vec4<f32>) -> vec4<f32> {
    let a = fg.a + bg.a * (1.0 - fg.a);
    let rgb = (fg.rgb * fg.a + bg.rgb * bg.a * (1.0 - fg.a)) / max(a, 1e-8);
    return select(vec4<f32>(rgb, a), vec4<f32>(0.0), a <= 0.0);
}
