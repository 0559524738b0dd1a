//! A style over Bevy's own rendering (issue 47, decision 0054), headless
//! on lavapipe: spheres and a plane with `StandardMaterial`, lit by a
//! `DirectionalLight`, drawn by Bevy's PBR renderer with depth and normal
//! prepasses; `examples/post/ink_over.npr` on the camera inks them. A
//! second camera at the same pose without the style is the reference.
//!
//! Checked: the ink lies on the depth discontinuities of the scene, which
//! is ray-traced here in f64 from the known spheres, plane and camera (all
//! within 1 px), and every other pixel is Bevy's PBR shading as the
//! reference camera draws it (within 2/255). A prepass removed is E0608,
//! naming the input and the component, and the camera shows what Bevy
//! drew until the prepass is back; MSAA on is E0609; a reload to a style
//! that reads motion vectors needs `MotionVectorPrepass` (E0608, then
//! drawn once it is added); a reload to red ink redraws the same lines red.

use crate::common;

use bevy::camera::{ClearColorConfig, RenderTarget};
use bevy::core_pipeline::prepass::{DepthPrepass, MotionVectorPrepass, NormalPrepass};
use bevy::prelude::*;
use bevy::render::render_resource::{PipelineCache, TextureFormat};
use bevy::render::view::{DebandDither, Tonemapping};
use bevy::render::RenderApp;
use common::*;
use glam::DVec3;
use std::time::Duration;

/// Long enough for lavapipe to compile Bevy's PBR pipelines on a busy machine.
const PATIENCE: Duration = Duration::from_secs(300);

/// The ink colour of `ink_over.npr` (#141414) and the red of the reload.
const INK: [u8; 3] = [0x14, 0x14, 0x14];
const RED_INK: [u8; 3] = [0xc0, 0x10, 0x10];

/// The scene, in metres: spheres resting on a square plane at y = 0.
const SPHERES: [([f64; 3], f64); 3] = [
    ([-1.3, 0.8, 0.0], 0.8),
    ([1.25, 0.6, 0.7], 0.6),
    ([0.4, 0.5, -1.6], 0.5),
];
const PLANE_HALF: f64 = 4.0;
const EYE: [f64; 3] = [0.0, 2.5, 7.0];
const LOOK_AT: [f64; 3] = [0.0, 0.6, 0.0];
const FOV_Y: f64 = std::f64::consts::FRAC_PI_4;

