// Approximate smooth screen-space UV gradients (Age of Sail §3.2, eqs. 9–10):
// ∇_s u = |∇_w u| T_s / |T_s|², ∇_s v = |∇_w v| B_s / |B_s|², where T_s, B_s are the
// screen-space projections (px per metre) of the unit tangent and bitangent,
// computed per vertex and interpolated, and |∇_w u|, |∇_w v| the world-space UV
// densities (UV per metre, constant per mesh as in the paper).
// Returns (∇u.x, ∇u.y, ∇v.x, ∇v.y) in UV per px, for `metatexture_grad`.
fn npr_uv_gradients(tangent: vec2<f32>, bitangent: vec2<f32>, density: vec2<f32>) -> vec4<f32> {
    // |T_s| → 0 (tangent along the view ray, or a zero tangent): the gradient
    // grows to 1e20·density but stays finite; MetaTexture clamps its scale.
    let gu = abs(density.x) * tangent / max(dot(tangent, tangent), 1e-20);
    let gv = abs(density.y) * bitangent / max(dot(bitangent, bitangent), 1e-20);
    return clamp(vec4<f32>(gu, gv), vec4<f32>(-1e30), vec4<f32>(1e30));
}
