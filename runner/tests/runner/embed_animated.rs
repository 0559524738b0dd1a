//! A TOML scene's animated ocean and blended patches through the embedding
//! runtime (`StyleRuntime::add_scene`) equal `npr render`'s renderer byte
//! for byte, at several times: the ocean's vertices follow the frame's time
//! (not its mesh at t = 0), and a patched object's patches are drawn over
//! their n-rings with their blending weights by the passes that read
//! `patch.weight` (not each patch's own faces at weight 1), and are one
//! surface for `lines` passes (their seams are no edges). A host that
//! divides the cow in code (`StyleRuntime::add_patches`) draws the same.
//! Objects playing a glTF clip (`animation = {...}`) play it at each
//! frame's time (`Instance::animation`), as the renderer does.
//! Each comparison fails without what the runtime carries (checked by
//! leaving it out when this was written). The runtime's frames after the
//! first create no GPU object (`npr_runner::gpu_count`).
//!
//! The reference is one `Renderer` (what `npr render` drives) rendering the
//! same frames in the same order as the runtime: the patched scene's style
//! is path-dependent (its tracker reads the previous frame), so both play
//! the same sequence. On a difference the runtime's image, the renderer's
//! and their difference (×8, opaque) are written under
//! `$CARGO_TARGET_TMPDIR/embed-animated/`.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{compile, examples, gpu, host_target, read_host, render_frame, write_mismatch};

use npr_runner::embed::{Frame, Instance, Lights, StyleRuntime, Target};
use npr_runner::readback::TargetImage;
use npr_runner::scene::patches::PatchSpec;
use npr_runner::scene::{primitives, Scene};
use npr_runner::{FrameSpec, Renderer};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 72;

/// The times the frames are rendered at, in order (frame indices 0, 1, 2).
const TIMES: [f64; 3] = [0.0, 1.5, 3.0];

fn load(scene: &str) -> Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&examples().join("scenes").join(scene), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// The host's offscreen texture the runtime presents into.
fn host_texture() -> wgpu::Texture {
    host_target(WIDTH, HEIGHT, wgpu::TextureFormat::Rgba8Unorm, &[])
}

/// How the host makes its instances of the scene: `add_scene`, or in code.
type Host = fn(&mut StyleRuntime, &Scene) -> Vec<Instance>;

/// Per time of [`TIMES`]: (the runtime's frame, the renderer's).
fn render_both(style: &str, scene_file: &str, host: Host) -> Vec<(TargetImage, TargetImage)> {
    let program = compile(style);
    let scene = load(scene_file);
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, program.clone()).expect("runtime");
    let mut instances: Vec<Instance> = host(&mut runtime, &scene);
    assert_eq!(instances.len(), scene.objects.len(), "one instance per scene object");
    let mut renderer = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let lights = Lights {
        key: scene.light,
        more: scene.more_lights,
    };
    let texture = host_texture();
    let view = texture.create_view(&Default::default());
    let mut frames = Vec::new();
    for (k, &time_s) in TIMES.iter().enumerate() {
        // The host animates what an instance does not carry: `spin`.
        for (instance, object) in instances.iter_mut().zip(&scene.objects) {
            instance.transform = object.model_at(time_s);
        }
        let frame = Frame {
            camera: &scene.camera,
            objects: &instances,
            lights: &lights,
            time_s,
            frame_index: k as u32,
            eye: 0,
        };
        let before = npr_runner::gpu_count::created_on_this_thread();
        render_frame(&mut runtime, &frame, Target::View(&view))
            .unwrap_or_else(|e| panic!("{scene_file} at {time_s} s: {:?}", e.diagnostics()));
        let after = npr_runner::gpu_count::created_on_this_thread();
        // After the first frame the ocean's vertices and the patches'
        // uniforms are written in place: the frame creates no GPU object.
        assert!(
            k == 0 || after == before,
            "{scene_file} at {time_s} s: the frame created GPU objects: {before:?} → {after:?}"
        );
        let hosted = read_host(&texture);

        let spec = FrameSpec {
            width: WIDTH,
            height: HEIGHT,
            time_s,
            frame: k as u32,
            eye: 0,
        };
        renderer.render(&scene, &spec).expect("render");
        let direct = renderer.read_output().expect("read back the output");
        assert_eq!(direct.format, npr_abi::Format::Rgba8unorm, "{style}: the output format");
        frames.push((hosted, direct));
    }
    assert_eq!(
        runtime.builds(),
        1,
        "{scene_file}: the runtime rebuilt its scene between frames"
    );
    frames
}

