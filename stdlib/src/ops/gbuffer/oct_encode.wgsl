// Octahedral encoding of a normal for a 2-channel G-buffer target (Cigolle
// et al. 2014 §3.1, signed variant; see oct.wgsl).
fn npr_oct_encode(n: vec3<f32>) -> vec2<f32> {
    return npr_oct__encode(n);
}
