//! The stereo operators' demos (`npr doc` renders them; see
//! [`crate::ops::Demo`]): a sphere in front of a wall seen by a stereo
//! camera (`examples/scenes/stereo_wide.toml`), the left eye
//! shown, with the G-buffer and reprojection of `examples/lsa_stereo.npr`.

use crate::ops::{render, Demo};

pub const CONTOUR_FADE: Demo = render(
    "The stereo contour fade on a sphere in front of a wall (left eye), over the sphere's shading: a dark band on the near side of the sphere's outline, its width set by how far the two eyes' outlines disagree (start 8 and end 1, wider than the defaults, so that it shows at this size).",
    "scenes/stereo_wide.toml",
    r#"style "contour_fade demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass show: image(gbuffer) {
  let band = contour_fade(gbuffer.pos.xyz, gbuffer.nrm.xyz, start: 8.0, end: 1.0)
  let shade = mix(#c8c0b0, #f4efe4, half_lambert(gbuffer.nrm.xyz, light.dir))
  out color: rgba8unorm = mix(shade, #141414, saturate(band))
}
output show.color
"#,
);

pub const REPROJECTION_MASK: Demo = render(
    "The stereo reprojection mask of a sphere in front of a wall (left eye): white where the two eyes' views cannot be matched (the strip of wall the sphere hides from the right eye, the sphere's rim), the grey-shaded scene where they agree.",
    "scenes/stereo_wide.toml",
    r#"style "reprojection_mask demo"
pass gbuffer: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out shade: r8unorm = half_lambert(normal, light.dir)
}
pass reproj: image(gbuffer) {
  out r: rgba32float = vec4(project_other_eye(gbuffer.pos.xyz).xy * resolution, 0.0, gbuffer.pos.w)
}
pass show: image(reproj, gbuffer) {
  let m = reprojection_mask(reproj.r, other_eye(reproj.r))
  let shade = mix(#505868, #a0a8b8, gbuffer.shade)
  out color: rgba8unorm = mix(shade, #ffffff, m)
}
output show.color
"#,
);

pub const STEREO_CONSISTENCY: Demo = render(
    "LSA contours of a sphere in front of a wall (left eye) bounded by `stereo_consistency`: lines only where both eyes draw them.",
    "scenes/stereo_wide.toml",
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
