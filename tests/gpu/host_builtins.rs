//! Geometry builtins in image passes over a host's frame (issue 47):
//! `depth`, `position.view`, `position.world`, `view_dir` and
//! `normal.view`, read from the style's
//! `input(depth)` and `input(normal, view)`, equal what a render pass reads
//! from npr's own geometry. npr renders a scene's G-buffer (render-pass
//! builtins, float32) into EXR layers; a second style reads those layers
//! as its inputs and writes the same builtins from an image pass. A file's
//! normals are world normals (the convention of files that are not
//! Blender's), which the runner turns into the view space the input
//! declares, so `normal.view` is compared with the first style's own. The two
//! must agree to what the inputs keep (each style's last pass reads every
//! target, so that all are kept and written as layers): they are stored as half floats, so
//! a depth keeps 11 significant bits.

use crate::blender_scene::{npr, scratch};
use npr_runner::inputs::files::read_exr;

const OWN: &str = "style \"own\"\n\
pass g: render(scene) {\n\
  out p: rgba32float = vec4(position.view, 1.0)\n\
  out n: rgba32float = vec4(normal, 1.0)\n\
  out v: rgba32float = vec4(normal.view, 1.0)\n\
  out d: r32float = depth\n\
  clear: #000000\n\
}\n\
pass all: image(g) {\n\
  out c: rgba32float = vec4(g.p.x, g.n.y + g.v.y, g.d, 1.0)\n\
}\n\
output all.c\n";

const OVER: &str = "style \"over\"\n\
texture depth_in = input(depth)\n\
texture normal_in = input(normal, view)\n\
pass q: image() {\n\
  out p: rgba32float = vec4(position.view, 1.0)\n\
  out n: rgba32float = vec4(normal.view, depth)\n\
}\n\
pass all: image(q) {\n\
  out c: rgba32float = vec4(q.p.x, q.n.y, q.n.w, 1.0)\n\
}\n\
output all.c\n";

const SPHERES: &str = "examples/scenes/spheres.toml";

/// `spheres.toml` through an orthographic camera 3.2 m high (decision
/// 0062), written beside the test's other files (its objects are
/// primitives, so nothing is read relative to it).
fn orthographic_spheres() -> String {
    let text = std::fs::read_to_string(SPHERES).expect("read spheres.toml");
    assert!(text.contains("fov = 40.0\n"), "spheres.toml's lens changed");
    let ortho = text.replace("fov = 40.0\n", "projection = \"orthographic\"\nheight = 3.2\n");
    std::fs::create_dir_all(scratch("")).expect("scratch dir");
    let path = scratch("spheres_ortho.toml");
    std::fs::write(&path, ortho).expect("write");
    path.to_str().expect("utf-8 path").to_owned()
}

#[test]
fn image_pass_builtins_over_inputs_equal_the_render_pass_builtins() {
    builtins_over_inputs_equal_the_render_pass_ones(SPHERES, "persp");
}

/// The same through an orthographic camera: `position.view` is rebuilt
/// with clip w = 1 (x_ndc / P₀₀, y_ndc / P₁₁, −d), not the perspective
/// divide.
#[test]
fn orthographic_image_pass_builtins_over_inputs_equal_the_render_pass_builtins() {
    builtins_over_inputs_equal_the_render_pass_ones(&orthographic_spheres(), "ortho");
}

