//! The WGSL modules the runner writes itself, beside the styles' that the
//! compiler emits: the deformation stage, the host-input conversion draw,
//! the present draw and the half-rounding probe. Listed so that a test can
//! give each to a compiler other than naga, as it does every style's
//! module (Chromium's Tint: `tests/general/webgpu_portability.rs`): they
//! run wherever the runtime does, a browser's WebGPU included.

/// Each module's name (its file, or the file that holds it) and text.
pub const ALL: &[(&str, &str)] = &[
    ("exec/deform.wgsl", crate::exec::deform::DEFORM_WGSL),
    ("inputs/gpu.rs", crate::inputs::gpu::CONVERT_WGSL),
    ("embed/present.rs", crate::embed::present::PRESENT_WGSL),
    ("half_rounding.rs", crate::half_rounding::SHADER),
];
