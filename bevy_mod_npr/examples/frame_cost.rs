//! The cost of a frame, in one run with the frames interleaved (one frame
//! of each in turn, so that the machine's load falls on all alike):
//! - a headless Bevy app whose camera is drawn by an npr style (bevy_mod_npr);
//! - the same app with the camera drawn by Bevy alone (no style: Bevy's
//!   own frame, which draws nothing here, as the entities have no material);
//! - with `--features bench-standard-material`, the same app with each
//!   mesh given Bevy's default material (`StandardMaterial::default()`) and
//!   a `DirectionalLight` where the style's light is: Bevy drawing the
//!   scene itself;
//! - `npr render`'s renderer on its own device, for the same style and scene.
//!
//! Every camera has the same post-processing (none: bevy_mod_npr turns Bevy's
//! tonemapping off on its cameras, the others get `Tonemapping::None`),
//! no MSAA, one size. Each frame is timed in two parts: the update (CPU:
//! Bevy's schedules, extraction, encoding, submission; for the renderer,
//! its `render`) and the wait for the device to finish it (on lavapipe the
//! "GPU" is the CPU too). Medians of `--frames` frames after a warm-up
//! that lasts until every pipeline is compiled; each app's image is then
//! read back and checked to show the scene (over 1% of it not the
//! corner's colour).
//!
//! `cargo run -p bevy_mod_npr --example frame_cost [--features bench-standard-material] -- [STYLE] [SCENE] [--frames N] [--size WxH]`
//! (defaults: examples/toon.npr, examples/scenes/spot.toml, 60, 256x256).

use bevy::camera::RenderTarget;
use bevy::image::Image;
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{PipelineCache, TextureFormat, TextureUsages};
use bevy::render::renderer::{RenderDevice, RenderQueue};
use bevy::render::sync_world::RenderEntity;
use bevy::render::texture::GpuImage;
use bevy::render::view::Tonemapping;
use bevy::render::RenderApp;
use bevy::time::TimeUpdateStrategy;
use bevy::window::ExitCondition;
use bevy_mod_npr::{npr_scene_camera, spawn_npr_scene, NprPlugin, NprRuntimes, NprStyle};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

struct Options {
    style: PathBuf,
    scene: PathBuf,
    frames: usize,
    size: (u32, u32),
}

fn options() -> Options {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut o = Options {
        style: repo.join("examples/toon.npr"),
        scene: repo.join("examples/scenes/spot.toml"),
        frames: 60,
        size: (256, 256),
    };
    let mut args = std::env::args().skip(1);
    let mut positional = 0;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--frames" => o.frames = args.next().and_then(|n| n.parse().ok()).expect("--frames N"),
            "--size" => {
                let s = args.next().expect("--size WxH");
                let (w, h) = s.split_once('x').expect("--size WxH");
                o.size = (w.parse().expect("width"), h.parse().expect("height"));
            }
            path if positional == 0 => {
                o.style = path.into();
                positional += 1;
            }
            path => o.scene = path.into(),
        }
    }
    o
}

