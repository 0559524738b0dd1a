//! The MetaTexture extensions' and Edge Breakup's demos (`npr doc` renders
//! them; see [`crate::ops::Demo`]).

use crate::ops::{render, Demo};

pub const RADIAL_ALPHA: Demo = render(
    "radial_alpha() − 1 as grey over the whole image: 0 (black) on the optical axis at the centre, growing towards the corners, where a texel must be widened to keep its size off-axis.",
    "scenes/spheres.toml",
    r#"style "radial_alpha demo"
pass show: image() {
  let a = (radial_alpha() - 1.0) * 4.0
  out color: rgba8unorm = vec4(a, a, a, 1.0)
}
output show.color
"#,
);

pub const UV_GRADIENTS: Demo = render(
    "A UV grid drawn on the spheres scene with lines 1 px wide at every distance: `uv_gradients` gives each pixel's UV step, which sets the line width in UV units.",
    "scenes/spheres.toml",
    r#"style "uv_gradients demo"
pass shade: render(scene) {
  let g = uv_gradients()
  let cells = 8.0
  let du = abs(fract(uv.x * cells + 0.5) - 0.5) / max(cells * length(g.xy), 1e-6)
  let dv = abs(fract(uv.y * cells + 0.5) - 0.5) / max(cells * length(g.zw), 1e-6)
  let line = 1.0 - smoothstep(0.5, 1.5, min(du, dv))
  out color: rgba8unorm = mix(mix(#9098a8, #f0e6d2, half_lambert(normal, light.dir)), #141414, line)
  clear: #e8e4da
}
output shade.color
"#,
);

pub const LIVE_TEXTURE: Demo = Demo::Render(crate::ops::DemoRender {
    shows: "One frame (t = 0.4 s) of a live texture on Spot the cow as dark/light: a three-channel noise's channels mixed by the time-varying weights of eq. 27, the phase offset by height so that the pattern travels.",
    scene: "scenes/spot.toml",
    style: r#"style "live_texture demo"
texture dither = noise(size: 64, octaves: 3, seed: 9, channels: 3, kind: gradient) { wrap: repeat, filter: linear }
pass shade: render(scene) {
  let t = sample(dither, uv * 4.0)
  let live = live_texture(t, freq: 0.75Hz, time: time + (position.world.y / 1m) * 1s)
  out color: rgba8unorm = mix(#2b2540, #f0e6d2, live)
  clear: #e8e4da
}
output shade.color
"#,
    time_s: 0.4,
});

pub const LINE_BOIL: Demo = render(
    "UV grid lines on the spheres scene at four consecutive line-boil steps (12 Hz) in red, green, blue and black: the offset jumps from step to step.",
    "scenes/spheres.toml",
    r#"style "line_boil demo"
pass shade: render(scene) {
  let cells = 6.0
  let w = 0.06
  let l0 = step(abs(fract(line_boil(uv, time: 0s).x * cells) - 0.5), w)
  let l1 = step(abs(fract(line_boil(uv, time: 0.09s).x * cells) - 0.5), w)
  let l2 = step(abs(fract(line_boil(uv, time: 0.17s).x * cells) - 0.5), w)
  let l3 = step(abs(fract(line_boil(uv, time: 0.26s).x * cells) - 0.5), w)
  let c = vec3(1.0 - l1 - l2 - l3, 1.0 - l0 - l2 - l3, 1.0 - l0 - l1 - l3)
  out color: rgba8unorm = vec4(saturate(c), 1.0)
  clear: #c0c0c0
}
output shade.color
"#,
);

pub const ROLL_COMPENSATE: Demo = render(
    "The constant offset (1, 0) expressed in the frame of the screen-space ∇u by `roll_compensate`, as colour (red = x, green = y): it turns with the UV direction across each surface.",
    "scenes/spheres.toml",
    r#"style "roll_compensate demo"
pass shade: render(scene) {
  let g = uv_gradients()
  let v = roll_compensate(vec2(1.0, 0.0), g.xy)
  out color: rgba8unorm = vec4(v * 0.5 + 0.5, 0.5, 1.0)
  clear: #808080
}
output shade.color
"#,
);

pub const DISTANCE_ATTENUATE: Demo = render(
    "Warp strength ρ = 1 attenuated with distance from the camera (falloff 4 m) on the spheres scene: bright near, fading into the distance across the ground.",
    "scenes/spheres.toml",
    r#"style "distance_attenuate demo"
pass shade: render(scene) {
  let rho = distance_attenuate(1.0, distance(position.world, camera.position), falloff: 4m)
  out color: rgba8unorm = vec4(rho, rho, rho, 1.0)
  clear: #000000
}
output shade.color
"#,
);

pub const WARP: Demo = render(
    "Edge breakup of Spot the cow: a clean two-tone shading warped by a noise vector field (strength 6 px), so its outlines and shadow edge turn ragged.",
    "scenes/spot.toml",
    r#"style "warp demo"
texture warp_noise = noise(size: 128, octaves: 4, seed: 11, channels: 2, kind: gradient) { wrap: repeat, filter: linear, mips: on }
pass field: render(scene) {
  let g = uv_gradients()
  let n = metatexture_grad(warp_noise, uv, g.xy, g.zw, width: 24px, contrast: variance)
  out vec: rg16float = n.xy * 2.0 - 1.0
  clear: #000000
}
pass shade: render(scene) {
  let lit = threshold(half_lambert(normal, light.dir), lo: 0.5, hi: 0.52)
  out color: rgba8unorm = mix(#2b2540, #f0e6d2, lit)
  clear: #e8e4da
}
pass final: image(shade, field) {
  out color: rgba8unorm = warp(shade.color, field.vec, strength: 6px)
}
output final.color
"#,
);
