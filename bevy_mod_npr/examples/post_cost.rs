//! The cost of a style over Bevy's own frame (decision 0054), in one run
//! with the frames interleaved (one frame of each app in turn, so that the
//! machine's load falls on both alike): two headless Bevy apps draw the
//! same `StandardMaterial` spheres and plane, lit by a `DirectionalLight`,
//! with depth and normal prepasses, no MSAA and no tonemapping; the camera
//! of one is inked by `examples/post/ink_over.npr`. Each frame is its
//! update plus the wait for the device; medians of `--frames` frames after
//! a warm-up that lasts until the style draws and no pipeline has waited
//! for 10 frames (at least 30). The inked image is then read back and must
//! hold ink.
//!
//! `cargo run -p bevy_mod_npr --example post_cost -- [--frames N] [--size WxH]`
//! (defaults: 60 frames, 256x256).

use bevy::camera::RenderTarget;
use bevy::core_pipeline::prepass::{DepthPrepass, NormalPrepass};
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{PipelineCache, TextureFormat, TextureUsages};
use bevy::render::renderer::{RenderDevice, RenderQueue};
use bevy::render::sync_world::RenderEntity;
use bevy::render::texture::GpuImage;
use bevy::render::view::{DebandDither, Tonemapping};
use bevy::render::RenderApp;
use bevy::time::TimeUpdateStrategy;
use bevy::window::ExitCondition;
use bevy_mod_npr::{NprPlugin, NprRuntimes, NprStyle};
use std::path::Path;
use std::time::{Duration, Instant};

