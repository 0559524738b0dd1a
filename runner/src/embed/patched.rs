//! A host's mesh divided into patches (Breslav et al. 2007 §3.6) for
//! `StyleRuntime::add_patches`: the same division and blending a scene's
//! `patches` and `blend_rings` make (`scene::parse_patches::expand`), each
//! patch a mesh of its own with its n-ring and weights and the whole mesh,
//! checked first so that a division that cannot be made is a value (E0405)
//! and registers nothing.

use super::meshes::MeshExtras;
use super::EmbedError;
use crate::scene::patch_blend::{blends, MAX_BLEND_RINGS};
use crate::scene::patches::{assign, patch_mesh, PatchOf, PatchSpec, MAX_PATCHES};
use crate::scene::Mesh;
use std::sync::Arc;

/// E0405, as a scene's bad `patches` or `blend_rings` is.
fn refuse(message: String, help: &str) -> EmbedError {
    EmbedError::from(crate::RunError::User(vec![npr_diag::Diagnostic::error(
        npr_diag::codes::BAD_SCENE,
        message,
    )
    .with_help(help.to_string())]))
}

/// Per patch of `mesh` divided as `spec` and blended over `blend_rings`
/// rings: its own faces, with its extras. `set` names the division (the
/// key `lines` passes join its patches by).
pub(super) fn divide(
    mesh: &Arc<Mesh>,
    spec: PatchSpec,
    blend_rings: u32,
    set: u64,
) -> Result<Vec<(Arc<Mesh>, MeshExtras)>, EmbedError> {
    if let PatchSpec::Split(n) = spec {
        if !(2..=MAX_PATCHES).contains(&n) {
            return Err(refuse(
                format!("a mesh is divided into 2..={MAX_PATCHES} patches, not {n}"),
                "ask for a count in that range, e.g. `PatchSpec::Split(4)`",
            ));
        }
    }
    if blend_rings > MAX_BLEND_RINGS {
        return Err(refuse(
            format!("patches blend over 0..={MAX_BLEND_RINGS} rings of faces, not {blend_rings}"),
            "ask for fewer rings (0: hard seams)",
        ));
    }
    let Some((labels, count)) = assign(mesh, spec) else {
        let asked = match spec {
            PatchSpec::Parts => "its parts: it has one".to_string(),
            PatchSpec::Split(n) => format!("{n} patches"),
        };
        return Err(refuse(
            format!(
                "the mesh `{}` ({} triangles) cannot be divided into {asked}",
                mesh.source,
                mesh.triangle_count()
            ),
            "split a mesh of one part by count (`PatchSpec::Split`), into fewer patches than it has triangles",
        ));
    };
    let mut blended: Vec<_> = if blend_rings > 0 {
        blends(mesh, &labels, count, blend_rings)
            .into_iter()
            .map(|b| Some(Arc::new(b)))
            .collect()
    } else {
        vec![None; count as usize]
    };
    let source = format!("patched mesh #{set}");
    Ok((0..count)
        .map(|index| {
            let extras = MeshExtras {
                time_varying: None,
                blend: blended[index as usize].take(),
                patch: Some(PatchOf {
                    source: source.clone(),
                    whole: mesh.clone(),
                    index,
                    count,
                }),
                rig: None,
            };
            (Arc::new(patch_mesh(mesh, &labels, index)), extras)
        })
        .collect())
}
