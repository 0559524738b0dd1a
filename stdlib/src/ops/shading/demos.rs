//! The shading operators' demos (`npr doc` renders them; see [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const LAMBERT: Demo = render(
    "Lambert diffuse on a sphere, a torus and a ground plane: bright where the surface faces the light, black past 90°.",
    "scenes/spheres.toml",
    r#"style "lambert demo"
pass shade: render(scene) {
  out color: rgba8unorm = mix(#101018, #f0e2c4, lambert(normal, light.dir))
  clear: #303040
}
output shade.color
"#,
);

pub const HALF_LAMBERT: Demo = render(
    "Half-Lambert on a sphere, a torus and a ground plane: the shading wraps round to the far side, which stays readable instead of black.",
    "scenes/spheres.toml",
    r#"style "half_lambert demo"
pass shade: render(scene) {
  out color: rgba8unorm = mix(#101018, #f0e2c4, half_lambert(normal, light.dir))
  clear: #303040
}
output shade.color
"#,
);

pub const TOON: Demo = render(
    "A three-step toon ramp of half-Lambert shading: each surface in three flat bands.",
    "scenes/spheres.toml",
    r#"style "toon demo"
pass shade: render(scene) {
  let band = toon(half_lambert(normal, light.dir), steps: 3)
  out color: rgba8unorm = mix(#3a2a5a, #e07a3a, band)
  clear: #202020
}
output shade.color
"#,
);

pub const THRESHOLD: Demo = render(
    "Half-Lambert shading thresholded between 0.45 and 0.55: a two-tone light/shadow split with a narrow smooth edge.",
    "scenes/spheres.toml",
    r#"style "threshold demo"
pass shade: render(scene) {
  let lit = threshold(half_lambert(normal, light.dir), lo: 0.45, hi: 0.55)
  out color: rgba8unorm = mix(#2b2540, #f0e6d2, lit)
  clear: #808080
}
output shade.color
"#,
);