/// Every frame of the runtime equals the renderer's, byte for byte.
fn assert_equal(frames: &[(TargetImage, TargetImage)], name: &str) {
    let mut failures = Vec::new();
    for ((hosted, direct), time_s) in frames.iter().zip(TIMES) {
        if hosted.bytes != direct.bytes {
            let max = hosted
                .bytes
                .iter()
                .zip(&direct.bytes)
                .map(|(a, b)| a.abs_diff(*b))
                .max();
            let pixels = hosted
                .bytes
                .chunks(4)
                .zip(direct.bytes.chunks(4))
                .filter(|(a, b)| a != b)
                .count();
            let at = format!("{name}_t{time_s}");
            let dir = write_mismatch("embed-animated", &at, hosted, direct);
            failures.push(format!(
                "at {time_s} s: {pixels} pixels differ, by up to {max:?}/255 (images: {}/{at}_*.png)",
                dir.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{name}: the runtime's frames differ from npr render's renderer:\n{}",
        failures.join("\n")
    );
}

/// Age of Sail's ocean (§6.1): its vertices are rebuilt at each frame's
/// time through the runtime as through `npr render`. The frames differ
/// from each other, so the comparison is of a moving sea.
#[test]
fn the_ocean_moves_through_the_runtime_as_through_the_renderer() {
    let frames = render_both("ocean.npr", "ocean.toml", |r, s| r.add_scene(s));
    assert_equal(&frames, "ocean");
    for (k, pair) in frames.windows(2).enumerate() {
        let changed = pair[0]
            .1
            .bytes
            .chunks(4)
            .zip(pair[1].1.bytes.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            changed > (WIDTH * HEIGHT / 10) as usize,
            "the sea barely moved between {} s and {} s ({changed} pixels changed)",
            TIMES[k],
            TIMES[k + 1]
        );
    }
}

/// The Blender arms bending out of step and the blob pulsing
/// (`characters.toml`'s `animation = {...}`): `add_scene` gives each
/// instance its clip, and the runtime's frames equal the renderer's, for a
/// render pass and for a `lines` pass (CPU-posed silhouettes). The
/// renderer's frames at 0 s and 1.5 s differ (the arms are straight at
/// 0 s, half bent at 1.5 s), so the runtime did not draw the rest pose.
#[test]
fn a_scenes_clips_play_through_the_runtime_as_through_the_renderer() {
    for style in ["toon.npr", "wavy_lines.npr"] {
        let frames = render_both(style, "characters.toml", |r, s| r.add_scene(s));
        assert_equal(&frames, &format!("characters_{style}"));
        let changed = frames[0]
            .1
            .bytes
            .chunks(4)
            .zip(frames[1].1.bytes.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            changed > 100,
            "{style}: the characters barely moved between 0 s and 1.5 s ({changed} pixels changed)"
        );
    }
}

/// The paper's cow in 6 patches blended over 2 rings (§3.6), turning: a
/// hatching pass that reads `patch.weight` draws each patch over its
/// n-ring with its weights through the runtime as through `npr render`.
#[test]
fn blended_patches_render_through_the_runtime_as_through_the_renderer() {
    let scene = load("patched_cow.toml");
    assert!(
        scene.objects.iter().all(|o| o.blend.is_some()),
        "patched_cow.toml should blend its patches"
    );
    let frames = render_both("hatching.npr", "patched_cow.toml", |r, s| r.add_scene(s));
    assert_equal(&frames, "patched_cow");
}

/// The patched cow under a `lines` pass: its patches are one surface
/// (their seams are no edges) through the runtime as through the renderer.
#[test]
fn a_patched_surface_draws_its_lines_through_the_runtime_as_through_the_renderer() {
    let frames = render_both("wavy_lines.npr", "patched_cow.toml", |r, s| r.add_scene(s));
    assert_equal(&frames, "patched_cow_lines");
}

/// A host that builds the patched cow in code, from the cow's mesh with
/// `add_patches` (6 patches by k-means, blended over 2 rings), draws what
/// the scene's `patches = 6`, `blend_rings = 2` draws.
#[test]
fn patches_a_host_makes_in_code_render_as_the_scenes() {
    let frames = render_both("hatching.npr", "patched_cow.toml", |runtime, scene| {
        let whole = scene.objects[0].patch.as_ref().expect("a patch").whole.clone();
        let handles = runtime
            .add_patches(whole, PatchSpec::Split(6), 2)
            .expect("divide the cow");
        handles
            .into_iter()
            .zip(&scene.objects)
            .map(|(handle, object)| Instance::new(handle, object.model))
            .collect()
    });
    assert_equal(&frames, "patched_cow_in_code");
}

/// A division `add_patches` cannot make is refused with E0405, as a
/// scene's `patches` is.
#[test]
fn patches_that_cannot_be_made_are_refused_with_a_code() {
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile("toon.npr")).expect("runtime");
    let cube = std::sync::Arc::new(primitives::cube(1.0));
    let refused = |r: Result<Vec<_>, npr_runner::embed::EmbedError>| r.expect_err("refused").code();
    // A cube has 12 triangles and no parts.
    assert_eq!(
        refused(runtime.add_patches(cube.clone(), PatchSpec::Split(13), 1)),
        "E0405"
    );
    assert_eq!(refused(runtime.add_patches(cube.clone(), PatchSpec::Parts, 1)), "E0405");
    assert_eq!(
        refused(runtime.add_patches(cube.clone(), PatchSpec::Split(1), 1)),
        "E0405"
    );
    assert_eq!(
        refused(runtime.add_patches(cube.clone(), PatchSpec::Split(65), 1)),
        "E0405"
    );
    assert_eq!(
        refused(runtime.add_patches(cube.clone(), PatchSpec::Split(2), 17)),
        "E0405"
    );
    let halves = runtime.add_patches(cube, PatchSpec::Split(2), 0).expect("two halves");
    assert_eq!(halves.len(), 2);
    let triangles: usize = halves
        .iter()
        .map(|&h| runtime.mesh(h).expect("registered").triangle_count())
        .sum();
    assert_eq!(triangles, 12, "the halves share the cube's triangles");
}
