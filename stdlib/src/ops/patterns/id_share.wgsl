// Fuzzy visibility (Breslav et al. 2007 §3.1, the "blurred depth test" of
// Luft and Deussen 2006 done on an ID image as in Kalnins et al. 2002): the
// share of the (2r + 1)² ID-image texels centred on `uv` that hold `id`.
// Texels outside the image count as another object's, so a point at the
// border of the view, or off it, weighs less, or nothing.
fn npr_id_share(ids: texture_2d<f32>, uv: vec2<f32>, id: f32, radius: f32) -> f32 {
    let dims = vec2<i32>(textureDimensions(ids));
    // Far outside (or not a number): no texel of the window is inside.
    let at = clamp(uv, vec2<f32>(-1.0), vec2<f32>(2.0));
    let c = vec2<i32>(floor(select(vec2<f32>(-1.0), at, at == at) * vec2<f32>(dims)));
    let r = i32(clamp(round(radius), 0.0, 8.0));
    var own = 0.0;
    for (var j = -r; j <= r; j = j + 1) {
        for (var i = -r; i <= r; i = i + 1) {
            let q = c + vec2<i32>(i, j);
            if (all(q >= vec2<i32>(0)) && all(q < dims)) {
                own = own + select(0.0, 1.0, abs(textureLoad(ids, q, 0).r - id) < 0.5);
            }
        }
    }
    return own / f32((2 * r + 1) * (2 * r + 1));
}
