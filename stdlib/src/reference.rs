//! CPU reference implementations in f64, one per operator, for the accuracy
//! tests. They follow the WGSL line by line in meaning, not in precision:
//! the GPU runs in f32 and the tests state the tolerance they allow.
//!
//! Each operator's reference lives with it in `stdlib/src/ops/<family>/`
//! (under the operator's own name), on the shared image type of
//! `image_f64`; this module re-exports every reference so that
//! `npr_stdlib::reference::<name>` reaches it.

pub use crate::image_f64::{sample_repeat, ImageF64};
pub use crate::ops::artmaps::reference::*;
pub use crate::ops::breakup::reference::*;
pub use crate::ops::colour::{luminance, over, overlay, saturation};
pub use crate::ops::filters::{downsample, gaussian, normal_depth_edges, sobel, GAUSSIAN_MAX_RADIUS};
pub use crate::ops::gbuffer::reference::{oct_decode, oct_encode};
pub use crate::ops::metatexture::reference::*;
pub use crate::ops::patterns::reference::*;
pub use crate::ops::sample::sample;
pub use crate::ops::shading::{half_lambert, lambert, threshold, toon};

/// Does operator `name` have an f64 reference (is it registered in [`crate::ops`])?
pub fn has_reference(name: &str) -> bool {
    crate::ops::find(name).is_some()
}
