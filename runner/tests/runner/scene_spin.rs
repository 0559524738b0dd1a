//! `spin = [x, y, z]` on a scene object: its model at time t is its placed
//! model turned by spin × t degrees about its own origin, and a scene with
//! nothing spinning is posed without a copy.

use glam::{Mat4, Vec3};
use npr_runner::scene::parse_scene;
use std::borrow::Cow;
use std::path::Path;

const CAMERA: &str = "[camera]\nposition = [0.0, 1.0, 6.0]\ntarget = [0.0, 0.0, 0.0]\n";

#[test]
fn a_spinning_object_turns_about_its_own_origin() {
    let text = format!(
        "{CAMERA}[[object]]\nprimitive = {{ kind = \"cube\" }}\ntranslate = [2.0, 0.0, 0.0]\nspin = [0.0, 45.0, 0.0]\n"
    );
    let scene = parse_scene(&text, npr_diag::FileId(0), Path::new(".")).expect("scene");
    let o = &scene.objects[0];
    assert_eq!(o.model_at(0.0), o.model);
    // 2 s at 45°/s: a quarter turn about +Y, in place at x = 2.
    let m = o.model_at(2.0);
    let p = m.transform_point3(Vec3::new(1.0, 0.0, 0.0));
    assert!((p - Vec3::new(2.0, 0.0, -1.0)).length() < 1e-5, "{p}");
    assert!((m.transform_point3(Vec3::ZERO) - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-6);
    let posed = scene.posed(2.0);
    assert!(matches!(posed, Cow::Owned(_)));
    assert_eq!(posed.objects[0].model, m);
}

#[test]
fn a_still_scene_is_posed_as_it_is() {
    let text = format!("{CAMERA}[[object]]\nprimitive = {{ kind = \"cube\" }}\n");
    let scene = parse_scene(&text, npr_diag::FileId(0), Path::new(".")).expect("scene");
    assert!(matches!(scene.posed(3.0), Cow::Borrowed(_)));
    assert_eq!(scene.objects[0].model_at(3.0), Mat4::IDENTITY);
}
