// Stereo consistency (LSA contours §4.2): bound this eye's line strength E(p)
// by M + (1 − M) · max over the 5×5 window W̄₅ around R_{i,j}(p) of the other
// eye's E, so a line survives where the reprojection is reliable (M → 0) only
// if the other eye drew a line within 2 px of where p lands. Both eyes are
// processed from the other's unbounded E (the paper goes l then r; reading
// the unbounded E keeps the result symmetric). `reproj` is R_{i,j} as for
// `reprojection_mask`; `mask` is M_{i,j}(p).
fn npr_stereo_consistency(e: texture_2d<f32>, e_other: texture_2d<f32>, reproj: texture_2d<f32>, mask: f32, uv: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(e));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    let ep = textureLoad(e, p, 0).r;
    let r = textureLoad(reproj, p, 0);
    let m = clamp(mask, 0.0, 1.0);
    if (!(r.w > 0.5) || !all(abs(r.xy) < vec2<f32>(1e7)) || !(m < 1.0)) {
        return ep;
    }
    let other_dims = vec2<i32>(textureDimensions(e_other));
    let c = vec2<i32>(floor(r.xy));
    var best = 0.0;
    for (var dy = -2; dy <= 2; dy = dy + 1) {
        for (var dx = -2; dx <= 2; dx = dx + 1) {
            let q = c + vec2<i32>(dx, dy);
            if (all(q >= vec2<i32>(0)) && all(q < other_dims)) {
                best = max(best, textureLoad(e_other, q, 0).r);
            }
        }
    }
    return min(ep, m + (1.0 - m) * best);
}
