// The complex product a·b of 2D vectors read as complex numbers (Breslav
// et al. 2007 §3.2): rotates b by the angle of a and scales it by |a|.
fn npr_complex_mul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}