fn builtins_over_inputs_equal_the_render_pass_ones(scene: &str, tag: &str) {
    std::fs::create_dir_all(scratch("")).expect("scratch dir");
    let (own_style, over_style) = (
        scratch(&format!("builtins_own_{tag}.npr")),
        scratch(&format!("builtins_over_{tag}.npr")),
    );
    std::fs::write(&own_style, OWN).expect("write");
    std::fs::write(&over_style, OVER).expect("write");
    let (own, over) = (
        scratch(&format!("builtins_own_{tag}.exr")),
        scratch(&format!("builtins_over_{tag}.exr")),
    );
    npr(&[
        "render",
        own_style.to_str().unwrap(),
        "--scene",
        scene,
        "--size",
        "96x72",
        "--layers",
        "-o",
        own.to_str().unwrap(),
    ]);
    npr(&[
        "render",
        over_style.to_str().unwrap(),
        "--inputs",
        own.to_str().unwrap(),
        "--map",
        "depth_in=g.d",
        "--map",
        "normal_in=g.n",
        "--scene",
        scene,
        "--layers",
        "-o",
        over.to_str().unwrap(),
    ]);
    let a = read_exr("own", &own).expect("read own");
    let b = read_exr("over", &over).expect("read over");
    let ch = |e: &npr_runner::inputs::files::ExrChannels, n: &str| {
        e.channels
            .get(n)
            .unwrap_or_else(|| panic!("no channel {n}: {:?}", e.channels.keys().collect::<Vec<_>>()))
            .clone()
    };
    let (own_p, own_n, own_d) = (
        ["R", "G", "B"].map(|c| ch(&a, &format!("g.p.{c}"))),
        ["R", "G", "B"].map(|c| ch(&a, &format!("g.v.{c}"))),
        ch(&a, "g.d.R"),
    );
    let (over_p, over_n, over_d) = (
        ["R", "G", "B"].map(|c| ch(&b, &format!("q.p.{c}"))),
        ["R", "G", "B"].map(|c| ch(&b, &format!("q.n.{c}"))),
        ch(&b, "q.n.A"),
    );
    let (mut surface, mut worst_p, mut worst_n, mut worst_d) = (0, 0.0f64, 0.0f64, 0.0f64);
    for i in 0..own_d.len() {
        let d = own_d[i] as f64;
        if d == 0.0 {
            // Nothing drawn: the input's depth is 0, and so is the rebuilt point.
            assert_eq!(over_d[i], 0.0, "pixel {i}: background depth");
            continue;
        }
        surface += 1;
        worst_d = worst_d.max((over_d[i] as f64 - d).abs() / d);
        // The rebuilt point against the rasterized one, relative to its length.
        let dp = (0..3)
            .map(|c| (over_p[c][i] as f64 - own_p[c][i] as f64).powi(2))
            .sum::<f64>()
            .sqrt();
        let length = (0..3).map(|c| (own_p[c][i] as f64).powi(2)).sum::<f64>().sqrt();
        worst_p = worst_p.max(dp / length);
        let dn = (0..3)
            .map(|c| (over_n[c][i] as f64 - own_n[c][i] as f64).powi(2))
            .sum::<f64>()
            .sqrt();
        worst_n = worst_n.max(dn);
    }
    assert!(surface > 96 * 72 / 10, "the scene covers the image: {surface} pixels");
    // Half-float depth: 11 significant bits, and the GPU may round toward
    // zero when it stores one (Vulkan leaves the mode to the driver;
    // lavapipe truncates: 8.2807 is kept as 8.2734): less than one step,
    // 2⁻¹⁰ (9.8e-4) of the value.
    assert!(worst_d < 9.8e-4, "depth differs by {worst_d:e} of itself");
    // The point on the pixel centre's ray at that depth: scaled by the
    // depth, so off by the depth's rounding of its length, plus f32
    // rounding of the ray (1e-6).
    assert!(worst_p < 9.9e-4, "position.view differs by {worst_p:e} of its length");
    // Unit normals in half floats: 2⁻¹¹ per component.
    assert!(worst_n <= 2e-3, "normal.view differs by {worst_n:e}");
}

const OWN_WORLD: &str = "style \"own world\"\n\
pass g: render(scene) {\n\
  out w: rgba32float = vec4(position.world, 1.0)\n\
  out e: rgba32float = vec4(view_dir, 1.0)\n\
  out p: rgba32float = vec4(position.view, 1.0)\n\
  out d: r32float = depth\n\
  clear: #000000\n\
}\n\
pass all: image(g) {\n\
  out c: rgba32float = vec4(g.w.x, g.e.y + g.p.z, g.d, 1.0)\n\
}\n\
output all.c\n";

const OVER_WORLD: &str = "style \"over world\"\n\
texture depth_in = input(depth)\n\
pass q: image() {\n\
  out w: rgba32float = vec4(position.world, 1.0)\n\
  out e: rgba32float = vec4(view_dir, 1.0)\n\
}\n\
pass all: image(q) {\n\
  out c: rgba32float = vec4(q.w.x, q.e.y, 0.0, 1.0)\n\
}\n\
output all.c\n";

