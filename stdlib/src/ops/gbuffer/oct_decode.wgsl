// The unit vector of an octahedral code (Cigolle et al. 2014 §3.1, signed
// variant; see oct.wgsl).
fn npr_oct_decode(e: vec2<f32>) -> vec3<f32> {
    return npr_oct__decode(e);
}
