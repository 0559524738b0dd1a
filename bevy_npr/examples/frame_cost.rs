//! The cost of a frame: a headless Bevy app whose camera is drawn by an
//! npr style (bevy_npr), the same app with the camera drawn by Bevy alone
//! (no style: Bevy's own frame, which draws nothing here, as the scene's
//! entities have no material), and `npr render`'s renderer on its own
//! device, for the same style, scene and size. Each frame's wall time
//! includes waiting for the GPU (lavapipe: the CPU) to finish it; the
//! medians of `--frames` frames after a warm-up are printed.
//!
//! `cargo run -p bevy_npr --example frame_cost -- [STYLE] [SCENE] [--frames N] [--size WxH]`
//! (defaults: examples/toon.npr, examples/scenes/spot.toml, 60, 256x256).

use bevy::camera::RenderTarget;
use bevy::image::Image;
use bevy::prelude::*;
use bevy::render::render_resource::TextureFormat;
use bevy::render::renderer::RenderDevice;
use bevy::render::RenderApp;
use bevy::time::TimeUpdateStrategy;
use bevy::window::ExitCondition;
use bevy_npr::{npr_scene_camera, spawn_npr_scene, NprPlugin, NprRuntimes, NprStyle};
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

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// A headless app (no window, no pipelined rendering, the clock stopped).
fn app(assets: &Path) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .build()
            .disable::<bevy::winit::WinitPlugin>()
            .disable::<bevy::render::pipelined_rendering::PipelinedRenderingPlugin>()
            .disable::<bevy::log::LogPlugin>()
            .set(AssetPlugin {
                file_path: assets.display().to_string(),
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
    app
}

/// Median ms of a Bevy frame (update and GPU work), with or without the style.
fn bevy_frames(o: &Options, scene: &runner::scene::Scene, with_style: bool) -> f64 {
    let dir = o
        .style
        .parent()
        .expect("the style's folder")
        .canonicalize()
        .expect("style folder");
    let mut app = app(&dir);
    let image = Image::new_target_texture(o.size.0, o.size.1, TextureFormat::Rgba8UnormSrgb, None);
    let image = app.world_mut().resource_mut::<Assets<Image>>().add(image);
    spawn_npr_scene(app.world_mut(), scene);
    let camera = app
        .world_mut()
        .spawn((npr_scene_camera(scene), RenderTarget::Image(image.into())))
        .id();
    if with_style {
        let file = o.style.file_name().expect("style file").to_string_lossy().into_owned();
        let style = app.world().resource::<AssetServer>().load(file);
        app.world_mut().entity_mut(camera).insert(NprStyle(style));
    }
    let render_camera = app
        .world()
        .get::<bevy::render::sync_world::RenderEntity>(camera)
        .map(|r| r.id());
    let wait = |app: &App| {
        let device = app.sub_app(RenderApp).world().resource::<RenderDevice>();
        device
            .wgpu_device()
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("wait for the GPU");
    };
    // Warm-up: the style loads and the runtime builds (or 30 frames without one).
    let started = Instant::now();
    let mut warm = 0;
    loop {
        app.update();
        wait(&app);
        warm += 1;
        let render = render_camera.or_else(|| {
            app.world()
                .get::<bevy::render::sync_world::RenderEntity>(camera)
                .map(|r| r.id())
        });
        let built = render.and_then(|r| app.sub_app(RenderApp).world().resource::<NprRuntimes>().builds(r));
        if (!with_style || built.is_some_and(|b| b > 0)) && warm >= 30 {
            break;
        }
        assert!(started.elapsed() < Duration::from_secs(300), "the style did not load");
    }
    let mut times = Vec::new();
    for _ in 0..o.frames {
        let t = Instant::now();
        app.update();
        wait(&app);
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    median(times)
}

/// Median ms of a frame of `npr render`'s renderer (render and GPU work).
fn npr_frames(o: &Options, scene: &runner::scene::Scene) -> f64 {
    let gpu = runner::Gpu::headless().expect("a GPU adapter");
    let mut sources = diag::SourceMap::new();
    let program = match compiler::compile_file(&o.style, &mut sources, &Default::default()) {
        Ok(c) => c.program(),
        Err(compiler::CompileError::User(d)) => panic!("{}", diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    };
    let mut renderer = runner::Renderer::new(&gpu.device, &gpu.queue, &program, scene).expect("renderer");
    let spec = runner::FrameSpec::still(o.size.0, o.size.1, 0);
    let mut times = Vec::new();
    for k in 0..o.frames + 30 {
        let t = Instant::now();
        renderer.render(scene, &spec).expect("frame");
        runner::readback::wait_idle(&gpu.device).expect("wait");
        if k >= 30 {
            times.push(t.elapsed().as_secs_f64() * 1e3);
        }
    }
    median(times)
}

fn main() {
    let o = options();
    let mut sources = diag::SourceMap::new();
    let scene = runner::scene::load_scene(&o.scene, &mut sources)
        .unwrap_or_else(|d| panic!("{}", diag::diagnostic::render(&d, &sources, false)));
    let styled = bevy_frames(&o, &scene, true);
    let plain = bevy_frames(&o, &scene, false);
    let npr = npr_frames(&o, &scene);
    println!(
        "{} on {}, {}x{}, median of {} frames (ms, GPU work included):",
        o.style.display(),
        o.scene.display(),
        o.size.0,
        o.size.1,
        o.frames
    );
    println!("  Bevy + bevy_npr        {styled:8.3}");
    println!("  Bevy alone (no style)  {plain:8.3}");
    println!("  bevy_npr's share       {:8.3}", styled - plain);
    println!("  npr render's renderer  {npr:8.3}");
}
