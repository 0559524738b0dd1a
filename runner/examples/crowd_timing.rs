//! Times a crowd posed through the embedding API (issue 48, "Cost";
//! docs/decisions/0055): 100 instances of the Blender arm
//! (`examples/models/arm.glb`, 2 joints) sharing one skinned mesh
//! (`StyleRuntime::add_skinned_mesh`), each playing the clip at its own
//! time, so each frame every instance has a new pose. The host's only
//! per-instance work is the pose: the clip sampled (`Rig::pose_into`) and
//! two joint matrices written into the instance's `SkinPose` in place.
//! Prints, in milliseconds per whole frame (render recorded, submitted,
//! waited for; a 64 × 64 lit style):
//! - `rigid`: the 100 instances without poses (one still mesh, shared buffers);
//! - `posed`: the same with their poses (the GPU stage deforms each);
//! - `pose`: the host's share of `posed` (sampling and writing the poses).
//!
//! `cargo run -p npr-runner --example crowd_timing`

// A host's own texture, as a host makes it (not counted: not the runner's).
#![allow(clippy::disallowed_methods)]

use npr_compiler::CompileOptions;
use npr_runner::embed::{Frame, Instance, Lights, SkinPose, Skinning, StyleRuntime, Target};
use npr_runner::scene::load_mesh_and_rig;
use npr_runner::scene::rig::{Pose, PoseScratch, Rig};
use npr_runner::scene::Camera;
use npr_runner::Gpu;
use std::path::Path;
use std::time::{Duration, Instant};

const CROWD: usize = 100;
const FRAMES: u32 = 60;

const STYLE: &str = r#"
style "timing"
pass shade: render(scene) {
  let lit = lambert(normal, light.dir)
  out c: rgba8unorm = vec4(lit, lit, lit, 1.0)
  clear: #000000
}
output shade.c
"#;

/// The arm's skin as a host gives it.
fn skinning(rig: &Rig) -> Skinning {
    Skinning {
        joint_count: rig.skins[0].joints.len(),
        joints: rig.joints.clone(),
        weights: rig.weights.clone(),
        morph_targets: Vec::new(),
    }
}

/// A 10 × 10 grid of arms, each `Instance` of `handle`.
fn crowd(handle: npr_runner::embed::MeshHandle, joints: Option<usize>) -> Vec<Instance> {
    (0..CROWD)
        .map(|i| {
            let at = glam::Vec3::new((i % 10) as f32 - 4.5, 0.0, -((i / 10) as f32) * 1.2);
            let instance = Instance::new(handle, glam::Mat4::from_translation(at));
            match joints {
                Some(n) => instance.with_pose(SkinPose::bind(n, 0)),
                None => instance,
            }
        })
        .collect()
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models");
    let gpu = Gpu::headless().expect("a GPU adapter (lavapipe: ./setup.sh --tests)");
    println!("adapter: {}", gpu.adapter_info.name);
    let mut sources = npr_diag::SourceMap::new();
    let program = npr_compiler::compile_source(
        "timing.npr",
        STYLE,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|_| panic!("the timing style compiles"))
    .program();
    let (_, rig) = load_mesh_and_rig(&dir.join("arm.glb")).expect("the arm");
    let rig = rig.expect("the arm's rig");
    let duration = rig.clips[0].duration;
    let camera = Camera::looking_at(glam::Vec3::new(0.0, 4.0, 10.0), glam::Vec3::new(0.0, 0.5, -5.0));
    let lights = Lights::default();
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("crowd"),
        size: wgpu::Extent3d {
            width: 64,
            height: 64,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    for posed in [false, true] {
        let mut runtime = StyleRuntime::new(&gpu.device, &gpu.queue, program.clone()).expect("runtime");
        let handle = runtime
            .add_skinned_mesh(rig.bind.clone(), skinning(&rig))
            .expect("the arm's skin");
        let joints = rig.skins[0].joints.len();
        let mut instances = crowd(handle, posed.then_some(joints));
        let (mut pose, mut scratch) = (
            Pose {
                world: Vec::new(),
                weights: Vec::new(),
            },
            PoseScratch::default(),
        );
        let mut posing = Duration::ZERO;
        let mut frame = |k: u32, posing: &mut Duration| {
            let started = Instant::now();
            if posed {
                for (i, instance) in instances.iter_mut().enumerate() {
                    let t = (0.04 * k as f32 + i as f32 * 0.37) % duration;
                    rig.pose_into(Some((0, t)), &mut pose, &mut scratch);
                    let out = instance.pose.as_mut().expect("posed");
                    for (j, m) in out.joints.iter_mut().enumerate() {
                        *m = rig.skin_joint_matrix(0, j, &pose);
                    }
                }
            }
            *posing += started.elapsed();
            let frame = Frame {
                camera: &camera,
                objects: &instances,
                lights: &lights,
                time_s: f64::from(k) / 24.0,
                frame_index: k,
                eye: 0,
            };
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            runtime
                .render(&mut encoder, &frame, Target::View(&view))
                .expect("frame");
            gpu.queue.submit([encoder.finish()]);
            gpu.device
                .poll(wgpu::PollType::wait_indefinitely())
                .expect("the device finishes the frame");
        };
        frame(0, &mut posing);
        posing = Duration::ZERO;
        let start = Instant::now();
        for k in 1..=FRAMES {
            frame(k, &mut posing);
        }
        let ms = start.elapsed().as_secs_f64() * 1000.0 / f64::from(FRAMES);
        let pose_ms = posing.as_secs_f64() * 1000.0 / f64::from(FRAMES);
        println!(
            "{CROWD} arms ({} vertices each), {}: {ms:.2} ms a frame (of which posing {pose_ms:.3} ms)",
            rig.bind.vertex_count(),
            if posed { "posed" } else { "rigid" }
        );
    }
}
