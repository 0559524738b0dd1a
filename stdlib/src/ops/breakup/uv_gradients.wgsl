// Smooth screen-space UV gradients from the per-vertex screen-space tangent
// frame (Age of Sail §3.2): T_s, B_s are the projections (px per metre) of the
// unit tangent and bitangent, computed per vertex and interpolated, and
// |∇_w u|, |∇_w v| the world-space UV densities (UV per metre, constant per mesh
// as in the paper). Returns (∇u.x, ∇u.y, ∇v.x, ∇v.y) in UV per px.
// mode 0 (inverse): the rows of [T_s B_s]⁻¹ scaled by the densities: the true
//   gradients when u and v run along orthogonal world directions. ∇u ⟂ B_s.
// mode 1 (paper): eqs. 9–10 as printed, ∇_s u = |∇_w u| T_s / |T_s|²: ∇u ∥ T_s,
//   so on a skewed view |∇u| is too small by sin∠(T_s, B_s) and ∇u·∇v has the
//   opposite sign of the true one (see reference::SKEW_SIGN).
fn npr_uv_gradients(tangent: vec2<f32>, bitangent: vec2<f32>, density: vec2<f32>, mode: i32) -> vec4<f32> {
    let rho = abs(density);
    if (mode == 1) {
        // |T_s| → 0 (tangent along the view ray, or a zero tangent) gives 0, not NaN.
        let gu = rho.x * tangent / max(dot(tangent, tangent), 1e-20);
        let gv = rho.y * bitangent / max(dot(bitangent, bitangent), 1e-20);
        return clamp(vec4<f32>(gu, gv), vec4<f32>(-1e30), vec4<f32>(1e30));
    }
    let det = tangent.x * bitangent.y - tangent.y * bitangent.x;
    // Edge-on (T_s ∥ B_s) the gradients grow without bound: keep them finite.
    let d = select(-1.0, 1.0, det >= 0.0) * max(abs(det), 1e-20);
    let gu = rho.x * vec2<f32>(bitangent.y, -bitangent.x) / d;
    let gv = rho.y * vec2<f32>(-tangent.y, tangent.x) / d;
    return clamp(vec4<f32>(gu, gv), vec4<f32>(-1e30), vec4<f32>(1e30));
}
