//! npr styles in Bevy: a `.npr` file is an asset (compiled by npr's
//! compiler, reloaded when the file changes), and a camera with
//! [`NprStyle`] is drawn by that style's passes, run by npr's runner inside
//! Bevy's renderer, on Bevy's own device, into the camera's image. A style
//! that declares inputs (`input(color)`, `input(depth)`, ...) post-processes
//! the frame Bevy drew instead: the camera's image and its prepass textures
//! are the inputs (`post.rs`, decision 0054).
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_mod_npr::{NprObject, NprPlugin, NprStyle};
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, NprPlugin))
//!     .add_systems(Startup, |mut commands: Commands, assets: Res<AssetServer>, mut meshes: ResMut<Assets<Mesh>>| {
//!         commands.spawn((
//!             Camera3d::default(),
//!             Transform::from_xyz(0.0, 1.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
//!             NprStyle(assets.load("toon.npr")),
//!         ));
//!         commands.spawn((
//!             Mesh3d(meshes.add(Sphere::new(1.0))),
//!             NprObject::tagged("caster").with("tint", Color::srgb(1.0, 0.6, 0.4)),
//!         ));
//!     })
//!     .run();
//! ```
//!
//! - `asset.rs`: [`NprStyleAsset`], and [`NprBundleLoader`] for precompiled
//!   `.nprb` bundles;
//! - `source_loader.rs`: [`NprStyleLoader`], which compiles `.npr` files
//!   (the `compiler` feature);
//! - `components.rs`: [`NprStyle`], [`NprParams`], [`NprObject`], [`NprLight`];
//! - `meshes.rs`: Bevy meshes as npr's, converted once per asset;
//! - `skins.rs`: `SkinnedMesh` entities as npr's posed instances;
//! - `extract.rs`: what the render world copies each frame;
//! - `render.rs`: the `Core3d` system that drives a runtime per camera;
//! - `post.rs`: a style over Bevy's own frame: the camera's image and
//!   prepass textures as the style's inputs;
//! - `report.rs`: diagnostics in Bevy's log, once per camera;
//! - `scene.rs`: npr's TOML scenes as Bevy entities.
//!
//! # Features: developing and shipping
//!
//! - `compiler` (default): `.npr` assets, compiled by npr's compiler when
//!   they load. Off, the plugin links only npr's runtime (no compiler,
//!   stdlib, parser or pest) and loads `.nprb` bundles, which
//!   `npr compile STYLE.npr -o STYLE.nprb` writes (the WGSL, the manifest
//!   and the style's image files in one file); `.nprb` loads in both.
//! - `file_watcher` (default): hot reload, Bevy's feature of that name: the
//!   asset folder is watched unless `AssetPlugin`'s
//!   `watch_for_changes_override` is `Some(false)`. The files a style
//!   `use`s and the images it reads are its dependencies: editing one
//!   reloads the style too (inside the asset folder). Off, the plugin
//!   builds for `wasm32-unknown-unknown`.
//!
//! A shipped game: `bevy_mod_npr = { version = "0.1", default-features =
//! false }` and `NprStyle(assets.load("toon.nprb"))`.
//!
//! The crate's feature `bench-standard-material` only serves the
//! `frame_cost` example (Bevy's `bevy_pbr`, to time `StandardMaterial`).

mod asset;
mod components;
mod extract;
mod meshes;
mod post;
mod render;
mod report;
mod runtimes;
mod scene;
mod skins;
#[cfg(feature = "compiler")]
mod source_loader;

pub use asset::{NprBundleLoader, NprLoadError, NprStyleAsset};
pub use components::{NprLight, NprObject, NprParams, NprStyle, NprValue};
pub use meshes::{bevy_mesh, npr_mesh};
pub use runtimes::NprRuntimes;
pub use scene::{npr_scene_camera, spawn_npr_scene};
#[cfg(feature = "compiler")]
pub use source_loader::NprStyleLoader;

use bevy::core_pipeline::{upscaling::upscaling, Core3d, Core3dSystems};
use bevy::prelude::*;
use bevy::render::view::{DebandDither, Tonemapping};
use bevy::render::{ExtractSchedule, RenderApp};

/// Adds the `.npr` asset, the components and the render system. Add it
/// after Bevy's `DefaultPlugins` (it reads the `AssetPlugin`'s folder).
pub struct NprPlugin;

impl Plugin for NprPlugin {
    fn build(&self, app: &mut App) {
        app.init_asset::<NprStyleAsset>().register_asset_loader(NprBundleLoader);
        #[cfg(feature = "compiler")]
        {
            // The compiler reads a style's `use`s and images from disk,
            // relative to the style's file in the asset folder.
            let folder = app
                .get_added_plugins::<AssetPlugin>()
                .first()
                .map_or_else(|| "assets".to_string(), |p| p.file_path.clone());
            let root = bevy::asset::io::file::FileAssetReader::get_base_path().join(folder);
            app.register_asset_loader(NprStyleLoader { root });
        }
        app.register_type::<NprParams>()
            .register_type::<NprObject>()
            .register_type::<NprLight>()
            .init_resource::<meshes::NprMeshes>()
            .add_systems(PostUpdate, meshes::convert_meshes.after(bevy::asset::AssetEventSystems))
            .add_systems(PostUpdate, tonemapping_over_bevy)
            .add_observer(no_tonemapping);
        let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
            warn!("NprPlugin: this app has no render app (add DefaultPlugins first): npr styles will not draw");
            return;
        };
        render_app
            .init_resource::<extract::ExtractedNprScene>()
            .init_resource::<NprRuntimes>()
            .add_systems(ExtractSchedule, extract::extract_npr)
            .add_systems(
                Core3d,
                render::draw_npr.after(Core3dSystems::PostProcess).before(upscaling),
            );
    }
}

/// The tonemapping and debanding a camera had before its style turned
/// them off, given back when the style turns out to read Bevy's frame.
#[derive(Component)]
struct TonemappingBeforeNpr(Tonemapping, DebandDither);

/// A camera drawn by a style gets `Tonemapping::None` and no debanding:
/// a style that draws the scene itself replaces the image after Bevy's
/// tonemapping pass, which would be work thrown away (and Bevy's default,
/// TonyMcMapface, needs a feature this crate leaves off to keep the build
/// small). What the camera had is kept for [`tonemapping_over_bevy`].
fn no_tonemapping(event: On<Add<NprStyle>>, cameras: Query<(&Tonemapping, &DebandDither)>, mut commands: Commands) {
    let before = cameras.get(event.entity).map_or(
        TonemappingBeforeNpr(Tonemapping::None, DebandDither::Disabled),
        |(t, d)| TonemappingBeforeNpr(*t, *d),
    );
    commands
        .entity(event.entity)
        .insert((Tonemapping::None, DebandDither::Disabled, before));
}

/// A style over Bevy's frame (one that declares inputs) reads the image
/// Bevy tonemapped: once the style has loaded, the camera gets back the
/// tonemapping and debanding it had before (decision 0054).
fn tonemapping_over_bevy(
    cameras: Query<(Entity, &NprStyle, &TonemappingBeforeNpr)>,
    styles: Res<Assets<NprStyleAsset>>,
    mut commands: Commands,
) {
    for (entity, style, before) in &cameras {
        let Some(asset) = styles.get(&style.0) else { continue };
        if !post::declared_inputs(&asset.program().manifest).is_empty() {
            commands
                .entity(entity)
                .insert((before.0, before.1))
                .remove::<TonemappingBeforeNpr>();
        }
    }
}