fn vec3(v: [f64; 3]) -> Vec3 {
    Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

/// A camera at the scene's pose into `image`, with the prepasses the
/// style reads, no MSAA and no tonemapping (the same on both cameras).
fn camera(app: &mut App, image: &Handle<Image>, order: isize) -> Entity {
    app.world_mut()
        .spawn((
            Camera3d::default(),
            Camera {
                order,
                clear_color: ClearColorConfig::Custom(Color::srgb(0.55, 0.7, 0.9)),
                ..Default::default()
            },
            RenderTarget::Image(image.clone().into()),
            Transform::from_translation(vec3(EYE)).looking_at(vec3(LOOK_AT), Vec3::Y),
            Projection::Perspective(PerspectiveProjection {
                fov: FOV_Y as f32,
                near: 0.1,
                ..Default::default()
            }),
            Msaa::Off,
            Tonemapping::None,
            DebandDither::Disabled,
            DepthPrepass,
            NormalPrepass,
        ))
        .id()
}

fn spawn_scene(app: &mut App) {
    let world = app.world_mut();
    let colours = [
        Color::srgb(0.9, 0.35, 0.25),
        Color::srgb(0.3, 0.75, 0.35),
        Color::srgb(0.95, 0.8, 0.3),
    ];
    for ((centre, radius), colour) in SPHERES.iter().zip(colours) {
        let mesh = world
            .resource_mut::<Assets<Mesh>>()
            .add(Sphere::new(*radius as f32).mesh().uv(96, 48));
        let material = world.resource_mut::<Assets<StandardMaterial>>().add(StandardMaterial {
            base_color: colour,
            perceptual_roughness: 0.5,
            ..Default::default()
        });
        world.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            Transform::from_translation(vec3(*centre)),
        ));
    }
    let plane = world.resource_mut::<Assets<Mesh>>().add(
        Plane3d::default()
            .mesh()
            .size(2.0 * PLANE_HALF as f32, 2.0 * PLANE_HALF as f32),
    );
    let grey = world.resource_mut::<Assets<StandardMaterial>>().add(StandardMaterial {
        base_color: Color::srgb(0.7, 0.7, 0.68),
        perceptual_roughness: 0.9,
        ..Default::default()
    });
    world.spawn((Mesh3d(plane), MeshMaterial3d(grey), Transform::default()));
    world.spawn((
        DirectionalLight {
            illuminance: 6000.0,
            ..Default::default()
        },
        Transform::from_xyz(3.0, 5.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
}

/// The scene ray-traced at each pixel's centre: (depth along the view
/// axis, 0 for the background; the world normal).
fn traced() -> Vec<Vec<(f64, DVec3)>> {
    let eye = DVec3::from_array(EYE);
    let forward = (DVec3::from_array(LOOK_AT) - eye).normalize();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    let half = (FOV_Y / 2.0).tan();
    let size = SIZE as f64;
    (0..SIZE)
        .map(|y| {
            (0..SIZE)
                .map(|x| {
                    let ndc_x = (x as f64 + 0.5) / size * 2.0 - 1.0;
                    let ndc_y = 1.0 - (y as f64 + 0.5) / size * 2.0;
                    let d = (forward + right * ndc_x * half + up * ndc_y * half).normalize();
                    let mut best: Option<(f64, DVec3)> = None;
                    for (centre, radius) in SPHERES {
                        let oc = eye - DVec3::from_array(centre);
                        let b = oc.dot(d);
                        let disc = b * b - (oc.length_squared() - radius * radius);
                        if disc >= 0.0 {
                            let t = -b - disc.sqrt();
                            if t > 0.0 && best.is_none_or(|(bt, _)| t < bt) {
                                let n = (eye + d * t - DVec3::from_array(centre)) / radius;
                                best = Some((t, n));
                            }
                        }
                    }
                    if d.y < 0.0 {
                        let t = -eye.y / d.y;
                        let p = eye + d * t;
                        if p.x.abs() <= PLANE_HALF && p.z.abs() <= PLANE_HALF && best.is_none_or(|(bt, _)| t < bt) {
                            best = Some((t, DVec3::Y));
                        }
                    }
                    best.map_or((0.0, DVec3::ZERO), |(t, n)| (t * d.dot(forward), n))
                })
                .collect()
        })
        .collect()
}

/// Where the traced depth jumps by more than `ratio` of the nearer depth
/// (the background infinitely far) between a pixel and its right or lower
/// neighbour; both pixels marked.
fn depth_jumps(scene: &[Vec<(f64, DVec3)>], ratio: f64) -> Vec<Vec<bool>> {
    marked(scene, |a, b| {
        let (a, b) = (far_if_none(a.0), far_if_none(b.0));
        let jump = if a.is_infinite() && b.is_infinite() {
            0.0
        } else {
            (a - b).abs()
        };
        jump > ratio * a.min(b)
    })
}

/// Where the traced normals turn by more than `threshold` (|Δn|).
fn normal_creases(scene: &[Vec<(f64, DVec3)>], threshold: f64) -> Vec<Vec<bool>> {
    marked(scene, |a, b| (a.1 - b.1).length() > threshold)
}

fn far_if_none(depth: f64) -> f64 {
    if depth == 0.0 {
        f64::INFINITY
    } else {
        depth
    }
}

fn marked(scene: &[Vec<(f64, DVec3)>], differs: impl Fn((f64, DVec3), (f64, DVec3)) -> bool) -> Vec<Vec<bool>> {
    let (h, w) = (scene.len(), scene[0].len());
    let mut m = vec![vec![false; w]; h];
    for y in 0..h {
        for x in 0..w {
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                if nx < w && ny < h && differs(scene[y][x], scene[ny][nx]) {
                    m[y][x] = true;
                    m[ny][nx] = true;
                }
            }
        }
    }
    m
}

/// Whether `m` is set within one pixel (8-neighbourhood) of (x, y).
fn near(m: &[Vec<bool>], x: usize, y: usize) -> bool {
    let (h, w) = (m.len(), m[0].len());
    (y.saturating_sub(1)..(y + 2).min(h)).any(|yy| (x.saturating_sub(1)..(x + 2).min(w)).any(|xx| m[yy][xx]))
}

/// The pixels of `image` of the colour `ink` (within 1/255).
fn inked(image: &image::RgbaImage, ink: [u8; 3]) -> Vec<Vec<bool>> {
    (0..image.height())
        .map(|y| {
            (0..image.width())
                .map(|x| {
                    let p = image.get_pixel(x, y).0;
                    (0..3).all(|c| p[c].abs_diff(ink[c]) <= 1)
                })
                .collect()
        })
        .collect()
}

/// The largest channel difference of two images' pixel (x, y).
fn difference(a: &image::RgbaImage, b: &image::RgbaImage, x: u32, y: u32) -> u8 {
    let (p, q) = (a.get_pixel(x, y).0, b.get_pixel(x, y).0);
    (0..4).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0)
}

