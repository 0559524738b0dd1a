//! bevy_mod_npr in a real Bevy app, headless on lavapipe: a camera with
//! `NprStyle` renders into an image, which is read back and compared with
//! `npr render` of the same style on the same scene (npr's scene file,
//! spawned as Bevy entities); a style edited on disk while the app runs is
//! picked up, and a broken save keeps the last good style, as is a file the
//! style `use`s or an image it reads; a parameter removed from `NprParams`
//! returns to the style's value; despawned meshes leave the runtime; bad
//! input is a logged code, never a panic.

mod common;
// Tests of other features in the same binary (a Bevy test binary is slow
// to link: one more per feature would cost CI minutes).
#[path = "headless/post.rs"]
mod post;
#[path = "headless/skinned.rs"]
mod skinned;

use bevy::asset::{AssetServer, LoadState};
use bevy::render::render_resource::TextureFormat;
use common::*;
use std::time::Duration;

/// Long enough for lavapipe to compile the pipelines on a busy machine.
const PATIENCE: Duration = Duration::from_secs(120);

/// Copies `example` (a style of examples/) into the test's asset folder.
fn copy_style(dir: &std::path::Path, example: &str) -> std::path::PathBuf {
    let to = dir.join(example);
    std::fs::copy(repo().join("examples").join(example), &to).expect("copy the style");
    to
}

/// Updates until the camera has drawn a frame with the style `name` and
/// Bevy's own pipelines are compiled: Bevy compiles them in the background
/// and skips a node whose pipeline is not ready, so until its upscaling
/// pipeline is, nothing (not even its clear) reaches the camera's image,
/// however long npr's runtime has been drawing (seen: more than 9 frames
/// on a busy machine).
fn wait_for_style(app: &mut bevy::app::App, camera: bevy::prelude::Entity, name: &str) {
    update_until(app, &format!("the camera to draw with \"{name}\""), PATIENCE, |app| {
        let pipelines_ready = app
            .sub_app(bevy::render::RenderApp)
            .world()
            .resource::<bevy::render::render_resource::PipelineCache>()
            .waiting_pipelines()
            .next()
            .is_none();
        pipelines_ready && runtime_of(app, camera).is_some_and(|(n, builds)| n == name && builds > 0)
    });
    // One more frame: the image of the frame just recorded is complete.
    app.update();
}

/// An app in `dir` whose camera draws the style file `file` (named
/// `name`) on `scene` into an sRGB image, after its first frame with it.
struct Drawing {
    app: bevy::app::App,
    image: bevy::asset::Handle<bevy::image::Image>,
    style: bevy::asset::Handle<bevy_mod_npr::NprStyleAsset>,
    camera: bevy::prelude::Entity,
}

fn draw(dir: &std::path::Path, file: &str, name: &str, scene: &npr_runner::scene::Scene) -> Drawing {
    let mut app = app(dir);
    let image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let style = app.world().resource::<AssetServer>().load(file.to_string());
    let camera = spawn_scene(&mut app, scene, style.clone(), &image);
    wait_for_style(&mut app, camera, name);
    Drawing {
        app,
        image,
        style,
        camera,
    }
}

/// The loaded style asset `handle` names.
fn style_asset(
    app: &bevy::app::App,
    handle: &bevy::asset::Handle<bevy_mod_npr::NprStyleAsset>,
) -> Option<bevy_mod_npr::NprStyleAsset> {
    app.world()
        .resource::<bevy::asset::Assets<bevy_mod_npr::NprStyleAsset>>()
        .get(handle)
        .cloned()
}

/// After an edit on disk of a file `handle`'s style reads: updates until
/// the asset's revision is past `revision`, then three frames (the render
/// world draws a new revision from the next frame on); the camera's image.
fn image_after_reload(
    app: &mut bevy::app::App,
    handle: &bevy::asset::Handle<bevy_mod_npr::NprStyleAsset>,
    revision: u64,
    image: &bevy::asset::Handle<bevy::image::Image>,
    what: &str,
) -> image::RgbaImage {
    update_until(app, what, PATIENCE, |app| {
        style_asset(app, handle).is_some_and(|s| s.revision() != revision)
    });
    for _ in 0..3 {
        app.update();
    }
    read_image(app, image)
}

