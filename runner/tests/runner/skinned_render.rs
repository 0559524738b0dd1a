//! The render of an object playing a clip equals the render of the same
//! pose skinned in f64 by an independent reference
//! (`common/skin_reference.rs`) and drawn as a rigid mesh: view depth
//! within 1e-4 relative wherever both cover a pixel, and the lit image
//! within a mean FLIP of 0.01, the image shadowed through a light-view
//! depth pass likewise, and the silhouette lines (built on the CPU
//! from the frame's mesh) within a mean FLIP of 0.01, for several poses of the Blender-exported
//! arm (skin) and blob (morph targets). The passes draw the GPU
//! deformation stage's vertices (docs/decisions/0053); the lines, and the
//! light camera of the shadowed style, read the CPU's deformation of the
//! same pose. On failure the images are written under the target's
//! temporary folder.

use crate::skin_reference;

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::scene::{Mesh, Scene};
use npr_runner::{FrameSpec, Gpu, Renderer, StyleProgram};
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        Gpu::headless()
            .unwrap_or_else(|e| panic!("runner tests need a GPU adapter (Mesa's lavapipe: `./setup.sh --tests`): {e}"))
    })
}

const SIZE: u32 = 96;

/// Mean FLIP bound of every image comparison's shadowed one.
const SHADOW_FLIP_BOUND: f32 = 0.01;

const SHADE: &str = r#"
style "skinned shade"
pass shade: render(scene) {
  let lit = lambert(normal, light.dir)
  out c: rgba8unorm = vec4(lit, lit * 0.8, 0.3 + 0.7 * lit, 1.0)
  clear: #000000
}
output shade.c
"#;

const DEPTH: &str = r#"
style "skinned depth"
pass shade: render(scene) {
  out z: r32float = position.view.z
  clear: #000000
}
output shade.z
"#;

/// Silhouettes only, drawn 2 px wide: built on the CPU from the object's
/// mesh of the frame (`lines/`), so they follow the deformation.
const LINES: &str = r#"
style "skinned lines"
pass ink: lines(scene) {
  silhouettes: true
  width: 2px
  out c: rgba8unorm = vec4(1.0, 1.0, 1.0, 1.0)
  clear: #000000
}
output ink.c
"#;

/// The light-view depth pass draws the object's vertices of the frame too:
/// its shadow on the ground moves with the pose.
const SHADOW: &str = r#"
style "skinned shadow"
pass depth: render(scene) view(light) {
  out d: r32float = position.light.z
  clear: #ffffff
}
pass shade: render(scene) {
  let lit = lambert(normal, light.dir) * shadow(depth.d, bias: 0.02, radius: 0)
  out c: rgba8unorm = vec4(lit, lit, lit, 1.0)
  clear: #000000
}
output shade.c
"#;

fn compile(name: &str, text: &str) -> StyleProgram {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source(name, text, Path::new("."), &mut sources, &CompileOptions::default()) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

fn blender() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models")
}

fn scene(text: &str) -> Scene {
    npr_runner::scene::parse_scene(text, npr_diag::FileId(0), &blender()).unwrap_or_else(|d| panic!("scene: {d:?}"))
}

/// The scene with its one object replaced by the f64 reference's mesh at
/// clip time `clip_t`, drawn rigidly.
fn reference_scene(scene: &Scene, file: &str, clip: &str, clip_t: f64) -> Scene {
    let deformed = skin_reference::deform(&blender().join(file), Some((clip, clip_t)));
    let mesh = Mesh::from_parts(
        deformed.positions.iter().map(|p| p.as_vec3().to_array()).collect(),
        Some(deformed.normals.iter().map(|n| n.as_vec3().to_array()).collect()),
        None,
        None,
        deformed.indices,
        format!("{file} skinned in f64"),
    );
    let mut rigid = scene.clone();
    rigid.objects[0].mesh = Arc::new(mesh);
    rigid.objects[0].animation = None;
    rigid
}

