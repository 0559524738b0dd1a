//! The `lines` pass kind (Klein et al. 2000, §5) through the compiler and the
//! real renderer on lavapipe, against exact truth: the cube's nine visible
//! creases are drawn and its three hidden ones are not; a sphere's
//! silhouette follows the analytic circle and keeps the inner half of its
//! width and the inward half of its wave (the visibility test at the edge
//! point, not per fragment); an animated width follows its keyframes;
//! strips are rebuilt only when something they depend on changes; edges
//! crossing the near plane draw without NaN; in a stereo frame each eye
//! draws the silhouette seen from that eye; a mesh divided into patches
//! (Breslav et al. 2007 §3.6) draws the lines of the undivided mesh, no
//! seam between patches as a boundary.
//!
//! Ink, recall and precision are those of `tests/common/lines.rs`.

use glam::{DMat4, DVec2, DVec3, Mat4};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer};
use std::path::Path;

use crate::common;
use common::lines::{self, distance, ink, recall_precision, style};
use common::{compile_text, gpu};

const SIZE: u32 = 256;
const FOV_DEG: f64 = 40.0;

fn scene(objects: &str, eye: DVec3) -> Scene {
    scene_looking_at(objects, eye, DVec3::ZERO)
}

fn scene_looking_at(objects: &str, eye: DVec3, target: DVec3) -> Scene {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("lines-pass");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    // Tests run in parallel: one file per call.
    static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = dir.join(format!("scene-{}-{n}.toml", std::process::id()));
    let text = format!(
        "[camera]\nposition = [{}, {}, {}]\ntarget = [{}, {}, {}]\nfov = {FOV_DEG}\nnear = 0.1\nfar = 100.0\n\n{objects}",
        eye.x, eye.y, eye.z, target.x, target.y, target.z
    );
    std::fs::write(&path, text).expect("write scene");
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn view_proj(eye: DVec3) -> DMat4 {
    view_proj_looking(eye, DVec3::ZERO)
}

fn view_proj_looking(eye: DVec3, target: DVec3) -> DMat4 {
    DMat4::perspective_rh(FOV_DEG.to_radians(), 1.0, 0.1, 100.0) * DMat4::look_at_rh(eye, target, DVec3::Y)
}

fn project(vp: DMat4, p: DVec3) -> DVec2 {
    lines::project(vp, p, SIZE)
}

fn render_at(text: &str, scene: &Scene, time_s: f64) -> Vec<DVec2> {
    lines::render_ink(text, scene, SIZE, time_s)
}

fn samples(vp: DMat4, segments: &[(DVec3, DVec3)]) -> Vec<DVec2> {
    lines::samples(vp, segments, SIZE)
}

const CUBE: &str = "[[object]]\nprimitive = { kind = \"cube\", size = 2.0 }\n";

#[test]
fn visible_cube_creases_are_drawn_and_hidden_ones_are_not() {
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let drawn = render_at(
        &style("silhouettes: false  creases: 40deg  width: 2px  amplitude: 0px  depth: test(shade, bias: 1px)"),
        &scene(CUBE, eye),
        0.0,
    );
    let vp = view_proj(eye);
    let c = DVec3::new;
    // The edges of the three faces turned to the eye (+X, +Y, +Z), and the
    // three at the far corner (−1, −1, −1).
    let mut visible = Vec::new();
    for (axis, u, v) in [
        (DVec3::X, DVec3::Y, DVec3::Z),
        (DVec3::Y, DVec3::Z, DVec3::X),
        (DVec3::Z, DVec3::X, DVec3::Y),
    ] {
        let corners = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)];
        for w in corners.windows(2) {
            visible.push((axis + u * w[0].0 + v * w[0].1, axis + u * w[1].0 + v * w[1].1));
        }
    }
    let far = c(-1.0, -1.0, -1.0);
    let hidden = [
        (far, c(1.0, -1.0, -1.0)),
        (far, c(-1.0, 1.0, -1.0)),
        (far, c(-1.0, -1.0, 1.0)),
    ];
    let visible = samples(vp, &visible);
    let (recall, precision) = recall_precision(&drawn, &visible, 1.0);
    // Hidden edges away from where they meet the silhouette (6 px).
    let hidden: Vec<DVec2> = samples(vp, &hidden)
        .into_iter()
        .filter(|h| distance(*h, &visible) > 6.0)
        .collect();
    let leaked = hidden
        .iter()
        .filter(|h| drawn.iter().any(|p| (*p - **h).length() <= 1.0))
        .count();
    eprintln!(
        "cube creases through the renderer: recall {recall:.4}, precision {precision:.4}, {} hidden samples, {leaked} with ink",
        hidden.len()
    );
    assert!(
        hidden.len() > 300,
        "the hidden edges are mostly away from the visible ones"
    );
    assert_eq!(leaked, 0, "hidden creases drawn");
    assert!(
        recall >= 0.99 && precision >= 0.99,
        "recall {recall}, precision {precision}"
    );
}

