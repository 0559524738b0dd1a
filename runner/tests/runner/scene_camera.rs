//! Camera poses from scene files: projection of the target, stereo eye
//! separation, and keyframe interpolation.

use glam::{Vec3, Vec4Swizzles};
use npr_runner::scene::{parse_scene, Camera, CameraPose, Scene};
use std::path::Path;

fn scene(text: &str) -> Scene {
    match parse_scene(text, npr_diag::FileId(0), Path::new(".")) {
        Ok(scene) => scene,
        Err(diagnostics) => panic!("scene did not parse: {diagnostics:#?}"),
    }
}

/// Clip space → NDC for a world point seen by `eye`.
fn ndc(pose: &CameraPose, eye: u32, aspect: f32, world: Vec3) -> Vec3 {
    let clip = pose.projection(aspect) * pose.view(eye) * world.extend(1.0);
    clip.xyz() / clip.w
}

const STILL: &str = r#"
[camera]
position = [1.0, 2.0, 5.0]
target = [0.5, 0.25, -1.0]
fov = 50.0
near = 0.5
far = 50.0
"#;

#[test]
fn the_target_projects_to_the_centre_of_the_image() {
    let pose = scene(STILL).camera.pose(0.0);
    for aspect in [1.0, 16.0 / 9.0, 0.5] {
        let centre = ndc(&pose, 0, aspect, pose.target);
        assert!(centre.x.abs() < 1e-5 && centre.y.abs() < 1e-5, "{centre:?}");
        assert!((0.0..=1.0).contains(&centre.z), "depth {}", centre.z);
    }
}

#[test]
fn near_and_far_map_to_wgpu_depth_zero_and_one() {
    let pose = scene(STILL).camera.pose(0.0);
    let forward = pose.forward();
    let at_near = ndc(&pose, 0, 1.0, pose.eye + forward * pose.near);
    let at_far = ndc(&pose, 0, 1.0, pose.eye + forward * pose.far);
    assert!(at_near.z.abs() < 1e-5, "{at_near:?}");
    assert!((at_far.z - 1.0).abs() < 1e-5, "{at_far:?}");
}

#[test]
fn the_field_of_view_reaches_the_top_edge() {
    let pose = scene(STILL).camera.pose(0.0);
    assert!((pose.fov_y_rad - 50f32.to_radians()).abs() < 1e-6);
    // A point at half the fov above the view axis lands on y = 1.
    let distance = 3.0;
    let up_edge = pose.eye + pose.forward() * distance + pose.true_up() * distance * (pose.fov_y_rad / 2.0).tan();
    let projected = ndc(&pose, 0, 1.0, up_edge);
    assert!(
        (projected.y - 1.0).abs() < 1e-4 && projected.x.abs() < 1e-4,
        "{projected:?}"
    );
}

#[test]
fn a_mono_camera_has_one_eye_position() {
    let camera = scene(STILL).camera;
    assert!(!camera.is_stereo());
    let pose = camera.pose(0.0);
    assert_eq!(pose.position(0), pose.position(1));
    assert_eq!(pose.position(0), Vec3::new(1.0, 2.0, 5.0));
    assert_eq!(pose.view(0), pose.view(1));
}

#[test]
fn stereo_eyes_are_ipd_apart_along_the_right_axis() {
    let camera = scene(&format!("{STILL}ipd = 0.064\n")).camera;
    assert!(camera.is_stereo());
    let pose = camera.pose(0.0);
    let (left, right) = (pose.position(0), pose.position(1));
    assert!(((right - left).length() - 0.064).abs() < 1e-6);
    // Symmetric about the mono eye, left eye to the left.
    assert!(((left + right) / 2.0 - pose.eye).length() < 1e-6);
    assert!((right - left).normalize().dot(pose.right()) > 0.999_999);
    // Parallel eyes: the target shifts by half the ipd in each eye's image,
    // left eye sees it to the right of centre.
    let in_left = ndc(&pose, 0, 1.0, pose.target);
    let in_right = ndc(&pose, 1, 1.0, pose.target);
    assert!(in_left.x > 0.0 && in_right.x < 0.0);
    assert!((in_left.x + in_right.x).abs() < 1e-5 && in_left.y.abs() < 1e-5);
    // Each eye's view maps its own position to the origin.
    for eye in [0, 1] {
        let origin = pose.view(eye).transform_point3(pose.position(eye));
        assert!(origin.length() < 1e-5);
    }
}