fn render(program: &StyleProgram, scene: &Scene, time_s: f64) -> Vec<u8> {
    let mut r = Renderer::new(&gpu().device, &gpu().queue, program, scene).expect("renderer");
    let spec = FrameSpec {
        width: SIZE,
        height: SIZE,
        time_s,
        frame: 0,
        eye: 0,
    };
    r.render(scene, &spec).expect("render");
    r.read_output().expect("read").bytes
}

fn rgba(bytes: &[u8]) -> image::RgbaImage {
    image::RgbaImage::from_raw(SIZE, SIZE, bytes.to_vec()).expect("size")
}

fn flip_mean(a: &image::RgbaImage, b: &image::RgbaImage) -> f32 {
    let rgb = |img: &image::RgbaImage| {
        let data: Vec<u8> = img.pixels().flat_map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
        nv_flip::FlipImageRgb8::with_data(img.width(), img.height(), &data)
    };
    let map = nv_flip::flip(rgb(b), rgb(a), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    nv_flip::FlipPool::from_image(&map).mean()
}

/// Renders `text`'s animated object at scene time `time_s` and the f64
/// reference of the same pose; checks depth and image.
fn check(text: &str, file: &str, clip: &str, time_s: f64) {
    let (shade, depth) = (compile("shade.npr", SHADE), compile("depth.npr", DEPTH));
    let animated = scene(text);
    let playing = animated.objects[0].animation.as_ref().expect("the object plays a clip");
    let clip_t = f64::from(playing.clip_time(time_s));
    let rigid = reference_scene(&animated, file, clip, clip_t);

    let z = |bytes: Vec<u8>| -> Vec<f32> { bytemuck_f32(&bytes) };
    let (za, zr) = (z(render(&depth, &animated, time_s)), z(render(&depth, &rigid, time_s)));
    let (mut covered, mut coverage_differs, mut worst) = (0usize, 0usize, 0.0f64);
    for (a, r) in za.iter().zip(&zr) {
        match (*a != 0.0, *r != 0.0) {
            (true, true) => {
                covered += 1;
                worst = worst.max(f64::from((a - r).abs()) / f64::from(r.abs()));
            }
            (false, false) => {}
            _ => coverage_differs += 1,
        }
    }
    let (ca, cr) = (
        rgba(&render(&shade, &animated, time_s)),
        rgba(&render(&shade, &rigid, time_s)),
    );
    let flip = flip_mean(&ca, &cr);
    let lines = compile("lines.npr", LINES);
    let (la, lr) = (
        rgba(&render(&lines, &animated, time_s)),
        rgba(&render(&lines, &rigid, time_s)),
    );
    let inked = lr.pixels().filter(|p| p.0[0] > 0).count();
    let lines_flip = flip_mean(&la, &lr);
    let shadow = compile("shadow.npr", SHADOW);
    let (sa, sr) = (
        rgba(&render(&shadow, &animated, time_s)),
        rgba(&render(&shadow, &rigid, time_s)),
    );
    let shadow_flip = flip_mean(&sa, &sr);
    eprintln!(
        "{file} at t = {time_s}: {covered} pixels covered, {coverage_differs} by one only, depth error {worst:e}, FLIP {flip}; \
         silhouette lines: {inked} pixels inked, FLIP {lines_flip}; shadowed: FLIP {shadow_flip}"
    );
    let ok = covered > 300
        && coverage_differs <= 2
        && worst <= 1e-4
        && flip <= 0.01
        && inked > 100
        && lines_flip <= 0.01
        && shadow_flip <= SHADOW_FLIP_BOUND;
    if !ok {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("skinned_render");
        std::fs::create_dir_all(&dir).expect("scratch");
        let stem = format!("{file}-{time_s}");
        ca.save(dir.join(format!("{stem}-actual.png"))).expect("save");
        cr.save(dir.join(format!("{stem}-reference.png"))).expect("save");
        la.save(dir.join(format!("{stem}-lines-actual.png"))).expect("save");
        lr.save(dir.join(format!("{stem}-lines-reference.png"))).expect("save");
        sa.save(dir.join(format!("{stem}-shadow-actual.png"))).expect("save");
        sr.save(dir.join(format!("{stem}-shadow-reference.png"))).expect("save");
        panic!(
            "{file} at t = {time_s}: {covered} pixels covered, {coverage_differs} covered by one only, \
             depth error {worst:e} relative, FLIP {flip}; lines: {inked} inked, FLIP {lines_flip}; shadow FLIP {shadow_flip}; images in {}",
            dir.display()
        );
    }
}

fn bytemuck_f32(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

const ARM: &str = "[camera]\nposition = [0.0, 1.0, 4.5]\ntarget = [0.0, 1.0, 0.0]\n\
                   [light]\ndirection = [-0.6, 1.0, 0.5]\n\
                   [[object]]\nmesh = \"arm.glb\"\nrotate = [0.0, 70.0, 0.0]\nanimation = { clip = \"bend\" }\n\
                   [[object]]\nprimitive = { kind = \"plane\", size = 4.0 }\n";

const BLOB: &str = "[camera]\nposition = [0.0, 0.8, 6.5]\ntarget = [0.0, 0.8, 0.0]\n\
                    [light]\ndirection = [-0.6, 1.0, 0.5]\n\
                    [[object]]\nmesh = \"blob.glb\"\nanimation = { clip = \"pulse\", speed = 0.5 }\n\
                    [[object]]\nprimitive = { kind = \"plane\", size = 5.0 }\ntranslate = [0.0, -1.2, 0.0]\n";

#[test]
fn the_skinned_arm_renders_as_its_f64_reference() {
    for t in [0.2, 0.55, 0.8] {
        check(ARM, "arm.glb", "bend", t);
    }
}

#[test]
fn the_morphing_blob_renders_as_its_f64_reference() {
    for t in [0.3, 1.1] {
        check(BLOB, "blob.glb", "pulse", t);
    }
}

/// The silhouette edges of the f64-skinned arm at clip time `clip_t`, seen
/// from the scene's camera, projected to pixels (y down): interior edges
/// (vertices welded by position across the UV seam) whose two triangles
/// face opposite ways from the camera (the definition of
/// `lines::edges`, computed here independently from the f64 mesh).
fn reference_silhouette(scene: &Scene, clip_t: f64) -> Vec<(glam::DVec2, glam::DVec2)> {
    use std::collections::HashMap;
    let deformed = skin_reference::deform(&blender().join("arm.glb"), Some(("bend", clip_t)));
    let model = scene.objects[0].model.as_dmat4();
    let world: Vec<glam::DVec3> = deformed.positions.iter().map(|p| model.transform_point3(*p)).collect();
    let key = |p: glam::DVec3| ((p * 1e5).round().as_i64vec3()).to_array();
    let mut welded: HashMap<[i64; 3], usize> = HashMap::new();
    let ids: Vec<usize> = world
        .iter()
        .map(|p| {
            let n = welded.len();
            *welded.entry(key(*p)).or_insert(n)
        })
        .collect();
    let pose = scene.camera.pose(0.0);
    let eye = pose.position(0).as_dvec3();
    let view_projection = (pose.projection(1.0) * pose.view(0)).as_dmat4();
    let project = |p: glam::DVec3| {
        let c = view_projection * p.extend(1.0);
        glam::DVec2::new(
            (c.x / c.w * 0.5 + 0.5) * f64::from(SIZE),
            (0.5 - c.y / c.w * 0.5) * f64::from(SIZE),
        )
    };
    // Per welded edge: each face's facing, and the edge's two vertices.
    type FacesOfEdge = HashMap<(usize, usize), Vec<(bool, usize, usize)>>;
    let mut faces_of_edge: FacesOfEdge = HashMap::new();
    for t in deformed.indices.chunks_exact(3) {
        let [a, b, c] = [t[0] as usize, t[1] as usize, t[2] as usize];
        let normal = (world[b] - world[a]).cross(world[c] - world[a]);
        let front = normal.dot(eye - (world[a] + world[b] + world[c]) / 3.0) > 0.0;
        for (u, v) in [(a, b), (b, c), (c, a)] {
            let edge = (ids[u].min(ids[v]), ids[u].max(ids[v]));
            faces_of_edge.entry(edge).or_default().push((front, u, v));
        }
    }
    faces_of_edge
        .values()
        .filter(|faces| faces.len() == 2 && faces[0].0 != faces[1].0)
        .map(|faces| (project(world[faces[0].1]), project(world[faces[0].2])))
        .collect()
}

fn distance_to_segment(p: glam::DVec2, (a, b): (glam::DVec2, glam::DVec2)) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t).distance(p)
}