/// A shipped program's style: `npr compile -o toon.nprb` (here the same
/// compile and `StyleProgram::to_bundle` that command runs), loaded by the
/// plugin's bundle loader with no `.npr` file in the asset folder, draws
/// what `npr render` draws of the style.
#[test]
fn a_precompiled_bundle_draws_what_npr_render_draws_of_its_style() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("toon_bundle");
    let source = repo().join("examples/toon.npr");
    let scene = load_scene("spot.toml");
    let expected = npr_render(&source, &scene);
    let mut sources = npr_diag::SourceMap::new();
    let options = npr_compiler::CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    let program = npr_compiler::compile_file(&source, &mut sources, &options)
        .unwrap_or_else(|e| panic!("{e:?}"))
        .program();
    let bytes = program.to_bundle(|p| std::fs::read(p)).expect("bundle");
    std::fs::write(dir.join("toon.nprb"), bytes).expect("write the bundle");
    assert!(!dir.join("toon.npr").exists(), "the asset folder holds only the bundle");

    let Drawing { app, image, style, .. } = draw(&dir, "toon.nprb", "Toon", &scene);
    assert_close("toon_bundle", &read_image(&app, &image), &expected);
    let asset = style_asset(&app, &style).expect("the bundle's asset");
    assert_eq!(
        asset.program().shaders,
        program.shaders,
        "the bundle's WGSL is the compiler's"
    );
}

#[test]
fn toon_on_spot_equals_npr_render_and_follows_its_params_set_and_removed() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("toon_spot");
    let style = copy_style(&dir, "toon.npr");
    let scene = load_scene("spot.toml");
    let expected = npr_render(&style, &scene);

    let Drawing {
        mut app,
        image,
        style: _,
        camera,
    } = draw(&dir, "toon.npr", "Toon", &scene);
    assert_close("toon_spot", &read_image(&app, &image), &expected);

    // Params changed at run time through the reflected component draw what
    // `npr render` draws of the style with those defaults.
    app.world_mut().entity_mut(camera).insert(
        bevy_mod_npr::NprParams::default()
            .with("bands", 2)
            .with("base", "#3a7ae0"),
    );
    for _ in 0..2 {
        app.update();
    }
    let text = std::fs::read_to_string(&style).expect("read the style");
    let set = dir.join("toon_set.npr");
    std::fs::write(
        &set,
        text.replace("param bands: int = 3", "param bands: int = 2")
            .replace("param base: color = #e07a3a", "param base: color = #3a7ae0"),
    )
    .expect("write the style with other defaults");
    assert_close("toon_spot_params", &read_image(&app, &image), &npr_render(&set, &scene));

    // Keys removed from NprParams return to the style's values: `base` to
    // its constant, `rim` (set here to 0.9) to its animation (0.1 at 0 s),
    // one at a time (removing `rim` rebuilds the runtime, which would reset
    // `base` too).
    let params = |app: &mut bevy::app::App, p: bevy_mod_npr::NprParams| {
        app.world_mut().entity_mut(camera).insert(p);
        for _ in 0..2 {
            app.update();
        }
    };
    let bands = bevy_mod_npr::NprParams::default().with("bands", 2);
    params(&mut app, bands.clone().with("base", "#3a7ae0").with("rim", 0.9));
    let blue = read_image(&app, &image);
    let with_bands = text.replace("param bands: int = 3", "param bands: int = 2");
    let bright_rim = dir.join("toon_bright_rim.npr");
    let rim = "param rim: float = 0.3 in 0..1 animate { 0s: 0.1, 4s: 0.5 }";
    assert!(text.contains(rim), "toon.npr's rim is animated");
    std::fs::write(&bright_rim, with_bands.replace(rim, "param rim: float = 0.9 in 0..1")).expect("write");
    // `base` back to its constant (set again from the style's value) ...
    params(&mut app, bands.clone().with("rim", 0.9));
    let base_removed = read_image(&app, &image);
    assert!(blue != base_removed, "removing `base` changes the image");
    assert_close(
        "toon_spot_base_removed",
        &base_removed,
        &npr_render(&bright_rim, &scene),
    );
    // ... and `rim` back to its animation (0.1 at 0 s: the runtime is rebuilt).
    params(&mut app, bands);
    let only_bands = dir.join("toon_bands.npr");
    std::fs::write(&only_bands, &with_bands).expect("write");
    let rim_removed = read_image(&app, &image);
    assert!(base_removed != rim_removed, "removing `rim` changes the image");
    assert_close("toon_spot_rim_removed", &rim_removed, &npr_render(&only_bands, &scene));
    assert!(logged_codes(&app).is_empty(), "{:?}", logged_codes(&app));
}

