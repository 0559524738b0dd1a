//! Drawing a camera with its style, in Bevy's render world: a system in
//! the `Core3d` schedule, after the post-processing passes (tonemapping
//! included) and before upscaling, that drives one
//! [`npr_runner::embed::StyleRuntime`] per camera on Bevy's `RenderDevice` and
//! `RenderQueue`, in the command encoder of Bevy's render context, into
//! the camera's main texture (its view target). Bevy's 3D view targets
//! hold linear light (an sRGB view when not HDR, `Rgba16Float` when HDR),
//! so the output is presented as a [`Target::LinearView`]: after Bevy's
//! upscaling to the window or image, the pixels are what `npr render`
//! writes.
//!
//! A style that declares inputs runs over Bevy's frame at the same place:
//! after Bevy's tonemapping, because npr's output is display-referred in
//! every host (decision 0054). It reads the main image as Bevy left it
//! and the camera's prepass textures (`post.rs`), and its output replaces
//! the image.
//!
//! Nothing here panics on bad input: each problem (a style the device
//! cannot run, a parameter value, a per-object param of the wrong type, a
//! tag no object has, a target the style cannot write) is logged once per
//! camera with its code, and the camera keeps its last good style or is
//! left as Bevy drew it.

use crate::extract::{ExtractedNprCamera, ExtractedNprScene};
use crate::meshes::Converted;
use crate::runtimes::{CameraRuntime, NprRuntimes};
use bevy::camera::CompositingSpace;
use bevy::core_pipeline::prepass::ViewPrepassTextures;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::camera::ExtractedCamera;
use bevy::render::renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery};
use bevy::render::view::{ResolvedCompositingSpace, ViewTarget};
use npr_abi::manifest::{ParamBinding, PassKindManifest};
use npr_diag::{codes, Diagnostic};
use npr_runner::embed::{Frame, Instance, StyleRuntime, Target};
use std::collections::BTreeMap;
use std::sync::Arc;

/// What `draw_npr` reads of the view: its target, its npr camera, how it
/// composites, and what a style over Bevy's frame reads (camera, MSAA,
/// prepass textures).
type NprView<'a> = (
    Entity,
    &'a ViewTarget,
    &'a ExtractedNprCamera,
    Option<&'a ResolvedCompositingSpace>,
    (&'a ExtractedCamera, &'a Msaa, Option<&'a ViewPrepassTextures>),
);

