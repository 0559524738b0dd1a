//! The stereo operators' demos (`npr doc` renders them; see
//! [`crate::ops::Demo`]): a sphere in front of a wall seen by a stereo
//! camera (`examples/scenes/stereo_sphere_on_plane.toml`), the left eye
//! shown, with the G-buffer and reprojection of `examples/lsa_stereo.npr`.

use crate::ops::{render, Demo};

pub const CONTOUR_FADE: Demo = render(
    "The stereo contour fade on a sphere in front of a wall (left eye): a dark band inside the sphere's outline, as wide as the two eyes' outlines disagree.",
    "scenes/stereo_sphere_on_plane.toml",
    r#"style "contour_fade demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass show: image(gbuffer) {
  let band = contour_fade(gbuffer.pos.xyz, gbuffer.nrm.xyz)
  out color: rgba8unorm = mix(#f4efe4, #141414, saturate(band))
}
output show.color
"#,
);

pub const REPROJECTION_MASK: Demo = render(
    "The stereo reprojection mask of a sphere in front of a wall (left eye): black where each pixel is seen by the other eye too, white on the strip of wall that the sphere hides from the right eye.",
    "scenes/stereo_sphere_on_plane.toml",
    r#"style "reprojection_mask demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
}
pass reproj: image(gbuffer) {
  out r: rgba32float = vec4(project_other_eye(gbuffer.pos.xyz).xy * resolution, 0.0, gbuffer.pos.w)
}
pass show: image(reproj) {
  let m = reprojection_mask(reproj.r, other_eye(reproj.r))
  out color: rgba8unorm = vec4(m, m, m, 1.0)
}
output show.color
"#,
);

pub const STEREO_CONSISTENCY: Demo = render(
    "LSA contours of a sphere in front of a wall (left eye) bounded by `stereo_consistency`: lines only where both eyes draw them.",
    "scenes/stereo_sphere_on_plane.toml",
    r#"style "stereo_consistency demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass error: image(gbuffer) {
  out e: rgba16float = lsa(gbuffer.pos, gbuffer.nrm)
}
pass lines: image(error) {
  let e = error.e
  out e: r16float = max(max(e.x, e.y), max(e.z, e.w))
}
pass reproj: image(gbuffer) {
  out r: rgba32float = vec4(project_other_eye(gbuffer.pos.xyz).xy * resolution, 0.0, gbuffer.pos.w)
}
pass final: image(lines, reproj) {
  let mask = reprojection_mask(reproj.r, other_eye(reproj.r))
  let line = stereo_consistency(lines.e, other_eye(lines.e), reproj.r, mask)
  out color: rgba8unorm = mix(#f4efe4, #141414, saturate(line))
}
output final.color
"#,
);
