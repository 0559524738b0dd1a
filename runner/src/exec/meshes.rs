//! The scene's meshes on the GPU: one vertex buffer per attribute and an
//! index buffer per object, uploaded once in `Renderer::new`; time-varying
//! primitives (the ocean) have their vertices rewritten in place per frame,
//! and so does an object given another mesh of the same topology (a host's
//! deforming mesh: `StyleRuntime::update_mesh`, docs/decisions/0045);
//! an object playing a clip has buffers of its own, which the GPU
//! deformation stage writes (`deform.rs`, docs/decisions/0053).
//! When a render pass reads `patch.weight` (Breslav et al. 2007 §3.6), every
//! mesh also gets a weight buffer (all 1), and each blended patch a second
//! mesh: its faces and n-ring with its weights, which such passes draw.

use crate::gpu_count::Create;
use crate::scene::{Mesh, Scene};
use crate::RunError;
use npr_abi::manifest::Attribute;
use std::collections::BTreeMap;
use std::sync::Arc;

/// The vertex format and byte stride of attribute `a` in its vertex buffer
/// (one buffer per attribute, tightly packed f32s).
pub(super) fn attribute_format(a: Attribute) -> (wgpu::VertexFormat, u64) {
    match a {
        Attribute::Position | Attribute::Normal | Attribute::PreviousPosition => (wgpu::VertexFormat::Float32x3, 12),
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
    /// The mesh whose vertices the buffers hold (a time-varying
    /// primitive's geometry at t = 0): an object given another one of the
    /// same topology has its vertices written over them (`update_deformed`).
    pub source: Arc<Mesh>,
    /// Bumped whenever the vertex buffers are written after their upload
    /// (a time-varying or deformed mesh): compute passes copy a member's
    /// vertices again when it changed.
    pub vertex_revision: u64,
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
            source: self.source.clone(),
            vertex_revision: self.vertex_revision,
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
            let still = shares_buffers(o);
            let key = std::sync::Arc::as_ptr(&o.mesh);
            if let Some((_, gpu)) = shared.iter().find(|(k, _)| still && *k == key) {
                return gpu.share();
            }
            let mut gpu = upload_mesh(device, &o.mesh, o.mesh.clone());
            if o.deforms() {
                // Its previous pose, which the deformation stage keeps
                // (`deform.rs`); every other mesh's is its position buffer.
                gpu.buffers.insert(
                    Attribute::PreviousPosition,
                    attribute_buffer(device, "previous positions", bytemuck::cast_slice(&o.mesh.positions)),
                );
            }
            // `Object::mesh` is a time-varying primitive's geometry at t = 0.
            gpu.built_for_s = o.time_varying.map(|_| 0.0);
            if weights {
                let ones = vec![1.0f32; o.mesh.vertex_count()];
                gpu.buffers.insert(
                    Attribute::PatchWeight,
                    vertex_buffer(device, "patch weights", bytemuck::cast_slice(&ones)),
                );
                if let Some(blend) = &o.blend {
                    // Derived from the object's mesh, never deformed (E0603).
                    let mut patch = upload_mesh(device, &blend.mesh, o.mesh.clone());
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

/// `mesh`'s buffers; `source` is the mesh they hold the vertices of
/// ([`GpuMesh::source`]).
pub(super) fn upload_mesh(device: &wgpu::Device, mesh: &Mesh, source: Arc<Mesh>) -> GpuMesh {
    let mut buffers = BTreeMap::new();
    let mk = |label: &str, data: &[u8]| attribute_buffer(device, label, data);
    let positions = mk("positions", bytemuck::cast_slice(&mesh.positions));
    // `position.previous` of a mesh nothing deforms: its current position.
    buffers.insert(Attribute::PreviousPosition, positions.clone());
    buffers.insert(Attribute::Position, positions);
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
        source,
        vertex_revision: 0,
        blend: None,
    }
}

/// A vertex attribute's buffer holding `data` (16 zero bytes when empty).
fn attribute_buffer(device: &wgpu::Device, label: &str, data: &[u8]) -> wgpu::Buffer {
    device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: if data.is_empty() { &[0u8; 16] } else { data },
        // COPY_DST: time-varying primitives are rewritten per frame;
        // STORAGE, COPY_SRC: compute passes over vertices read them (time-varying ones
        // copied each frame), the deformation stage writes them and copies the positions.
        usage: wgpu::BufferUsages::VERTEX
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC,
    })
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
        write_vertices(queue, gpu, &mesh);
        gpu.built_for_s = Some(time_s);
        gpu.vertex_revision += 1;
    }
    Ok(())
}