/// `position.world` and `view_dir` rebuilt in an image pass from the
/// host's depth and the frame's camera (the view's rotation undone with
/// `camera.right`, `camera.up`, `camera.forward`) equal the render pass's
/// own, on a camera that looks down and sideways at the spheres.
#[test]
fn image_pass_world_position_and_view_dir_over_inputs_equal_the_render_pass_ones() {
    world_position_and_view_dir_equal_the_render_pass_ones(SPHERES, "persp");
}

/// The same through an orthographic camera, where `view_dir` is
/// −`camera.forward` at every pixel, in the render pass and rebuilt.
#[test]
fn orthographic_image_pass_world_position_and_view_dir_equal_the_render_pass_ones() {
    world_position_and_view_dir_equal_the_render_pass_ones(&orthographic_spheres(), "ortho");
}

fn world_position_and_view_dir_equal_the_render_pass_ones(scene: &str, tag: &str) {
    std::fs::create_dir_all(scratch("")).expect("scratch dir");
    let (own_style, over_style) = (
        scratch(&format!("world_own_{tag}.npr")),
        scratch(&format!("world_over_{tag}.npr")),
    );
    std::fs::write(&own_style, OWN_WORLD).expect("write");
    std::fs::write(&over_style, OVER_WORLD).expect("write");
    let (own, over) = (
        scratch(&format!("world_own_{tag}.exr")),
        scratch(&format!("world_over_{tag}.exr")),
    );
    let render = |style: &std::path::Path, extra: &[&str], out: &std::path::Path| {
        let mut args = vec!["render", style.to_str().unwrap(), "--scene", scene, "--layers"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["-o", out.to_str().unwrap()]);
        npr(&args);
    };
    render(&own_style, &["--size", "96x72"], &own);
    render(
        &over_style,
        &["--inputs", own.to_str().unwrap(), "--map", "depth_in=g.d"],
        &over,
    );
    let a = read_exr("own", &own).expect("read own");
    let b = read_exr("over", &over).expect("read over");
    let ch = |e: &npr_runner::inputs::files::ExrChannels, n: &str| {
        e.channels
            .get(n)
            .unwrap_or_else(|| panic!("no channel {n}: {:?}", e.channels.keys().collect::<Vec<_>>()))
            .clone()
    };
    let rgb = |e, layer: &str| ["R", "G", "B"].map(|c| ch(e, &format!("{layer}.{c}")));
    let (own_w, own_e, own_p, own_d) = (rgb(&a, "g.w"), rgb(&a, "g.e"), rgb(&a, "g.p"), ch(&a, "g.d.R"));
    let (over_w, over_e) = (rgb(&b, "q.w"), rgb(&b, "q.e"));
    let (mut surface, mut worst_w, mut worst_e) = (0, 0.0f64, 0.0f64);
    for i in 0..own_d.len() {
        let d = own_d[i] as f64;
        if d == 0.0 {
            continue;
        }
        surface += 1;
        let diff = |p: &[Vec<f32>; 3], q: &[Vec<f32>; 3]| {
            (0..3)
                .map(|c| (p[c][i] as f64 - q[c][i] as f64).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        // Relative to the point's distance from the eye, |position.view|.
        let length = (0..3).map(|c| (own_p[c][i] as f64).powi(2)).sum::<f64>().sqrt();
        worst_w = worst_w.max(diff(&over_w, &own_w) / length);
        worst_e = worst_e.max(diff(&over_e, &own_e));
    }
    assert!(surface > 96 * 72 / 10, "the scene covers the image: {surface} pixels");
    // The rebuilt view-space point is off by the half-float depth's
    // rounding (under 2⁻¹⁰ = 9.77e-4 of its length, `position.view`
    // above); undoing the rotation keeps lengths, and adding the camera's
    // position rounds in f32 (about 1e-7 of its 5 m, over at least 2 m):
    // under 9.9e-4 of the point's distance from the eye.
    assert!(
        worst_w < 9.9e-4,
        "position.world differs by {worst_w:e} of its distance from the eye"
    );
    // Both points lie on the pixel centre's ray, so the direction does not
    // depend on the depth's rounding at all: f32 rounding of the ray and
    // the rotation only.
    assert!(worst_e < 1e-4, "view_dir differs by {worst_e:e}");
}
