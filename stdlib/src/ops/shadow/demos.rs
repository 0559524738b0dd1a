//! `shadow`'s demo (`npr doc` renders it; see [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const SHADOW: Demo = render(
    "A sphere and a torus lit low from the left, casting shadows to the right onto the ground: Lambert shading times the shadow-map visibility (PCF radius 1) from a light-view depth pass.",
    "scenes/spheres_shadows.toml",
    r#"style "shadow demo"
pass depth: render(caster) view(light) {
  out d: r32float = position.light.z
  clear: #ffffff
}
pass shade: render(scene) {
  let lit = lambert(normal, light.dir) * shadow(depth.d, bias: 0.004, radius: 1)
  out color: rgba8unorm = mix(#2b2540, #f0e6d2, lit)
  clear: #e8e4da
}
output shade.color
"#,
);
