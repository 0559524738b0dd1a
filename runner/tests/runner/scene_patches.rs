//! `patches = N` and `patches = "parts"` on a scene object (Breslav et al.
//! 2007 §3.6): the object becomes one object per patch, named `<name>.<k>`,
//! which together are the whole mesh with its transform, tags and bindings;
//! a mesh that cannot be divided as asked is an error at the `patches` value.
//! `blend_rings = n` gives each patch its faces and n-ring with its §3.6
//! weights (what passes reading `patch.weight` draw); 0 none.

use npr_runner::scene::{parse_scene, Scene};
use std::path::{Path, PathBuf};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenes")
}

fn parse(text: &str, dir: &Path) -> Result<Scene, String> {
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("patches.toml", text.to_string());
    parse_scene(text, file, dir).map_err(|d| npr_diag::diagnostic::render(&d, &sources, false))
}

const CAMERA: &str = "[camera]\nposition = [0.0, 1.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n";

fn area(mesh: &npr_runner::scene::Mesh) -> f64 {
    mesh.indices
        .chunks_exact(3)
        .map(|t| {
            let p = |i: u32| glam::DVec3::from(mesh.positions[i as usize].map(f64::from));
            0.5 * (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])).length()
        })
        .sum()
}

#[test]
fn a_cow_split_in_four_is_four_objects_that_make_up_the_cow() {
    let whole = parse(
        &format!("{CAMERA}[[object]]\nname = \"cow\"\nmesh = \"../models/cow.obj\"\n"),
        &scenes_dir(),
    )
    .expect("scene");
    let split = parse(
        &format!("{CAMERA}[[object]]\nname = \"cow\"\nmesh = \"../models/cow.obj\"\ntranslate = [1.0, 0.0, 0.0]\ntags = [\"herd\"]\nparams = {{ tint = 0.5 }}\npatches = 4\n"),
        &scenes_dir(),
    )
    .expect("scene");
    let names: Vec<&str> = split.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["cow.0", "cow.1", "cow.2", "cow.3"]);
    let cow = &whole.objects[0].mesh;
    let triangles: usize = split.objects.iter().map(|o| o.mesh.triangle_count()).sum();
    assert_eq!(triangles, cow.triangle_count());
    let total: f64 = split.objects.iter().map(|o| area(&o.mesh)).sum();
    assert!(
        (total - area(cow)).abs() < 1e-9 * area(cow),
        "{total} against {}",
        area(cow)
    );
    for o in &split.objects {
        assert!(
            o.mesh.triangle_count() > cow.triangle_count() / 10,
            "{} is a sliver",
            o.name
        );
        assert!(o.has_tag("herd") && o.params["tint"] == vec![0.5]);
        assert_eq!(o.model, glam::Mat4::from_translation(glam::Vec3::X));
        assert!(o.mesh.validate().is_ok());
    }
}

#[test]
fn an_obj_with_two_groups_has_two_parts() {
    let dir = std::env::temp_dir().join("npr_scene_patches");
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(
        dir.join("two.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\ng left\nf 1 2 3 4\ng right\nf 2 5 6 3\n",
    )
    .expect("write");
    let scene = parse(
        &format!("{CAMERA}[[object]]\nmesh = \"two.obj\"\npatches = \"parts\"\n"),
        &dir,
    )
    .expect("scene");
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["two.0", "two.1"]);
    assert!(scene.objects.iter().all(|o| o.mesh.triangle_count() == 2));
}

#[test]
fn a_division_that_cannot_be_made_is_an_error_at_its_value() {
    let cases = [
        ("patches = \"parts\"", "has a single part"),
        ("patches = 1", "must be \"parts\" or a count in 2..=64"),
        ("patches = 65", "must be \"parts\" or a count in 2..=64"),
        ("patches = \"halves\"", "must be \"parts\" or a count in 2..=64"),
    ];
    for (line, message) in cases {
        let text = format!("{CAMERA}[[object]]\nmesh = \"../models/cow.obj\"\n{line}\n");
        let err = parse(&text, &scenes_dir()).expect_err(line);
        assert!(err.contains(message) && err.contains("E0405"), "{line}:\n{err}");
        assert!(
            err.contains(&format!("6 │ {line}")),
            "{line}: the span is the value:\n{err}"
        );
    }
    // A cube has 12 triangles: not 20 patches.
    let text = format!("{CAMERA}[[object]]\nprimitive = {{ kind = \"cube\" }}\npatches = 20\n");
    let err = parse(&text, Path::new(".")).expect_err("cube");
    assert!(err.contains("cannot be split into 20 patches (12 triangles)"), "{err}");
}

