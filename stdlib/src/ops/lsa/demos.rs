//! The LSA contour operators' demos (`npr doc` renders them; see
//! [`crate::ops::Demo`]): the world-space G-buffer of
//! `examples/lsa_contours.npr`, each variant's line strength shown as ink.

use crate::ops::{render, Demo};

pub const LSA: Demo = render(
    "LSA contours (plane fit and anti-aliasing on) of Spot the cow: ink lines of the silhouette and the inner contours, from the line strength's largest direction channel.",
    "scenes/spot.toml",
    r#"style "lsa demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass ink: image(gbuffer) {
  let e = lsa(gbuffer.pos, gbuffer.nrm, plane: true, aa: true)
  out color: rgba8unorm = mix(#f4efe4, #141414, max(max(e.x, e.y), max(e.z, e.w)))
}
output ink.color
"#,
);

pub const LSA_SUM: Demo = render(
    "`lsa_sum` (LSA without anti-aliasing) on the spheres scene: contours of the sphere, the torus and the ground's far edge, with stair-stepped edges.",
    "scenes/spheres.toml",
    r#"style "lsa_sum demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass ink: image(gbuffer) {
  let e = lsa_sum(gbuffer.pos, gbuffer.nrm, plane: true)
  out color: rgba8unorm = mix(#f4efe4, #141414, max(max(e.x, e.y), max(e.z, e.w)))
}
output ink.color
"#,
);

pub const LSA_CURV_AA: Demo = render(
    "`lsa_curv_aa` (LSA without the plane fit, anti-aliased) on the spheres scene: contours of the sphere and the torus.",
    "scenes/spheres.toml",
    r#"style "lsa_curv_aa demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass ink: image(gbuffer) {
  let e = lsa_curv_aa(gbuffer.pos, gbuffer.nrm, aa: true)
  out color: rgba8unorm = mix(#f4efe4, #141414, max(max(e.x, e.y), max(e.z, e.w)))
}
output ink.color
"#,
);

pub const LSA_CURV: Demo = render(
    "`lsa_curv` (curvature term only: no plane fit, no anti-aliasing) on the spheres scene: contours of the sphere and the torus.",
    "scenes/spheres.toml",
    r#"style "lsa_curv demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass ink: image(gbuffer) {
  let e = lsa_curv(gbuffer.pos, gbuffer.nrm)
  out color: rgba8unorm = mix(#f4efe4, #141414, max(max(e.x, e.y), max(e.z, e.w)))
}
output ink.color
"#,
);

pub const LSA_DENSITY: Demo = render(
    "LSA contours of Spot the cow after the line-density filter (strength 1): the lines thinned to about a pixel, compare with `lsa`'s image.",
    "scenes/spot.toml",
    r#"style "lsa_density demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass error: image(gbuffer) {
  out e: rgba16float = lsa(gbuffer.pos, gbuffer.nrm)
}
pass ink: image(error) {
  let e = lsa_density(error.e, strength: 1.0)
  out color: rgba8unorm = mix(#f4efe4, #141414, max(max(e.x, e.y), max(e.z, e.w)))
}
output ink.color
"#,
);
