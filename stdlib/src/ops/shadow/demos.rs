//! `shadow`'s demo (`npr doc` renders it; see [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const SHADOW: Demo = render(
    "Spot the cow and a lamp casting shadows onto the ground: Lambert shading times the shadow-map visibility (PCF radius 1) from a light-view depth pass.",
    "scenes/age_of_sail.toml",
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
