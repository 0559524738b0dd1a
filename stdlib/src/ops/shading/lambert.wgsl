// Lambert diffuse term max(n·l, 0) with both vectors normalized; a zero
// vector gives 0 instead of NaN.
fn npr_lambert(n: vec3<f32>, l: vec3<f32>) -> f32 {
    let nn = n * inverseSqrt(max(dot(n, n), 1e-30));
    let ll = l * inverseSqrt(max(dot(l, l), 1e-30));
    return max(dot(nn, ll), 0.0);
}
