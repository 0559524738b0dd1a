//! The WGSL the runner's own fullscreen draws share (the host-depth draw,
//! the host-input conversion, presenting into a host's views, the
//! half-rounding probe): one vertex stage that covers the target with a
//! single triangle from the vertex index alone (no vertex buffer), and the
//! sRGB transfer functions. They are macros that expand to string
//! literals, so a module's WGSL stays a `const` built with `concat!`.

/// `vs`: the triangle (−1, 1), (3, 1), (−1, −3) in clip space, which
/// covers the target; fragments see their pixel in `@builtin(position)`.
/// Draw it with `draw(0..3, 0..1)` and no vertex buffers.
macro_rules! fullscreen_vertex_wgsl {
    () => {
        "
@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
}
"
    };
}

/// The sRGB transfer function (IEC 61966-2-1) both ways, as `crate::srgb`
/// computes them on the CPU: `srgb_to_linear` (the EOTF, what an sRGB
/// view's load does) and `linear_to_srgb` (what its store does).
macro_rules! srgb_wgsl {
    () => {
        "
fn srgb_to_linear(x: f32) -> f32 {
    if x <= 0.04045 {
        return x / 12.92;
    }
    return pow((x + 0.055) / 1.055, 2.4);
}

fn linear_to_srgb(x: f32) -> f32 {
    if x <= 0.0031308 {
        return x * 12.92;
    }
    return 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}
"
    };
}

pub(crate) use {fullscreen_vertex_wgsl, srgb_wgsl};
