//! The scene's meshes on the GPU: one vertex buffer per attribute and an
//! index buffer per object, uploaded once in `Renderer::new`; time-varying
//! primitives (the ocean) have their vertices rewritten in place per frame.
//! When a render pass reads `patch.weight` (Breslav et al. 2007 §3.6), every
//! mesh also gets a weight buffer (all 1), and each blended patch a second
//! mesh: its faces and n-ring with its weights, which such passes draw.

use crate::gpu_count::Create;
use crate::scene::{Mesh, Scene};
use crate::RunError;
use abi::manifest::Attribute;
use std::collections::BTreeMap;

/// The vertex format and byte stride of attribute `a` in its vertex buffer
/// (one buffer per attribute, tightly packed f32s).
pub(super) fn attribute_format(a: Attribute) -> (wgpu::VertexFormat, u64) {
    match a {
        Attribute::Position | Attribute::Normal => (wgpu::VertexFormat::Float32x3, 12),
        Attribute::Uv => (wgpu::VertexFormat::Float32x2, 8),
        Attribute::Tangent => (wgpu::VertexFormat::Float32x4, 16),
        Attribute::PatchWeight => (wgpu::VertexFormat::Float32, 4),
    }
}

pub(super) struct GpuMesh {
    pub buffers: BTreeMap<Attribute, wgpu::Buffer>,
    pub index: wgpu::Buffer,
    pub index_count: u32,
    pub vertex_count: usize,
    /// For a time-varying primitive: the time its vertices were built for.
    pub built_for_s: Option<f64>,
    /// A blended patch (`Object::blend`), with its weights: what render
    /// passes reading `patch.weight` draw instead of this mesh.
    pub blend: Option<Box<GpuMesh>>,
}

impl GpuMesh {
    /// Another handle on the same buffers (wgpu's handles are shared).
    fn share(&self) -> GpuMesh {
        GpuMesh {
            buffers: self.buffers.clone(),
            index: self.index.clone(),
            index_count: self.index_count,
            vertex_count: self.vertex_count,
            built_for_s: self.built_for_s,
            blend: self.blend.as_ref().map(|b| Box::new(b.share())),
        }
    }

    /// The mesh a render pass draws for this object: a blended patch's faces
    /// and n-ring when the pass reads `patch.weight`, else the object's own.
    pub fn drawn_by(&self, attributes: &[Attribute]) -> &GpuMesh {
        match &self.blend {
            Some(blend) if attributes.contains(&Attribute::PatchWeight) => blend,
            _ => self,
        }
    }
}

/// Every object's mesh; a time-varying primitive's is its geometry at t = 0.
/// With `weights` (a render pass reads `patch.weight`), a weight buffer for
/// each (1 at every vertex) and each blended patch's mesh with its weights.
pub(super) fn upload_scene(device: &wgpu::Device, scene: &Scene, weights: bool) -> Vec<GpuMesh> {
    // Objects of one still mesh (a host's instances of one `add_mesh`) share
    // its buffers: uploaded once, and the passes bind the same buffers for
    // each, which wgpu records faster than as many distinct ones.
    let mut shared: Vec<(*const Mesh, GpuMesh)> = Vec::new();
    scene
        .objects
        .iter()
        .map(|o| {
            let still = o.time_varying.is_none() && o.blend.is_none();
            let key = std::sync::Arc::as_ptr(&o.mesh);
            if let Some((_, gpu)) = shared.iter().find(|(k, _)| still && *k == key) {
                return gpu.share();
            }
            let mut gpu = upload_mesh(device, &o.mesh);
            // `Object::mesh` is a time-varying primitive's geometry at t = 0.
            gpu.built_for_s = o.time_varying.map(|_| 0.0);
            if weights {
                let ones = vec![1.0f32; o.mesh.vertex_count()];
                gpu.buffers.insert(
                    Attribute::PatchWeight,
                    vertex_buffer(device, "patch weights", bytemuck::cast_slice(&ones)),
                );
                if let Some(blend) = &o.blend {
                    let mut patch = upload_mesh(device, &blend.mesh);
                    patch.buffers.insert(
                        Attribute::PatchWeight,
                        vertex_buffer(device, "patch weights", bytemuck::cast_slice(&blend.weights)),
                    );
                    gpu.blend = Some(Box::new(patch));
                }
            }
            if still {
                shared.push((key, gpu.share()));
            }
            gpu
        })
        .collect()
}

