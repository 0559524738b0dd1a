//! Image passes: the fullscreen-triangle vertex shader and the fragment
//! prologue. An image pass has no geometry and no per-object data; what it
//! reads (targets, textures, parameters) is declared by `bindings.rs`.

/// One triangle that covers the viewport, and the varyings it writes.
pub(super) const IMAGE_VERTEX: &str = "struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(linear) screen_uv: vec2<f32>,
}

// One triangle that covers the viewport; screen_uv is (0,0) at the top-left corner.
@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> Varyings {
    let p = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    var out: Varyings;
    out.clip = vec4<f32>(p * 2.0 - vec2<f32>(1.0), 0.0, 1.0);
    out.screen_uv = vec2<f32>(p.x, 1.0 - p.y);
    return out;
}

";

/// The fragment shader's opening: `screen_uv` is the interpolated varying.
pub(super) const FRAGMENT_PROLOGUE: &str = "@fragment\nfn fs_main(in: Varyings) -> FragOut {\n";
