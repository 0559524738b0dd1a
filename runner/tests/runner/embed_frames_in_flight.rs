//! A host that does not wait for each frame: frames recorded into one
//! encoder, or submitted while earlier ones still run. Each frame's
//! uniforms go through a staging buffer of its own, taken from a ring that
//! gets its buffers back once the GPU copied from them
//! (`runner/src/exec/upload.rs`, decision 0047). Shown here: several
//! frames in one encoder each render their own camera, objects and time
//! (byte for byte what one frame per submit renders), the ring makes one
//! buffer per frame then in flight and reuses them once they are back,
//! and a host that waits for each frame creates none.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{compile, gpu, host_target, read_host, write_mismatch};

use npr_runner::embed::{Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::gpu_count::created_on_this_thread;
use npr_runner::scene::{primitives, Camera};

const WIDTH: u32 = 64;
const HEIGHT: u32 = 48;

/// The objects of frame `k`: a sphere moving right and turning, a cube
/// whose per-object tint changes.
fn objects(sphere: MeshHandle, cube: MeshHandle, k: u32) -> Vec<Instance> {
    let t = k as f32;
    vec![
        Instance::new(
            sphere,
            glam::Mat4::from_translation(glam::Vec3::new(-0.6 + 0.3 * t, 0.0, 0.0))
                * glam::Mat4::from_rotation_y(0.4 * t),
        ),
        Instance::new(cube, glam::Mat4::from_translation(glam::Vec3::new(0.7, -0.3, -0.5)))
            .with_param("tint", &[0.2 * f64::from(k), 0.5, 1.0 - 0.2 * f64::from(k), 1.0]),
    ]
}

/// Frame `k`'s camera: it moves between frames too.
fn camera(k: u32) -> Camera {
    Camera::looking_at(glam::Vec3::new(0.3 * k as f32, 1.0, 4.0), glam::Vec3::ZERO)
}

/// A toon runtime with its two meshes.
fn runtime() -> (StyleRuntime, MeshHandle, MeshHandle) {
    let mut runtime = StyleRuntime::new(&gpu().device, &gpu().queue, compile("toon.npr")).expect("runtime");
    let sphere = runtime.add_mesh(primitives::sphere(0.6, 24, 12));
    let cube = runtime.add_mesh(primitives::cube(0.8));
    (runtime, sphere, cube)
}

/// Record frame `k` into `encoder`, presenting into `texture`.
fn record(
    runtime: &mut StyleRuntime,
    (sphere, cube): (MeshHandle, MeshHandle),
    k: u32,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) {
    let (objects, camera, lights) = (objects(sphere, cube, k), camera(k), Lights::default());
    let frame = Frame {
        camera: &camera,
        objects: &objects,
        lights: &lights,
        time_s: f64::from(k) / 24.0,
        frame_index: k,
        eye: 0,
    };
    let view = texture.create_view(&Default::default());
    runtime
        .render(encoder, &frame, Target::View(&view))
        .unwrap_or_else(|e| panic!("frame {k}: {:?}", e.diagnostics()));
}

/// Frame `k` in an encoder of its own, submitted and waited for.
fn submit_and_wait(runtime: &mut StyleRuntime, meshes: (MeshHandle, MeshHandle), k: u32, texture: &wgpu::Texture) {
    let mut encoder = gpu().device.create_command_encoder(&Default::default());
    record(runtime, meshes, k, &mut encoder, texture);
    gpu().queue.submit([encoder.finish()]);
    wait();
}

fn wait() {
    gpu().device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
}

fn target() -> wgpu::Texture {
    host_target(WIDTH, HEIGHT, wgpu::TextureFormat::Rgba8Unorm, &[])
}

/// Frames 1, 2 and 3 recorded into one encoder and submitted once: each
/// image equals the one a frame per submit (waited for) renders. Before
/// decision 0047 the three frames' copies read one staging buffer that
/// the last frame's `write_buffer` had filled, so all three showed frame 3.
#[test]
fn frames_recorded_into_one_encoder_each_render_their_own_uniforms() {
    let (mut batched, sphere, cube) = runtime();
    submit_and_wait(&mut batched, (sphere, cube), 0, &target());
    let textures = [target(), target(), target()];
    let mut encoder = gpu().device.create_command_encoder(&Default::default());
    for (k, texture) in (1..).zip(&textures) {
        record(&mut batched, (sphere, cube), k, &mut encoder, texture);
    }
    gpu().queue.submit([encoder.finish()]);
    wait();

    let (mut one_by_one, sphere, cube) = runtime();
    let mut images = Vec::new();
    for k in 0..4 {
        let texture = target();
        submit_and_wait(&mut one_by_one, (sphere, cube), k, &texture);
        images.push(read_host(&texture));
    }
    for (k, texture) in (1..).zip(&textures) {
        let (actual, expected) = (read_host(texture), &images[k]);
        if actual.bytes != expected.bytes {
            let at = write_mismatch("frames_in_flight", &format!("frame{k}"), &actual, expected);
            panic!(
                "frame {k} recorded with frames 1..3 in one encoder differs from frame {k} rendered alone: images in {}",
                at.display()
            );
        }
    }
    // The frames differ from each other, so equal images mean each read its own.
    assert_ne!(images[1].bytes, images[3].bytes, "frames 1 and 3 render the same image");
}

/// Frames in flight take a staging buffer each; back from the GPU, they
/// are taken again: three frames in one encoder make two buffers (the
/// first frame's is back), the next three make none, and frames waited
/// for one by one make none.
#[test]
fn the_staging_ring_grows_to_the_frames_in_flight_and_no_further() {
    let (mut runtime, sphere, cube) = runtime();
    let texture = target();
    submit_and_wait(&mut runtime, (sphere, cube), 0, &texture);
    let three_frames = |runtime: &mut StyleRuntime, from: u32| {
        let before = created_on_this_thread();
        let mut encoder = gpu().device.create_command_encoder(&Default::default());
        for k in from..from + 3 {
            record(runtime, (sphere, cube), k, &mut encoder, &texture);
        }
        gpu().queue.submit([encoder.finish()]);
        wait();
        let after = created_on_this_thread();
        (after.buffers - before.buffers, after.total() - before.total())
    };
    assert_eq!(
        three_frames(&mut runtime, 1),
        (2, 2),
        "three frames in flight, one staging buffer back: two new buffers and nothing else"
    );
    assert_eq!(
        three_frames(&mut runtime, 4),
        (0, 0),
        "three frames in flight again, three staging buffers back: nothing new"
    );
    let before = created_on_this_thread();
    for k in 7..12 {
        submit_and_wait(&mut runtime, (sphere, cube), k, &texture);
    }
    assert_eq!(
        created_on_this_thread(),
        before,
        "frames waited for one by one created GPU objects"
    );
}
