//! Image passes: the fullscreen-triangle vertex shader and the fragment
//! prologue. An image pass has no geometry and no per-object data; what it
//! reads (targets, textures, parameters) is declared by `bindings.rs`. A
//! tiled image pass (`tiled/`) shares the varyings and the prologue's
//! `screen_uv`, so both schedules see the same value at every pixel.

/// What the fragment (or a tiled pass's pixel function) receives.
pub(super) const IMAGE_VARYINGS: &str = "struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(linear) screen_uv: vec2<f32>,
}

";

/// One triangle that covers the viewport.
pub(super) const IMAGE_VERTEX: &str =
    "// One triangle that covers the viewport; screen_uv is (0,0) at the top-left corner.
@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> Varyings {
    let p = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    var out: Varyings;
    out.clip = vec4<f32>(p * 2.0 - vec2<f32>(1.0), 0.0, 1.0);
    out.screen_uv = vec2<f32>(p.x, 1.0 - p.y);
    return out;
}

";

/// The signature of an image pass's fragment shader (a tiled pass's pixel
/// function is `tiled/`'s).
pub(super) const FRAGMENT_SIGNATURE: &str = "@fragment\nfn fs_main(in_raw: Varyings) -> FragOut {\n";

/// The first lines of the function that computes one pixel: the fragment
/// shader, or (tiled) the function each invocation calls. `screen_uv` is
/// the pixel centre over the pass size, as in render passes: exact, where
/// the interpolated varying may be an ulp off, which a compute invocation
/// could not repeat.
pub(super) fn pixel_prologue(scale: f64) -> String {
    format!(
        "    var in = in_raw;\n    in.screen_uv = in_raw.clip.xy / {};\n",
        super::render::pass_size_wgsl(scale)
    )
}
