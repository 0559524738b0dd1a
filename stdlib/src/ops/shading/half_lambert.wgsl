// Valve's half-Lambert: (0.5·(n·l) + 0.5)², which keeps shape in the shadow side.
fn npr_half_lambert(n: vec3<f32>, l: vec3<f32>) -> f32 {
    let nn = n * inverseSqrt(max(dot(n, n), 1e-30));
    let ll = l * inverseSqrt(max(dot(l, l), 1e-30));
    let h = 0.5 * dot(nn, ll) + 0.5;
    return h * h;
}
