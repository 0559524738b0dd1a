// Animated line boil (Age of Sail §4.2): a periodically changing offset of the
// texture coordinates. The offset changes `rate` times per second (12 Hz at
// 24 fps is "on twos") and repeats every `cycle` steps; step k moves uv by
// amount · R(k), R the R₂ low-discrepancy sequence (fract(k·(1/φ₂, 1/φ₂²))), so
// consecutive drawings differ as much as possible.
fn npr_line_boil(uv: vec2<f32>, amount: f32, rate: f32, cycle: i32, time: f32) -> vec2<f32> {
    let n = f32(max(cycle, 1));
    // 1e-3 of a step absorbs f32 rounding of frame times (e.g. 1/24 s · 12 Hz).
    let s = floor(time * max(rate, 0.0) + 1e-3);
    let k = s - n * floor(s / n);
    let r = fract(k * vec2<f32>(0.7548776662466927, 0.5698402909980532));
    return uv + amount * r;
}