/// Written where a check fails: the styled image, the reference and the
/// traced discontinuities.
fn save_failure(name: &str, styled: &image::RgbaImage, reference: &image::RgbaImage) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("bevy_mod_npr_failures");
    std::fs::create_dir_all(&dir).expect("failure folder");
    styled.save(dir.join(format!("{name}.actual.png"))).expect("write");
    reference
        .save(dir.join(format!("{name}.reference.png")))
        .expect("write");
    let jumps = depth_jumps(&traced(), 0.04);
    let mut diff = image::RgbaImage::new(SIZE, SIZE);
    for (x, y, p) in diff.enumerate_pixels_mut() {
        let v = difference(styled, reference, x, y).saturating_mul(16);
        let j = if jumps[y as usize][x as usize] { 255 } else { 0 };
        *p = image::Rgba([v, j, 0, 255]);
    }
    diff.save(dir.join(format!("{name}.diff.png"))).expect("write");
    dir
}

/// The lines of `styled` (pixels of colour `ink`) lie on the traced
/// scene's discontinuities within 1 px and cover its silhouettes within
/// 1 px; every other pixel is the reference's within 2/255.
fn assert_inked_over(name: &str, styled: &image::RgbaImage, reference: &image::RgbaImage, ink: [u8; 3]) {
    let scene = traced();
    let lines = inked(styled, ink);
    let (w, h) = (SIZE as usize, SIZE as usize);
    let pixels = || (0..h).flat_map(|y| (0..w).map(move |x| (x, y)));
    // Silhouettes: a jump of a quarter of the nearer depth, far above the
    // style's 8 %.
    let silhouettes = depth_jumps(&scene, 0.25);
    let silhouette_count = pixels().filter(|&(x, y)| silhouettes[y][x]).count();
    assert!(
        silhouette_count > 300,
        "{name}: the scene has silhouettes ({silhouette_count} pixels)"
    );
    let missed: Vec<_> = pixels()
        .filter(|&(x, y)| silhouettes[y][x] && !near(&lines, x, y))
        .collect();
    // Every line pixel within 1 px of a jump or crease at half the style's
    // thresholds (a pixel just at a threshold counts either way).
    let support_d = depth_jumps(&scene, 0.04);
    let support_n = normal_creases(&scene, 0.3);
    let stray: Vec<_> = pixels()
        .filter(|&(x, y)| lines[y][x] && !near(&support_d, x, y) && !near(&support_n, x, y))
        .collect();
    // Between the lines, Bevy's PBR as the reference camera drew it.
    let changed: Vec<_> = pixels()
        .filter(|&(x, y)| !lines[y][x] && difference(styled, reference, x as u32, y as u32) > 2)
        .collect();
    let line_count = pixels().filter(|&(x, y)| lines[y][x]).count();
    if !missed.is_empty() || !stray.is_empty() || !changed.is_empty() || line_count < silhouette_count / 3 {
        let dir = save_failure(name, styled, reference);
        panic!(
            "{name}: {} of {silhouette_count} silhouette pixels have no line within 1 px (e.g. {:?}); {} of \
             {line_count} line pixels lie on no discontinuity (e.g. {:?}); {} other pixels differ from Bevy's \
             own image by more than 2/255 (e.g. {:?}); images in {}",
            missed.len(),
            &missed[..missed.len().min(6)],
            stray.len(),
            &stray[..stray.len().min(6)],
            changed.len(),
            &changed[..changed.len().min(6)],
            dir.display()
        );
    }
}

