//! The generated WGSL `struct Frame` and the Rust `FrameBlock` agree byte for
//! byte: naga's layouter (WGSL's uniform layout rules) puts every member at
//! the offset `offset_of!` gives, and the struct sizes are equal.

use npr_abi::frame::{FrameBlock, FRAME_FIELDS};
use npr_abi::FRAME_WGSL;

#[test]
fn frame_layout_matches_naga() {
    let source = format!(
        "{FRAME_WGSL}@group(0) @binding(0) var<uniform> frame: Frame;\n\
         @fragment fn main() -> @location(0) vec4<f32> {{ return frame.camera_pos + frame.eye_left; }}\n"
    );
    let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{e:?}"));
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layout");
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Frame"))
        .expect("struct Frame");
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("Frame is not a struct");
    };
    assert_eq!(members.len(), FRAME_FIELDS.len());
    for (m, f) in members.iter().zip(FRAME_FIELDS) {
        assert_eq!(m.name.as_deref(), Some(f.name));
        assert_eq!(m.offset as usize, f.offset, "offset of `{}`", f.name);
        assert_eq!(layouter[m.ty].size as usize, f.size, "size of `{}`", f.name);
    }
    assert_eq!(*span as usize, core::mem::size_of::<FrameBlock>());
    assert_eq!(layouter[handle].size as usize, core::mem::size_of::<FrameBlock>());
    assert_eq!(npr_abi::FRAME_UNIFORM_SIZE as usize, core::mem::size_of::<FrameBlock>());
    // Spot checks of `offset_of!` itself, against the fields by name.
    assert_eq!(core::mem::offset_of!(FrameBlock, resolution), 240);
    assert_eq!(core::mem::offset_of!(FrameBlock, light_view_proj), 272);
    assert_eq!(core::mem::offset_of!(FrameBlock, camera_forward), 512);
}
