//! A render pass's draws are recorded once into a render bundle
//! (`exec/render_pass.rs`) and executed by every frame until the size or
//! the scene changes. These tests count the bundles a frame records (the
//! first frame records them, a steady frame none, a scene change and a
//! resize record them again) and show that a renderer whose scene
//! changed renders, byte for byte, what a renderer built for the new
//! scene renders: bundles kept from the old scene would still draw the
//! removed object, from the old scene's buffers. Over Age of Sail (a depth pass from the light,
//! per-object textures), halftone on the patched cow (blended patches
//! drawn over their n-ring, a `depth: test` pass; it tracks its objects,
//! so its history starts over after the change, which makes the targets
//! anew) and toon.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{compile, examples, gpu, write_mismatch};

use npr_runner::gpu_count::created_on_this_thread;
use npr_runner::{FrameSpec, Renderer};

/// Bundles `render` recorded.
fn bundles_recorded(render: impl FnOnce()) -> u64 {
    let before = created_on_this_thread().render_bundles;
    render();
    created_on_this_thread().render_bundles - before
}

/// `restart`: the style tracks its objects from frame to frame (a scene
/// change carries that state over, which a new renderer has not), so the
/// test starts the history over after the change, as a host's cut does.
fn draws_follow_the_scene(style: &str, scene_file: &str, restart: bool) {
    let program = compile(&format!("{style}.npr"));
    let path = examples().join("scenes").join(scene_file);
    let scene = npr_runner::scene::load_scene(&path, &mut npr_diag::SourceMap::new()).expect("scene");
    assert!(scene.objects.len() > 1, "{scene_file}: the test removes an object");
    let mut renderer = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let spec = |frame| FrameSpec::animated(72, 56, frame, FrameSpec::DEFAULT_FPS, 0);

    let first = bundles_recorded(|| renderer.render(&scene, &spec(0)).expect("render"));
    assert!(first > 0, "{style}: the first frame recorded no render pass's draws");
    let steady = bundles_recorded(|| renderer.render(&scene, &spec(1)).expect("render"));
    assert_eq!(steady, 0, "{style}: a steady frame recorded draws again");

    // The last object gone: a scene change at the same size. (The others
    // stay where they were: a moved one would carry its previous
    // transform over, which a renderer built for the new scene has not.)
    let mut changed = scene.clone();
    changed.objects.pop();
    renderer.set_scene(&changed).expect("set the changed scene");
    if restart {
        renderer.restart_history();
    }
    let again = bundles_recorded(|| renderer.render(&changed, &spec(2)).expect("render"));
    assert_eq!(
        again, first,
        "{style}: after a scene change every render pass records its draws again"
    );
    let kept = renderer.read_output().expect("read the changed scene's frame");

    let mut fresh = Renderer::new(&gpu().device, &gpu().queue, &program, &changed).expect("renderer");
    fresh.render(&changed, &spec(2)).expect("render");
    let expected = fresh.read_output().expect("read the fresh renderer's frame");
    if kept.bytes != expected.bytes {
        let at = write_mismatch("render_bundles", style, &kept, &expected);
        panic!(
            "{style}: after a scene change the renderer draws otherwise than one built for the new scene; images in {}",
            at.display()
        );
    }

    let resized = FrameSpec::animated(64, 48, 3, FrameSpec::DEFAULT_FPS, 0);
    let resize = bundles_recorded(|| renderer.render(&changed, &resized).expect("render"));
    assert_eq!(
        resize, first,
        "{style}: after a resize every render pass records its draws again"
    );
}

#[test]
fn age_of_sail_draws_follow_the_scene() {
    draws_follow_the_scene("age_of_sail", "age_of_sail.toml", false);
}

#[test]
fn halftone_patch_draws_follow_the_scene() {
    draws_follow_the_scene("halftone", "patched_cow.toml", true);
}

#[test]
fn toon_draws_follow_the_scene() {
    draws_follow_the_scene("toon", "spheres.toml", false);
}
