//! Emit: WGSL per pass and the manifest.

pub mod manifest;
pub mod wgsl;
