//! The MetaTexture operators' demos (`npr doc` renders them; see
//! [`crate::ops::Demo`]): a gradient-noise grain that keeps its screen size
//! on Spot and on the spheres, thresholded into the shading as in
//! `examples/metatexture.npr`.

use crate::ops::{render, Demo};

pub const METATEXTURE_GRAD: Demo = render(
    "Grain from `metatexture_grad` (UV gradients from `uv_gradients`) on the spheres scene: noise texels about 16 px wide on screen at every distance, breaking up the light/shadow edge.",
    "scenes/spheres.toml",
    r#"style "metatexture_grad demo"
texture grain = noise(size: 128, octaves: 4, seed: 3, kind: gradient) { wrap: repeat, filter: linear, mips: on }
pass shade: render(scene) {
  let g = uv_gradients()
  let n = metatexture_grad(grain, uv, g.xy, g.zw, width: 16px, contrast: variance).r
  let lit = half_lambert(normal, light.dir) + (n - 0.5) * 0.6
  out color: rgba8unorm = mix(#2b2540, #f0e6d2, threshold(lit, lo: 0.55, hi: 0.6))
  clear: #e8e4da
}
output shade.color
"#,
);

pub const METATEXTURE: Demo = render(
    "Grain from `metatexture` (derivatives from the fragment) on Spot the cow: noise texels about 16 px wide on screen, breaking up the light/shadow edge.",
    "scenes/spot.toml",
    r#"style "metatexture demo"
texture grain = noise(size: 128, octaves: 4, seed: 3, kind: gradient) { wrap: repeat, filter: linear, mips: on }
pass shade: render(scene) {
  let n = metatexture(grain, width: 16px, contrast: variance).r
  let lit = half_lambert(normal, light.dir) + (n - 0.5) * 0.6
  out color: rgba8unorm = mix(#2b2540, #f0e6d2, threshold(lit, lo: 0.55, hi: 0.6))
  clear: #e8e4da
}
output shade.color
"#,
);

pub const METATEXTURE4_GRAD: Demo = render(
    "The 4-tap `metatexture4_grad` grain as a grey value on the spheres scene: noise of the same screen size on the near sphere and the far ground.",
    "scenes/spheres.toml",
    r#"style "metatexture4_grad demo"
texture grain = noise(size: 128, octaves: 4, seed: 3, kind: gradient) { wrap: repeat, filter: linear, mips: on }
pass shade: render(scene) {
  let g = uv_gradients()
  let n = metatexture4_grad(grain, uv, g.xy, g.zw, width: 16px, contrast: variance).r
  out color: rgba8unorm = vec4(n, n, n, 1.0)
  clear: #808080
}
output shade.color
"#,
);

pub const METATEXTURE4: Demo = render(
    "The 4-tap `metatexture4` grain as a grey value on Spot the cow: noise texels of one screen size over the whole body.",
    "scenes/spot.toml",
    r#"style "metatexture4 demo"
texture grain = noise(size: 128, octaves: 4, seed: 3, kind: gradient) { wrap: repeat, filter: linear, mips: on }
pass shade: render(scene) {
  let n = metatexture4(grain, width: 16px, contrast: variance).r
  out color: rgba8unorm = vec4(n, n, n, 1.0)
  clear: #808080
}
output shade.color
"#,
);

pub const METATEXTURE_CONTOUR_GRAD: Demo = render(
    "Contour-oriented grain from `metatexture_contour_grad` on the spheres scene: the noise is stretched along the occluding contours, like strokes following the outline.",
    "scenes/spheres.toml",
    r#"style "metatexture_contour_grad demo"
texture grain = noise(size: 128, octaves: 4, seed: 3, kind: gradient) { wrap: repeat, filter: linear, mips: on }
pass shade: render(scene) {
  let g = uv_gradients()
  let n = metatexture_contour_grad(grain, uv, g.xy, g.zw, width: 16px, contrast: variance, orient: contour, band: 1.0).r
  out color: rgba8unorm = vec4(n, n, n, 1.0)
  clear: #808080
}
output shade.color
"#,
);

pub const METATEXTURE_CONTOUR: Demo = render(
    "Contour-oriented grain from `metatexture_contour` on Spot the cow: the noise is stretched along the silhouette.",
    "scenes/spot.toml",
    r#"style "metatexture_contour demo"
texture grain = noise(size: 128, octaves: 4, seed: 3, kind: gradient) { wrap: repeat, filter: linear, mips: on }
pass shade: render(scene) {
  let n = metatexture_contour(grain, width: 16px, contrast: variance, orient: contour, band: 1.0).r
  out color: rgba8unorm = vec4(n, n, n, 1.0)
  clear: #808080
}
output shade.color
"#,
);
