// Radial-angle compensation α (Age of Sail §3.3, eqs. 12–13): Q = (s_x/P₀₀, s_y/P₁₁)
// with s the NDC position, α = |Q|² + 1. Q is the tangent of the view ray's angle
// off the optical axis, so α = 1/cos²θ and `width · α` (eq. 11) keeps a texture's
// angular size constant across a wide field of view.
fn npr_radial_alpha(screen_uv: vec2<f32>, focal: vec2<f32>) -> f32 {
    let s = vec2<f32>(screen_uv.x * 2.0 - 1.0, 1.0 - screen_uv.y * 2.0);
    // A degenerate projection (P₀₀ or P₁₁ → 0) must not divide by zero.
    let f = max(abs(focal), vec2<f32>(1e-6));
    let q = s / f;
    let a = dot(q, q) + 1.0;
    // A NaN screen position (e.g. a varying of a triangle clipped at the eye plane) gives α = 1.
    return select(min(a, 1e12), 1.0, !(a >= 1.0));
}
