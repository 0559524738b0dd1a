//! `sample`'s demo (`npr doc` renders it; see [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const SAMPLE: Demo = render(
    "The gallery's stone texture read with `sample` at twice the spheres' UVs, shaded by half-Lambert.",
    "scenes/spheres.toml",
    r#"style "sample demo"
texture stone = image("textures/gallery_stone.png", srgb) { wrap: repeat, filter: linear }
pass shade: render(scene) {
  let t = sample(stone, uv * 2.0)
  out color: rgba8unorm = vec4(t.rgb * half_lambert(normal, light.dir), 1.0)
  clear: #808080
}
output shade.color
"#,
);
