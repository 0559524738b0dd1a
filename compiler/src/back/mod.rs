//! The back end: physical textures and uniform blocks for the live IR
//! (`allocate`), WGSL and the manifest (`emit`), naga's validation of
//! every module emitted (`validate`; a failure is a compiler bug), and what
//! the passes need of the device beyond WebGPU's defaults (`device_needs`).

pub mod allocate;
pub mod device_needs;
pub mod emit;
pub mod validate;