fn median(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

struct Run {
    app: App,
    camera: Entity,
    image: Handle<Image>,
    inked: bool,
    frames: Vec<f64>,
}

impl Run {
    fn new(size: (u32, u32), inked: bool) -> Run {
        let styles = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/post");
        let mut app = App::new();
        app.add_plugins(
            DefaultPlugins
                .build()
                .disable::<bevy::winit::WinitPlugin>()
                .disable::<bevy::render::pipelined_rendering::PipelinedRenderingPlugin>()
                .disable::<bevy::log::LogPlugin>()
                .set(AssetPlugin {
                    file_path: styles.canonicalize().expect("examples/post").display().to_string(),
                    ..Default::default()
                })
                .set(WindowPlugin {
                    primary_window: None,
                    exit_condition: ExitCondition::DontExit,
                    ..Default::default()
                }),
        )
        .add_plugins(NprPlugin)
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
        app.finish();
        app.cleanup();
        let mut image = Image::new_target_texture(size.0, size.1, TextureFormat::Rgba8UnormSrgb, None);
        image.texture_descriptor.usage |= TextureUsages::COPY_SRC;
        let image = app.world_mut().resource_mut::<Assets<Image>>().add(image);
        scene(app.world_mut());
        let camera = app
            .world_mut()
            .spawn((
                Camera3d::default(),
                RenderTarget::Image(image.clone().into()),
                Transform::from_xyz(0.0, 2.5, 7.0).looking_at(Vec3::new(0.0, 0.6, 0.0), Vec3::Y),
                Msaa::Off,
                Tonemapping::None,
                DebandDither::Disabled,
                DepthPrepass,
                NormalPrepass,
            ))
            .id();
        if inked {
            let style = app.world().resource::<AssetServer>().load("ink_over.npr");
            app.world_mut().entity_mut(camera).insert(NprStyle(style));
        }
        let mut run = Run {
            app,
            camera,
            image,
            inked,
            frames: Vec::new(),
        };
        run.warm_up();
        run
    }

    fn warm_up(&mut self) {
        let started = Instant::now();
        let (mut frames, mut settled) = (0, 0);
        loop {
            self.frame();
            frames += 1;
            let world = self.app.sub_app(RenderApp).world();
            settled = match world.resource::<PipelineCache>().waiting_pipelines().count() {
                0 => settled + 1,
                _ => 0,
            };
            let drawn = !self.inked || {
                let render = self.app.world().get::<RenderEntity>(self.camera).map(|r| r.id());
                render
                    .and_then(|r| world.resource::<NprRuntimes>().builds(r))
                    .is_some_and(|b| b > 0)
            };
            if drawn && settled >= 10 && frames >= 30 {
                break;
            }
            assert!(
                started.elapsed() < Duration::from_secs(600),
                "the app did not settle in 600 s"
            );
        }
        self.frames.clear();
    }

    fn frame(&mut self) {
        let t = Instant::now();
        self.app.update();
        let device = self.app.sub_app(RenderApp).world().resource::<RenderDevice>();
        device
            .wgpu_device()
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("wait for the GPU");
        self.frames.push(t.elapsed().as_secs_f64() * 1e3);
    }

    fn image(&self, size: (u32, u32)) -> image::RgbaImage {
        let world = self.app.sub_app(RenderApp).world();
        let gpu = world
            .resource::<RenderAssets<GpuImage>>()
            .get(self.image.id())
            .expect("the image is on the GPU");
        npr_runner::readback::read_texture(
            world.resource::<RenderDevice>().wgpu_device(),
            world.resource::<RenderQueue>(),
            &gpu.texture,
            size.0,
            size.1,
            npr_abi::Format::Rgba8unorm,
            "post_cost",
        )
        .unwrap_or_else(|e| panic!("reading the image back: {e}"))
        .to_rgba8()
    }
}

/// Three `StandardMaterial` spheres on a plane, and a directional light.
fn scene(world: &mut World) {
    for (centre, radius) in [
        ([-1.3, 0.8, 0.0], 0.8),
        ([1.25, 0.6, 0.7], 0.6),
        ([0.4, 0.5, -1.6], 0.5),
    ] {
        let mesh = world
            .resource_mut::<Assets<Mesh>>()
            .add(Sphere::new(radius).mesh().uv(96, 48));
        let material = world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial::from_color(Color::srgb(0.9, 0.4, 0.3)));
        world.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            Transform::from_translation(Vec3::from_array(centre)),
        ));
    }
    let plane = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(8.0, 8.0));
    let grey = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial::from_color(Color::srgb(0.7, 0.7, 0.68)));
    world.spawn((Mesh3d(plane), MeshMaterial3d(grey), Transform::default()));
    world.spawn((
        DirectionalLight {
            illuminance: 6000.0,
            ..Default::default()
        },
        Transform::from_xyz(3.0, 5.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
}

fn main() {
    let mut frames = 60;
    let mut size = (256, 256);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--frames" => frames = args.next().and_then(|n| n.parse().ok()).expect("--frames N"),
            "--size" => {
                let s = args.next().expect("--size WxH");
                let (w, h) = s.split_once('x').expect("--size WxH");
                size = (w.parse().expect("width"), h.parse().expect("height"));
            }
            other => panic!("unknown argument {other}"),
        }
    }
    let mut runs = [Run::new(size, false), Run::new(size, true)];
    for round in 0..frames {
        for k in 0..2 {
            runs[(round + k) % 2].frame();
        }
    }
    let ink = runs[1]
        .image(size)
        .pixels()
        .filter(|p| p.0[..3] == [0x14, 0x14, 0x14])
        .count();
    assert!(ink > 100, "the inked app drew {ink} ink pixels");
    let (plain, inked) = (median(&runs[0].frames), median(&runs[1].frames));
    println!("{}x{}, median of {frames} interleaved frames (ms):", size.0, size.1);
    println!("  Bevy, StandardMaterial + prepasses      {plain:8.3}");
    println!("  the same, inked by ink_over.npr         {inked:8.3}");
    println!("  the post-process's share (ms)           {:8.3}", inked - plain);
    println!("  inked / plain                           {:8.2}", inked / plain);
}
