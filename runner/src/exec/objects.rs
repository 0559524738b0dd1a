//! The object uniform blocks (model matrix, normal matrix, per-object
//! params), read from the [`Scene`] every frame and written into the one
//! dynamic-offset object buffer (through the frame's staging bytes,
//! `upload.rs`, rewritten in place: a frame allocates nothing for them).
//! The scene's structure (objects, meshes, tags, bound images) is fixed
//! when the renderer is built; only these values may change.

use crate::scene::Scene;
use crate::{animation, RunError};
use abi::manifest::*;
use abi::ObjectHead;
use glam::Mat4;

/// Every object's uniform block at its dynamic offset (`stride` apart, zero
/// padded), written over `bytes` (`stride` × objects long): the [`ObjectHead`]
/// (`model`, the normal matrix — inverse transpose of `model`, or the
/// identity where `model` is singular — the previous frame's `model`, and
/// the ids: index, index + 1, vertex count), then the per-object param
/// slots. Bindings with the wrong number of components or out of range
/// (E0405, E0401) come back as `RunError::User`.
pub(super) fn write_object_blocks(
    (manifest, object_params): (&Manifest, &[usize]),
    scene: &Scene,
    stride: u64,
    (previous_models, vertex_counts): (&[Mat4], &[usize]),
    bytes: &mut [u8],
) -> Result<(), RunError> {
    let stride = stride as usize;
    // Padding past the params is never written, so it stays zero.
    let params_at = OBJECT_PARAMS_OFFSET as usize;
    let params_end = (manifest.object_uniform_size as usize).clamp(params_at, stride);
    let mut diags = Vec::new();
    for (index, (block, o)) in bytes.chunks_exact_mut(stride).zip(&scene.objects).enumerate() {
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
        block[..params_at].copy_from_slice(bytemuck::bytes_of(&head));
        animation::write_object_params(
            &manifest.params,
            object_params,
            o,
            &mut block[params_at..params_end],
            &mut diags,
        );
    }
    if !diags.is_empty() {
        return Err(RunError::User(diags));
    }
    Ok(())
}