/// The `Core3d` system: draws the current view with its style.
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw_npr(
    view: ViewQuery<NprView>,
    scene: Res<ExtractedNprScene>,
    mut runtimes: ResMut<NprRuntimes>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    mut ctx: RenderContext,
) {
    let (entity, view_target, camera, space, (extracted, msaa, prepass)) = view.into_inner();
    let Some(style) = scene.styles.get(&camera.style) else {
        // Not loaded yet, or it never compiled (logged by the loader).
        return;
    };
    let NprRuntimes { cameras, reports } = &mut *runtimes;
    let at = |what: String| format!("camera {}: {what}", camera.main);

    // A new style (first load or hot reload) gets a new runtime; one the
    // device cannot run keeps the last. So does a removed `NprParams` key
    // of an animated parameter: `set_param` cannot give its keyframes back.
    let restarts = cameras
        .get(&entity)
        .is_none_or(|c| c.revision != style.revision() || !unset_params(c, camera, style.program()).1.is_empty());
    if restarts {
        match StyleRuntime::new(device.wgpu_device(), &queue, (**style.program()).clone()) {
            Ok(runtime) => {
                info!("{}", at(format!("drawn with the style \"{}\"", style.name())));
                reports.forget(entity);
                cameras.insert(
                    entity,
                    CameraRuntime {
                        runtime,
                        revision: style.revision(),
                        meshes: HashMap::default(),
                        params: BTreeMap::new(),
                        instances: Vec::new(),
                        mesh_revision: 0,
                    },
                );
            }
            Err(e) => {
                reports.log(entity, &prefixed(&camera.main, e.diagnostics()));
                let Some(kept) = cameras.get_mut(&entity) else { return };
                // Not retried every frame: the same style would fail again.
                kept.revision = style.revision();
                // An animated parameter whose key was removed keeps its set value.
                kept.params.retain(|name, _| camera.params.contains_key(name));
            }
        }
    }
    let Some(state) = cameras.get_mut(&entity) else { return };

    let npr_camera = match &camera.camera {
        Ok(c) => c,
        Err(why) => {
            let d = Diagnostic::error(codes::BAD_SCENE, at(format!("npr cannot draw it: {why}")))
                .with_help("give the camera a perspective projection");
            reports.log(entity, &[d]);
            return;
        }
    };

    // A key removed from `NprParams`: the parameter gets the style's default back.
    for name in unset_params(state, camera, style.program()).0 {
        let result = match default_value(style.program(), &name) {
            Some(text) => state.runtime.set_param(&name, &text).map_err(|e| e.diagnostics()),
            None => Ok(()),
        };
        if let Err(diags) = result {
            reports.log(entity, &prefixed(&camera.main, diags));
        }
        state.params.remove(&name);
    }
    for (name, value) in &camera.params {
        if state.params.get(name) != Some(value) {
            if let Err(e) = state.runtime.set_param(name, value) {
                reports.log(entity, &prefixed(&camera.main, e.diagnostics()));
            }
            state.params.insert(name.clone(), value.clone());
        }
    }

    let problems = instances(state, &scene);
    reports.log(entity, &prefixed(&camera.main, problems));
    reports.log(
        entity,
        &prefixed(&camera.main, absent_tags(&state.runtime, &state.instances)),
    );

    let format = view_target.main_texture_format();
    let view = view_target.main_texture_view();
    if !crate::post::declared_inputs(state.runtime.manifest()).is_empty() {
        let frame = crate::post::BevyFrame {
            main: view,
            space: ResolvedCompositingSpace::space(space),
            prepass,
            msaa_samples: msaa.samples(),
            viewport: extracted.viewport.is_some(),
            near: npr_camera.near,
        };
        let problems = crate::post::give_inputs(&mut state.runtime, &frame);
        if !problems.is_empty() {
            // Left as Bevy drew it; checked again next frame.
            reports.log(entity, &prefixed(&camera.main, problems));
            return;
        }
        reports.forget_codes(entity, &crate::post::CODES);
    }
    let target = match ResolvedCompositingSpace::space(space) {
        None | Some(CompositingSpace::Linear) => Target::LinearView { view, format },
        // A 2D-style stack that composites in sRGB keeps encoded values.
        Some(CompositingSpace::Srgb) => Target::View(view),
        Some(CompositingSpace::Oklab) => {
            let d = Diagnostic::error(
                codes::BAD_RENDER_TARGET,
                at("its view target composites in Oklab, which npr's output (sRGB) cannot be written as".into()),
            )
            .with_help("use CompositingSpace::Linear (the default of 3D cameras) on a camera drawn by npr");
            reports.log(entity, &[d]);
            return;
        }
    };
    let frame = Frame {
        camera: npr_camera,
        objects: &state.instances,
        lights: &scene.lights,
        time_s: scene.time_s,
        frame_index: scene.frame,
        eye: 0,
    };
    if let Err(e) = state.runtime.render(ctx.command_encoder(), &frame, target) {
        reports.log(entity, &prefixed(&camera.main, e.diagnostics()));
    }
}

/// The parameters given to the runtime whose keys `NprParams` no longer
/// has: (those with a constant default, those that are animated).
fn unset_params(
    state: &CameraRuntime,
    camera: &ExtractedNprCamera,
    program: &npr_runner::StyleProgram,
) -> (Vec<String>, Vec<String>) {
    state
        .params
        .keys()
        .filter(|name| !camera.params.contains_key(*name))
        .cloned()
        .partition(|name| {
            program
                .manifest
                .params
                .iter()
                .find(|p| &p.name == name)
                .is_none_or(|p| p.keyframes.is_empty())
        })
}

/// The style's own value of the parameter `name`, written as `set_param`
/// takes it; `None` for a name the style does not have (its `set_param`
/// was refused and logged, so nothing is to undo).
fn default_value(program: &npr_runner::StyleProgram, name: &str) -> Option<String> {
    let p = program.manifest.params.iter().find(|p| p.name == name)?;
    if p.default_percent_of_height {
        return Some(format!("{}%", p.default.first().copied().unwrap_or(0.0)));
    }
    npr_abi::param_value::format_literal(&npr_abi::param_value::ParamShape::of_manifest(p), &p.default)
}

/// `diags` with the camera named, for the log.
fn prefixed(camera: &Entity, diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    diags
        .into_iter()
        .map(|mut d| {
            d.message = format!("camera {camera}: {}", d.message);
            d
        })
        .collect()
}

