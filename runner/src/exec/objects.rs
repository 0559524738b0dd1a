//! Per-object state read from the [`Scene`] every frame: the object uniform
//! blocks (model matrix, normal matrix, per-object params) written into the
//! one dynamic-offset object buffer, and the world bounds the light camera
//! is fitted to. The scene's structure (objects, meshes, tags, bound images)
//! is fixed when the renderer is built; only these values may change.

use crate::scene::Scene;
use crate::{animation, RunError};
use abi::manifest::*;
use abi::ObjectHead;
use glam::{Mat4, Vec3};

/// Every object's uniform block at its dynamic offset (`stride` apart, zero
/// padded): the [`ObjectHead`] (`model`, the normal matrix — inverse
/// transpose of `model`, or the identity where `model` is singular — the
/// previous frame's `model`, and the ids: index, index + 1, vertex count),
/// then the per-object param slots.
/// Bindings with the wrong number of components or out of range (E0405,
/// E0401) come back as `RunError::User`.
pub(super) fn object_blocks(
    manifest: &Manifest,
    scene: &Scene,
    stride: u64,
    previous_models: &[Mat4],
    vertex_counts: &[usize],
) -> Result<Vec<u8>, RunError> {
    let stride = stride as usize;
    let mut bytes = vec![0u8; stride * scene.objects.len()];
    let mut diags = Vec::new();
    for (index, (block, o)) in bytes.chunks_exact_mut(stride).zip(&scene.objects).enumerate() {
        let params = animation::object_param_bytes(manifest, o, &mut diags);
        let normal_matrix = o.model.inverse().transpose();
        let normal_matrix = if normal_matrix.is_finite() {
            normal_matrix
        } else {
            Mat4::IDENTITY
        };
        let head = ObjectHead {
            model: o.model.to_cols_array_2d(),
            normal_matrix: normal_matrix.to_cols_array_2d(),
            previous_model: previous_models.get(index).unwrap_or(&o.model).to_cols_array_2d(),
            ids: [
                index as u32,
                index as u32 + 1,
                vertex_counts.get(index).map_or(0, |n| *n as u32),
                0,
            ],
        };
        let params_at = OBJECT_PARAMS_OFFSET as usize;
        block[..params_at].copy_from_slice(bytemuck::bytes_of(&head));
        block[params_at..params_at + params.len()].copy_from_slice(&params);
    }
    if !diags.is_empty() {
        return Err(RunError::User(diags));
    }
    Ok(bytes)
}

/// World bounds for the light camera of a frame (`scene::light_view_proj`):
/// what the whole scene spans (its depth range) and what the light-view
/// passes draw, the shadow casters (its x, y extent).
pub(super) fn light_bounds(manifest: &Manifest, scene: &Scene) -> ((Vec3, Vec3), (Vec3, Vec3)) {
    // Objects any light-view pass draws; all of them when such a pass has no tag.
    let tags: Vec<Option<&String>> = manifest
        .passes
        .iter()
        .filter_map(|p| match &p.kind {
            PassKindManifest::Render {
                tag, light_view: true, ..
            } => Some(tag.as_ref()),
            _ => None,
        })
        .collect();
    let drawn = scene.bounds_of(|o| tags.iter().any(|t| t.is_none_or(|t| o.tags.contains(t))));
    let casters = if drawn.0.is_finite() { drawn } else { scene.bounds() };
    (scene.bounds(), casters)
}

/// Whether some object of `scene` has another transform than in `models`.
pub(super) fn moved(models: &[Mat4], scene: &Scene) -> bool {
    models.len() != scene.objects.len() || models.iter().zip(&scene.objects).any(|(m, o)| *m != o.model)
}
