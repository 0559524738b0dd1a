//! Skinned and morphing glTF files (issue 48): the runner's CPU pose and
//! deformation (`scene::rig`) against hand-computed positions and against
//! an independent f64 reference (`common/skin_reference.rs`), on a
//! hand-built skinned triangle and on the Blender-exported characters of
//! `examples/models/` (made by `tests/data/blender/make_characters.py`);
//! scenes playing clips; and the coded errors of bad files and bad
//! `animation` fields.

use crate::skin_reference;

use glam::Vec3;
use npr_runner::scene::{load_mesh_and_rig, parse_scene};
use std::path::{Path, PathBuf};

fn blender(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/models")
        .join(name)
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn close(a: [f32; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (f64::from(a[i]) - b[i]).abs() <= tol)
}

#[test]
fn the_skinned_triangle_poses_as_computed_by_hand() {
    let (rest, rig) = load_mesh_and_rig(&data("skinned_triangle.gltf")).expect("loads");
    let rig = rig.expect("a rig");
    // The rest pose: joint matrices are identity (bone1's inverse bind
    // undoes its translation), the morph weight is 0.
    for (p, want) in rest
        .positions
        .iter()
        .zip([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    {
        assert!(close(*p, want, 1e-6), "rest {p:?} vs {want:?}");
    }
    let clip = rig.clip_index("wave").expect("clip wave");
    let h = std::f64::consts::FRAC_1_SQRT_2;
    // t = 0.5: bone1 turned 45° about Z about (0, 1, 0); the STEP weight is
    // still 0. Vertex 1, (1, 0, 0), is half on each bone: bone0 leaves it,
    // bone1 takes it to R45·(1, −1) + (0, 1) = (√2, 1).
    let half = rig.deform(&rig.pose(Some((clip, 0.5))));
    let v1 = [(1.0 + 2.0 * h) / 2.0, 0.5, 0.0];
    assert!(close(half.positions[1], v1, 1e-6), "{:?} vs {v1:?}", half.positions[1]);
    assert!(
        close(half.positions[2], [-h, 1.0 + h, 0.0], 1e-6),
        "{:?}",
        half.positions[2]
    );
    assert!(
        close(half.positions[0], [0.0, 0.0, 0.0], 1e-6),
        "{:?}",
        half.positions[0]
    );
    // t = 1: 90°, and the STEP weight has reached 1 (vertex 0 moves +0.5 z).
    let end = rig.deform(&rig.pose(Some((clip, 1.0))));
    assert!(close(end.positions[0], [0.0, 0.0, 0.5], 1e-6), "{:?}", end.positions[0]);
    assert!(close(end.positions[1], [1.0, 1.0, 0.0], 1e-6), "{:?}", end.positions[1]);
    assert!(
        close(end.positions[2], [-1.0, 1.0, 0.0], 1e-6),
        "{:?}",
        end.positions[2]
    );
}

/// Largest distance between the runner's deformation and the f64 reference,
/// positions and normals, at clip `clip` time `t`.
fn worst_error(path: &Path, clip: Option<(&str, f64)>) -> (f64, f64) {
    let (_, rig) = load_mesh_and_rig(path).expect("loads");
    let rig = rig.expect("a rig");
    let pose = rig.pose(clip.map(|(name, t)| (rig.clip_index(name).expect("clip"), t as f32)));
    let mesh = rig.deform(&pose);
    let reference = skin_reference::deform(path, clip);
    assert_eq!(mesh.positions.len(), reference.positions.len());
    assert_eq!(mesh.indices, reference.indices, "the same triangles in the same order");
    let mut worst = (0.0f64, 0.0f64);
    for (i, p) in mesh.positions.iter().enumerate() {
        let d = (Vec3::from_array(*p).as_dvec3() - reference.positions[i]).length();
        let n = (Vec3::from_array(mesh.normals[i]).as_dvec3() - reference.normals[i]).length();
        worst = (worst.0.max(d), worst.1.max(n));
    }
    worst
}

#[test]
fn the_blender_arm_bends_as_the_f64_reference_does() {
    let path = blender("arm.glb");
    let (rest, rig) = load_mesh_and_rig(&path).expect("arm.glb loads");
    let rig = rig.expect("arm.glb has a rig");
    assert_eq!(rig.skins.len(), 1);
    assert_eq!(rig.skins[0].joints.len(), 2);
    // 12 × 17 on the tube, and the UV seam's 17 again.
    assert_eq!(rest.vertex_count(), 12 * 17 + 17);
    assert!(rest.uvs.is_some());
    let names: Vec<&str> = rig.clips.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["bend"]);
    let duration = f64::from(rig.clips[0].duration);
    // The clip turns the lower bone 70° at its middle: the tip moves far.
    let tip_rest = rest.positions.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
    let bent = rig.deform(&rig.pose(Some((0, (duration / 2.0) as f32))));
    let tip_bent = bent.positions.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
    assert!(tip_rest - tip_bent > 0.3, "the arm bends: top {tip_rest} → {tip_bent}");
    for t in [0.0, 0.13, duration * 0.37, duration / 2.0, duration * 0.8, duration] {
        let (dp, dn) = worst_error(&path, Some(("bend", t)));
        assert!(
            dp < 2e-6 * 2.0 && dn < 1e-5,
            "t = {t}: position error {dp}, normal error {dn}"
        );
    }
    let (dp, dn) = worst_error(&path, None);
    assert!(dp < 4e-6 && dn < 1e-5, "rest: {dp}, {dn}");
}

#[test]
fn the_blender_blob_morphs_as_the_f64_reference_does() {
    let path = blender("blob.glb");
    let (_, rig) = load_mesh_and_rig(&path).expect("blob.glb loads");
    let rig = rig.expect("blob.glb has a rig");
    assert!(rig.skins.is_empty());
    let node = rig.pieces[0].node;
    assert_eq!(rig.default_weights[node], [0.25, 0.0], "the exported default weights");
    assert_eq!(rig.pieces[0].targets.len(), 2);
    let duration = f64::from(rig.clips[rig.clip_index("pulse").expect("clip pulse")].duration);
    for t in [0.0, 0.2, duration / 2.0, duration * 0.9] {
        let (dp, dn) = worst_error(&path, Some(("pulse", t)));
        assert!(
            dp < 4e-6 && dn < 1e-5,
            "t = {t}: position error {dp}, normal error {dn}"
        );
    }
    // Rest: the default 0.25 of `inflate` is applied (radius 1 → 1.075).
    let (rest, _) = load_mesh_and_rig(&path).expect("loads");
    let radius = rest
        .positions
        .iter()
        .map(|p| Vec3::from_array(*p).length())
        .fold(0.0f32, f32::max);
    assert!((radius - 1.075).abs() < 1e-4, "rest radius {radius}");
}

const CAMERA: &str = "[camera]\nposition = [0.0, 1.0, 6.0]\ntarget = [0.0, 1.0, 0.0]\n";

fn scene_text(objects: &str) -> String {
    format!("{CAMERA}{objects}")
}

#[test]
fn objects_play_clips_with_speed_loop_and_offset() {
    let dir = blender("");
    let text = scene_text(
        "[[object]]\nname = \"a\"\nmesh = \"arm.glb\"\nanimation = { clip = \"bend\" }\n\
         [[object]]\nname = \"b\"\nmesh = \"arm.glb\"\nanimation = { clip = \"bend\", speed = 2.0, loop = false, offset = 0.25 }\n\
         [[object]]\nname = \"still\"\nmesh = \"arm.glb\"\n",
    );
    let scene = parse_scene(&text, npr_diag::FileId(0), &dir).expect("scene");
    let [a, b, still] = &scene.objects[..] else {
        panic!("three objects")
    };
    let (a, b) = (
        a.animation.as_ref().expect("a plays"),
        b.animation.as_ref().expect("b plays"),
    );
    assert!(still.animation.is_none());
    assert!(std::sync::Arc::ptr_eq(&a.rig, &b.rig), "one file's rig, shared");
    let d = f64::from(a.rig.clips[0].duration);
    assert_eq!(a.clip_time(d * 1.5), (d * 0.5) as f32, "looping wraps");
    assert_eq!(b.clip_time(0.1), 0.45f32);
    // Not looping: past the end the sampler holds the last pose.
    assert_eq!(b.clip_time(d), (0.25 + 2.0 * d) as f32);
    assert_eq!(
        b.rig.deform(&b.rig.pose(Some((0, b.clip_time(d))))).positions,
        b.rig.deform(&b.rig.pose(Some((0, d as f32)))).positions
    );
    // Posed at t: a's mesh is the rig deformed at t; the still object keeps its mesh.
    let posed = scene.posed(0.4);
    let want = a.rig.deform(&a.rig.pose(Some((0, 0.4))));
    assert_eq!(posed.objects[0].mesh.positions, want.positions);
    assert!(std::sync::Arc::ptr_eq(&posed.objects[2].mesh, &scene.objects[2].mesh));
    // A scene where nothing plays (a rigged file drawn still) is not
    // copied: a rigid object costs nothing per frame.
    let still = parse_scene(
        &scene_text("[[object]]\nmesh = \"arm.glb\"\n"),
        npr_diag::FileId(0),
        &dir,
    )
    .expect("scene");
    assert!(matches!(still.posed(0.4), std::borrow::Cow::Borrowed(_)));
}

fn scene_errors(objects: &str, dir: &Path) -> String {
    let text = scene_text(objects);
    let mut sources = npr_diag::SourceMap::default();
    let file = sources.add("scene.toml", text.clone());
    let diags = parse_scene(&text, file, dir).expect_err("the scene is refused");
    npr_diag::diagnostic::render(&diags, &sources, false)
}

#[test]
fn a_missing_clip_is_named_with_the_files_clips() {
    let out = scene_errors(
        "[[object]]\nmesh = \"arm.glb\"\nanimation = { clip = \"walk\" }\n",
        &blender(""),
    );
    assert!(out.contains("error[E0405]: the mesh has no clip `walk`"), "{out}");
    assert!(out.contains("the file's clips are `bend`"), "{out}");
    let out = scene_errors(
        "[[object]]\nprimitive = { kind = \"cube\" }\nanimation = { clip = \"walk\" }\n",
        &blender(""),
    );
    assert!(out.contains("error[E0405]"), "{out}");
    assert!(out.contains("the object's mesh has no animations"), "{out}");
    let out = scene_errors(
        "[[object]]\nmesh = \"arm.glb\"\nanimation = { speed = 2.0 }\n",
        &blender(""),
    );
    assert!(out.contains("`animation` has no `clip`"), "{out}");
}

/// The skinned triangle with `from` replaced by `to` in its JSON, loaded.
fn load_variant(from: &str, to: &str) -> npr_runner::scene::MeshLoadError {
    let text = std::fs::read_to_string(data("skinned_triangle.gltf")).expect("read");
    assert!(text.contains(from), "the test file has `{from}`");
    let dir = std::env::temp_dir().join(format!("npr-gltf-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(format!("variant-{}.gltf", from.len() * 31 + to.len()));
    std::fs::write(&path, text.replace(from, to)).expect("write");
    let err = load_mesh_and_rig(&path).expect_err("the variant is refused");
    assert!(
        err.message.contains(&path.display().to_string()),
        "names the file: {}",
        err.message
    );
    err
}

#[test]
fn bad_rigs_get_a_code_the_file_and_the_gltf_path() {
    let err = load_variant("\"WEIGHTS_0\":3", "\"WEIGHTS_0\":9");
    assert_eq!(err.code, "E0402");
    assert!(
        err.message.contains("`/meshes/0/primitives/0/attributes/WEIGHTS_0`") && err.message.contains("sum to 0.5"),
        "{}",
        err.message
    );
    let joints: Vec<String> = (0..300).map(|i| (1 + i % 2).to_string()).collect();
    let err = load_variant("\"joints\":[1,2]", &format!("\"joints\":[{}]", joints.join(",")));
    assert_eq!(err.code, "E0404");
    assert!(
        err.message.contains("`/skins/0/joints`") && err.message.contains("300 joints"),
        "{}",
        err.message
    );
    let err = load_variant("\"output\":7", "\"output\":10");
    assert_eq!(err.code, "E0402");
    assert!(
        err.message.contains("`/animations/0/samplers/0/output`"),
        "{}",
        err.message
    );
    // Weights animated on a node without morph targets.
    let err = load_variant("{\"node\":3,\"path\":\"weights\"}", "{\"node\":2,\"path\":\"weights\"}");
    assert_eq!(err.code, "E0402");
    assert!(
        err.message.contains("`/animations/0/channels/1/target`"),
        "{}",
        err.message
    );
    // A sampler whose accessor does not exist: the glTF reader's own check.
    let err = load_variant("\"output\":7", "\"output\":70");
    assert_eq!(err.code, "E0402");
    assert!(err.message.contains("output"), "{}", err.message);
}
