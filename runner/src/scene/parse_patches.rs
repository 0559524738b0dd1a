//! An object's `patches = "parts"` or `patches = 6` and `blend_rings = n`
//! (Breslav et al. 2007 §3.6), and the expansion of a patched object into
//! one object per patch once every object has its unique name: `cow` split
//! in 4 becomes `cow.0` … `cow.3`, each with the object's transform, tags
//! and bindings, its own faces as its mesh, and (unless `blend_rings = 0`)
//! its faces with their n-ring and weights for passes that blend.

use super::patch_blend::{blends, DEFAULT_BLEND_RINGS, MAX_BLEND_RINGS};
use super::patches::{assign, patch_mesh, PatchOf, PatchSpec, MAX_PATCHES};
use super::toml_fields::{describe, At, Fields, Report};
use super::Object;
use std::sync::Arc;
use toml::de::DeValue;

/// How an object is divided into patches and blended across them.
#[derive(Debug, Clone)]
pub struct PatchRequest {
    pub spec: At<PatchSpec>,
    /// n of the §3.6 n-ring; 0: no blending (hard seams).
    pub blend_rings: u32,
}

/// Reads `patches` and `blend_rings`, if present; `blend_rings` without
/// `patches` is an error.
pub fn read_request(fields: &mut Fields, report: &mut Report) -> Option<PatchRequest> {
    let spec = read_patches(fields, report);
    let rings = fields.integer("blend_rings", report);
    let blend_rings = match &rings {
        Some(At { value, span }) if !(0..=i64::from(MAX_BLEND_RINGS)).contains(value) => {
            report.bad_scene(
                *span,
                format!("`blend_rings` must be in 0..={MAX_BLEND_RINGS}, not {value}"),
                "not a ring count",
                "write e.g. `blend_rings = 2`: patterns cross-fade over the 2 rings of faces around each patch boundary (0: hard seams)",
            );
            DEFAULT_BLEND_RINGS
        }
        Some(At { value, .. }) => *value as u32,
        None => DEFAULT_BLEND_RINGS,
    };
    match (spec, rings) {
        (Some(spec), _) => Some(PatchRequest { spec, blend_rings }),
        (None, Some(rings)) => {
            report.bad_scene(
                rings.span,
                "`blend_rings` needs `patches`",
                "this object is not divided into patches",
                "add `patches = 4` (or \"parts\") to divide it, or remove `blend_rings`",
            );
            None
        }
        (None, None) => None,
    }
}

/// Reads `patches`, if present.
fn read_patches(fields: &mut Fields, report: &mut Report) -> Option<At<PatchSpec>> {
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
pub fn expand(objects: Vec<(Object, Option<PatchRequest>)>, report: &mut Report) -> Vec<Object> {
    let mut out = Vec::with_capacity(objects.len());
    for (object, request) in objects {
        let Some(PatchRequest { spec, blend_rings }) = request else {
            out.push(object);
            continue;
        };
        if object.time_varying.is_some() || object.animation.is_some() {
            report.bad_scene(
                spec.span,
                "an animated primitive or an object playing a clip cannot be divided into patches",
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
        let mut blended = if blend_rings > 0 {
            blends(&object.mesh, &labels, count, blend_rings)
                .into_iter()
                .map(|b| Some(Arc::new(b)))
                .collect()
        } else {
            vec![None; count as usize]
        };
        for patch in 0..count {
            let mut piece = object.clone();
            piece.name = format!("{}.{patch}", object.name);
            piece.mesh = Arc::new(patch_mesh(&object.mesh, &labels, patch));
            piece.blend = blended[patch as usize].take();
            piece.patch = Some(PatchOf {
                source: object.name.clone(),
                whole: object.mesh.clone(),
                index: patch,
                count,
            });
            out.push(piece);
        }
    }
    out
}
