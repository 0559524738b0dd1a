//! The dynamic 2D patterns' demos (`npr doc` renders them; see
//! [`crate::ops::Demo`]). The tracker of `examples/lib/dynamic_pattern.npr`
//! needs several frames of motion to show anything, so each demo shows its
//! operator in a single frame: the halftones on the shaded spheres, the
//! pattern frame and its complex multiply as a grid, `id_share` on an ID image.

use crate::ops::{render, Demo};

pub const ID_SHARE: Demo = render(
    "The share of ID-image texels within 4 px that belong to the sphere (object 1) in the spheres scene: white inside it, a soft ramp across its outline, black elsewhere.",
    "scenes/spheres.toml",
    r#"style "id_share demo"
pass ids: render(scene) {
  out id: r32float = object.id
}
pass show: image(ids) {
  let s = id_share(ids.id, screen_uv, 1.0, 4px)
  out color: rgba8unorm = vec4(s, s, s, 1.0)
}
output show.color
"#,
);

pub const COMPLEX_MUL: Demo = render(
    "A grid of pattern coordinates multiplied by the complex number 1.2·e^(i·30°) with `complex_mul`: the grid turned by 30° and scaled 1.2× about the image centre.",
    "scenes/spheres.toml",
    r#"style "complex_mul demo"
pass show: image() {
  let q = (frag_coord - resolution * 0.5) / 12px
  let z = complex_mul(vec2(1.2 * cos(30deg), 1.2 * sin(30deg)), q)
  let d = abs(fract(z + 0.5) - 0.5)
  let line = 1.0 - smoothstep(0.04, 0.1, min(d.x, d.y))
  out color: rgba8unorm = mix(#f5f0e1, #1f2a44, line)
}
output show.color
"#,
);

pub const PATTERN_UV: Demo = render(
    "Pattern coordinates from an origin and two basis vectors (u = (14, 5) px, v = (−4, 11) px) with `pattern_uv`: a skewed grid of cells, one per unit square.",
    "scenes/spheres.toml",
    r#"style "pattern_uv demo"
pass show: image() {
  let p = pattern_uv(vec2(64.0, 48.0), vec2(14.0, 5.0), vec2(-4.0, 11.0))
  let checker = step(0.5, fract((floor(p.x) + floor(p.y)) * 0.5))
  out color: rgba8unorm = mix(#f5f0e1, #1f2a44, checker * 0.8)
}
output show.color
"#,
);

pub const HALFTONE_SCREEN: Demo = render(
    "The spheres' half-Lambert tone thresholded against the procedural dot screen (8 px cells): dots that grow into the shadows.",
    "scenes/spheres.toml",
    r#"style "halftone_screen demo"
pass shade: render(scene) {
  let s = halftone_screen(frag_coord / 8px)
  let paper = step(s, half_lambert(normal, light.dir))
  out color: rgba8unorm = mix(#1f2a44, #f5f0e1, paper)
  clear: #f5f0e1
}
output shade.color
"#,
);

pub const HALFTONE: Demo = render(
    "A tone-corrected halftone of the spheres' half-Lambert shading on a 6 px screen: the dots' mean darkness follows the tone.",
    "scenes/spheres.toml",
    r#"style "halftone demo"
texture dots = halftone_table(edge: 0.1)
pass shade: render(scene) {
  let paper = halftone(dots, frag_coord / 6px, half_lambert(normal, light.dir))
  out color: rgba8unorm = mix(#1f2a44, #f5f0e1, paper)
  clear: #f5f0e1
}
output shade.color
"#,
);