/// The sphere's silhouette from `eye` on the z axis: the circle p·ê = 1/d of
/// radius √(1 − 1/d²), as (its samples, its centre and radius on screen).
fn sphere_rim(eye: DVec3) -> (Vec<DVec2>, DVec2, f64) {
    sphere_rim_seen(eye, view_proj(eye))
}

/// The same from any `eye` through `vp`: the circle around ê/d in the plane
/// normal to ê (u, v spanning it).
fn sphere_rim_seen(eye: DVec3, vp: DMat4) -> (Vec<DVec2>, DVec2, f64) {
    let d = eye.length();
    let e = eye / d;
    let u = e.any_orthonormal_vector();
    let v = e.cross(u);
    let r = (1.0 - 1.0 / (d * d)).sqrt();
    let truth: Vec<DVec2> = (0..=1024)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / 1024.0;
            project(vp, (u * a.cos() + v * a.sin()) * r + e / d)
        })
        .collect();
    let centre = project(vp, e / d);
    let radius = (truth[0] - centre).length();
    (truth, centre, radius)
}

const SPHERE: &str = "[[object]]\nprimitive = { kind = \"sphere\", radius = 1.0, segments = 64, rings = 32 }\n";

#[test]
fn a_sphere_silhouette_keeps_its_inner_half_and_its_inward_waves() {
    let eye = DVec3::new(0.0, 0.0, 4.0);
    let (truth, centre, radius) = sphere_rim(eye);
    let straight = render_at(
        &style("width: 3px  amplitude: 0px  depth: test(shade, bias: 1px)"),
        &scene(SPHERE, eye),
        0.0,
    );
    let (recall, precision) = recall_precision(&straight, &truth, 1.5);
    let inner = straight
        .iter()
        .filter(|p| (**p - centre).length() < radius - 0.25)
        .count();
    let outer = straight
        .iter()
        .filter(|p| (**p - centre).length() > radius + 0.25)
        .count();
    // A wave of 3 px: the line reaches 3 px (+ half its width) inside the rim.
    let wavy = render_at(
        &style("width: 2px  amplitude: 3px  wavelength: 20px  depth: test(shade, bias: 1px)"),
        &scene(SPHERE, eye),
        0.0,
    );
    let deepest = wavy
        .iter()
        .map(|p| radius - (*p - centre).length())
        .fold(f64::MIN, f64::max);
    let farthest = wavy
        .iter()
        .map(|p| (*p - centre).length() - radius)
        .fold(f64::MIN, f64::max);
    eprintln!(
        "sphere silhouette through the renderer: recall {recall:.4}, precision {precision:.4}; \
         {inner} ink pixels inside the rim, {outer} outside; the wave reaches {deepest:.2} px in, {farthest:.2} px out"
    );
    assert!(
        recall >= 0.99 && precision >= 0.99,
        "recall {recall}, precision {precision}"
    );
    // The polygonal rim lies up to (1 − cos(π/64))·r inside the circle, so
    // the inner side gets slightly more ink; without the edge-point test the
    // surface inside the rim hid most of it (52 against ~800 pixels).
    assert!(
        inner as f64 >= 0.8 * outer as f64,
        "inner half lost: {inner} inside, {outer} outside"
    );
    assert!((3.0..=5.5).contains(&deepest), "inward waves reach {deepest} px");
    assert!((3.0..=5.5).contains(&farthest), "outward waves reach {farthest} px");
}

