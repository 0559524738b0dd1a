//! Warnings about a scene's per-object bindings that the style does not
//! read: a misspelt param name, or a style-wide param bound per object.
//!
//! They are warnings, not errors, because one scene may serve several
//! styles; but a binding that is silently dropped is how a misspelling
//! goes unnoticed, so each one near a per-object param of the style is
//! shown at its place with "did you mean", as is a style-wide param bound
//! per object. Names the style has nothing near (a binding for another
//! style of the same scene) are listed together in one line. A param the style declares but
//! does not use (`ParamBinding::Removed`) is not reported: the binding is
//! right, the style just does not need it here.

use crate::scene::Scene;
use npr_abi::manifest::{Manifest, ParamBinding};
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, Span};

/// W0401 for every binding of every object whose name is no per-object
/// param or per-object texture of `manifest`.
pub fn scene_warnings(manifest: &Manifest, scene: &Scene) -> Vec<Diagnostic> {
    let per_object: Vec<&str> = manifest
        .params
        .iter()
        .filter(|p| p.binding == ParamBinding::PerObject)
        .map(|p| p.name.as_str())
        .chain(
            manifest
                .textures
                .iter()
                .filter(|t| t.per_object)
                .map(|t| t.name.as_str()),
        )
        .collect();
    let mut diags = Vec::new();
    // Names this style has nothing near: most likely meant for another
    // style that shares the scene, so one line for them all.
    let mut elsewhere: std::collections::BTreeMap<&str, Vec<&str>> = Default::default();
    for o in &scene.objects {
        let bound = o
            .params
            .keys()
            .map(|n| (n, o.param_spans.get(n).copied()))
            .chain(o.textures.iter().map(|(n, b)| (n, Some(b.span))));
        for (name, span) in bound {
            if per_object.contains(&name.as_str()) {
                continue;
            }
            let declared = manifest.params.iter().find(|p| p.name == *name);
            if declared.is_some_and(|p| p.binding == ParamBinding::Removed) {
                continue;
            }
            // A style-wide texture or style param bound to an image is E0405
            // (`check_texture_bindings`), not this warning.
            let is_style_texture = manifest.textures.iter().any(|t| t.name == *name);
            if o.textures.contains_key(name) && (declared.is_some() || is_style_texture) {
                continue;
            }
            let style_wide = declared.is_some() || is_style_texture;
            if !style_wide && did_you_mean(name, per_object.iter().copied()).is_none() {
                elsewhere.entry(name.as_str()).or_default().push(&o.name);
                continue;
            }
            diags.push(unread(manifest, &o.name, name, span, style_wide, &per_object));
        }
    }
    if !elsewhere.is_empty() {
        let list: Vec<String> = elsewhere
            .iter()
            .map(|(name, objects)| {
                let on: Vec<String> = objects.iter().map(|o| format!("`{o}`")).collect();
                format!("`{name}` (on {})", on.join(", "))
            })
            .collect();
        diags.push(Diagnostic::warning(
            codes::UNUSED_BINDING,
            format!(
                "style \"{}\" does not read the scene's per-object {}, so {} ignored",
                manifest.style,
                list.join(", "),
                if list.len() == 1 { "it is" } else { "they are" }
            ),
        ));
    }
    diags
}

fn unread(
    manifest: &Manifest,
    object: &str,
    name: &str,
    span: Option<Span>,
    style_wide: bool,
    per_object: &[&str],
) -> Diagnostic {
    let mut d = Diagnostic::warning(
        codes::UNUSED_BINDING,
        format!(
            "object `{object}` binds `{name}`, which style \"{}\" does not read per object",
            manifest.style
        ),
    );
    if let Some(s) = span {
        d = d.with_primary(s, "this binding is ignored");
    }
    let help = if style_wide {
        format!(
            "`{name}` is a style-wide name, the same for every object; declare `object param {name}` in the style to bind it per object"
        )
    } else if let Some(s) = did_you_mean(name, per_object.iter().copied()) {
        format!("did you mean `{s}`?")
    } else if per_object.is_empty() {
        format!("style \"{}\" reads no per-object params", manifest.style)
    } else {
        format!("its per-object params are: {}", per_object.join(", "))
    };
    d.with_help(help)
}
