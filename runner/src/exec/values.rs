//! The buffers of compute passes: per pass, its per-object value buffer
//! (`vec4<f32>` slots, `objects × slots`; two copies, written by frame
//! parity, when the pass keeps state), and for a pass over vertices its
//! partials buffer (one `vec4` per value per element workgroup) and its
//! dispatch uniform. Built once with the renderer (the object count and
//! vertex counts are fixed); the value buffers are zeroed again whenever
//! the history resets (a new size), so state restarts from its first value.

use super::meshes::GpuMesh;
use abi::manifest::*;

/// The buffers of one compute pass.
pub(super) struct PassBuffers {
    /// This frame's values at `copies[parity % copies.len()]`; the previous
    /// frame's at the other copy (passes with state).
    pub copies: Vec<wgpu::Buffer>,
    /// Per object, `partials_per_object` × values partials (passes over vertices).
    pub partials: Option<wgpu::Buffer>,
    /// `vec4<u32>`, x: partials per object (passes over vertices).
    pub dispatch: Option<wgpu::Buffer>,
    pub slots: u32,
    /// Element workgroups of the object with the most vertices.
    pub partials_per_object: u32,
}

impl PassBuffers {
    /// This frame's copy (`previous: false`) or the previous frame's.
    pub fn copy(&self, parity: usize, previous: bool) -> &wgpu::Buffer {
        let n = self.copies.len();
        &self.copies[(parity + usize::from(previous)) % n]
    }
}

/// Element workgroups for `vertices` elements.
pub(super) fn element_workgroups(vertices: usize) -> u32 {
    (vertices as u64)
        .div_ceil(ELEMENTS_PER_WORKGROUP as u64)
        .min(u32::MAX as u64) as u32
}

/// The buffers of every manifest pass (`None` for passes that are not compute).
pub(super) fn create(device: &wgpu::Device, manifest: &Manifest, meshes: &[GpuMesh]) -> Vec<Option<PassBuffers>> {
    let objects = meshes.len().max(1) as u64;
    manifest
        .passes
        .iter()
        .map(|p| {
            let PassKindManifest::Compute {
                domain,
                values,
                history,
                ..
            } = &p.kind
            else {
                return None;
            };
            let slots = values.len() as u32 + u32::from(*history);
            let value_buffer = |copy: usize| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("npr values of `{}` #{copy}", p.name)),
                    size: objects * slots as u64 * 16,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            let copies = (0..if *history { 2 } else { 1 }).map(value_buffer).collect();
            let (partials, dispatch, per_object) = match domain {
                ComputeDomain::Objects => (None, None, 0),
                ComputeDomain::Vertices => {
                    let per_object = meshes
                        .iter()
                        .map(|m| element_workgroups(m.vertex_count))
                        .max()
                        .unwrap_or(0)
                        .max(1);
                    let partials = device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(&format!("npr partials of `{}`", p.name)),
                        size: objects * per_object as u64 * values.len().max(1) as u64 * 16,
                        usage: wgpu::BufferUsages::STORAGE,
                        mapped_at_creation: false,
                    });
                    let dispatch = device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(&format!("npr dispatch of `{}`", p.name)),
                        size: 16,
                        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    });
                    (Some(partials), Some(dispatch), per_object)
                }
            };
            Some(PassBuffers {
                copies,
                partials,
                dispatch,
                slots,
                partials_per_object: per_object,
            })
        })
        .collect()
}

/// Zero every value buffer (state restarts from its first value) and write
/// the dispatch uniforms.
pub(super) fn reset(queue: &wgpu::Queue, buffers: &[Option<PassBuffers>]) {
    for b in buffers.iter().flatten() {
        for c in &b.copies {
            queue.write_buffer(c, 0, &vec![0u8; c.size() as usize]);
        }
        if let Some(d) = &b.dispatch {
            queue.write_buffer(d, 0, bytemuck::cast_slice(&[b.partials_per_object, 0, 0, 0]));
        }
    }
}
