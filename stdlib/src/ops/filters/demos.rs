//! The image filters' demos (`npr doc` renders them; see [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const GAUSSIAN: Demo = render(
    "Hard two-tone shading of the spheres scene blurred by a separable Gaussian (σ = 3 px, x then y): every edge is soft.",
    "scenes/spheres.toml",
    r#"style "gaussian demo"
pass shade: render(scene) {
  out c: rgba8unorm = mix(#2b2540, #f0e6d2, step(0.5, half_lambert(normal, light.dir)))
  clear: #f0e6d2
}
pass blur_x: image(shade) {
  out c: rgba8unorm = gaussian(shade.c, sigma: 3px, axis: x)
}
pass blur_y: image(blur_x) {
  out c: rgba8unorm = gaussian(blur_x.c, sigma: 3px, axis: y)
}
output blur_y.c
"#,
);

pub const DOWNSAMPLE: Demo = render(
    "The shaded spheres scene downsampled three times by 2×2 box filters (to 1/8 size) and shown at full size: blocks of 8×8 pixels.",
    "scenes/spheres.toml",
    r#"style "downsample demo"
pass shade: render(scene) {
  out c: rgba8unorm = mix(#2b2540, #f0e6d2, half_lambert(normal, light.dir))
  clear: #808080
}
pass half: image(shade) scale 1/2 {
  out c: rgba8unorm = downsample(shade.c)
}
pass quarter: image(half) scale 1/4 {
  out c: rgba8unorm = downsample(half.c)
}
pass eighth: image(quarter) scale 1/8 {
  out c: rgba8unorm = downsample(quarter.c)
}
pass show: image(eighth) {
  out c: rgba8unorm = eighth.c
}
output show.c
"#,
);

pub const SOBEL: Demo = render(
    "Sobel on a linear-depth G-buffer of the spheres scene, thresholded at 0.4 m per pixel: ink where depth jumps (the objects' outlines and the ground's far edge), paper elsewhere.",
    "scenes/spheres.toml",
    r#"style "sobel demo"
pass gbuffer: render(scene) {
  out depth: r32float = depth
}
pass ink_lines: image(gbuffer) {
  let edge = threshold(sobel(gbuffer.depth), lo: 0.4, hi: 0.4)
  out color: rgba8unorm = mix(#f4efe4, #141414, edge)
}
output ink_lines.color
"#,
);

pub const NORMAL_DEPTH_EDGES: Demo = render(
    "Normal-and-depth edges of Spot the cow over two-tone shading: ink on the silhouette and on creases where the view-space normal turns.",
    "scenes/spot.toml",
    r#"style "normal_depth_edges demo"
pass gbuffer: render(scene) {
  out normal: rgba16float = vec4(normal.view * 0.5 + 0.5, 1.0)
  out depth: r32float = depth
  out shade: r8unorm = half_lambert(normal, light.dir)
}
pass ink_lines: image(gbuffer) {
  let edge = normal_depth_edges(gbuffer.normal, gbuffer.depth, depth_threshold: 50mm, normal_threshold: 0.4)
  let tone = mix(#f4efe4 * 0.78, #f4efe4, toon(gbuffer.shade, steps: 2))
  out color: rgba8unorm = mix(tone, #141414, edge)
}
output ink_lines.color
"#,
);
