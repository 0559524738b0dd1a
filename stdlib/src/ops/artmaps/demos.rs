//! The art-map operators' demos (`npr doc` renders them; see
//! [`crate::ops::Demo`]): the gallery of `examples/artmap_gallery.npr`
//! seen from its door, its textures filtered per level by the example
//! filters.

use crate::ops::{render, Demo};

pub const SAMPLE_BIASED: Demo = render(
    "The gallery's walls and pillars hatched with an art-map (each mip level filtered by `filters/hatching.npr`) read by `sample_biased`: strokes keep their screen size with distance.",
    "scenes/gallery.toml",
    r#"style "sample_biased demo"
object param repeat: float = 1 in 0.01..1000
texture walls = artmap(image("textures/gallery_wall.png", srgb), filter: "filters/hatching.npr", levels: auto) { wrap: repeat }
pass shade: render(scene) {
  let w = sample_biased(walls, uv * repeat, bias: 0.0).rgb
  out color: rgba8unorm = vec4(w * mix(1.0, half_lambert(normal, light.dir), 0.35), 1.0)
  clear: #f4efe4
}
output shade.color
"#,
);

pub const SAMPLE_RIPMAP: Demo = render(
    "The gallery's floor, walls and pillars in watercolour from a rip-map read by `sample_ripmap`: the floor seen at a grazing angle stays sharp along its length instead of blurring.",
    "scenes/gallery.toml",
    r#"style "sample_ripmap demo"
object param repeat: float = 1 in 0.01..1000
texture floor_map = ripmap(image("textures/gallery_floor.png", srgb), filter: "filters/watercolor.npr")
pass shade: render(scene) {
  let f = sample_ripmap(floor_map, uv * repeat).rgb
  out color: rgba8unorm = vec4(f * mix(1.0, half_lambert(normal, light.dir), 0.35), 1.0)
  clear: #f4efe4
}
output shade.color
"#,
);