#[test]
fn an_edited_style_is_picked_up_and_a_broken_save_keeps_it() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("hot_reload");
    let style = copy_style(&dir, "toon.npr");
    let scene = load_scene("spot.toml");
    let Drawing {
        mut app,
        image,
        style: handle,
        camera,
    } = draw(&dir, "toon.npr", "Toon", &scene);
    let before = read_image(&app, &image);

    // A new colour and a new name, saved while the app runs.
    let text = std::fs::read_to_string(&style).expect("read the style");
    let edited = text
        .replace("style \"Toon\"", "style \"Toon edited\"")
        .replace("param base: color = #e07a3a", "param base: color = #3a7ae0");
    assert_ne!(text, edited, "the edit must change the style");
    std::fs::write(&style, &edited).expect("save the edit");
    wait_for_style(&mut app, camera, "Toon edited");
    let after = read_image(&app, &image);
    assert_ne!(before, after, "the edited style draws another image");
    assert_close("hot_reload_edited", &after, &npr_render(&style, &scene));

    // A save that does not compile: the load fails, the camera keeps the edit.
    std::fs::write(&style, edited.replace("output shade.color", "output shade.colour +")).expect("save");
    update_until(&mut app, "the broken save to fail to load", PATIENCE, |app| {
        matches!(
            app.world().resource::<AssetServer>().load_state(&handle),
            LoadState::Failed(_)
        )
    });
    for _ in 0..3 {
        app.update();
    }
    assert_eq!(
        runtime_of(&mut app, camera).map(|r| r.0),
        Some("Toon edited".to_string())
    );
    assert_close("hot_reload_broken", &read_image(&app, &image), &after);
}

/// A style with a tagged pass and an object param, for the bad-input cases.
const TAGGED: &str = "style \"Tagged\"\n\
object param tint: color = #ffffff\n\
pass shade: render(hero) {\n  out color: rgba8unorm = vec4(tint.rgb * lambert(normal, light.dir), 1.0)\n  clear: #102030\n}\n\
output shade.color\n";

