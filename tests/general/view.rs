//! `npr view` in a real window under Xvfb (on whatever Vulkan driver the
//! machine has: lavapipe in CI): a screenshot of the window, taken through
//! the X server, against `npr render --keep-params` of the same style,
//! scene, time and (scene) camera; input typed and dragged through XTEST
//! (fly, orbit, pan, back to the scene camera, time running; a parameter
//! stepped as `--set` would set it); the animated ocean at the view's
//! time; and hot reload: a save
//! changes the window, a broken save prints its diagnostic and keeps the
//! last frame.
//!
//! Bound: every channel within 1/255 of `npr render`'s PNG, with no
//! outliers allowed. Both run the same compiled style on the same driver,
//! so the image should be equal; the one level allows for the window's
//! present pass (a `textureLoad` copy) and nothing else.

use crate::common;

use common::live::{save_by_rename, scratch, Live};
use common::xvfb::Xvfb;
use std::path::Path;

const SIZE: u32 = 256;
const MAX_ABS: u8 = 1;

fn render(style: &Path, scene: &str, out: &Path) -> image::RgbaImage {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["render", style.to_str().expect("utf-8"), "--scene", scene])
        .args([
            "--size",
            &format!("{SIZE}x{SIZE}"),
            "--time",
            "1",
            "--keep-params",
            "-o",
        ])
        .arg(out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("npr render");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    image::open(out).expect("render output").to_rgba8()
}

fn view(x: &Xvfb, style: &Path, scene: &str) -> Live {
    Live::start_with_env(
        &[
            "view",
            style.to_str().expect("utf-8"),
            "--scene",
            scene,
            "--size",
            &format!("{SIZE}x{SIZE}"),
            "--time",
            "1",
            "--paused",
        ],
        &[("DISPLAY", &x.display)],
    )
}

/// The window after a few more frames (it redraws continuously).
fn screenshot_after_frames(x: &Xvfb, v: &Live, width: u32) -> image::RgbaImage {
    std::thread::sleep(std::time::Duration::from_millis(500));
    x.screenshot(v.child.id(), width, SIZE)
}

/// Fail, writing actual and diff images, unless `actual` is within the bound of `expected`.
fn assert_matches(actual: &image::RgbaImage, expected: &image::RgbaImage, dir: &Path, what: &str) {
    let (max, over) = npr_lab::harness::per_pixel(actual, expected, MAX_ABS);
    if over > 0 {
        let a = dir.join(format!("{what}_actual.png"));
        let d = dir.join(format!("{what}_diff.png"));
        actual.save(&a).expect("write actual");
        npr_lab::harness::diff_image(actual, expected)
            .save(&d)
            .expect("write diff");
        panic!(
            "{what}: the window differs from npr render by up to {max}/255 at {over} pixel(s) (bound {MAX_ABS}); \
             FLIP mean {:.4}; wrote {} and {}",
            npr_lab::harness::flip_mean(actual, expected),
            a.display(),
            d.display()
        );
    }
}

#[test]
fn the_window_shows_what_npr_render_writes() {
    let dir = scratch("view", "screenshot");
    let x = Xvfb::start();
    // An animated camera and an animated parameter: the pinned time shows.
    let (style, scene) = (Path::new("examples/toon.npr"), "examples/scenes/orbit.toml");
    let mut v = view(&x, style, scene);
    v.wait_for("view: build 1 shown");
    let shot = screenshot_after_frames(&x, &v, SIZE);
    let reference = render(style, scene, &dir.join("render.png"));
    assert_matches(&shot, &reference, &dir, "toon_orbit");
    // The frame time is in the title, with the time and the camera.
    let title = x.title(v.child.id());
    let shown = |s: &str| title.contains(s);
    assert!(
        shown("npr view — examples/toon.npr — ")
            && shown(" ms (")
            && shown("t = 1.00 s (paused)")
            && shown("scene camera"),
        "{title}"
    );
}