/// Fill `state.instances` with the scene's objects (registering their
/// meshes once); per-object params the style does not have, or of the
/// wrong size, are left out (the object gets the default) and returned as
/// diagnostics.
fn instances(state: &mut CameraRuntime, scene: &ExtractedNprScene) -> Vec<Diagnostic> {
    let mut problems = Vec::new();
    state.instances.clear();
    if state.mesh_revision != scene.mesh_revision {
        // Meshes Bevy forgot (no entity has them, or the asset is gone) or
        // changed leave the runtime; those drawn again are registered again.
        let runtime = &mut state.runtime;
        state.meshes.retain(|id, (registered, handle)| {
            let kept = matches!(scene.meshes.get(id), Some(Converted::Mesh(m, _)) if Arc::ptr_eq(m, registered));
            if !kept {
                let _ = runtime.remove_mesh(*handle);
            }
            kept
        });
        state.mesh_revision = scene.mesh_revision;
    }
    let per_object: Vec<(String, u32, String)> = state
        .runtime
        .manifest()
        .params
        .iter()
        .filter(|p| p.binding == ParamBinding::PerObject)
        .map(|p| (p.name.clone(), p.components, p.ty.clone()))
        .collect();
    for object in &scene.objects {
        let Some(Converted::Mesh(mesh, skinning)) = scene.meshes.get(&object.mesh) else {
            // Not converted yet (next frame), or unusable (logged once when converted).
            continue;
        };
        let handle = match state.meshes.get(&object.mesh) {
            Some((registered, handle)) if Arc::ptr_eq(registered, mesh) => *handle,
            old => {
                if let Some((_, stale)) = old {
                    // The asset changed: its old npr mesh goes.
                    let _ = state.runtime.remove_mesh(*stale);
                }
                let handle = crate::skins::register(&mut state.runtime, mesh, skinning.as_deref(), &mut problems);
                state.meshes.insert(object.mesh, (mesh.clone(), handle));
                handle
            }
        };
        // The entity is who the object is from frame to frame: a despawn or
        // spawn elsewhere in the list keeps its state (docs/decisions/0046).
        let mut instance = Instance::new(handle, object.transform).with_id(object.entity.to_bits());
        crate::skins::attach_pose(
            &state.runtime,
            handle,
            &mut instance,
            object.entity,
            skinning.as_deref(),
            object.joints.as_ref(),
            &mut problems,
        );
        if let Some(o) = &object.object {
            instance.tags.clone_from(&o.tags);
            instance.casts_shadows = o.casts_shadows;
            for (name, value) in &o.params {
                match per_object.iter().find(|(n, _, _)| n == name) {
                    None => problems.push(
                        Diagnostic::warning(
                            codes::UNUSED_BINDING,
                            format!(
                                "entity {}: NprObject sets `{name}`, which is not an `object param` of the style",
                                object.entity
                            ),
                        )
                        .with_help(match per_object.is_empty() {
                            true => "the style has no object params".to_string(),
                            false => format!(
                                "its object params are: {}",
                                per_object.iter().map(|p| p.0.as_str()).collect::<Vec<_>>().join(", ")
                            ),
                        }),
                    ),
                    Some((_, n, ty)) if value.len() != *n as usize && !(*n == 4 && value.len() == 3) => problems.push(
                        Diagnostic::error(
                            codes::BAD_SCENE,
                            format!(
                                "entity {}: NprObject gives `{name}` {} component(s), but it is a `{ty}` of {n}",
                                object.entity,
                                value.len()
                            ),
                        )
                        .with_help("the object is drawn with the param's default; give a value of its type"),
                    ),
                    Some(_) => {
                        instance.params.insert(name.clone(), value.clone());
                    }
                }
            }
        }
        state.instances.push(instance);
    }
    problems
}

/// W0402 for each tag a pass of the style draws that no object has.
fn absent_tags(runtime: &StyleRuntime, instances: &[Instance]) -> Vec<Diagnostic> {
    let mut diags = Vec::new();
    for pass in &runtime.manifest().passes {
        let tag = match &pass.kind {
            PassKindManifest::Render { tag, .. }
            | PassKindManifest::Compute { tag, .. }
            | PassKindManifest::Lines { tag, .. } => tag.as_ref(),
            _ => None,
        };
        if let Some(tag) = tag {
            if !instances.iter().any(|i| i.tags.contains(tag)) {
                diags.push(
                    Diagnostic::warning(
                        codes::ABSENT_TAG,
                        format!(
                            "pass `{}` draws objects tagged `{tag}`, and no entity has that tag",
                            pass.name
                        ),
                    )
                    .with_help(format!(
                        "add NprObject::tagged(\"{tag}\") to the entities it should draw"
                    )),
                );
            }
        }
    }
    diags
}