#[test]
fn bad_input_is_a_logged_code_and_the_app_keeps_running() {
    use bevy::prelude::*;
    use bevy_mod_npr::{NprObject, NprStyle};
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("bad_input");
    std::fs::write(dir.join("tagged.npr"), TAGGED).expect("write style");
    std::fs::write(
        dir.join("broken.npr"),
        "style \"Broken\"\npass p: render(scene) {\n  out c: rgba8unorm = \n}\n",
    )
    .expect("write style");
    let scene = load_scene("spot.toml");
    let mut app = app(&dir);

    // A style that does not compile: the load fails (logged by the
    // loader with its code and place), the camera stays as Bevy draws it.
    let broken_image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let broken = app.world().resource::<AssetServer>().load("broken.npr");
    let broken_camera = spawn_scene(&mut app, &scene, broken.clone(), &broken_image);
    // The good style on a second camera, over the same entities: a tag
    // no entity has (the scene's object is tagged "caster"), then bad params.
    let image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let tagged = app.world().resource::<AssetServer>().load("tagged.npr");
    let camera = app
        .world_mut()
        .spawn((
            Camera3d::default(),
            bevy::camera::RenderTarget::Image(image.clone().into()),
            Msaa::Off,
            Transform::from_xyz(2.3, 0.9, -2.5).looking_at(Vec3::ZERO, Vec3::Y),
            NprStyle(tagged),
        ))
        .id();
    wait_for_style(&mut app, camera, "Tagged");
    update_until(&mut app, "the broken style to fail", PATIENCE, |app| {
        matches!(
            app.world().resource::<AssetServer>().load_state(&broken),
            LoadState::Failed(_)
        )
    });
    app.update();
    assert_eq!(
        runtime_of(&mut app, broken_camera),
        None,
        "no runtime for a style that never compiled"
    );
    assert!(
        logged_codes(&app).contains(&"W0402"),
        "the absent tag: {:?}",
        logged_codes(&app)
    );
    // The tagged pass draws nothing: the style's clear colour, everywhere.
    let cleared = read_image(&app, &image);
    assert!(
        cleared.pixels().all(|p| p.0 == cleared.get_pixel(0, 0).0),
        "nothing tagged `hero` is drawn"
    );

    // An entity tagged `hero` with a tint of the wrong size and a param the style lacks.
    let mesh = app
        .world_mut()
        .resource_mut::<Assets<Mesh>>()
        .add(Sphere::new(0.6).mesh().uv(32, 16));
    app.world_mut().spawn((
        Mesh3d(mesh),
        Transform::default(),
        NprObject::tagged("hero")
            .with("tint", Vec2::new(1.0, 0.0))
            .with("tnit", Color::srgb(1.0, 0.0, 0.0)),
    ));
    update_until(&mut app, "the hero to be drawn", PATIENCE, |app| {
        let image = read_image(app, &image);
        image.pixels().any(|p| p.0 != cleared.get_pixel(0, 0).0)
    });
    let codes = logged_codes(&app);
    assert!(codes.contains(&"E0405"), "the tint of the wrong size: {codes:?}");
    assert!(codes.contains(&"W0401"), "the param the style lacks: {codes:?}");
    // The hero is drawn with the default tint (white): grey, not red.
    let drawn = read_image(&app, &image);
    let centre = drawn.get_pixel(SIZE / 2, SIZE / 2).0;
    assert!(
        centre[0] > 20 && centre[0].abs_diff(centre[1]) <= 2,
        "a grey sphere: {centre:?}"
    );

    // A parameter value the style refuses: E0101 (no such name), still running.
    app.world_mut()
        .entity_mut(camera)
        .insert(bevy_mod_npr::NprParams::default().with("nosuch", 1));
    for _ in 0..3 {
        app.update();
    }
    assert!(logged_codes(&app).contains(&"E0101"), "{:?}", logged_codes(&app));
    assert_eq!(runtime_of(&mut app, camera).map(|r| r.0), Some("Tagged".to_string()));
}

#[test]
fn two_cameras_one_hdr_draw_lsa_contours_and_toon_on_spheres() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("two_cameras");
    let lsa = copy_style(&dir, "lsa_contours.npr");
    let toon = copy_style(&dir, "toon.npr");
    let scene = load_scene("spheres.toml");
    let mut app = app(&dir);
    let lsa_image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let toon_image = target_image(&mut app, TextureFormat::Rgba8UnormSrgb);
    let lsa_handle = app.world().resource::<AssetServer>().load("lsa_contours.npr");
    let toon_handle = app.world().resource::<AssetServer>().load("toon.npr");
    let lsa_camera = spawn_scene(&mut app, &scene, lsa_handle, &lsa_image);
    // HDR: Bevy's view target is Rgba16Float, encoded by its upscaling pass.
    app.world_mut().entity_mut(lsa_camera).insert(bevy::camera::Hdr);
    let toon_camera = spawn_camera(&mut app, &scene, toon_handle, &toon_image);
    wait_for_style(&mut app, lsa_camera, "LSA contours");
    wait_for_style(&mut app, toon_camera, "Toon");
    // The two view targets: linear light in a float texture, and in an sRGB one.
    for (camera, format) in [
        (lsa_camera, TextureFormat::Rgba16Float),
        (toon_camera, TextureFormat::Rgba8UnormSrgb),
    ] {
        let render = render_entity(&mut app, camera);
        let target = app
            .sub_app(bevy::render::RenderApp)
            .world()
            .get::<bevy::render::view::ViewTarget>(render)
            .map(|t| t.main_texture_format());
        assert_eq!(target, Some(format));
    }
    assert_close(
        "lsa_contours_spheres_hdr",
        &read_image(&app, &lsa_image),
        &npr_render(&lsa, &scene),
    );
    assert_close(
        "toon_spheres",
        &read_image(&app, &toon_image),
        &npr_render(&toon, &scene),
    );
}

