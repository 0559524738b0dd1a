//! The per-frame uniform block: one `#[repr(C)]` Rust struct, [`FrameBlock`],
//! which the runner fills and uploads with `bytemuck::bytes_of`, and the WGSL
//! `struct Frame` every shader that reads it declares, [`FRAME_WGSL`]. Both
//! come from the one field list in the `frame_block!` invocation below, so a
//! field cannot be added to one and not the other.
//!
//! Every field is 4-byte aligned in Rust and placed where WGSL's uniform
//! layout rules put it (matrices and `vec4`s at multiples of 16, the `vec2`
//! at a multiple of 8), so the Rust struct has no padding; the test
//! `frame_layout_matches_naga` checks every offset against naga's layouter.
//!
//! The block grows only at its end (see ARCHITECTURE.md).

use bytemuck::{Pod, Zeroable};

/// A WGSL `mat4x4<f32>`, column-major (`glam::Mat4::to_cols_array_2d`).
pub type Mat4x4 = [[f32; 4]; 4];
/// A WGSL `vec4<f32>`.
pub type Vec4 = [f32; 4];
/// A WGSL `vec2<f32>`.
pub type Vec2 = [f32; 2];

/// One member of the frame block, as the WGSL text and the layout test see it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameField {
    pub name: &'static str,
    /// The WGSL type (`mat4x4<f32>`, `vec4<f32>`, `vec2<f32>`, `f32`).
    pub wgsl: &'static str,
    /// Comment lines above the member (the Rust field's doc lines).
    pub above: &'static [&'static str],
    /// The comment after the member; empty for none.
    pub trailing: &'static str,
    /// Byte offset in [`FrameBlock`].
    pub offset: usize,
    /// Byte size in [`FrameBlock`].
    pub size: usize,
}

/// Declares [`FrameBlock`] and [`FRAME_FIELDS`] from one list of
/// `name: RustType = "wgsl type" [, "trailing comment"];`, where `///` doc
/// lines above a field become comment lines above the WGSL member.
macro_rules! frame_block {
    ($( $(#[doc = $above:literal])* $name:ident : $rust:ty = $wgsl:literal $(, $trail:literal)? ; )*) => {
        /// The `Frame` uniform block (`struct Frame` in WGSL, [`FRAME_WGSL`]),
        /// byte for byte. Fill it and upload `bytemuck::bytes_of(&block)`.
        #[repr(C)]
        #[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
        pub struct FrameBlock {
            $(
                $(#[doc = $above])*
                $(#[doc = $trail])?
                pub $name: $rust,
            )*
        }

        /// The members of [`FrameBlock`] in order, with their WGSL types.
        pub const FRAME_FIELDS: &[FrameField] = &[
            $(
                FrameField {
                    name: stringify!($name),
                    wgsl: $wgsl,
                    above: &[$($above),*],
                    trailing: concat!("" $(, $trail)?),
                    offset: core::mem::offset_of!(FrameBlock, $name),
                    size: core::mem::size_of::<$rust>(),
                },
            )*
        ];
    };
}

frame_block! {
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
    _pad: f32 = "f32";
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
}

/// Trailing comments start in this column (or one space after a longer member).
const COMMENT_COLUMN: usize = 30;

/// A byte buffer written in a const context; counts past `N` without writing,
/// so a first run with a large `N` measures the text.
struct Text<const N: usize> {
    bytes: [u8; N],
    len: usize,
}

impl<const N: usize> Text<N> {
    const fn push(&mut self, s: &str) {
        let b = s.as_bytes();
        let mut i = 0;
        while i < b.len() {
            if self.len < N {
                self.bytes[self.len] = b[i];
            }
            self.len += 1;
            i += 1;
        }
    }

    const fn spaces(&mut self, n: usize) {
        let mut i = 0;
        while i < n {
            self.push(" ");
            i += 1;
        }
    }
}

/// `struct Frame { ... }` from [`FRAME_FIELDS`]: 4-space indent, doc lines
/// as `//` lines above, trailing comments from column 30.
const fn render<const N: usize>() -> Text<N> {
    let mut t = Text { bytes: [0; N], len: 0 };
    t.push("struct Frame {\n");
    let mut i = 0;
    while i < FRAME_FIELDS.len() {
        let f = &FRAME_FIELDS[i];
        let mut j = 0;
        while j < f.above.len() {
            t.push("    //");
            t.push(f.above[j]);
            t.push("\n");
            j += 1;
        }
        t.push("    ");
        t.push(f.name);
        t.push(": ");
        t.push(f.wgsl);
        t.push(",");
        if !f.trailing.is_empty() {
            let width = 4 + f.name.len() + 2 + f.wgsl.len() + 1;
            t.spaces(if width + 1 < COMMENT_COLUMN {
                COMMENT_COLUMN - width
            } else {
                1
            });
            t.push("// ");
            t.push(f.trailing);
        }
        t.push("\n");
        i += 1;
    }
    t.push("}\n");
    t
}

const FRAME_WGSL_LEN: usize = render::<8192>().len;
const FRAME_WGSL_BYTES: [u8; FRAME_WGSL_LEN] = render::<FRAME_WGSL_LEN>().bytes;

/// The WGSL declaration of `struct Frame`, generated from [`FrameBlock`]'s fields.
pub const FRAME_WGSL: &str = match core::str::from_utf8(&FRAME_WGSL_BYTES) {
    Ok(s) => s,
    Err(_) => panic!("FRAME_WGSL is not UTF-8"),
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_block_is_528_bytes_without_padding() {
        assert_eq!(core::mem::size_of::<FrameBlock>(), 528);
        let sum: usize = FRAME_FIELDS.iter().map(|f| f.size).sum();
        assert_eq!(sum, core::mem::size_of::<FrameBlock>());
        assert_eq!(crate::FRAME_UNIFORM_SIZE, 528);
    }

    #[test]
    fn trailing_comments_line_up() {
        assert!(FRAME_WGSL.contains("    light_dir: vec4<f32>,     // xyz: towards the light, w: intensity\n"));
        assert!(FRAME_WGSL.contains("    camera_forward: vec4<f32>, // xyz: unit view direction\n"));
        assert!(FRAME_WGSL.ends_with("}\n"));
    }
}