/// The ocean of Age of Sail §6.1 comes through `StyleRuntime::add_scene`
/// with its animated vertices: the window shows its waves at t = 1 s, as
/// `npr render --time 1` draws them (it showed the mesh at t = 0 before).
#[test]
fn the_window_shows_the_ocean_at_the_frames_time() {
    let dir = scratch("view", "ocean");
    let x = Xvfb::start();
    let (style, scene) = (Path::new("examples/ocean.npr"), "examples/scenes/ocean.toml");
    let mut v = view(&x, style, scene);
    v.wait_for("view: build 1 shown");
    let shot = screenshot_after_frames(&x, &v, SIZE);
    let reference = render(style, scene, &dir.join("render.png"));
    assert_matches(&shot, &reference, &dir, "ocean");
}

#[test]
fn a_stereo_style_shows_both_eyes_side_by_side() {
    let dir = scratch("view", "stereo");
    let x = Xvfb::start();
    let (style, scene) = (
        Path::new("examples/lsa_stereo.npr"),
        "examples/scenes/stereo_sphere_on_plane.toml",
    );
    let mut v = view(&x, style, scene);
    v.wait_for("view: build 1 shown");
    let shot = screenshot_after_frames(&x, &v, 2 * SIZE);
    for eye in 0..2u32 {
        let out = dir.join(format!("eye{eye}.png"));
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
            .args(["render", style.to_str().expect("utf-8"), "--scene", scene])
            .args(["--size", &format!("{SIZE}x{SIZE}"), "--time", "1", "--keep-params"])
            .args(["--eye", &eye.to_string(), "-o"])
            .arg(&out)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env("XDG_RUNTIME_DIR", std::env::temp_dir())
            .output()
            .expect("npr render");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let reference = image::open(&out).expect("eye").to_rgba8();
        let half = image::imageops::crop_imm(&shot, eye * SIZE, 0, SIZE, SIZE).to_image();
        assert_matches(&half, &reference, &dir, &format!("eye{eye}"));
    }
}

#[test]
fn a_save_redraws_the_window_and_a_broken_save_keeps_the_last_frame() {
    let dir = scratch("view", "reload");
    let x = Xvfb::start();
    let style = dir.join("toon.npr");
    let original = std::fs::read_to_string("examples/toon.npr").expect("toon.npr");
    std::fs::write(&style, &original).expect("copy style");
    let scene = "examples/scenes/orbit.toml";
    let mut v = view(&x, &style, scene);
    v.wait_for("view: build 1 shown");
    let first = screenshot_after_frames(&x, &v, SIZE);

    // A new base colour: the window shows the edited style.
    let edited = original.replace("param base: color = #e07a3a", "param base: color = #3a7ae0");
    assert_ne!(edited, original, "the edit must apply");
    save_by_rename(&style, &edited);
    v.wait_for("view: build 2 shown");
    let second = screenshot_after_frames(&x, &v, SIZE);
    let (changed_by, changed_pixels) = npr_lab::harness::per_pixel(&first, &second, MAX_ABS);
    assert!(
        changed_pixels > (SIZE * SIZE / 20) as usize,
        "the save changed only {changed_pixels} pixels (by up to {changed_by})"
    );
    assert_matches(&second, &render(&style, scene, &dir.join("edited.png")), &dir, "edited");

    // A broken save: the diagnostic is printed and the frame stays.
    save_by_rename(&style, &edited.replace("output shade.color", "output shade.colour"));
    let printed = v.wait_for("view: build 3 failed");
    assert!(
        printed.iter().any(|l| l.contains("error[E") && l.contains(']')),
        "no diagnostic with a code before the failure line: {printed:#?}"
    );
    let third = screenshot_after_frames(&x, &v, SIZE);
    let (max, over) = npr_lab::harness::per_pixel(&third, &second, 0);
    assert_eq!(over, 0, "a broken save changed the window (by up to {max})");
}