/// The silhouette lines of the skinned arm (built on the CPU from the
/// frame's deformed mesh, drawn 2 px wide) lie on the silhouette of the
/// mesh skinned in f64 by the independent reference, for three poses:
/// every pixel inked at least half has its centre within 2.5 px of a
/// reference silhouette edge (the stroke's half width, 1 px; half a pixel
/// of antialiased coverage; and 1 px of tolerance on the line itself),
/// and at least 90 % of points sampled every 0.5 px along the reference
/// silhouette have such ink within that distance (parts hidden behind
/// the arm itself are not drawn: the remaining 10 % allow for them).
#[test]
fn lines_on_the_skinned_arm_lie_on_the_f64_skinned_silhouette() {
    let lines = compile("lines.npr", LINES);
    let animated = scene(ARM);
    for clip_t in [0.2, 0.55, 0.8] {
        let truth = reference_silhouette(&animated, clip_t);
        assert!(truth.len() > 20, "t {clip_t}: {} silhouette edges", truth.len());
        let image = rgba(&render(&lines, &animated, clip_t));
        let inked: Vec<glam::DVec2> = image
            .enumerate_pixels()
            .filter(|(_, _, p)| p.0[0] >= 128)
            .map(|(x, y, _)| glam::DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5))
            .collect();
        assert!(inked.len() > 50, "t {clip_t}: only {} pixels inked", inked.len());
        let reach = 2.5;
        let stray: Vec<&glam::DVec2> = inked
            .iter()
            .filter(|p| truth.iter().all(|s| distance_to_segment(**p, *s) > reach))
            .collect();
        let samples: Vec<glam::DVec2> = truth
            .iter()
            .flat_map(|&(a, b)| {
                let n = ((b - a).length() / 0.5).ceil().max(1.0) as usize;
                (0..=n).map(move |k| a.lerp(b, k as f64 / n as f64))
            })
            .filter(|p| p.x >= 0.0 && p.y >= 0.0 && p.x < f64::from(SIZE) && p.y < f64::from(SIZE))
            .collect();
        let covered = samples
            .iter()
            .filter(|s| inked.iter().any(|p| p.distance(**s) <= reach))
            .count();
        let recall = covered as f64 / samples.len() as f64;
        let farthest = stray
            .iter()
            .map(|p| {
                truth
                    .iter()
                    .map(|s| distance_to_segment(**p, *s))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max);
        if !stray.is_empty() || recall < 0.9 {
            let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("skinned-silhouette");
            std::fs::create_dir_all(&dir).expect("output dir");
            image.save(dir.join(format!("arm-lines-{clip_t}.png"))).expect("save");
        }
        assert!(
            stray.is_empty() && recall >= 0.9,
            "t {clip_t}: {} of {} inked pixels farther than {reach} px from the f64 silhouette (first {:?}, \
             farthest {farthest:.2} px); recall {recall:.3} of {} samples",
            stray.len(),
            inked.len(),
            stray.first(),
            samples.len()
        );
    }
}
