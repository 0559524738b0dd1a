//! f64 references of the art-map operators: the level of detail that
//! `sample_biased` selects (the isotropic LOD of the WebGPU/Vulkan
//! specifications: log2 of the longer screen-derivative footprint in
//! texels, plus the bias), and the level per axis of `sample_ripmap`.

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

/// The levels (along u, along v) `sample_ripmap` selects, unclamped: per
/// axis, log2 of the larger screen derivative of that coordinate in level-0
/// texels.
pub fn sample_ripmap_lods(duv_dx: [f64; 2], duv_dy: [f64; 2], width: u32, height: u32) -> [f64; 2] {
    [
        (duv_dx[0].abs().max(duv_dy[0].abs()) * width as f64).log2(),
        (duv_dx[1].abs().max(duv_dy[1].abs()) * height as f64).log2(),
    ]
}

/// The value a rip-map read gives of an atlas whose level (i, j) is the
/// constant `(i·step, j·step)`: the two levels, clamped, times `step`.
pub fn sample_ripmap(lods: [f64; 2], levels: [u32; 2], step: f64) -> [f64; 2] {
    [
        lods[0].clamp(0.0, (levels[0] - 1) as f64) * step,
        lods[1].clamp(0.0, (levels[1] - 1) as f64) * step,
    ]
}
