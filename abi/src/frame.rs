//! The per-frame uniform block: one `#[repr(C)]` Rust struct, [`FrameBlock`],
//! which the runner fills and uploads with `bytemuck::bytes_of`, and the WGSL
//! `struct Frame` every shader that reads it declares, [`FRAME_WGSL`]. Both
//! come from the one field list in the `uniform_block!` invocation below, so a
//! field cannot be added to one and not the other.
//!
//! Every field is 4-byte aligned in Rust and placed where WGSL's uniform
//! layout rules put it (matrices and `vec4`s at multiples of 16, the `vec2`
//! at a multiple of 8), so the Rust struct has no padding; the test
//! `frame_layout_matches_naga` checks every offset against naga's layouter.
//!
//! The block grows only at its end (docs/decisions/0011).
//!
//! ## The camera model (decision 0062)
//! `ortho_height` is 0 for a perspective camera and the view's height in
//! metres for an orthographic one. A view-space point (x, y, −d) has clip
//! w = d through a perspective projection and 1 through an orthographic
//! one, so the view-space point of a pixel at NDC (x_ndc, y_ndc) and depth
//! d is (x_ndc·w / P₀₀, y_ndc·w / P₁₁, −d) with P₀₀, P₁₁ in `focal.xy`; the
//! direction towards the eye is `camera_pos` − p for a perspective camera
//! and −`camera_forward` at every point for an orthographic one. Shaders,
//! the compiler's rebuilt positions and the runner's silhouette test all
//! follow this.

use crate::block::{render, uniform_block};
pub use crate::block::{BlockField, Mat4x4, Vec2, Vec4};

uniform_block! {
    /// The `Frame` uniform block (`struct Frame` in WGSL, [`FRAME_WGSL`]),
    /// byte for byte. Fill it and upload `bytemuck::bytes_of(&block)`.
    struct FrameBlock;
    fields FRAME_FIELDS;
    view: Mat4x4 = "mat4x4<f32>";
    proj: Mat4x4 = "mat4x4<f32>";
    view_proj: Mat4x4 = "mat4x4<f32>";
    camera_pos: Vec4 = "vec4<f32>";
    light_dir: Vec4 = "vec4<f32>", "xyz: towards the light, w: intensity";
    light_color: Vec4 = "vec4<f32>";
    resolution: Vec2 = "vec2<f32>", "output size in px";
    time: f32 = "f32", "seconds";
    frame_index: f32 = "f32";
    eye: f32 = "f32", "0 = left (or mono), 1 = right";
    near: f32 = "f32";
    far: f32 = "f32";
    ortho_height: f32 = "f32", "0: perspective; > 0: orthographic view height in m (decision 0062)";
    /// Orthographic light camera fitted to the scene bounds, for `view(light)`
    /// passes and `position.light` (z in [0, 1], w = 1).
    light_view_proj: Mat4x4 = "mat4x4<f32>";
    /// The other eye's view-projection in a stereo frame (= view_proj in mono).
    other_view_proj: Mat4x4 = "mat4x4<f32>";
    center_view_proj: Mat4x4 = "mat4x4<f32>", "stereo: the centre camera's view_proj (= view_proj in mono)";
    focal: Vec4 = "vec4<f32>", "xy: proj[0][0], proj[1][1] (camera.focal); zw: 0";
    eye_left: Vec4 = "vec4<f32>", "xyz: the left eye's position (= camera in mono)";
    eye_right: Vec4 = "vec4<f32>", "xyz: the right eye's position (= camera in mono)";
    camera_forward: Vec4 = "vec4<f32>", "xyz: unit view direction";
    /// The view-projection of the previous frame this renderer began (=
    /// view_proj on the first frame and after a reset): `project_previous`.
    previous_view_proj: Mat4x4 = "mat4x4<f32>";
    /// The scene's `[light2]`, `[light3]` and `[light4]` (`light2.dir` … in a
    /// style), as `light_dir` and `light_color`; all zero for an absent one.
    more_light_dir: [Vec4; 3] = "array<vec4<f32>, 3>", "light2..light4: xyz towards the light, w: intensity";
    more_light_color: [Vec4; 3] = "array<vec4<f32>, 3>";
}

const FRAME_WGSL_LEN: usize = render::<8192>("struct Frame {\n", FRAME_FIELDS, "}\n").len;
const FRAME_WGSL_BYTES: [u8; FRAME_WGSL_LEN] = render::<FRAME_WGSL_LEN>("struct Frame {\n", FRAME_FIELDS, "}\n").bytes;

/// The WGSL declaration of `struct Frame`, generated from [`FrameBlock`]'s fields.
pub const FRAME_WGSL: &str = crate::block::as_str(&FRAME_WGSL_BYTES);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_block_is_688_bytes_without_padding() {
        assert_eq!(core::mem::size_of::<FrameBlock>(), 688);
        let sum: usize = FRAME_FIELDS.iter().map(|f| f.size).sum();
        assert_eq!(sum, core::mem::size_of::<FrameBlock>());
        assert_eq!(crate::FRAME_UNIFORM_SIZE, 688);
    }

    #[test]
    fn trailing_comments_line_up() {
        assert!(FRAME_WGSL.contains("    light_dir: vec4<f32>,     // xyz: towards the light, w: intensity\n"));
        assert!(FRAME_WGSL.contains("    camera_forward: vec4<f32>, // xyz: unit view direction\n"));
        assert!(FRAME_WGSL.ends_with("}\n"));
    }
}
