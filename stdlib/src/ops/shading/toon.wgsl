// N-step quantization: x in [0, 1] falls into one of `steps` equal bands;
// band k of n maps to k / (n - 1), so 0 stays 0 and 1 stays 1 (one step: 0).
fn npr_toon(x: f32, steps: i32) -> f32 {
    let n = f32(max(steps, 1));
    let band = min(floor(clamp(x, 0.0, 1.0) * n), n - 1.0);
    return select(0.0, band / (n - 1.0), n > 1.0);
}
