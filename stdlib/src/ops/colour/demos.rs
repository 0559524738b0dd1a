//! The colour operators' demos (`npr doc` renders them; see [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const OVER: Demo = render(
    "Half-transparent red stripes composited over the shaded spheres scene with `over`: the shading shows through them.",
    "scenes/spheres.toml",
    r#"style "over demo"
object param tint: color = #ffffff
pass shade: render(scene) {
  let bg = mix(#202030, tint, half_lambert(normal, light.dir))
  let fg = vec4(0.9, 0.1, 0.1, 0.6 * step(0.5, fract(frag_coord.x / 16px)))
  out color: rgba8unorm = over(fg, bg)
  clear: #808080
}
output shade.color
"#,
);

pub const LUMINANCE: Demo = render(
    "The tinted spheres scene: the left half in colour, the right half its luminance as grey.",
    "scenes/spheres.toml",
    r#"style "luminance demo"
object param tint: color = #ffffff
pass shade: render(scene) {
  let c = mix(#203060, tint, half_lambert(normal, light.dir))
  let y = luminance(c)
  out color: rgba8unorm = if screen_uv.x < 0.5 { c } else { vec4(y, y, y, 1.0) }
  clear: #808080
}
output shade.color
"#,
);

pub const SATURATION: Demo = render(
    "The tinted spheres scene: the left half with saturation 0.2 (nearly grey), the right half with saturation 2.5.",
    "scenes/spheres.toml",
    r#"style "saturation demo"
object param tint: color = #ffffff
pass shade: render(scene) {
  let c = mix(#203060, tint, half_lambert(normal, light.dir))
  out color: rgba8unorm = if screen_uv.x < 0.5 { saturation(c, amount: 0.2) } else { saturation(c, amount: 2.5) }
  clear: #808080
}
output shade.color
"#,
);

pub const OVERLAY: Demo = render(
    "The tinted spheres scene overlaid with blue (Age of Sail's shadow colour control): the left half untouched, the right half overlaid at opacity 0.8.",
    "scenes/spheres.toml",
    r#"style "overlay demo"
object param tint: color = #ffffff
pass shade: render(scene) {
  let c = mix(#403020, tint, half_lambert(normal, light.dir))
  out color: rgba8unorm = if screen_uv.x < 0.5 { c } else { overlay(c, #3c4f9a, opacity: 0.8) }
  clear: #808080
}
output shade.color
"#,
);
