//! WGSL text every pass kind may include: the helper functions the emitter calls (`npr_load`, `npr_project`,
//! `npr_project_dir`, `npr_unit`; the `Frame` block is `abi::FRAME_WGSL`). Constants only; which module includes
//! which is decided in `mod.rs` and the per-kind files.

/// `project(p)` and `project_other_eye(p)`.
pub(super) const PROJECT_HELPER: &str = "// World point -> (screen u, screen v, NDC depth) under `view_proj`; w <= 0
// (behind the eye) maps far outside the screen.
fn npr_project(view_proj: mat4x4<f32>, p: vec3<f32>) -> vec3<f32> {
    let c = view_proj * vec4<f32>(p, 1.0);
    if (c.w <= 1e-8) {
        return vec3<f32>(-1e9, -1e9, 1.0);
    }
    let ndc = c.xyz / c.w;
    return vec3<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5, ndc.z);
}
";

/// Target reads as values (nearest texel at `screen_uv`).
pub(super) const LOAD_HELPER: &str = "// Nearest texel of `t` at `uv`, so targets of different scales line up.
fn npr_load(t: texture_2d<f32>, uv: vec2<f32>) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(t));
    let p = clamp(vec2<i32>(floor(uv * vec2<f32>(dims))), vec2<i32>(0), dims - vec2<i32>(1));
    return textureLoad(t, p, 0);
}
";

/// The analytic Jacobian of projection + viewport applied to a world direction.
pub(super) const PROJECT_DIR_HELPER: &str =
    "// Pixels moved per metre along world direction `dir` at `world`: the derivative of
// pixel = (ndc.x, -ndc.y) * size / 2 + size / 2 with ndc = clip.xy / clip.w (quotient rule).
// Screen y points down, like frag_coord and dpdy.
fn npr_project_dir(vp: mat4x4<f32>, world: vec4<f32>, dir: vec3<f32>, size: vec2<f32>) -> vec2<f32> {
    let c = vp * world;
    let d = vp * vec4<f32>(dir, 0.0);
    // Behind or on the eye plane the triangle is clipped; stay finite.
    let w = max(c.w, 1e-6);
    let dndc = (d.xy * w - c.xy * d.w) / (w * w);
    return vec2<f32>(dndc.x, -dndc.y) * 0.5 * size;
}

";

/// Normalisation that never makes NaN: render passes' builtins use it.
pub(super) const UNIT_HELPER: &str = "// Unit vector, or zero for a zero input (never NaN).
fn npr_unit(v: vec3<f32>) -> vec3<f32> {
    return v * inverseSqrt(max(dot(v, v), 1e-30));
}

";
