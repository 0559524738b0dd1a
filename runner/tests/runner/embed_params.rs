//! A parameter a host sets between frames shows in the next frame: the
//! runtime writes only the animated parameters of the style block while
//! nothing else changed (`exec/frame.rs`), so a set value must have the
//! whole block written again. Each case renders a frame, sets the
//! parameter, renders the same frame again, and compares that with a
//! runtime that had the value set before its first frame (byte for byte)
//! and with the frame before the change (which must differ).

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{compile, gpu, host_target, read_host, render_frame, write_mismatch};

use npr_runner::embed::{Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::scene::{primitives, Camera};
use npr_runner::TargetImage;

/// Frame at `time_s` of `runtime`: `sphere` and the default light. The
/// same objects every time, so that no scene change rewrites the blocks.
fn frame(runtime: &mut StyleRuntime, sphere: MeshHandle, time_s: f64) -> TargetImage {
    let objects = [Instance::new(sphere, glam::Mat4::IDENTITY)];
    let camera = Camera::looking_at(glam::Vec3::new(0.0, 1.0, 3.0), glam::Vec3::ZERO);
    let lights = Lights::default();
    let frame = Frame {
        camera: &camera,
        objects: &objects,
        lights: &lights,
        time_s,
        frame_index: 0,
        eye: 0,
    };
    let texture = host_target(64, 48, wgpu::TextureFormat::Rgba8Unorm, &[]);
    render_frame(runtime, &frame, Target::View(&texture.create_view(&Default::default())))
        .unwrap_or_else(|e| panic!("{:?}", e.diagnostics()));
    read_host(&texture)
}

fn check(style: &str, (name, value): (&str, &str), time_s: f64) {
    let runtime = || {
        let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile(style)).expect("runtime");
        let sphere = runtime.add_mesh(primitives::sphere(0.8, 24, 12));
        (runtime, sphere)
    };
    let set = |runtime: &mut StyleRuntime| {
        runtime
            .set_param(name, value)
            .unwrap_or_else(|e| panic!("{:?}", e.diagnostics()))
    };
    let (mut changed, sphere) = runtime();
    let before = frame(&mut changed, sphere, time_s);
    set(&mut changed);
    let after = frame(&mut changed, sphere, time_s);
    assert_eq!(
        (changed.builds(), changed.scene_changes()),
        (1, 0),
        "{style}: set_param rebuilt the renderer or its scene"
    );
    let (mut from_start, sphere) = runtime();
    set(&mut from_start);
    let expected = frame(&mut from_start, sphere, time_s);
    if after.bytes != expected.bytes {
        let at = write_mismatch("embed_params", &format!("{style}_{name}"), &after, &expected);
        panic!(
            "{style}: {name} = {value} set between frames renders otherwise than set from the start: images in {}",
            at.display()
        );
    }
    assert_ne!(before.bytes, after.bytes, "{style}: {name} = {value} changed nothing");
}

/// A constant parameter (`bands`): the style block's static part.
#[test]
fn a_constant_param_set_between_frames_shows_in_the_next() {
    check("toon.npr", ("bands", "6"), 0.0);
}

/// An animated parameter (`rim`, keyframed) set to a constant: it leaves
/// the animated ones, and keeps its value at every time.
#[test]
fn an_animated_param_set_between_frames_stops_animating() {
    check("toon.npr", ("rim", "1.0"), 2.0);
}