#[test]
fn an_animated_width_follows_its_keyframes() {
    let eye = DVec3::new(0.0, 0.0, 4.0);
    let (_, _, radius) = sphere_rim(eye);
    let text = style("width: w  amplitude: 0px  depth: test(shade, bias: 1px)");
    let at = |t: f64| render_at(&text, &scene(SPHERE, eye), t).len() as f64;
    let (thin, half_way, thick) = (at(0.0), at(0.5), at(1.0));
    // Ink ≈ circumference × width: 2 px, 5 px, 8 px.
    let circumference = std::f64::consts::TAU * radius;
    eprintln!(
        "animated width: {:.2}, {:.2}, {:.2} px of ink per px of rim (keys 2, 5, 8 px)",
        thin / circumference,
        half_way / circumference,
        thick / circumference
    );
    for (measured, want) in [(thin, 2.0), (half_way, 5.0), (thick, 8.0)] {
        let width = measured / circumference;
        assert!(
            (width - want).abs() <= 0.1 * want + 0.3,
            "width {width} px, keyframes say {want} px"
        );
    }
}

#[test]
fn strips_are_rebuilt_only_when_the_view_or_an_object_changes() {
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let mut scene = scene(CUBE, eye);
    let program = compile_text(&style("creases: 40deg  depth: test(shade, bias: 1px)"));
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let spec = FrameSpec::still(SIZE, SIZE, 0);
    let rebuilds = |r: &Renderer| r.lines_rebuilds()[0].1;
    r.render(&scene, &spec).expect("frame 1");
    let first = ink(&r);
    r.render(&scene, &spec).expect("frame 2");
    assert_eq!(rebuilds(&r), 1, "an unchanged frame reuses the strips");
    assert_eq!(ink(&r), first, "and draws the same lines");
    scene.objects[0].model = Mat4::from_translation(glam::Vec3::new(0.3, 0.0, 0.0));
    r.render(&scene, &spec).expect("frame 3");
    assert_eq!(rebuilds(&r), 2, "a moved object rebuilds them");
    assert_ne!(ink(&r), first, "and the lines move with it");
    r.render(&scene, &FrameSpec::still(SIZE / 2, SIZE / 2, 0))
        .expect("frame 4");
    assert_eq!(rebuilds(&r), 3, "a new size rebuilds them");
}

#[test]
fn edges_crossing_the_near_plane_draw_without_nan() {
    // The eye inside the cube near one of its edges along z, looking down
    // it: that edge runs from behind the eye (clipped at the near plane far
    // off screen) to the far face (render passes draw back faces, so the
    // inside has a depth).
    let eye = DVec3::new(0.8, 0.8, 0.6);
    let drawn = render_at(
        &style("creases: 40deg  amplitude: 2px  depth: test(shade, bias: 1px)"),
        &scene_looking_at(CUBE, eye, DVec3::new(0.95, 0.95, -1.0)),
        0.0,
    );
    eprintln!("near-plane edges: {} ink pixels", drawn.len());
    assert!(!drawn.is_empty(), "the edges in front of the eye are drawn");
    assert!(
        drawn.len() < (SIZE * SIZE / 4) as usize,
        "no strip blew up across the image ({} pixels)",
        drawn.len()
    );
}

