//! Checks of a scene against a style before anything is uploaded: vertex
//! attributes the style reads (E0403) and image bindings of per-object
//! texture params (E0405).

use crate::scene::Scene;
use npr_abi::manifest::*;

/// E0403 for every object that lacks a vertex attribute the style reads.
pub fn check_scene(manifest: &Manifest, scene: &Scene) -> Vec<npr_diag::Diagnostic> {
    let required: Vec<crate::scene::Attribute> = manifest
        .scene_attributes
        .iter()
        .map(|a| match a {
            Attribute::Position => crate::scene::Attribute::Position,
            Attribute::Normal => crate::scene::Attribute::Normal,
            Attribute::Uv => crate::scene::Attribute::Uv,
            Attribute::Tangent => crate::scene::Attribute::Tangent,
            Attribute::PatchWeight => crate::scene::Attribute::PatchWeight,
            Attribute::PreviousPosition => crate::scene::Attribute::PreviousPosition,
        })
        .collect();
    let mut diags = scene.check_attributes(
        &required,
        &format!("style \"{}\" needs per-vertex data", manifest.style),
    );
    diags.extend(check_texture_bindings(manifest, scene));
    diags
}

/// E0405 where a scene binds an image to something that is not a per-object
/// texture param of the style, or a number or colour to one that is. Names
/// the style does not declare at all are left alone, as for numeric params
/// (one scene may serve several styles).
pub fn check_texture_bindings(manifest: &Manifest, scene: &Scene) -> Vec<npr_diag::Diagnostic> {
    use npr_diag::{codes, Diagnostic};
    let mut diags = Vec::new();
    let is_object_texture = |name: &str| manifest.textures.iter().any(|t| t.per_object && t.name == name);
    for o in &scene.objects {
        for (name, b) in &o.textures {
            if is_object_texture(name) {
                continue;
            }
            let what = if let Some(p) = manifest.params.iter().find(|p| p.name == *name) {
                format!("a {} param", p.ty)
            } else if manifest.textures.iter().any(|t| t.name == *name) {
                "a style-wide texture".to_string()
            } else {
                continue;
            };
            diags.push(
                Diagnostic::error(
                    codes::BAD_SCENE,
                    format!("object `{}` binds an image to `{name}`, which is {what}", o.name),
                )
                .with_primary(b.span, "an image binding")
                .with_help(format!(
                    "only `object param {name}: texture` params take images; give `{name}` a value of its type"
                )),
            );
        }
        for name in o.params.keys() {
            if !is_object_texture(name) {
                continue;
            }
            let mut d = Diagnostic::error(
                codes::BAD_SCENE,
                format!("object `{}` binds a value to texture param `{name}`", o.name),
            )
            .with_help(format!(
                "bind an image: `{name} = \"textures/file.png\"` or `{name} = {{ image = \"file.png\", srgb = false }}`"
            ));
            if let Some(s) = o.param_spans.get(name) {
                d = d.with_primary(*s, "not an image path");
            }
            diags.push(d);
        }
    }
    diags
}
