//! The fixed head of the per-object uniform block (`struct Object`, group 1
//! binding 0 of every pass that runs per object): one `#[repr(C)]` struct,
//! [`ObjectHead`], which the runner fills, and the WGSL members
//! [`OBJECT_HEAD_WGSL`] the compiler declares before the per-object
//! parameter slots, from one field list. The parameter slots start at
//! [`crate::manifest::OBJECT_PARAMS_OFFSET`], the head's size.

use crate::block::{render, uniform_block};
pub use crate::block::{BlockField, Mat4x4, UVec4};

uniform_block! {
    /// The head of the `Object` block, byte for byte.
    struct ObjectHead;
    fields OBJECT_HEAD_FIELDS;
    model: Mat4x4 = "mat4x4<f32>";
    /// Inverse transpose of `model` (the identity where `model` is singular).
    normal_matrix: Mat4x4 = "mat4x4<f32>";
    /// `model` in the previous frame this renderer began (= model on the
    /// first frame and after a reset): `position.previous`.
    previous_model: Mat4x4 = "mat4x4<f32>";
    ids: UVec4 = "vec4<u32>", "x: index, y: id (index + 1), z: vertex count, w: 0";
}

const LEN: usize = render::<4096>("", OBJECT_HEAD_FIELDS, "").len;
const BYTES: [u8; LEN] = render::<LEN>("", OBJECT_HEAD_FIELDS, "").bytes;

/// The WGSL members of [`ObjectHead`], one per line, to open `struct Object`.
pub const OBJECT_HEAD_WGSL: &str = crate::block::as_str(&BYTES);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_head_is_208_bytes_without_padding() {
        assert_eq!(core::mem::size_of::<ObjectHead>(), 208);
        let sum: usize = OBJECT_HEAD_FIELDS.iter().map(|f| f.size).sum();
        assert_eq!(sum, core::mem::size_of::<ObjectHead>());
        assert_eq!(crate::manifest::OBJECT_PARAMS_OFFSET, 208);
        assert!(OBJECT_HEAD_WGSL.starts_with("    model: mat4x4<f32>,\n"));
    }
}
