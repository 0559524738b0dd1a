//! An object's `patches = "parts"` or `patches = 6` (Breslav et al. 2007
//! §3.6), and the expansion of a patched object into one object per patch
//! once every object has its unique name: `cow` split in 4 becomes `cow.0` …
//! `cow.3`, each with the object's transform, tags and bindings.

use super::patches::{assign, patch_mesh, PatchSpec, MAX_PATCHES};
use super::toml_fields::{describe, At, Fields, Report};
use super::Object;
use std::sync::Arc;
use toml::de::DeValue;

/// Reads `patches`, if present.
pub fn read_patches(fields: &mut Fields, report: &mut Report) -> Option<At<PatchSpec>> {
    let value = fields.raw("patches")?;
    let span = report.span(value.span());
    let help = format!("write `patches = \"parts\"` (the mesh file's objects or primitives) or a count, e.g. `patches = 4` (2..={MAX_PATCHES})");
    let spec = match value.get_ref() {
        DeValue::String(s) if s.as_ref() == "parts" => Some(PatchSpec::Parts),
        DeValue::Integer(int) => match i64::from_str_radix(int.as_str(), int.radix()) {
            Ok(n) if (2..=MAX_PATCHES as i64).contains(&n) => Some(PatchSpec::Split(n as u32)),
            _ => None,
        },
        _ => None,
    };
    if spec.is_none() {
        report.bad_scene(
            span,
            format!(
                "`patches` must be \"parts\" or a count in 2..={MAX_PATCHES}, not {}",
                describe(value.get_ref())
            ),
            "not a patch division",
            help,
        );
    }
    spec.map(|value| At { value, span })
}

/// Replaces each patched object by its patches, in place; reports an
/// object whose mesh cannot be divided as asked.
pub fn expand(objects: Vec<(Object, Option<At<PatchSpec>>)>, report: &mut Report) -> Vec<Object> {
    let mut out = Vec::with_capacity(objects.len());
    for (object, spec) in objects {
        let Some(spec) = spec else {
            out.push(object);
            continue;
        };
        if object.time_varying.is_some() {
            report.bad_scene(
                spec.span,
                "an animated primitive cannot be divided into patches",
                "rebuilt every frame",
                "remove `patches` from this object",
            );
            continue;
        }
        let Some((labels, count)) = assign(&object.mesh, spec.value) else {
            let (message, help) = match spec.value {
                PatchSpec::Parts => (
                    format!("the mesh of `{}` has a single part", object.name),
                    "split it by count instead, e.g. `patches = 4`, or give the file several `o`/`g` groups"
                        .to_string(),
                ),
                PatchSpec::Split(n) => (
                    format!(
                        "the mesh of `{}` cannot be split into {n} patches ({} triangles)",
                        object.name,
                        object.mesh.triangle_count()
                    ),
                    "use fewer patches".to_string(),
                ),
            };
            report.bad_scene(spec.span, message, "cannot divide this mesh", help);
            continue;
        };
        for patch in 0..count {
            let mut piece = object.clone();
            piece.name = format!("{}.{patch}", object.name);
            piece.mesh = Arc::new(patch_mesh(&object.mesh, &labels, patch));
            out.push(piece);
        }
    }
    out
}