#[test]
fn a_stereo_frame_draws_each_eyes_own_silhouette() {
    // A style that reads the other eye is stereo: both eyes render each
    // frame. A 0.5 m baseline, so the eyes' rims differ by several pixels;
    // each eye's lines must follow the silhouette seen from that eye.
    let half = 0.25;
    let text = format!(
        "{}\npass both: image(ink) {{\n  out c: rgba8unorm = ink.ink + 0.0 * other_eye(ink.ink)\n}}\noutput both.c\n",
        style("width: 2px  amplitude: 0px  depth: test(shade, bias: 1px)").replace("output ink.ink\n", "")
    );
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("lines-pass");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let path = dir.join(format!("stereo-{}.toml", std::process::id()));
    std::fs::write(
        &path,
        format!("[camera]\nposition = [0.0, 0.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nfov = {FOV_DEG}\nipd = {}\nnear = 0.1\nfar = 100.0\n\n{SPHERE}", 2.0 * half),
    )
    .expect("write scene");
    let mut sources = npr_diag::SourceMap::new();
    let scene = npr_runner::scene::load_scene(&path, &mut sources).unwrap_or_else(|d| panic!("{d:?}"));
    let program = compile_text(&text);
    assert!(program.manifest.is_stereo(), "the style renders both eyes");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let mut drawn = Vec::new();
    for eye in 0..2u32 {
        r.render(&scene, &FrameSpec::still(SIZE, SIZE, eye)).expect("render");
        drawn.push(ink(&r));
    }
    let truths: Vec<Vec<DVec2>> = [-half, half]
        .iter()
        .map(|dx| {
            let at = DVec3::new(*dx, 0.0, 4.0);
            sphere_rim_seen(at, view_proj_looking(at, DVec3::new(*dx, 0.0, 0.0))).0
        })
        .collect();
    for eye in 0..2 {
        let (recall, precision) = recall_precision(&drawn[eye], &truths[eye], 1.0);
        let (cross_recall, _) = recall_precision(&drawn[eye], &truths[1 - eye], 1.0);
        eprintln!(
            "stereo eye {eye}: recall {recall:.4}, precision {precision:.4}; against the other eye's rim recall {cross_recall:.4}"
        );
        assert!(
            recall >= 0.99 && precision >= 0.99,
            "eye {eye}: recall {recall}, precision {precision}"
        );
        assert!(
            cross_recall < 0.9,
            "eye {eye} drew the other eye's rim (recall {cross_recall})"
        );
    }
}

#[test]
fn a_cylinders_rims_and_sides_are_drawn_where_they_are_seen() {
    // Radius 1, height 2, seen from above and to the side. Truth: the top
    // rim (all of it faces the eye, which is above the cap), the half of the
    // bottom rim whose side faces the eye, and the two side generators where
    // the eye's ray grazes the side, n·(e − p) = 0. The mesh has 128
    // segments: its rims lie within r(1 − cos(π/128)) ≈ 0.0003 of the circle.
    let eye = DVec3::new(0.0, 2.6, 4.2);
    let drawn = render_at(
        &style("creases: 40deg  width: 2px  amplitude: 0px  depth: test(shade, bias: 1px)"),
        &scene(
            "[[object]]\nprimitive = { kind = \"cylinder\", radius = 1.0, height = 2.0, segments = 128 }\n",
            eye,
        ),
        0.0,
    );
    let vp = view_proj(eye);
    let circle = |a: f64, y: f64| DVec3::new(a.cos(), y, -a.sin());
    let mut truth = Vec::new();
    for k in 0..2048 {
        let a = std::f64::consts::TAU * f64::from(k) / 2048.0;
        truth.push(project(vp, circle(a, 1.0)));
        let bottom = circle(a, -1.0);
        let outwards = DVec3::new(a.cos(), 0.0, -a.sin());
        if outwards.dot(eye - bottom) > 0.0 {
            truth.push(project(vp, bottom));
        }
    }
    // The grazing azimuths: cos(a − φ) = 1/ρ for the eye at horizontal
    // distance ρ and azimuth φ (outwards · (e − p) = ρ cos(a − φ) − 1).
    let (rho, phi) = (eye.x.hypot(eye.z), (-eye.z).atan2(eye.x));
    for side in [-1.0, 1.0] {
        let a = phi + side * (1.0 / rho).acos();
        for k in 0..=512 {
            let y = -1.0 + 2.0 * f64::from(k) / 512.0;
            truth.push(project(vp, circle(a, y)));
        }
    }
    let (recall, precision) = recall_precision(&drawn, &truth, 1.0);
    eprintln!(
        "cylinder through the renderer: recall {recall:.4}, precision {precision:.4}, {} ink pixels",
        drawn.len()
    );
    assert!(
        recall >= 0.99 && precision >= 0.99,
        "recall {recall}, precision {precision}"
    );
    // The measure can fail: without the depth test the hidden half of the
    // bottom rim is inked too, and precision drops.
    let untested = render_at(
        &style("creases: 40deg  width: 2px  amplitude: 0px"),
        &scene(
            "[[object]]\nprimitive = { kind = \"cylinder\", radius = 1.0, height = 2.0, segments = 128 }\n",
            eye,
        ),
        0.0,
    );
    let (_, precision_untested) = recall_precision(&untested, &truth, 1.0);
    eprintln!("cylinder without the depth test: precision {precision_untested:.4}");
    assert!(
        precision_untested < 0.9,
        "precision without the depth test {precision_untested}"
    );
}