#[test]
fn a_resized_target_is_drawn_at_its_new_size() {
    use bevy::prelude::*;
    use bevy::render::render_resource::Extent3d;
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("resize");
    let style = copy_style(&dir, "toon.npr");
    let scene = load_scene("spot.toml");
    let Drawing {
        mut app,
        image,
        style: _,
        camera,
    } = draw(&dir, "toon.npr", "Toon", &scene);
    let builds = runtime_of(&mut app, camera).map(|r| r.1);

    // Taller than wide: the aspect changes too.
    let size = (96, 160);
    app.world_mut()
        .resource_mut::<Assets<Image>>()
        .get_mut(&image)
        .expect("the target image")
        .resize(Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        });
    for _ in 0..3 {
        app.update();
    }
    assert_eq!(
        runtime_of(&mut app, camera).map(|r| r.1),
        builds,
        "a new size keeps the scene's resources"
    );
    assert_close(
        "resized",
        &read_image_sized(&app, &image, size),
        &npr_render_sized(&style, &scene, size),
    );
}

#[test]
fn an_edited_file_that_the_style_uses_is_picked_up() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("used_file");
    // Toon with its `base` colour declared in a file it `use`s.
    let toon = std::fs::read_to_string(repo().join("examples/toon.npr")).expect("read toon.npr");
    let main = toon
        .replace("param base: color = #e07a3a\n", "")
        .replace("style \"Toon\"\n", "style \"Toon\"\nuse \"lib/palette.npr\"\n");
    assert!(main.contains("use \"lib/palette.npr\"") && !main.contains("param base"));
    let style = dir.join("main.npr");
    std::fs::write(&style, main).expect("write the style");
    std::fs::create_dir_all(dir.join("lib")).expect("lib folder");
    let palette = dir.join("lib/palette.npr");
    std::fs::write(&palette, "style \"Palette\"\nparam base: color = #e07a3a\n").expect("write the palette");

    let scene = load_scene("spot.toml");
    let Drawing {
        mut app,
        image,
        style: handle,
        camera: _,
    } = draw(&dir, "main.npr", "Toon", &scene);
    let loaded = style_asset(&app, &handle).expect("the style is loaded");
    assert_eq!(
        loaded.files_read(),
        [palette.canonicalize().expect("the palette's path")],
        "the style read its palette"
    );
    let before = read_image(&app, &image);
    assert_close("used_file_before", &before, &npr_render(&style, &scene));

    std::fs::write(&palette, "style \"Palette\"\nparam base: color = #3a7ae0\n").expect("edit the palette");
    let after = image_after_reload(
        &mut app,
        &handle,
        loaded.revision(),
        &image,
        "the style to reload after its palette changed",
    );
    assert!(before != after, "the edited palette draws another image");
    assert_close("used_file_after", &after, &npr_render(&style, &scene));
}

