//! A headless Bevy app on lavapipe (no window: the camera renders into an
//! image, read back from the render world), npr's scenes spawned as Bevy
//! entities, and the comparison with `npr render`'s renderer.

#![allow(dead_code)]

use bevy::asset::AssetPlugin;
use bevy::camera::RenderTarget;
use bevy::image::Image;
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{TextureFormat, TextureUsages};
use bevy::render::renderer::{RenderDevice, RenderQueue};
use bevy::render::sync_world::RenderEntity;
use bevy::render::texture::GpuImage;
use bevy::render::RenderApp;
use bevy::time::TimeUpdateStrategy;
use bevy::window::ExitCondition;
use bevy_mod_npr::{npr_scene_camera, spawn_npr_scene, NprPlugin, NprRuntimes, NprStyle};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// The images' side: small, lavapipe renders on the CPU.
pub const SIZE: u32 = 128;

/// One Bevy app at a time: each has its own render device, and two cores
/// serve them all.
pub static ONE_APP: Mutex<()> = Mutex::new(());

pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A fresh folder for a test's assets (styles copied there, edited there).
pub fn asset_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bevy_mod_npr").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("test asset folder");
    dir
}

/// A headless app whose assets are `assets` (watched: hot reload), with
/// Bevy's clock stopped at 0 s so that animated params match `npr render
/// --time 0`.
pub fn app(assets: &Path) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .build()
            .disable::<bevy::winit::WinitPlugin>()
            .disable::<bevy::render::pipelined_rendering::PipelinedRenderingPlugin>()
            .disable::<bevy::log::LogPlugin>()
            .set(AssetPlugin {
                file_path: assets.display().to_string(),
                watch_for_changes_override: Some(true),
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

/// An image a camera renders into (readable: COPY_SRC).
pub fn target_image(app: &mut App, format: TextureFormat) -> Handle<Image> {
    let mut image = Image::new_target_texture(SIZE, SIZE, format, None);
    image.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    app.world_mut().resource_mut::<Assets<Image>>().add(image)
}

/// `scene` (an npr scene file, loaded by npr) as Bevy entities, and its
/// camera with `style`, rendering into `image`. Returns the camera.
pub fn spawn_scene(
    app: &mut App,
    scene: &npr_runner::scene::Scene,
    style: Handle<bevy_mod_npr::NprStyleAsset>,
    image: &Handle<Image>,
) -> Entity {
    spawn_npr_scene(app.world_mut(), scene);
    spawn_camera(app, scene, style, image)
}

/// A camera at `scene`'s camera, drawn with `style` into `image`.
pub fn spawn_camera(
    app: &mut App,
    scene: &npr_runner::scene::Scene,
    style: Handle<bevy_mod_npr::NprStyleAsset>,
    image: &Handle<Image>,
) -> Entity {
    app.world_mut()
        .spawn((
            npr_scene_camera(scene),
            RenderTarget::Image(image.clone().into()),
            NprStyle(style),
        ))
        .id()
}

/// Update `app` until `done` (checked after each frame), or fail after `timeout`.
pub fn update_until(app: &mut App, what: &str, timeout: Duration, mut done: impl FnMut(&mut App) -> bool) {
    let started = Instant::now();
    loop {
        app.update();
        if done(app) {
            return;
        }
        assert!(
            started.elapsed() < timeout,
            "timed out after {timeout:?} waiting for {what}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The render entity of a main-world camera.
pub fn render_entity(app: &mut App, camera: Entity) -> Entity {
    app.world()
        .get::<RenderEntity>(camera)
        .expect("the camera is synced to the render world")
        .id()
}

/// The style name and build count of a camera's runtime.
pub fn runtime_of(app: &mut App, camera: Entity) -> Option<(String, u64)> {
    let render = render_entity(app, camera);
    let runtimes = app.sub_app(RenderApp).world().resource::<NprRuntimes>();
    Some((runtimes.style_name(render)?.to_string(), runtimes.builds(render)?))
}

/// The codes the render world logged.
pub fn logged_codes(app: &App) -> Vec<&'static str> {
    app.sub_app(RenderApp).world().resource::<NprRuntimes>().logged_codes()
}

/// The bytes of `image` (RGBA8, as stored: sRGB-encoded for an sRGB image).
pub fn read_image(app: &App, image: &Handle<Image>) -> image::RgbaImage {
    read_image_sized(app, image, (SIZE, SIZE))
}

/// [`read_image`] of an image of `size`.
pub fn read_image_sized(app: &App, image: &Handle<Image>, size: (u32, u32)) -> image::RgbaImage {
    let world = app.sub_app(RenderApp).world();
    let gpu = world
        .resource::<RenderAssets<GpuImage>>()
        .get(image.id())
        .expect("the target image is on the GPU");
    let device = world.resource::<RenderDevice>();
    let queue = world.resource::<RenderQueue>();
    let read = npr_runner::readback::read_texture(
        device.wgpu_device(),
        queue,
        &gpu.texture,
        size.0,
        size.1,
        npr_abi::Format::Rgba8unorm,
        "bevy target",
    )
    .unwrap_or_else(|e| panic!("reading the camera's image back: {e}"));
    read.to_rgba8()
}

/// Compile `style` as `npr render` does (no kept params).
pub fn compile(style: &Path) -> npr_runner::StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    match npr_compiler::compile_file(style, &mut sources, &Default::default()) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    }
}

pub fn load_scene(name: &str) -> npr_runner::scene::Scene {
    let path = repo().join("examples/scenes").join(name);
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// What `npr render STYLE --scene SCENE --size 128x128 --time 0` writes:
/// the renderer it drives, on a headless device of its own.
pub fn npr_render(style: &Path, scene: &npr_runner::scene::Scene) -> image::RgbaImage {
    npr_render_sized(style, scene, (SIZE, SIZE))
}

/// [`npr_render`] at `size`.
pub fn npr_render_sized(style: &Path, scene: &npr_runner::scene::Scene, size: (u32, u32)) -> image::RgbaImage {
    let gpu = npr_runner::Gpu::headless()
        .unwrap_or_else(|e| panic!("no GPU adapter (install Mesa's lavapipe: ./setup.sh --tests): {e}"));
    let spec = npr_runner::FrameSpec::still(size.0, size.1, 0);
    npr_runner::render_frame(&gpu, &compile(style), scene, &spec)
        .unwrap_or_else(|e| panic!("npr render: {e:?}"))
        .to_rgba8()
}

/// The per-pixel bound: at most `MAX_FAR` of the pixels may have a
/// channel more than `NEAR` steps (of 255) off (edge pixels whose
/// coverage flips with the last bit of a transform: Bevy's `Transform`
/// and camera are rebuilt from npr's matrices), and the mean difference
/// stays under `MEAN` steps. On failure the actual, expected and diff
/// images are written to the target folder.
pub const NEAR: u8 = 2;
pub const MAX_FAR: f64 = 0.01;
pub const MEAN: f64 = 0.5;

pub fn assert_close(name: &str, actual: &image::RgbaImage, expected: &image::RgbaImage) {
    // A flat reference would make the comparison say little.
    let first = expected.get_pixel(0, 0).0;
    let differing = expected.pixels().filter(|p| p.0 != first).count();
    assert!(
        differing > (expected.width() * expected.height() / 20) as usize,
        "{name}: npr render's image is nearly flat ({differing} pixels differ from the corner)"
    );
    if std::env::var_os("BEVY_NPR_KEEP_IMAGES").is_some() {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bevy_mod_npr_images");
        std::fs::create_dir_all(&dir).expect("image folder");
        actual
            .save(dir.join(format!("{name}.actual.png")))
            .expect("write image");
        expected
            .save(dir.join(format!("{name}.expected.png")))
            .expect("write image");
    }
    let mut far = 0usize;
    let mut sum = 0u64;
    let mut diff = image::RgbaImage::new(actual.width(), actual.height());
    for ((a, e), d) in actual.pixels().zip(expected.pixels()).zip(diff.pixels_mut()) {
        let worst = (0..4).map(|c| a[c].abs_diff(e[c])).max().unwrap_or(0);
        sum += (0..4).map(|c| a[c].abs_diff(e[c]) as u64).sum::<u64>();
        if worst > NEAR {
            far += 1;
        }
        let v = worst.saturating_mul(16);
        *d = image::Rgba([v, v, v, 255]);
    }
    let pixels = (actual.width() * actual.height()) as f64;
    let far_share = far as f64 / pixels;
    let mean = sum as f64 / (pixels * 4.0);
    if far_share > MAX_FAR || mean > MEAN {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bevy_mod_npr_failures");
        std::fs::create_dir_all(&dir).expect("failure folder");
        for (suffix, img) in [("actual", actual), ("expected", expected), ("diff", &diff)] {
            img.save(dir.join(format!("{name}.{suffix}.png")))
                .expect("write failure image");
        }
        panic!(
            "{name}: {:.2}% of pixels differ by more than {NEAR}/255 (bound {:.2}%), mean difference {mean:.3}/255 \
             (bound {MEAN}); images in {}",
            far_share * 100.0,
            MAX_FAR * 100.0,
            dir.display()
        );
    }
}