#[test]
fn help_lists_the_key_bindings() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["view", "--help"])
        .output()
        .expect("npr view --help");
    let help = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{help}");
    for line in [
        "space       pause / run time",
        "tab         switch orbit / fly camera",
        "- =         step the chosen parameter",
    ] {
        assert!(help.contains(line), "`{line}` missing from:\n{help}");
    }
}

#[test]
fn without_a_display_it_says_how_to_get_one() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["view", "examples/toon.npr", "--scene", "examples/scenes/spot.toml"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("npr view");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("error[E0505]: npr view cannot open a window"), "{err}");
    assert!(err.contains("apt-get install -y xvfb"), "{err}");
}

/// How many pixels of `a` and `b` differ by more than the bound.
fn changed(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    npr_lab::harness::per_pixel(a, b, MAX_ABS).1
}

#[test]
fn keys_and_drags_move_the_camera_and_c_brings_back_the_scene_camera() {
    let dir = scratch("view", "camera_input");
    let x = Xvfb::start();
    let (style, scene) = (Path::new("examples/toon.npr"), "examples/scenes/orbit.toml");
    let mut v = view(&x, style, scene);
    v.wait_for("view: build 1 shown");
    let pid = v.child.id();
    let reference = render(style, scene, &dir.join("render.png"));
    assert_matches(&screenshot_after_frames(&x, &v, SIZE), &reference, &dir, "start");
    let enough = (SIZE * SIZE / 20) as usize;

    // W held: the fly camera moves forward.
    x.key(pid, u32::from(b'w'), std::time::Duration::from_millis(300));
    let flown = screenshot_after_frames(&x, &v, SIZE);
    assert!(
        changed(&flown, &reference) > enough,
        "flying forward left the image as it was"
    );
    x.key(pid, u32::from(b'c'), std::time::Duration::from_millis(50));
    assert_matches(
        &screenshot_after_frames(&x, &v, SIZE),
        &reference,
        &dir,
        "back_from_fly",
    );

    // A left drag orbits; a right drag pans.
    for button in [1, 3] {
        x.drag(pid, button, (100, 128), (180, 150));
        let moved = screenshot_after_frames(&x, &v, SIZE);
        assert!(
            changed(&moved, &reference) > enough,
            "a drag with button {button} left the image as it was"
        );
        x.key(pid, u32::from(b'c'), std::time::Duration::from_millis(50));
        assert_matches(
            &screenshot_after_frames(&x, &v, SIZE),
            &reference,
            &dir,
            &format!("back_from_drag{button}"),
        );
    }

    // Space runs the time: the scene's camera swings round.
    x.key(pid, u32::from(b' '), std::time::Duration::from_millis(50));
    let running = screenshot_after_frames(&x, &v, SIZE);
    assert!(
        changed(&running, &reference) > enough,
        "running time left the image as it was"
    );
}

#[test]
fn the_parameter_keys_step_a_parameter_as_set_would() {
    let dir = scratch("view", "param_keys");
    let x = Xvfb::start();
    let (style, scene) = (Path::new("examples/toon.npr"), "examples/scenes/orbit.toml");
    let mut v = view(&x, style, scene);
    v.wait_for("view: build 1 shown");
    let pid = v.child.id();
    // `bands` is the first parameter: `=` steps it from 3 to 4.
    x.key(pid, u32::from(b'='), std::time::Duration::from_millis(50));
    v.wait_for("view: bands = 4");
    let shot = screenshot_after_frames(&x, &v, SIZE);
    let out = dir.join("bands4.png");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["render", style.to_str().expect("utf-8"), "--scene", scene])
        .args(["--size", &format!("{SIZE}x{SIZE}"), "--time", "1", "--keep-params"])
        .args(["--set", "bands=4", "-o"])
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("npr render");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_matches(&shot, &image::open(&out).expect("bands=4").to_rgba8(), &dir, "bands4");
}