#[test]
fn blend_rings_give_each_patch_its_faces_and_n_ring_with_its_weights() {
    let text =
        |rings: &str| format!("{CAMERA}[[object]]\nname = \"cow\"\nmesh = \"../models/cow.obj\"\npatches = 6\n{rings}");
    // The default is the paper's 1-ring; more rings draw more faces.
    let mut drawn = Vec::new();
    for rings in ["", "blend_rings = 1\n", "blend_rings = 2\n", "blend_rings = 4\n"] {
        let scene = parse(&text(rings), &scenes_dir()).expect("scene");
        let mut faces = 0;
        for o in &scene.objects {
            let blend = o.blend.as_ref().expect("blended");
            // Its own faces first, as its own mesh has them.
            assert_eq!(blend.own_indices, o.mesh.indices.len());
            assert!(
                blend.mesh.triangle_count() > o.mesh.triangle_count(),
                "{}: a ring",
                o.name
            );
            assert_eq!(
                blend.mesh.positions[..o.mesh.positions.len()],
                o.mesh.positions[..],
                "{}: the own vertices first",
                o.name
            );
            assert!(blend.weights.iter().all(|w| (0.0..=1.0).contains(w)));
            // Weight 1 deep inside, above 0 on every own vertex.
            assert!(blend.weights[..o.mesh.positions.len()].iter().all(|w| *w > 0.0));
            faces += blend.mesh.triangle_count();
        }
        let own: usize = scene.objects.iter().map(|o| o.mesh.triangle_count()).sum();
        println!(
            "cow in 6 patches, {} ring(s): {faces} triangles drawn by a blending pass, {own} own ({:.0}% more)",
            blend_rings_of(&scene),
            100.0 * (faces as f64 / own as f64 - 1.0)
        );
        drawn.push((blend_rings_of(&scene), faces));
    }
    assert_eq!(drawn[0], drawn[1], "the default is 1 ring");
    assert!(drawn[2].1 > drawn[1].1 && drawn[3].1 > drawn[2].1, "{drawn:?}");
    // 0 rings: no blending, the hard seams of the patches' own faces.
    let scene = parse(&text("blend_rings = 0\n"), &scenes_dir()).expect("scene");
    assert!(scene.objects.iter().all(|o| o.blend.is_none()));
}

fn blend_rings_of(scene: &Scene) -> u32 {
    scene.objects[0].blend.as_ref().map_or(0, |b| b.rings)
}

#[test]
fn blend_rings_out_of_range_or_without_patches_are_errors_at_their_value() {
    let cases = [
        (
            "patches = 4\nblend_rings = 17",
            "`blend_rings` must be in 0..=16, not 17",
            "7 │ blend_rings = 17",
        ),
        (
            "patches = 4\nblend_rings = -1",
            "`blend_rings` must be in 0..=16, not -1",
            "7 │ blend_rings = -1",
        ),
        (
            "patches = 4\nblend_rings = 1.5",
            "`blend_rings` must be a whole number",
            "7 │ blend_rings = 1.5",
        ),
        (
            "blend_rings = 2",
            "`blend_rings` needs `patches`",
            "6 │ blend_rings = 2",
        ),
    ];
    for (lines, message, at) in cases {
        let text = format!("{CAMERA}[[object]]\nmesh = \"../models/cow.obj\"\n{lines}\n");
        let err = parse(&text, &scenes_dir()).expect_err(lines);
        assert!(err.contains(message) && err.contains("E0405"), "{lines}:\n{err}");
        assert!(err.contains(at), "{lines}: the span is the value:\n{err}");
    }
}
