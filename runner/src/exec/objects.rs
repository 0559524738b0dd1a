//! The object uniform blocks (model matrix, normal matrix, per-object
//! params), read from the [`Scene`] every frame and written into the one
//! dynamic-offset object buffer (through the frame's staging bytes,
//! `upload.rs`, rewritten in place: a frame allocates nothing for them).
//! The scene's structure (objects, meshes, tags, bound images) is fixed
//! when the renderer is built; only these values may change.

use crate::scene::Scene;
use crate::{animation, RunError};
use glam::Mat4;
use npr_abi::manifest::*;
use npr_abi::ObjectHead;

/// Which per-object params an object block writes and the params region
/// of an object that binds none, found once per renderer (a frame then
/// reads only those params, and copies the defaults for an object without
/// bindings: most of a host's objects).
pub(super) struct ObjectParams {
    /// [`animation::object_param_indices`] of the manifest.
    indices: Vec<usize>,
    /// [`animation::object_param_defaults`]: the region's bytes.
    defaults: Vec<u8>,
}

impl ObjectParams {
    /// The object params of `manifest`, for blocks `stride` bytes apart.
    pub fn new(manifest: &Manifest, stride: u64) -> ObjectParams {
        let indices = animation::object_param_indices(manifest);
        let (at, end) = params_region(manifest, stride);
        let defaults = animation::object_param_defaults(&manifest.params, &indices, end - at);
        ObjectParams { indices, defaults }
    }
}

/// Where an object block's params lie in its `stride` bytes: from the end
/// of the [`ObjectHead`] to the manifest's block size (the padding past it
/// is never written, so it stays zero).
fn params_region(manifest: &Manifest, stride: u64) -> (usize, usize) {
    let at = OBJECT_PARAMS_OFFSET as usize;
    (at, (manifest.object_uniform_size as usize).clamp(at, stride as usize))
}

/// Every object's uniform block at its dynamic offset (`stride` apart, zero
/// padded), written over `bytes` (`stride` × objects long): the [`ObjectHead`]
/// (`model`, the normal matrix — inverse transpose of `model`, or the
/// identity where `model` is singular — the previous frame's `model`, and
/// the ids: index, index + 1, vertex count), then the per-object param
/// slots. Bindings with the wrong number of components or out of range
/// (E0405, E0401) come back as `RunError::User`.
pub(super) fn write_object_blocks(
    (manifest, object_params): (&Manifest, &ObjectParams),
    scene: &Scene,
    stride: u64,
    (previous_models, vertex_counts): (&[Mat4], &[usize]),
    bytes: &mut [u8],
) -> Result<(), RunError> {
    let (params_at, params_end) = params_region(manifest, stride);
    let stride = stride as usize;
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
        let params = &mut block[params_at..params_end];
        if o.params.is_empty() && o.material.is_none() {
            params.copy_from_slice(&object_params.defaults);
        } else {
            animation::write_object_params(&manifest.params, &object_params.indices, o, params, &mut diags);
        }
    }
    if !diags.is_empty() {
        return Err(RunError::User(diags));
    }
    Ok(())
}
