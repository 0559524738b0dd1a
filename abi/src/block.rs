//! The machinery shared by the fixed uniform blocks ([`crate::frame`],
//! [`crate::object`]): a `uniform_block!` macro that declares a `#[repr(C)]`
//! Rust struct and the list of its members with their WGSL types from one
//! field list, and [`render`], which writes the WGSL members in a const
//! context. A block's Rust and WGSL definitions therefore cannot drift
//! apart; each block's layout test checks the offsets with naga's layouter.

/// A WGSL `mat4x4<f32>`, column-major (`glam::Mat4::to_cols_array_2d`).
pub type Mat4x4 = [[f32; 4]; 4];
/// A WGSL `vec4<f32>`.
pub type Vec4 = [f32; 4];
/// A WGSL `vec2<f32>`.
pub type Vec2 = [f32; 2];
/// A WGSL `vec4<u32>`.
pub type UVec4 = [u32; 4];

/// One member of a uniform block, as the WGSL text and the layout test see it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlockField {
    pub name: &'static str,
    /// The WGSL type (`mat4x4<f32>`, `vec4<f32>`, `vec2<f32>`, `f32`, `vec4<u32>`).
    pub wgsl: &'static str,
    /// Comment lines above the member (the Rust field's doc lines).
    pub above: &'static [&'static str],
    /// The comment after the member; empty for none.
    pub trailing: &'static str,
    /// Byte offset in the Rust struct.
    pub offset: usize,
    /// Byte size in the Rust struct.
    pub size: usize,
}

/// Declares `#[repr(C)] struct $block` and `const $fields: &[BlockField]`
/// from one list of `name: RustType = "wgsl type" [, "trailing comment"];`,
/// where `///` doc lines above a field become comment lines above the WGSL
/// member.
macro_rules! uniform_block {
    ($(#[doc = $doc:literal])* struct $block:ident; fields $fields:ident;
     $( $(#[doc = $above:literal])* $name:ident : $rust:ty = $wgsl:literal $(, $trail:literal)? ; )*) => {
        $(#[doc = $doc])*
        #[repr(C)]
        #[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct $block {
            $(
                $(#[doc = $above])*
                // A trailing comment is WGSL's as much as rustdoc's: it may
                // write `proj[0][0]`, which is no link.
                $(#[doc = $trail] #[allow(rustdoc::broken_intra_doc_links)])?
                pub $name: $rust,
            )*
        }

        #[doc = concat!("The members of [`", stringify!($block), "`] in order, with their WGSL types.")]
        pub const $fields: &[$crate::block::BlockField] = &[
            $(
                $crate::block::BlockField {
                    name: stringify!($name),
                    wgsl: $wgsl,
                    above: &[$($above),*],
                    trailing: concat!("" $(, $trail)?),
                    offset: core::mem::offset_of!($block, $name),
                    size: core::mem::size_of::<$rust>(),
                },
            )*
        ];
    };
}
pub(crate) use uniform_block;

/// The WGSL text of a block: `head`, then the members of `fields` (4-space
/// indent, doc lines as `//` lines above, trailing comments from column
/// 30), then `tail`. Call it twice in a const context: once with a large
/// `N` to measure, once with the measured length.
pub(crate) const fn render<const N: usize>(head: &str, fields: &[BlockField], tail: &str) -> Text<N> {
    let mut t = Text { bytes: [0; N], len: 0 };
    t.push(head);
    let mut i = 0;
    while i < fields.len() {
        let f = &fields[i];
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
    t.push(tail);
    t
}

/// Trailing comments start in this column (or one space after a longer member).
const COMMENT_COLUMN: usize = 30;

/// A byte buffer written in a const context; counts past `N` without writing,
/// so a first run with a large `N` measures the text.
pub(crate) struct Text<const N: usize> {
    pub bytes: [u8; N],
    pub len: usize,
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

/// `&str` of the rendered bytes (WGSL text is ASCII, so this cannot fail
/// for a block whose names and comments are ASCII; a non-ASCII one fails
/// the build).
pub(crate) const fn as_str(bytes: &[u8]) -> &str {
    match core::str::from_utf8(bytes) {
        Ok(s) => s,
        Err(_) => panic!("a uniform block's WGSL is not UTF-8"),
    }
}