/// The paper's cow in 6 patches (`examples/scenes/patched_cow.toml`, §3.6)
/// and the same cow undivided: the same feature edges at 40° (no seam
/// between patches is a boundary or a crease unless the surface bends
/// there), and the same ink, pixel for pixel, so no line runs along a seam.
/// Drawn patch by patch, every seam edge was a boundary edge.
#[test]
fn a_patched_cows_lines_are_the_undivided_cows() {
    use npr_runner::lines::edges::{EdgeKind, EdgeMesh};
    let root = common::root();
    let path = root.join("examples/scenes/patched_cow.toml");
    let mut sources = npr_diag::SourceMap::new();
    let patched = npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let text = std::fs::read_to_string(&path).expect("scene");
    assert!(text.contains("patches = 6\n"), "the scene splits the cow in 6");
    let whole_text = text.replace("patches = 6\n", "").replace("blend_rings = 2\n", "");
    let file = sources.add("whole_cow.toml", whole_text.clone());
    let whole = npr_runner::scene::parse_scene(&whole_text, file, &root.join("examples/scenes"))
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    assert_eq!((patched.objects.len(), whole.objects.len()), (6, 1));

    let edges = |meshes: Vec<&npr_runner::scene::Mesh>| {
        let mut counts = [0usize; 2];
        for mesh in meshes {
            for (_, kind) in EdgeMesh::new(mesh).creases(40.0) {
                counts[usize::from(kind == EdgeKind::Boundary)] += 1;
            }
        }
        counts
    };
    let surfaces = |scene: &Scene| {
        let drawn: Vec<_> = scene.objects.iter().map(|o| (o, o.mesh.as_ref())).collect();
        edges(
            npr_runner::lines::objects::line_objects(&drawn)
                .iter()
                .map(|s| s.mesh)
                .collect(),
        )
    };
    let [creases, boundaries] = surfaces(&whole);
    let per_patch = edges(patched.objects.iter().map(|o| o.mesh.as_ref()).collect());
    eprintln!(
        "cow at 40°: {creases} creases, {boundaries} boundary edges; patch by patch {} and {}",
        per_patch[0], per_patch[1]
    );
    assert_eq!(surfaces(&patched), [creases, boundaries]);
    assert!(
        per_patch[1] > boundaries + 100,
        "patch by patch, the seams are boundaries: {per_patch:?}"
    );

    let text = style("creases: 40deg  depth: test(shade, bias: 1px)");
    let (a, b) = (render_at(&text, &patched, 0.0), render_at(&text, &whole, 0.0));
    eprintln!("ink: {} px patched, {} px whole", a.len(), b.len());
    assert!(b.len() > 500, "the cow's lines are drawn: {} px", b.len());
    assert_eq!(a, b, "the patched cow's lines differ from the whole cow's");
}
