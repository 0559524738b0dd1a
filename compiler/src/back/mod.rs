//! The back end: physical textures and uniform blocks for the live IR
//! (`allocate`), WGSL and the manifest (`emit`), and naga's validation of
//! every module emitted (`validate`; a failure is a compiler bug).

pub mod allocate;
pub mod emit;
pub mod validate;
