//! npr's toon style on a Bevy scene: a sphere, a torus and a ground plane,
//! a camera circling them, the style loaded from `examples/toon.npr` of
//! this repository and reloaded when that file is saved (edit `bands` or
//! `base` while it runs). Its `rim` parameter is set from Bevy each frame
//! through `NprParams`.
//!
//! `cargo run -p bevy_mod_npr --example toon [-- --frames N]`: `--frames N`
//! takes a screenshot at frame N, prints its corner colour and number of
//! colours, and quits (bevy_mod_npr/tests/example.rs runs it under Xvfb).

use bevy::prelude::*;
use bevy::render::view::window::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::window::WindowResolution;
use bevy_mod_npr::{NprLight, NprObject, NprParams, NprPlugin, NprStyle};

/// Quit after this many frames (`--frames N`).
#[derive(Resource)]
struct FrameLimit(Option<u32>);

fn main() {
    let frames = std::env::args()
        .skip_while(|a| a != "--frames")
        .nth(1)
        .and_then(|n| n.parse().ok());
    App::new()
        .add_plugins((
            DefaultPlugins
                .set(AssetPlugin {
                    // The repository's examples/ folder: edit examples/toon.npr and see it change.
                    file_path: "../examples".into(),
                    watch_for_changes_override: Some(true),
                    ..Default::default()
                })
                .set(WindowPlugin {
                    primary_window: Some(Window {
                        title: "bevy_mod_npr: toon".into(),
                        resolution: WindowResolution::new(640, 480),
                        ..Default::default()
                    }),
                    ..Default::default()
                }),
            NprPlugin,
        ))
        .insert_resource(FrameLimit(frames))
        .add_systems(Startup, setup)
        .add_systems(Update, (orbit, pulse_rim, quit_after))
        .run();
}

fn setup(mut commands: Commands, assets: Res<AssetServer>, mut meshes: ResMut<Assets<Mesh>>) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 2.4, 6.0).looking_at(Vec3::new(0.0, 0.35, 0.0), Vec3::Y),
        NprStyle(assets.load("toon.npr")),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Sphere::new(0.7).mesh().uv(64, 32))),
        Transform::from_xyz(-0.8, 0.7, 0.0),
        NprObject::default().with("tint", Color::srgb_u8(0xff, 0x90, 0x70)),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Torus::new(0.35, 0.75))),
        Transform::from_xyz(0.9, 0.45, 0.2).with_rotation(Quat::from_rotation_x(60f32.to_radians())),
        NprObject::default().with("tint", Color::srgb_u8(0x80, 0xb0, 0xff)),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(6.0, 6.0))),
        NprObject::tagged("ground"),
    ));
    commands.spawn((
        NprLight::default(),
        Transform::default().looking_to(-Vec3::new(0.5, 1.0, 0.7), Vec3::Y),
    ));
}

/// The camera circles the scene.
fn orbit(time: Res<Time>, mut cameras: Query<&mut Transform, With<NprStyle>>) {
    let angle = time.elapsed_secs() * 0.4;
    for mut transform in &mut cameras {
        *transform = Transform::from_xyz(6.0 * angle.sin(), 2.4, 6.0 * angle.cos())
            .looking_at(Vec3::new(0.0, 0.35, 0.0), Vec3::Y);
    }
}

/// A style parameter driven from Bevy: the rim light pulses.
fn pulse_rim(time: Res<Time>, mut params: Query<&mut NprParams>) {
    let rim = 0.3 + 0.2 * (time.elapsed_secs() * 2.0).sin();
    for mut p in &mut params {
        p.set("rim", format!("{rim:.3}"));
    }
}

/// With `--frames N`: at frame N, a screenshot of the window; its corner
/// colour and number of colours are printed (the style's clear colour and
/// its bands, not Bevy's clear colour), then the app quits.
fn quit_after(
    mut commands: Commands,
    limit: Res<FrameLimit>,
    mut frames: Local<u32>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(limit) = limit.0 else { return };
    *frames += 1;
    if *frames == limit {
        commands.spawn(Screenshot::primary_window()).observe(
            |captured: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
                let image = &captured.image;
                let bytes = image.data.as_deref().unwrap_or_default();
                let pixels: Vec<[u8; 4]> = bytes.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]).collect();
                let colours: std::collections::BTreeSet<[u8; 4]> = pixels.iter().copied().collect();
                let corner = pixels.first().copied().unwrap_or_default();
                println!(
                    "screenshot {}x{} {:?}: corner {:?}, {} colours",
                    image.width(),
                    image.height(),
                    image.texture_descriptor.format,
                    corner,
                    colours.len()
                );
                exit.write(AppExit::Success);
            },
        );
    }
    if *frames > limit + 300 {
        eprintln!("no screenshot 300 frames after frame {limit}");
        exit.write(AppExit::error());
    }
}