#[test]
fn despawned_meshes_leave_the_runtime() {
    use bevy::prelude::*;
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("mesh_churn");
    let style = copy_style(&dir, "toon.npr");
    let scene = load_scene("spot.toml");
    let Drawing {
        mut app,
        image,
        style: _,
        camera,
    } = draw(&dir, "toon.npr", "Toon", &scene);
    let render = render_entity(&mut app, camera);
    let mesh_count = |app: &App| {
        app.sub_app(bevy::render::RenderApp)
            .world()
            .resource::<bevy_mod_npr::NprRuntimes>()
            .mesh_count(render)
            .expect("the camera has a runtime")
    };
    let objects = scene.objects.len();
    assert_eq!(mesh_count(&app), objects, "one mesh per object of the scene");

    let despawn_meshes = |app: &mut App| {
        let world = app.world_mut();
        let entities: Vec<Entity> = world.query_filtered::<Entity, With<Mesh3d>>().iter(world).collect();
        for entity in entities {
            world.despawn(entity);
        }
    };
    // Despawned and spawned again, with new mesh assets each time: the
    // old ones leave the runtime.
    for round in 0..5 {
        despawn_meshes(&mut app);
        bevy_mod_npr::spawn_npr_scene(app.world_mut(), &scene);
        for _ in 0..3 {
            app.update();
        }
        assert_eq!(
            mesh_count(&app),
            objects,
            "round {round}: the runtime holds the drawn meshes only"
        );
    }
    assert_close("mesh_churn", &read_image(&app, &image), &npr_render(&style, &scene));

    // Despawned while the app keeps the mesh assets alive: no entity draws
    // them, so they leave the runtime all the same.
    let kept: Vec<Handle<Mesh>> = {
        let world = app.world_mut();
        world.query::<&Mesh3d>().iter(world).map(|m| m.0.clone()).collect()
    };
    despawn_meshes(&mut app);
    for _ in 0..3 {
        app.update();
    }
    assert_eq!(kept.len(), objects);
    assert_eq!(mesh_count(&app), 0, "no entity draws a mesh any more");
}

/// Meshes kept only in the render world (a common memory setting) are
/// drawn, survive a despawn and a respawn with the same handles, and may
/// be added frames before an entity draws them (Bevy has extracted their
/// data by then); nothing panics (issue 48: this panicked the app).
#[test]
fn render_world_only_meshes_are_drawn_despawned_and_respawned() {
    use bevy::asset::RenderAssetUsages;
    use bevy::prelude::*;
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("render_world_meshes");
    let style = copy_style(&dir, "toon.npr");
    let scene = load_scene("spot.toml");
    let Drawing {
        mut app,
        image,
        style: _,
        camera,
    } = draw(&dir, "toon.npr", "Toon", &scene);
    let render = render_entity(&mut app, camera);
    let mesh_count = |app: &App| {
        app.sub_app(bevy::render::RenderApp)
            .world()
            .resource::<bevy_mod_npr::NprRuntimes>()
            .mesh_count(render)
            .expect("the camera has a runtime")
    };
    let despawn_meshes = |app: &mut App| {
        let world = app.world_mut();
        let entities: Vec<Entity> = world.query_filtered::<Entity, With<Mesh3d>>().iter(world).collect();
        for entity in entities {
            world.despawn(entity);
        }
    };
    let add_meshes = |app: &mut App| -> Vec<Handle<Mesh>> {
        let mut assets = app.world_mut().resource_mut::<Assets<Mesh>>();
        scene
            .objects
            .iter()
            .map(|object| {
                let mut mesh = bevy_mod_npr::bevy_mesh(&object.mesh);
                mesh.asset_usage = RenderAssetUsages::RENDER_WORLD;
                assets.add(mesh)
            })
            .collect()
    };
    let spawn = |app: &mut App, handles: &[Handle<Mesh>]| {
        for (object, handle) in scene.objects.iter().zip(handles) {
            app.world_mut().spawn((
                Mesh3d(handle.clone()),
                Transform::from_matrix(Mat4::from_cols_array(&object.model.to_cols_array())),
                bevy_mod_npr::NprObject {
                    tags: object.tags.clone(),
                    params: object.params.clone(),
                    casts_shadows: object.casts_shadows,
                },
            ));
        }
    };
    let settle = |app: &mut App| {
        for _ in 0..3 {
            app.update();
        }
    };
    let expected = npr_render(&style, &scene);
    let objects = scene.objects.len();

    // Added and spawned in one frame.
    despawn_meshes(&mut app);
    let handles = add_meshes(&mut app);
    spawn(&mut app, &handles);
    settle(&mut app);
    assert_eq!(mesh_count(&app), objects, "every render-world-only mesh is drawn");
    assert_close("render_world_meshes", &read_image(&app, &image), &expected);
    let data_gone = {
        let assets = app.world().resource::<Assets<Mesh>>();
        handles.iter().all(|h| {
            assets
                .get(h)
                .is_some_and(|m| m.try_attribute_option(Mesh::ATTRIBUTE_POSITION).is_err())
        })
    };
    assert!(
        data_gone,
        "Bevy has taken the meshes' data from the main world: the test tests that case"
    );

    // Despawned: they leave the runtime; spawned again with the same
    // handles, whose data is gone from the main world: drawn again.
    despawn_meshes(&mut app);
    settle(&mut app);
    assert_eq!(mesh_count(&app), 0, "no entity draws a mesh");
    spawn(&mut app, &handles);
    settle(&mut app);
    assert_eq!(mesh_count(&app), objects, "the respawned meshes are drawn");
    assert_close("render_world_meshes_respawned", &read_image(&app, &image), &expected);

    // Added, extracted by Bevy over several frames, then drawn.
    despawn_meshes(&mut app);
    let early = add_meshes(&mut app);
    settle(&mut app);
    spawn(&mut app, &early);
    settle(&mut app);
    assert_eq!(
        mesh_count(&app),
        objects,
        "meshes added before their entities are drawn"
    );
    assert_close("render_world_meshes_added_early", &read_image(&app, &image), &expected);
    assert!(
        !logged_codes(&app).contains(&"E0402"),
        "no mesh was refused: {:?}",
        logged_codes(&app)
    );
}

