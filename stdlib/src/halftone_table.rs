//! The halftone tone-correction table (Breslav et al. 2007 §3.5) is built by
//! the runtime from the manifest (`npr_abi::halftone::table`); this re-exports it
//! for the operators' references and converts it to and from the reference
//! images the GPU tests compare.

pub use npr_abi::halftone::table::*;

/// The table a 256 × 17 texture of [`HalftoneTable::texels`] holds
/// (channel r), as the shader reads it.
pub fn table_from_image(image: &crate::image_f64::ImageF64) -> HalftoneTable {
    assert_eq!(
        (image.width, image.height),
        (TONES as u32, ROWS as u32),
        "a halftone table texture"
    );
    let at = |i: usize, j: usize| image.pixels[j * TONES + i][0];
    HalftoneTable::from_thresholds(
        at(0, BLENDS),
        (0..BLENDS).map(|j| std::array::from_fn(|i| at(i, j))).collect(),
    )
}

/// The table as a 256 × 17 texture (f32 texels, in channel r).
pub fn table_image(table: &HalftoneTable) -> crate::image_f64::ImageF64 {
    let texels = table.texels();
    crate::image_f64::ImageF64::new(TONES as u32, ROWS as u32, |x, y| {
        [f64::from(texels[y as usize * TONES + x as usize]), 0.0, 0.0, 1.0]
    })
}
