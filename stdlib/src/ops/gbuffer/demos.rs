//! The G-buffer packing operators' demos (`npr doc` renders them; see
//! [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const OCT_ENCODE: Demo = render(
    "The world normals of the spheres scene octahedrally encoded by `oct_encode`, as colour (red, green = the two components): two numbers per pixel that still tell every direction apart.",
    "scenes/spheres.toml",
    r#"style "oct_encode demo"
pass shade: render(scene) {
  out color: rgba8unorm = vec4(oct_encode(normal) * 0.5 + 0.5, 0.0, 1.0)
  clear: #000000
}
output shade.color
"#,
);

pub const OCT_DECODE: Demo = render(
    "Half-Lambert shading of Spot the cow computed in an image pass from normals packed into an rg16float G-buffer and unpacked by `oct_decode`: the same shading as from full normals.",
    "scenes/spot.toml",
    r#"style "oct_decode demo"
pass gbuffer: render(scene) {
  out n: rg16float = oct_encode(normal)
  out mask: r8unorm = 1.0
}
pass shade: image(gbuffer) {
  let lit = half_lambert(oct_decode(gbuffer.n), light.dir)
  out color: rgba8unorm = mix(#202020, mix(#2b2540, #f0e6d2, lit), gbuffer.mask)
}
output shade.color
"#,
);
