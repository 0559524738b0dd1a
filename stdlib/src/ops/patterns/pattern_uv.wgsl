// Pattern coordinates of the image point q (Breslav et al. 2007 §3.3): the
// pattern frame maps uv (0, 0) to o and (1, 0), (0, 1) to o + u, o + v, so
// uv = ((q − o)·u/|u|², (q − o)·v/|v|²). A zero u or v gives 0 there.
fn npr_pattern_uv(o: vec2<f32>, u: vec2<f32>, v: vec2<f32>, q: vec2<f32>) -> vec2<f32> {
    let d = q - o;
    let uu = dot(u, u);
    let vv = dot(v, v);
    return vec2<f32>(select(0.0, dot(d, u) / uu, uu > 0.0), select(0.0, dot(d, v) / vv, vv > 0.0));
}
