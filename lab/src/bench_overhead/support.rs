//! What the independent baseline of `npr bench overhead` can draw, checked
//! before it builds anything: a manifest or scene that needs more is
//! refused with a sentence naming what, never drawn differently.
//!
//! Supported: render passes (every object, or every tagged one) with vertex
//! attributes, the object block and their own depth buffer, image passes,
//! outputs that replace their target, and in group 0 the frame
//! block, the style block (keyframed parameters too), targets of this frame and
//! the linear clamp sampler. Everything else the runner does — compute
//! passes, lines passes, tiled image passes, history, stereo, `view(light)`, kept and tested depth, blending,
//! declared and per-object textures, time-varying meshes, patch weights — is refused.

use npr_abi::manifest::*;
use npr_runner::scene::Scene;

/// `Err` names the first thing the baseline does not do.
pub fn check(manifest: &Manifest, scene: &Scene) -> Result<(), String> {
    for pass in &manifest.passes {
        let what = |s: &str| Err(format!("{s} (pass `{}`)", pass.name));
        match &pass.kind {
            PassKindManifest::Compute { .. } => return what("compute passes"),
            PassKindManifest::Lines { .. } => return what("lines passes"),
            PassKindManifest::TiledImage { .. } => return what("tiled image passes (compile with `--schedule naive`)"),
            PassKindManifest::Render { light_view: true, .. } => return what("`view(light)` passes"),
            PassKindManifest::Render { depth, .. } if *depth != DepthMode::Own => {
                return what("`depth: keep` and `depth: test(...)`")
            }
            PassKindManifest::Render { .. } | PassKindManifest::Image { .. } => {}
        }
        if pass.blend.iter().any(|b| *b != Blend::Replace) {
            return what("blending (`over`, `add`, `multiply`)");
        }
        if !pass.object_bindings.is_empty() {
            return what("per-object textures");
        }
        for b in &pass.bindings {
            match &b.resource {
                Resource::FrameUniforms | Resource::StyleUniforms | Resource::LinearClampSampler => {}
                Resource::Target { copy, .. } => match copy {
                    TargetCopy::This => {}
                    TargetCopy::Previous => return what("reads of earlier frames (`previous(...)`)"),
                    TargetCopy::OtherEye => return what("stereo styles (`other_eye(...)`)"),
                },
                Resource::Texture { .. } | Resource::TextureSampler { .. } => return what("declared textures"),
                Resource::ObjectValues { .. } => return what("per-object values of compute passes"),
            }
        }
    }
    // Covered by the passes above; kept so that a new way for a style to
    // be stereo or path-dependent is refused too.
    if manifest.is_stereo() {
        return Err("stereo styles".into());
    }
    if manifest.is_path_dependent() {
        return Err("styles that depend on earlier frames".into());
    }
    if manifest.scene_attributes.contains(&Attribute::PatchWeight) {
        return Err("patch weights (`patch.weight`)".into());
    }
    for o in &scene.objects {
        if o.time_varying.is_some() {
            return Err(format!("time-varying meshes (object `{}`)", o.name));
        }
        if let Some(a) = manifest.scene_attributes.iter().find(|a| !o.mesh.has(**a)) {
            return Err(format!("object `{}` has no {}", o.name, a.plural_name()));
        }
    }
    Ok(())
}