const ANIMATED: &str = r#"
[camera]
target = [0.0, 0.0, 0.0]
[[camera.keys]]
time = 1.0
position = [0.0, 0.0, 4.0]
[[camera.keys]]
time = 3.0
position = [4.0, 2.0, 0.0]
target = [1.0, 1.0, 1.0]
[[camera.keys]]
time = 2.0
position = [2.0, 0.0, 2.0]
"#;

#[test]
fn keyframes_are_exact_at_keys_and_linear_between() {
    let camera = scene(ANIMATED).camera;
    assert_eq!(camera.keys().len(), 3);
    assert_eq!(camera.duration_s(), 2.0);
    let eye = |t: f64| camera.pose(t).eye;
    // Keys were written out of order; they are sorted by time.
    assert_eq!(eye(1.0), Vec3::new(0.0, 0.0, 4.0));
    assert_eq!(eye(2.0), Vec3::new(2.0, 0.0, 2.0));
    assert_eq!(eye(3.0), Vec3::new(4.0, 2.0, 0.0));
    // Midpoints.
    assert!((eye(1.5) - Vec3::new(1.0, 0.0, 3.0)).length() < 1e-6);
    assert!((eye(2.5) - Vec3::new(3.0, 1.0, 1.0)).length() < 1e-6);
    assert!((camera.pose(2.5).target - Vec3::splat(0.5)).length() < 1e-6);
    // A quarter of the way.
    assert!((eye(1.25) - Vec3::new(0.5, 0.0, 3.5)).length() < 1e-6);
}

#[test]
fn keyframes_are_held_outside_their_range() {
    let camera = scene(ANIMATED).camera;
    assert_eq!(camera.pose(-10.0).eye, Vec3::new(0.0, 0.0, 4.0));
    assert_eq!(camera.pose(0.999).eye, Vec3::new(0.0, 0.0, 4.0));
    assert_eq!(camera.pose(99.0).eye, Vec3::new(4.0, 2.0, 0.0));
    assert_eq!(camera.pose(99.0).target, Vec3::ONE);
}

#[test]
fn keys_inherit_the_camera_target() {
    let camera = scene(ANIMATED).camera;
    assert_eq!(camera.keys()[0].target, Vec3::ZERO);
    assert_eq!(camera.keys()[2].target, Vec3::ONE);
}

#[test]
fn defaults_fill_in_lens_and_up() {
    let camera = scene("[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n").camera;
    assert_eq!(camera.up, Vec3::Y);
    assert!((camera.fov_y_rad - 40f32.to_radians()).abs() < 1e-7);
    assert_eq!((camera.near, camera.far), (0.1, 100.0));
    assert_eq!(camera.ipd_m, None);
}

#[test]
fn a_path_through_a_straight_down_pose_stays_finite() {
    // Between these keys the camera passes directly above the target.
    let camera = scene(
        "[camera]\ntarget = [0.0, 0.0, 0.0]\n[[camera.keys]]\ntime = 0.0\nposition = [-1.0, 5.0, 0.0]\n[[camera.keys]]\ntime = 1.0\nposition = [1.0, 5.0, 0.0]\n",
    )
    .camera;
    let pose = camera.pose(0.5);
    assert_eq!(pose.eye, Vec3::new(0.0, 5.0, 0.0));
    assert!(pose.view(0).is_finite() && pose.projection(1.0).is_finite());
    let centre = ndc(&pose, 0, 1.0, pose.target);
    assert!(centre.x.abs() < 1e-5 && centre.y.abs() < 1e-5);
}