/// A mesh whose data Bevy has taken is refused with a reason, not a panic.
#[test]
fn a_mesh_without_its_data_is_refused_with_a_reason() {
    use bevy::asset::RenderAssetUsages;
    let scene = load_scene("spot.toml");
    let mut mesh = bevy_mod_npr::bevy_mesh(&scene.objects[0].mesh);
    mesh.asset_usage = RenderAssetUsages::RENDER_WORLD;
    let _gpu_data = mesh.take_gpu_data().expect("the data is there to take");
    let why = bevy_mod_npr::npr_mesh(&mesh, "cow").expect_err("no data to read");
    assert!(why.contains("extracted to the render world"), "{why}");
}

#[test]
fn an_edited_image_that_the_style_reads_is_picked_up() {
    let _one = ONE_APP.lock().unwrap_or_else(|e| e.into_inner());
    let dir = asset_dir("image_file");
    let paper = dir.join("paper.png");
    let write_paper = |rgb: [u8; 3]| {
        image::RgbImage::from_pixel(4, 4, image::Rgb(rgb))
            .save(&paper)
            .expect("write the image");
    };
    write_paper([200, 60, 40]);
    let style = dir.join("textured.npr");
    std::fs::write(
        &style,
        "style \"Textured\"\ntexture paper = image(\"paper.png\", srgb)\n\
         pass shade: render(scene) {\n  out color: rgba8unorm = sample(paper, uv) * half_lambert(normal, light.dir)\n  clear: #202020\n}\n\
         output shade.color\n",
    )
    .expect("write the style");

    let scene = load_scene("spot.toml");
    let Drawing {
        mut app,
        image,
        style: handle,
        camera: _,
    } = draw(&dir, "textured.npr", "Textured", &scene);
    let loaded = style_asset(&app, &handle).expect("the style is loaded");
    assert_eq!(loaded.files_read(), [paper.canonicalize().expect("the image's path")]);
    let before = read_image(&app, &image);
    assert_close("image_file_before", &before, &npr_render(&style, &scene));

    write_paper([40, 120, 220]);
    let after = image_after_reload(
        &mut app,
        &handle,
        loaded.revision(),
        &image,
        "the style to reload after its image changed",
    );
    assert!(before != after, "the edited image draws another image");
    assert_close("image_file_after", &after, &npr_render(&style, &scene));
}