/// The PBR shading shows: the reference has many colours on the spheres
/// and plane (not a flat fill), few of them the ink.
fn assert_shaded(reference: &image::RgbaImage) {
    let colours: std::collections::BTreeSet<[u8; 4]> = reference.pixels().map(|p| p.0).collect();
    assert!(
        colours.len() > 200,
        "Bevy's image is nearly flat: {} colours",
        colours.len()
    );
}

/// Bevy's pipelines compiled and `done` true, then one more frame (the
/// image of the frame just recorded is complete).
fn settle(app: &mut App, what: &str, mut done: impl FnMut(&mut App) -> bool) {
    update_until(app, what, PATIENCE, |app| {
        let ready = app
            .sub_app(RenderApp)
            .world()
            .resource::<PipelineCache>()
            .waiting_pipelines()
            .next()
            .is_none();
        ready && done(app)
    });
    for _ in 0..2 {
        app.update();
    }
}

fn codes_logged(app: &App, code: &str) -> usize {
    logged_codes(app).iter().filter(|c| **c == code).count()
}

/// The last message logged with `code`, the camera's id replaced.
fn last_message(app: &App, code: &str, camera: Entity) -> String {
    let messages = app
        .sub_app(RenderApp)
        .world()
        .resource::<bevy_mod_npr::NprRuntimes>()
        .logged_messages();
    messages
        .iter()
        .rev()
        .find(|m| m.contains(&format!("[{code}]")))
        .unwrap_or_else(|| panic!("no {code} logged: {messages:?}"))
        .replace(&format!("camera {camera}"), "camera <camera>")
}

/// Whether the styled camera's runtime drew (built its GPU resources)
/// with the style `name`.
fn drawn_with(app: &mut App, camera: Entity, name: &str) -> bool {
    runtime_of(app, camera).is_some_and(|(n, builds)| n == name && builds > 0)
}