#[test]
fn looking_at_builds_a_still_camera() {
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO);
    assert_eq!(camera.keys().len(), 1);
    assert_eq!(camera.pose(123.0).eye, Vec3::new(0.0, 0.0, 2.0));
}

const ORTHO: &str = r#"
[camera]
position = [1.0, 2.0, 5.0]
target = [0.5, 0.25, -1.0]
projection = "orthographic"
height = 4.0
near = 0.5
far = 50.0
"#;

/// An orthographic camera (decision 0062): a point `height`/2 above the
/// view axis lands on the top edge at every depth, the width follows the
/// aspect, and near and far still map to wgpu's depth 0 and 1.
#[test]
fn an_orthographic_camera_is_height_high_at_every_depth() {
    let camera = scene(ORTHO).camera;
    assert_eq!(camera.ortho_height_m, Some(4.0));
    let pose = camera.pose(0.0);
    let aspect = 1.5;
    for distance in [0.5, 3.0, 40.0] {
        let centre = pose.eye + pose.forward() * distance;
        let top = ndc(&pose, 0, aspect, centre + pose.true_up() * 2.0);
        assert!(
            (top.y - 1.0).abs() < 1e-5 && top.x.abs() < 1e-5,
            "{top:?} at {distance} m"
        );
        let side = ndc(&pose, 0, aspect, centre + pose.right() * 3.0);
        assert!(
            (side.x - 1.0).abs() < 1e-5 && side.y.abs() < 1e-5,
            "{side:?} at {distance} m"
        );
    }
    let at_near = ndc(&pose, 0, 1.0, pose.eye + pose.forward() * pose.near);
    let at_far = ndc(&pose, 0, 1.0, pose.eye + pose.forward() * pose.far);
    assert!(
        at_near.z.abs() < 1e-5 && (at_far.z - 1.0).abs() < 1e-5,
        "{at_near:?} {at_far:?}"
    );
    // The eye is at infinity behind the camera: (−forward, 0).
    let eye = pose.homogeneous_eye(0);
    assert_eq!(eye.w, 0.0);
    assert!((eye.truncate() + pose.forward()).length() < 1e-6);
}

/// Each wrong orthographic lens is E0405 at the key that is wrong.
#[test]
fn a_wrong_orthographic_lens_is_refused_at_its_key() {
    let base = "[camera]\nposition = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n";
    for (lens, key, says) in [
        ("projection = \"orthographic\"\n", "projection", "needs a `height`"),
        ("projection = \"orthographic\"\nheight = -1.0\n", "height", "positive"),
        (
            "projection = \"orthographic\"\nheight = 2.0\nfov = 30.0\n",
            "fov",
            "no field of view",
        ),
        (
            "projection = \"orthographic\"\nheight = 2.0\nipd = 0.06\n",
            "ipd",
            "cannot be stereo",
        ),
        ("height = 2.0\n", "height", "this camera is perspective"),
        ("projection = \"fisheye\"\n", "projection", "unknown camera projection"),
    ] {
        let text = format!("{base}{lens}");
        let Err(diagnostics) = parse_scene(&text, npr_diag::FileId(0), Path::new(".")) else {
            panic!("{lens:?} parsed");
        };
        let d = &diagnostics[0];
        assert_eq!(d.code, "E0405", "{lens:?}: {d:?}");
        assert!(d.message.contains(says), "{lens:?}: {}", d.message);
        // The label is on the key's line (its value, or the key).
        let start = d.labels[0].span.start as usize;
        let line = text[..start].rsplit('\n').next().unwrap_or("").to_owned() + &text[start..];
        assert!(line.starts_with(key), "{lens:?}: label at {line:?}");
    }
}
