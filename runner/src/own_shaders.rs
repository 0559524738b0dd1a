//! The WGSL modules the runner writes itself, beside the styles' that the
//! compiler emits: the deformation stage, the host-input conversion draw,
//! the host depth draw, the present draw and the half-rounding probe. Listed so that a test can
//! give each to a compiler other than naga, as it does every style's
//! module (Chromium's Tint: `tests/general/webgpu_portability.rs`): they
//! run wherever the runtime does, a browser's WebGPU included.

/// Each module's name (its file, or the file that holds it) and text.
pub fn all() -> Vec<(&'static str, String)> {
    vec![
        ("exec/deform.wgsl", crate::exec::deform::DEFORM_WGSL.to_string()),
        ("inputs/gpu.rs", crate::inputs::gpu::CONVERT_WGSL.to_string()),
        ("embed/present.rs", crate::embed::present::PRESENT_WGSL.to_string()),
        ("half_rounding.rs", crate::half_rounding::SHADER.to_string()),
        ("exec/host_depth.rs", crate::exec::host_depth_wgsl()),
    ]
}