#[test]
fn ink_over_bevy_pbr_lies_on_its_silhouettes_and_follows_prepasses_and_reloads() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("post_ink_over");
    let style_file = dir.join("ink_over.npr");
    let text = std::fs::read_to_string(repo().join("examples/post/ink_over.npr")).expect("read the example");
    std::fs::write(&style_file, &text).expect("copy the style");

    let mut app = app(&dir);
    spawn_scene(&mut app);
    let plain_image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let styled_image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    camera(&mut app, &plain_image, 0);
    let styled = camera(&mut app, &styled_image, 1);
    let style = app.world().resource::<AssetServer>().load("ink_over.npr");
    app.world_mut().entity_mut(styled).insert(bevy_mod_npr::NprStyle(style));
    settle(&mut app, "the ink style over Bevy's frame", |app| {
        drawn_with(app, styled, "Ink over")
    });
    let reference = read_image(&app, &plain_image);
    assert_shaded(&reference);
    let inked_frame = read_image(&app, &styled_image);
    assert_inked_over("post_ink_over", &inked_frame, &reference, INK);
    assert!(logged_codes(&app).is_empty(), "{:?}", logged_codes(&app));

    // The normal prepass removed: E0608 naming the input and the
    // component; the camera shows what Bevy drew.
    app.world_mut().entity_mut(styled).remove::<NormalPrepass>();
    settle(&mut app, "E0608 for the removed NormalPrepass", |app| {
        codes_logged(app, "E0608") == 1
    });
    let message = last_message(&app, "E0608", styled);
    assert!(
        message.contains("`normal_in`") && message.contains("NormalPrepass"),
        "{message}"
    );
    insta::assert_snapshot!("E0608_normal_prepass_removed", message);
    let plain = read_image(&app, &styled_image);
    let reference = read_image(&app, &plain_image);
    let worst = (0..SIZE)
        .flat_map(|y| (0..SIZE).map(move |x| (x, y)))
        .map(|(x, y)| difference(&plain, &reference, x, y))
        .max();
    assert!(
        worst <= Some(2),
        "without its normals the camera shows what Bevy drew: a pixel differs by {worst:?}/255"
    );
    // Logged once, however many frames it lasts.
    for _ in 0..3 {
        app.update();
    }
    assert_eq!(codes_logged(&app, "E0608"), 1, "{:?}", logged_codes(&app));

    // Back: the lines return, no restart.
    app.world_mut().entity_mut(styled).insert(NormalPrepass);
    settle(&mut app, "the lines back with NormalPrepass", |app| {
        let image = read_image(app, &styled_image);
        inked(&image, INK).iter().flatten().any(|i| *i)
    });
    assert_inked_over(
        "post_prepass_back",
        &read_image(&app, &styled_image),
        &read_image(&app, &plain_image),
        INK,
    );

    // MSAA on: the prepass textures are multisampled, E0609.
    app.world_mut().entity_mut(styled).insert(Msaa::Sample4);
    settle(&mut app, "E0609 for MSAA", |app| codes_logged(app, "E0609") == 1);
    insta::assert_snapshot!("E0609_msaa", last_message(&app, "E0609", styled));
    app.world_mut().entity_mut(styled).insert(Msaa::Off);
    settle(&mut app, "the lines back without MSAA", |app| {
        let image = read_image(app, &styled_image);
        inked(&image, INK).iter().flatten().any(|i| *i)
    });

    // A reload to a style that also reads motion vectors: E0608 naming
    // MotionVectorPrepass, until the camera has it.
    let with_motion = text
        .replace("style \"Ink over\"", "style \"Ink over motion\"")
        .replace(
            "texture normal_in = input(normal, view)",
            "texture normal_in = input(normal, view)\ntexture motion_in = input(motion)",
        )
        .replace(
            "let edge = if jump > depth_ratio * near",
            "let moved = length(sample(motion_in, screen_uv).rg)\n  \
             let edge = if moved > 1000.0 || jump > depth_ratio * near",
        );
    assert_ne!(with_motion.matches("motion_in").count(), 0);
    std::fs::write(&style_file, &with_motion).expect("save the edit");
    settle(&mut app, "E0608 for the missing MotionVectorPrepass", |app| {
        codes_logged(app, "E0608") == 2
    });
    let message = last_message(&app, "E0608", styled);
    assert!(
        message.contains("`motion_in`") && message.contains("MotionVectorPrepass"),
        "{message}"
    );
    app.world_mut().entity_mut(styled).insert(MotionVectorPrepass);
    settle(&mut app, "the style reading motion to draw", |app| {
        drawn_with(app, styled, "Ink over motion")
    });
    // A still scene: no motion, the same lines.
    assert_inked_over(
        "post_with_motion",
        &read_image(&app, &styled_image),
        &read_image(&app, &plain_image),
        INK,
    );

    // A reload to red ink: the same lines, red.
    let red = text
        .replace("style \"Ink over\"", "style \"Ink over red\"")
        .replace("param ink: color = #141414", "param ink: color = #c01010");
    assert_ne!(red, text);
    std::fs::write(&style_file, &red).expect("save the edit");
    settle(&mut app, "the red style to draw", |app| {
        drawn_with(app, styled, "Ink over red")
    });
    let red_frame = read_image(&app, &styled_image);
    assert_inked_over("post_red", &red_frame, &read_image(&app, &plain_image), RED_INK);
    assert_eq!(
        inked(&red_frame, RED_INK),
        inked(&inked_frame, INK),
        "the reloaded style draws the same lines"
    );
    assert_eq!(
        logged_codes(&app),
        ["E0608", "E0609", "E0608"],
        "nothing else was logged"
    );
}
