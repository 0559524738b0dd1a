//! Line sets (decision 0056) through the compiler and the real renderer on
//! lavapipe: a cube seen from a corner, an `outline` set of silhouettes in
//! red and a `detail` set of creases in blue. The red ink follows the
//! silhouette hexagon and the blue ink the three visible inner creases; the
//! six silhouette sides are creases too, and are drawn once, by the set of
//! higher priority (blue there would mean the crease set drew them over the
//! outline). With the priorities swapped, the crease set takes every edge
//! and the outline set draws nothing.

use glam::{DMat4, DVec2, DVec3};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer};
use std::path::Path;

use crate::common;
use common::lines::{recall_precision, samples};
use common::{compile_text, gpu};

const SIZE: u32 = 256;
const EYE: DVec3 = DVec3::new(3.0, 2.5, 4.0);

fn cube_scene() -> Scene {
    scene_of("cube", "[[object]]\nprimitive = { kind = \"cube\", size = 2.0 }\n")
}

/// A scene seen from EYE with `objects`, written as `name`.
fn scene_of(name: &str, objects: &str) -> Scene {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("lines-sets");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let path = dir.join(format!("{name}-{}.toml", std::process::id()));
    let text = format!(
        "[camera]\nposition = [{}, {}, {}]\ntarget = [0, 0, 0]\nfov = 40\nnear = 0.1\nfar = 100.0\n\n{objects}",
        EYE.x, EYE.y, EYE.z
    );
    std::fs::write(&path, text).expect("write scene");
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// A fill with a kept depth and a lines pass of two sets, the outline's
/// priority `outline_priority` (the detail set's is 0).
fn two_sets(outline_priority: i32) -> String {
    format!(
        "style \"Sets\"
pass shade: render(scene) {{
  out color: rgba8unorm = #808080
  depth: keep
}}
pass ink: lines(scene) {{
  amplitude: 0px
  set outline {{ edges: silhouette, color: #ff0000, priority: {outline_priority} }}
  set detail {{ edges: crease(40deg), color: #0000ff }}
  depth: test(shade, bias: 1px)
  out ink: rgba8unorm = vec4(line.color.rgb, 1.0) {{ blend: over }}
  clear: #ffffff
}}
output ink.ink
"
    )
}

/// (red pixels, blue pixels) of the rendered style.
fn render(text: &str) -> (Vec<DVec2>, Vec<DVec2>) {
    render_on(text, &cube_scene())
}

fn render_on(text: &str, scene: &Scene) -> (Vec<DVec2>, Vec<DVec2>) {
    let scene = scene.clone();
    let program = compile_text(text);
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    r.render(&scene, &FrameSpec::still(SIZE, SIZE, 0)).expect("render");
    let image = r.read_output().expect("read back");
    let (mut red, mut blue) = (Vec::new(), Vec::new());
    for y in 0..image.height {
        for x in 0..image.width {
            let [r, _, b, _] = image.texel(x, y);
            let centre = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
            if r > 0.5 && b < 0.5 {
                red.push(centre);
            } else if b > 0.5 && r < 0.5 {
                blue.push(centre);
            }
        }
    }
    (red, blue)
}

fn view_proj() -> DMat4 {
    DMat4::perspective_rh(40f64.to_radians(), 1.0, 0.1, 100.0) * DMat4::look_at_rh(EYE, DVec3::ZERO, DVec3::Y)
}

/// The six silhouette sides from EYE: between +X, +Y, +Z (towards the eye)
/// and −X, −Y, −Z.
fn silhouette() -> Vec<(DVec3, DVec3)> {
    let c = DVec3::new;
    vec![
        (c(1.0, -1.0, -1.0), c(1.0, -1.0, 1.0)),
        (c(1.0, -1.0, -1.0), c(1.0, 1.0, -1.0)),
        (c(-1.0, 1.0, -1.0), c(-1.0, 1.0, 1.0)),
        (c(-1.0, 1.0, -1.0), c(1.0, 1.0, -1.0)),
        (c(-1.0, -1.0, 1.0), c(-1.0, 1.0, 1.0)),
        (c(-1.0, -1.0, 1.0), c(1.0, -1.0, 1.0)),
    ]
}

/// The three visible creases that are not silhouettes: they meet at the
/// corner nearest the eye.
fn inner_creases() -> Vec<(DVec3, DVec3)> {
    let c = DVec3::new;
    vec![
        (c(1.0, 1.0, -1.0), c(1.0, 1.0, 1.0)),
        (c(1.0, -1.0, 1.0), c(1.0, 1.0, 1.0)),
        (c(-1.0, 1.0, 1.0), c(1.0, 1.0, 1.0)),
    ]
}

#[test]
fn each_set_draws_its_edges_in_its_colour_and_a_shared_edge_once() {
    let (red, blue) = render(&two_sets(1));
    let vp = view_proj();
    let outline = samples(vp, &silhouette(), SIZE);
    let inner = samples(vp, &inner_creases(), SIZE);
    let (recall, precision) = recall_precision(&red, &outline, 1.0);
    assert!(
        recall >= 0.95 && precision >= 0.95,
        "outline: recall {recall}, precision {precision} ({} red px)",
        red.len()
    );
    // Blue only along the inner creases: a silhouette side drawn by the
    // crease set too would be blue over the red.
    let (recall, precision) = recall_precision(&blue, &inner, 1.0);
    assert!(
        recall >= 0.95 && precision >= 0.95,
        "detail: recall {recall}, precision {precision} ({} blue px)",
        blue.len()
    );
}

#[test]
fn the_higher_set_takes_every_edge_it_selects() {
    // The detail set first: every silhouette side of a cube is a crease.
    let (red, blue) = render(&two_sets(-1));
    assert!(
        red.is_empty(),
        "{} red px: the outline set drew edges the crease set took",
        red.len()
    );
    let vp = view_proj();
    let mut all = silhouette();
    all.extend(inner_creases());
    let (recall, precision) = recall_precision(&blue, &samples(vp, &all, SIZE), 1.0);
    assert!(
        recall >= 0.95 && precision >= 0.95,
        "recall {recall}, precision {precision}"
    );
}

#[test]
fn a_sets_tag_narrows_the_passs_objects() {
    // Two cubes side by side (x = ∓1.6); only the right one is `hero`. The
    // red set draws the hero's silhouette, the blue one every object's
    // silhouette it has left: the other cube's. A set's tag selects
    // objects, so neither draws the other's edges.
    let objects =
        "[[object]]\nprimitive = { kind = \"cube\", size = 1.0 }\ntranslate = [1.0, 0.0, -1.0]\ntags = [\"hero\"]\n\n\
                   [[object]]\nprimitive = { kind = \"cube\", size = 1.0 }\ntranslate = [-1.0, 0.0, 1.0]\n";
    let scene = scene_of("two-cubes", objects);
    let text = "style \"Sets\"
pass ink: lines(scene) {
  amplitude: 0px
  set hero { edges: silhouette, tag: hero, color: #ff0000, priority: 1 }
  set rest { edges: silhouette, color: #0000ff }
  out ink: rgba8unorm = vec4(line.color.rgb, 1.0) { blend: over }
  clear: #ffffff
}
output ink.ink
";
    let (red, blue) = render_on(text, &scene);
    let vp = view_proj();
    let screen_x = |x: f64, z: f64| common::lines::project(vp, DVec3::new(x, 0.0, z), SIZE).x;
    // Each cube's centre on screen, and the midpoint between them.
    let (hero_x, other_x) = (screen_x(1.0, -1.0), screen_x(-1.0, 1.0));
    let middle = 0.5 * (hero_x + other_x);
    assert!(
        red.len() > 100 && blue.len() > 100,
        "{} red, {} blue",
        red.len(),
        blue.len()
    );
    let on_hero_side = |p: &DVec2| (p.x - middle) * (hero_x - middle) > 0.0;
    assert!(red.iter().all(on_hero_side), "red ink off the hero cube");
    assert!(blue.iter().all(|p| !on_hero_side(p)), "blue ink on the hero cube");
}

#[test]
fn set_strips_are_rebuilt_only_when_the_view_or_an_object_changes() {
    let mut scene = cube_scene();
    let program = compile_text(&two_sets(1));
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let spec = FrameSpec::still(SIZE, SIZE, 0);
    let rebuilds = |r: &Renderer| r.lines_rebuilds()[0].1;
    r.render(&scene, &spec).expect("frame 1");
    r.render(&scene, &spec).expect("frame 2");
    assert_eq!(rebuilds(&r), 1, "an unchanged frame reuses the sets' strips");
    scene.objects[0].model = glam::Mat4::from_translation(glam::Vec3::new(0.3, 0.0, 0.0));
    r.render(&scene, &spec).expect("frame 3");
    assert_eq!(rebuilds(&r), 2, "a moved object rebuilds them");
}
