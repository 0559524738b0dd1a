// Reprojection mask M_{i,j} (LSA contours §4.2, eqs. 9–11). `reproj` holds,
// per pixel p_i of this eye, R_{i,j}(p_i): its surface point's fractional
// pixel position in the other eye (pixel centres at +0.5), w = 1 on geometry
// and 0 on background; `reproj_other` is the same target of the other eye,
// R_{j,i}. Eq. 9: D = R_{j,i}([R_{i,j}(p)]) − p, the round trip; eq. 10:
// J(p, q) = (R_{i,j}(q) − R_{i,j}(p)) − (q − p) for the 8 neighbours q;
// eq. 11: M = max(m(|D|), n(max_q |J|)), m and n linear maps of
// [m_lo, m_hi] and [n_lo, n_hi] px onto [0, 1] (paper: [2, 4] and [3, 6]).
// M = 1 (no correspondence to enforce) where p or its round trip leaves the
// geometry or the other image, or a neighbour is background.
fn npr_reprojection_mask(reproj: texture_2d<f32>, reproj_other: texture_2d<f32>, uv: vec2<f32>, m_lo: f32, m_hi: f32, n_lo: f32, n_hi: f32) -> f32 {
    let dims = vec2<i32>(textureDimensions(reproj));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    let r = textureLoad(reproj, p, 0);
    if (!(r.w > 0.5) || !all(abs(r.xy) < vec2<f32>(1e7))) {
        return 1.0;
    }
    let other_dims = vec2<i32>(textureDimensions(reproj_other));
    // [R_{i,j}(p)]: the pixel of the other eye that contains the reprojection.
    let pj = vec2<i32>(floor(r.xy));
    if (any(pj < vec2<i32>(0)) || any(pj >= other_dims)) {
        return 1.0;
    }
    let back = textureLoad(reproj_other, pj, 0);
    if (!(back.w > 0.5)) {
        return 1.0;
    }
    let d = length(back.xy - (vec2<f32>(p) + vec2<f32>(0.5)));
    var j_max = 0.0;
    for (var dy = -1; dy <= 1; dy = dy + 1) {
        for (var dx = -1; dx <= 1; dx = dx + 1) {
            let q = p + vec2<i32>(dx, dy);
            if ((dx == 0 && dy == 0) || any(q < vec2<i32>(0)) || any(q >= dims)) {
                continue;
            }
            let rq = textureLoad(reproj, q, 0);
            if (!(rq.w > 0.5)) {
                j_max = 1e9;
                continue;
            }
            let j = (rq.xy - r.xy) - vec2<f32>(f32(dx), f32(dy));
            j_max = max(j_max, length(j));
        }
    }
    let m = clamp((d - m_lo) / max(m_hi - m_lo, 1e-6), 0.0, 1.0);
    let n = clamp((j_max - n_lo) / max(n_hi - n_lo, 1e-6), 0.0, 1.0);
    // NaN-safe: a NaN comparison above returned 1 already; here both are finite.
    return max(m, n);
}
