// Smooth threshold band: 0 below lo, 1 above hi, smoothstep between; a hard
// step at lo when the band is empty (lo >= hi), never NaN.
fn npr_threshold(x: f32, lo: f32, hi: f32) -> f32 {
    if (hi <= lo) {
        return select(0.0, 1.0, x >= lo);
    }
    let t = clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}