fn median(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// What draws a Bevy app's camera: the style, Bevy with no material, Bevy with `StandardMaterial`.
#[derive(Clone, Copy, PartialEq)]
enum Drawn {
    Style,
    BevyAlone,
    StandardMaterial,
}

/// One frame's milliseconds: the update (CPU) and the wait for the device.
#[derive(Default)]
struct Times {
    update: Vec<f64>,
    wait: Vec<f64>,
}

impl Times {
    fn push(&mut self, update: f64, wait: f64) {
        self.update.push(update);
        self.wait.push(wait);
    }

    /// Medians of (update, wait, whole frame).
    fn medians(&self) -> (f64, f64, f64) {
        let whole: Vec<f64> = self.update.iter().zip(&self.wait).map(|(u, w)| u + w).collect();
        (median(&self.update), median(&self.wait), median(&whole))
    }
}

/// A headless Bevy app (no window, no pipelined rendering, the clock
/// stopped) with `scene` drawn into an image as `drawn` says.
struct BevyRun {
    app: App,
    camera: Entity,
    image: Handle<Image>,
    times: Times,
}

impl BevyRun {
    fn new(o: &Options, scene: &npr_runner::scene::Scene, drawn: Drawn) -> BevyRun {
        let dir = o
            .style
            .parent()
            .expect("the style's folder")
            .canonicalize()
            .expect("style folder");
        let mut app = App::new();
        app.add_plugins(
            DefaultPlugins
                .build()
                .disable::<bevy::winit::WinitPlugin>()
                .disable::<bevy::render::pipelined_rendering::PipelinedRenderingPlugin>()
                .disable::<bevy::log::LogPlugin>()
                .set(AssetPlugin {
                    file_path: dir.display().to_string(),
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
        let mut image = Image::new_target_texture(o.size.0, o.size.1, TextureFormat::Rgba8UnormSrgb, None);
        image.texture_descriptor.usage |= TextureUsages::COPY_SRC;
        let image = app.world_mut().resource_mut::<Assets<Image>>().add(image);
        spawn_npr_scene(app.world_mut(), scene);
        let camera = app
            .world_mut()
            .spawn((
                npr_scene_camera(scene),
                RenderTarget::Image(image.clone().into()),
                Tonemapping::None,
            ))
            .id();
        match drawn {
            Drawn::Style => {
                let file = o.style.file_name().expect("style file").to_string_lossy().into_owned();
                let style = app.world().resource::<AssetServer>().load(file);
                app.world_mut().entity_mut(camera).insert(NprStyle(style));
            }
            Drawn::BevyAlone => {}
            Drawn::StandardMaterial => standard_material::give(app.world_mut()),
        }
        let mut run = BevyRun {
            app,
            camera,
            image,
            times: Times::default(),
        };
        run.warm_up(drawn);
        run
    }

    /// Update until the style's runtime is built (a styled camera) and no
    /// pipeline has been waiting for compilation for 10 frames; at least 30 frames.
    fn warm_up(&mut self, drawn: Drawn) {
        let started = Instant::now();
        let (mut frames, mut settled) = (0, 0);
        loop {
            self.frame();
            frames += 1;
            let render_world = self.app.sub_app(RenderApp).world();
            let waiting = render_world.resource::<PipelineCache>().waiting_pipelines().count();
            settled = if waiting == 0 { settled + 1 } else { 0 };
            let built = match drawn {
                Drawn::Style => {
                    let render = self.app.world().get::<RenderEntity>(self.camera).map(|r| r.id());
                    let runtimes = render_world.resource::<NprRuntimes>();
                    render.and_then(|r| runtimes.builds(r)).is_some_and(|b| b > 0)
                }
                _ => true,
            };
            if built && settled >= 10 && frames >= 30 {
                break;
            }
            assert!(
                started.elapsed() < Duration::from_secs(300),
                "the app did not settle in 300 s (style loaded: {built}, pipelines waiting: {waiting})"
            );
        }
        self.times = Times::default();
    }

    /// One timed frame.
    fn frame(&mut self) {
        let t = Instant::now();
        self.app.update();
        let update = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let device = self.app.sub_app(RenderApp).world().resource::<RenderDevice>();
        device
            .wgpu_device()
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("wait for the GPU");
        self.times.push(update, t.elapsed().as_secs_f64() * 1e3);
    }

    /// The camera's image, as stored (sRGB-encoded bytes).
    fn image(&self, size: (u32, u32)) -> image::RgbaImage {
        let world = self.app.sub_app(RenderApp).world();
        let gpu = world
            .resource::<RenderAssets<GpuImage>>()
            .get(self.image.id())
            .expect("the image is on the GPU");
        let device = world.resource::<RenderDevice>();
        let queue = world.resource::<RenderQueue>();
        npr_runner::readback::read_texture(
            device.wgpu_device(),
            queue,
            &gpu.texture,
            size.0,
            size.1,
            npr_abi::Format::Rgba8unorm,
            "frame_cost",
        )
        .unwrap_or_else(|e| panic!("reading the image back: {e}"))
        .to_rgba8()
    }
}

/// Bevy's default material on every mesh, and Bevy's light at the style's.
#[cfg(feature = "bench-standard-material")]
mod standard_material {
    use bevy::prelude::*;

    pub fn give(world: &mut World) {
        let material = world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial::default());
        let meshes: Vec<Entity> = world.query_filtered::<Entity, With<Mesh3d>>().iter(world).collect();
        for entity in meshes {
            world.entity_mut(entity).insert(MeshMaterial3d(material.clone()));
        }
        let lights: Vec<Entity> = world
            .query_filtered::<Entity, With<bevy_mod_npr::NprLight>>()
            .iter(world)
            .collect();
        for entity in lights {
            world.entity_mut(entity).insert(DirectionalLight::default());
        }
    }
}

#[cfg(not(feature = "bench-standard-material"))]
mod standard_material {
    pub fn give(_: &mut bevy::prelude::World) {
        unreachable!("built without bench-standard-material")
    }
}

/// `npr render`'s renderer on a headless device of its own.
struct NprRun {
    gpu: npr_runner::Gpu,
    renderer: npr_runner::Renderer,
    spec: npr_runner::FrameSpec,
    times: Times,
}

impl NprRun {
    fn new(o: &Options, scene: &npr_runner::scene::Scene) -> NprRun {
        let gpu = npr_runner::Gpu::headless().expect("a GPU adapter (./setup.sh --tests installs lavapipe)");
        let mut sources = npr_diag::SourceMap::new();
        let program = match npr_compiler::compile_file(&o.style, &mut sources, &Default::default()) {
            Ok(c) => c.program(),
            Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
            Err(e) => panic!("{e:?}"),
        };
        let renderer = npr_runner::Renderer::new(&gpu.device, &gpu.queue, &program, scene).expect("renderer");
        let spec = npr_runner::FrameSpec::still(o.size.0, o.size.1, 0);
        let mut run = NprRun {
            gpu,
            renderer,
            spec,
            times: Times::default(),
        };
        for _ in 0..30 {
            run.frame(scene);
        }
        run.times = Times::default();
        run
    }

    fn frame(&mut self, scene: &npr_runner::scene::Scene) {
        let t = Instant::now();
        self.renderer.render(scene, &self.spec).expect("frame");
        let update = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        npr_runner::readback::wait_idle(&self.gpu.device).expect("wait");
        self.times.push(update, t.elapsed().as_secs_f64() * 1e3);
    }
}

/// Fails when `image` is nearly one colour: the app did not draw the
/// scene. (A line style on a white page colours a few percent of it.)
fn check_drawn(name: &str, image: &image::RgbaImage) {
    let first = image.get_pixel(0, 0).0;
    let differing = image.pixels().filter(|p| p.0 != first).count();
    let share = differing as f64 / (image.width() * image.height()) as f64;
    assert!(
        share > 0.01,
        "{name}: only {:.1}% of the image differs from its corner: the scene was not drawn",
        share * 100.0
    );
}

fn main() {
    let o = options();
    let mut sources = npr_diag::SourceMap::new();
    let scene = npr_runner::scene::load_scene(&o.scene, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let mut runs = vec![
        ("Bevy + bevy_mod_npr", BevyRun::new(&o, &scene, Drawn::Style)),
        ("Bevy alone (no material)", BevyRun::new(&o, &scene, Drawn::BevyAlone)),
    ];
    if cfg!(feature = "bench-standard-material") {
        runs.push((
            "Bevy, StandardMaterial",
            BevyRun::new(&o, &scene, Drawn::StandardMaterial),
        ));
    }
    let mut npr = NprRun::new(&o, &scene);
    // Interleaved: each round draws one frame of each, starting with another each round.
    for round in 0..o.frames {
        let n = runs.len() + 1;
        for k in 0..n {
            match (round + k) % n {
                i if i < runs.len() => runs[i].1.frame(),
                _ => npr.frame(&scene),
            }
        }
    }
    check_drawn("Bevy + bevy_mod_npr", &runs[0].1.image(o.size));
    for (name, run) in runs.iter().skip(2) {
        check_drawn(name, &run.image(o.size));
    }

    println!(
        "{} on {}, {}x{}, median of {} interleaved frames (ms):",
        o.style.display(),
        o.scene.display(),
        o.size.0,
        o.size.1,
        o.frames
    );
    println!("  {:<28} {:>8} {:>8} {:>8}", "", "update", "wait", "frame");
    let mut frame_ms = Vec::new();
    for (name, run) in &runs {
        let (u, w, f) = run.times.medians();
        println!("  {name:<28} {u:8.3} {w:8.3} {f:8.3}");
        frame_ms.push(f);
    }
    let (u, w, f) = npr.times.medians();
    println!("  {:<28} {u:8.3} {w:8.3} {f:8.3}", "npr render's renderer");
    let share = frame_ms[0] - frame_ms[1];
    println!("  bevy_mod_npr's share (npr - alone)        {share:8.3}");
    println!("  share / npr render's frame            {:8.2}", share / f);
    match frame_ms.get(2) {
        Some(standard) => {
            println!(
                "  Bevy + bevy_mod_npr / StandardMaterial    {:8.2}",
                frame_ms[0] / standard
            );
            println!(
                "  share / StandardMaterial's share      {:8.2}",
                share / (standard - frame_ms[1])
            );
        }
        None => println!("  (StandardMaterial: run with --features bench-standard-material)"),
    }
}