/// A vertex buffer holding `data` (16 zero bytes when empty: wgpu refuses empty buffers).
fn vertex_buffer(device: &wgpu::Device, label: &str, data: &[u8]) -> wgpu::Buffer {
    device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: if data.is_empty() { &[0u8; 16] } else { data },
        usage: wgpu::BufferUsages::VERTEX,
    })
}

pub(super) fn upload_mesh(device: &wgpu::Device, mesh: &Mesh) -> GpuMesh {
    let mut buffers = BTreeMap::new();
    let mk = |label: &str, data: &[u8]| {
        device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: if data.is_empty() { &[0u8; 16] } else { data },
            // COPY_DST: time-varying primitives are rewritten per frame;
            // STORAGE, COPY_SRC: compute passes over vertices read them (time-varying ones copied each frame).
            usage: wgpu::BufferUsages::VERTEX
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC,
        })
    };
    buffers.insert(
        Attribute::Position,
        mk("positions", bytemuck::cast_slice(&mesh.positions)),
    );
    buffers.insert(Attribute::Normal, mk("normals", bytemuck::cast_slice(&mesh.normals)));
    if let Some(uv) = &mesh.uvs {
        buffers.insert(Attribute::Uv, mk("uvs", bytemuck::cast_slice(uv)));
    }
    if let Some(t) = &mesh.tangents {
        buffers.insert(Attribute::Tangent, mk("tangents", bytemuck::cast_slice(t)));
    }
    let index = device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("indices"),
        contents: if mesh.indices.is_empty() {
            &[0u8; 16]
        } else {
            bytemuck::cast_slice(&mesh.indices)
        },
        usage: wgpu::BufferUsages::INDEX,
    });
    GpuMesh {
        buffers,
        index,
        index_count: mesh.indices.len() as u32,
        vertex_count: mesh.positions.len(),
        built_for_s: None,
        blend: None,
    }
}

/// Rebuilds the vertices of time-varying primitives (the ocean of Age of
/// Sail §6.1) for `time_s` and writes them over the uploaded buffers; the
/// vertex count and indices never change, so nothing is reallocated. A
/// mesh already built for this time (another eye, a partial frame) is
/// left alone.
pub(super) fn update_time_varying(
    queue: &wgpu::Queue,
    meshes: &mut [GpuMesh],
    scene: &Scene,
    time_s: f64,
) -> Result<(), RunError> {
    for (index, object) in scene.objects.iter().enumerate() {
        let Some(primitive) = &object.time_varying else {
            continue;
        };
        let gpu = meshes.get_mut(index).ok_or_else(|| {
            RunError::Internal(format!(
                "object `{}` is not in the scene this renderer was built for",
                object.name
            ))
        })?;
        if gpu.built_for_s == Some(time_s) {
            continue;
        }
        let mesh = primitive.build_at(time_s);
        if mesh.vertex_count() != gpu.vertex_count || mesh.indices.len() as u32 != gpu.index_count {
            return Err(RunError::Internal(format!(
                "object `{}` changed its vertex count over time ({} → {})",
                object.name,
                gpu.vertex_count,
                mesh.vertex_count()
            )));
        }
        let write = |attribute: Attribute, bytes: &[u8]| {
            if let Some(buffer) = gpu.buffers.get(&attribute) {
                queue.write_buffer(buffer, 0, bytes);
            }
        };
        write(Attribute::Position, bytemuck::cast_slice(&mesh.positions));
        write(Attribute::Normal, bytemuck::cast_slice(&mesh.normals));
        if let Some(uvs) = &mesh.uvs {
            write(Attribute::Uv, bytemuck::cast_slice(uvs));
        }
        if let Some(tangents) = &mesh.tangents {
            write(Attribute::Tangent, bytemuck::cast_slice(tangents));
        }
        gpu.built_for_s = Some(time_s);
    }
    Ok(())
}
