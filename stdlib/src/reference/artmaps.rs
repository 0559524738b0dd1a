//! f64 references of the art-map operators: the level of detail that
//! `sample_biased` selects (the isotropic LOD of the WebGPU/Vulkan
//! specifications: log2 of the longer screen-derivative footprint in
//! texels, plus the bias).

/// The level of detail of a read at `uv` whose screen derivatives are
/// `duv_dx`, `duv_dy` (uv per pixel), on a `width × height` level 0, with
/// `bias` levels added; not clamped to the levels the texture has.
pub fn sample_biased_lod(duv_dx: [f64; 2], duv_dy: [f64; 2], width: u32, height: u32, bias: f64) -> f64 {
    let texels = |d: [f64; 2]| (d[0] * width as f64).hypot(d[1] * height as f64);
    texels(duv_dx).max(texels(duv_dy)).log2() + bias
}

/// The value a trilinear read gives of a texture whose level i is the
/// constant `i as f64 * step`: the LOD clamped to the levels, times `step`.
pub fn sample_biased(lod: f64, levels: u32, step: f64) -> f64 {
    lod.clamp(0.0, (levels - 1) as f64) * step
}
