// Live texture (Age of Sail §6.1, eqs. 27–30): T' = L₀ + (T·L₁) cos(ft) + (T·L₂) sin(ft)
// with L₀ = (½, ½, ½), L₁ = (0.707, 0, −0.707), L₂ = (−0.408, 0.816, −0.408).
// f is in cycles per second, so the phase "ft" is 2π·f·t (one full cycle per 1/f s).
// T·L₁ and T·L₂ are scalars, so T' has three equal components: the scalar is returned.
// L₁, L₂ are orthonormal and ⟂ (1,1,1): for channels with equal means and
// variances and no correlation, the mean stays ½ + … and the variance is constant in t.
fn npr_live_texture(t: vec4<f32>, freq: f32, time: f32) -> f32 {
    let l1 = vec3<f32>(0.707, 0.0, -0.707);
    let l2 = vec3<f32>(-0.408, 0.816, -0.408);
    // fract keeps the phase accurate in f32 for long times.
    let phase = 6.283185307179586 * fract(freq * time);
    return 0.5 + dot(t.rgb, l1) * cos(phase) + dot(t.rgb, l2) * sin(phase);
}