/// Writes the vertices of every object whose mesh is not the one its
/// buffers hold ([`GpuMesh::source`]) over those buffers, in place: a
/// host's deforming mesh (`StyleRuntime::update_mesh` gives its objects
/// a new `Mesh` of the same topology each time it deforms). Each group of
/// objects sharing buffers (instances of one still mesh) is written once.
/// Nothing is written, and the error says why, when the new mesh does not
/// fit the buffers (another vertex count, other indices, an attribute
/// added or dropped) or when objects sharing buffers were given different
/// meshes: each of those is a new scene (`Renderer::set_scene`). A
/// time-varying primitive's or a blended patch's mesh is not read (their
/// vertices are made from the primitive and the patch division, as
/// before). A frame without a deformed mesh costs one pointer comparison
/// per object.
pub(super) fn update_deformed(queue: &wgpu::Queue, meshes: &mut [GpuMesh], scene: &Scene) -> Result<(), RunError> {
    let deformed = |i: usize| !Arc::ptr_eq(&meshes[i].source, &scene.objects[i].mesh);
    if !(0..meshes.len().min(scene.objects.len())).any(deformed) {
        return Ok(());
    }
    // An object playing a clip has buffers of its own (`shares_buffers`),
    // which the GPU deformation stage writes (`deform.rs`, decision 0053):
    // its mesh of the frame, deformed on the CPU for the lines and the
    // light bounds, is not written (the loop below skips it).
    // Per group of shared buffers (by the mesh they were uploaded from):
    // the first deformed object's index and its new mesh.
    let mut moves: Vec<(*const Mesh, usize)> = Vec::new();
    for (i, (object, gpu)) in scene.objects.iter().zip(meshes.iter()).enumerate() {
        // An animated primitive's and a blended patch's vertices are made
        // from the primitive and the division, not read from their mesh.
        if Arc::ptr_eq(&gpu.source, &object.mesh) || !shares_buffers(object) {
            continue;
        }
        fits(object, gpu)?;
        let old = Arc::as_ptr(&gpu.source);
        match moves.iter().find(|(o, _)| *o == old) {
            Some(&(_, first)) if !Arc::ptr_eq(&scene.objects[first].mesh, &object.mesh) => {
                return Err(shared_apart(&scene.objects[first].name, &object.name));
            }
            Some(_) => {}
            None => moves.push((old, i)),
        }
    }
    // An object still drawing a group's old mesh would draw its new vertices.
    for (object, gpu) in scene.objects.iter().zip(meshes.iter()) {
        let old = Arc::as_ptr(&gpu.source);
        if let Some(&(_, first)) = moves.iter().find(|(o, _)| *o == old) {
            if shares_buffers(object) && !Arc::ptr_eq(&scene.objects[first].mesh, &object.mesh) {
                return Err(shared_apart(&scene.objects[first].name, &object.name));
            }
        }
    }
    for &(old, first) in &moves {
        let mesh = &scene.objects[first].mesh;
        let gpu = &meshes[first];
        write_vertices(queue, gpu, mesh);
        for (object, gpu) in scene.objects.iter().zip(meshes.iter_mut()) {
            if Arc::as_ptr(&gpu.source) == old && shares_buffers(object) {
                gpu.source = mesh.clone();
                gpu.vertex_revision += 1;
            }
        }
    }
    Ok(())
}

/// Writes `mesh`'s vertex attributes over `gpu`'s buffers, in place (the
/// buffers `gpu` has: a pass reading no tangents made none).
fn write_vertices(queue: &wgpu::Queue, gpu: &GpuMesh, mesh: &Mesh) {
    let write = |attribute: Attribute, bytes: &[u8]| {
        if let Some(buffer) = gpu.buffers.get(&attribute) {
            if !bytes.is_empty() {
                queue.write_buffer(buffer, 0, bytes);
            }
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
}

/// Whether `upload_scene` shares the object's buffers with the other
/// objects of its mesh (a still mesh's, neither animated nor a patch). An
/// object playing a clip or posed by its host has buffers of its own:
/// objects of one file may play other clips, or the same at other times,
/// and a host's instances of one skinned mesh have poses of their own.
fn shares_buffers(object: &crate::scene::Object) -> bool {
    object.time_varying.is_none() && object.blend.is_none() && !object.deforms()
}

/// Whether `object`'s (new) mesh can be written over `gpu`'s buffers.
fn fits(object: &crate::scene::Object, gpu: &GpuMesh) -> Result<(), RunError> {
    let refuse = |why: String| {
        RunError::User(vec![npr_diag::Diagnostic::error(
            npr_diag::codes::BAD_SCENE,
            format!("object `{}` was given another mesh: {why}", object.name),
        )
        .with_help(
            "a frame may give an object a deformed copy of its mesh (same vertex count, same \
             indices, same attributes); give other meshes with Renderer::set_scene",
        )])
    };
    let (new, old) = (&object.mesh, &gpu.source);
    if new.vertex_count() != old.vertex_count() {
        return Err(refuse(format!(
            "it has {} vertices, its buffers {}",
            new.vertex_count(),
            old.vertex_count()
        )));
    }
    if new.indices != old.indices {
        return Err(refuse("its triangles are not the same".into()));
    }
    if new.normals.len() != old.normals.len()
        || new.uvs.as_ref().map(Vec::len) != old.uvs.as_ref().map(Vec::len)
        || new.tangents.as_ref().map(Vec::len) != old.tangents.as_ref().map(Vec::len)
    {
        return Err(refuse("its normals, UVs or tangents are not the same arrays".into()));
    }
    Ok(())
}

/// Objects that share one mesh's buffers were given different meshes.
fn shared_apart(first: &str, other: &str) -> RunError {
    RunError::User(vec![npr_diag::Diagnostic::error(
        npr_diag::codes::BAD_SCENE,
        format!("objects `{first}` and `{other}` drew one mesh and were given different ones"),
    )
    .with_help(
        "give every object of a deformed mesh the same new mesh, or other meshes with Renderer::set_scene",
    )])
}
