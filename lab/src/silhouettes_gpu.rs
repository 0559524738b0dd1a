//! Silhouette classification in a wgpu compute pass: the per-frame part of
//! the `lines` pass (Klein et al. 2000 §5: silhouettes are the edges whose
//! two faces differ in facing from the current eye) that a GPU could take
//! over, with its read-back of one flag bit per edge and their unpacking
//! into the edge indices that chaining needs. `npr bench lines` times it
//! against the CPU's `EdgeMesh::silhouettes` on the same meshes, and
//! `tests/gpu/lines_classify.rs` checks that both give the same edges. It is
//! not wired into the renderer (docs/decisions/0030, "Lines are built on
//! the CPU", says why with the numbers).
//!
//! What is static per mesh (the face planes and each edge's two faces) is
//! uploaded once in [`GpuSilhouettes::new`]; per eye only 32 bytes go up
//! and ⌈edges / 32⌉ words come back.

use glam::DVec3;
use npr_runner::lines::edges::EdgeMesh;
use npr_runner::{Gpu, RunError};

const SHADER: &str = include_str!("silhouettes_gpu/classify.wgsl");
const WORKGROUP: u32 = 64;
/// The most workgroups in one dispatch dimension (WebGPU's default limit).
const MAX_GROUPS_X: u32 = 65535;
/// `edge_faces` of an edge without exactly two faces.
const NO_FACE: u32 = u32::MAX;

/// One mesh's classification pipeline and buffers.
pub struct GpuSilhouettes {
    pipeline: wgpu::ComputePipeline,
    group: wgpu::BindGroup,
    params: wgpu::Buffer,
    flags: wgpu::Buffer,
    readback: wgpu::Buffer,
    edges: u32,
    words: u32,
    groups: (u32, u32),
    row_words: u32,
}

fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// The face planes (n, −n·corner) in f64, rounded to f32 once: the test
/// `n·eye + d > 0` is then `EdgeMesh::is_front`'s `n·(eye − corner) > 0`
/// up to f32 rounding (exact when the plane and the eye are exact in f32,
/// as for a cube's faces).
pub fn face_planes(mesh: &EdgeMesh) -> Vec<[f32; 4]> {
    mesh.faces
        .iter()
        .zip(&mesh.normals)
        .map(|(f, n)| {
            let d = -n.dot(mesh.positions[f[0] as usize]);
            [n.x as f32, n.y as f32, n.z as f32, d as f32]
        })
        .collect()
}

impl GpuSilhouettes {
    /// Upload `mesh`'s static data and build the pipeline.
    pub fn new(gpu: &Gpu, mesh: &EdgeMesh) -> Result<GpuSilhouettes, RunError> {
        let device = &gpu.device;
        let edges =
            u32::try_from(mesh.edges.len()).map_err(|_| RunError::Internal("more edges than a u32 counts".into()))?;
        let words = edges.div_ceil(32);
        let needed = words.div_ceil(WORKGROUP).max(1);
        let groups = (needed.min(MAX_GROUPS_X), needed.div_ceil(MAX_GROUPS_X));
        let row_words = groups.0 * WORKGROUP;
        let mut planes = face_planes(mesh);
        if planes.is_empty() {
            planes.push([0.0; 4]); // a storage binding may not be empty
        }
        let mut edge_faces: Vec<[u32; 2]> = mesh
            .edges
            .iter()
            .map(|e| match e.faces[..] {
                [f, g] => [f, g],
                _ => [NO_FACE, NO_FACE],
            })
            .collect();
        if edge_faces.is_empty() {
            edge_faces.push([NO_FACE, NO_FACE]);
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let init = |label: &str, bytes: &[u8], usage: wgpu::BufferUsages| {
            wgpu::util::DeviceExt::create_buffer_init(
                device,
                &wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents: bytes,
                    usage,
                },
            )
        };
        let planes_buffer = init(
            "silhouette planes",
            bytemuck::cast_slice(&planes),
            wgpu::BufferUsages::STORAGE,
        );
        let faces_buffer = init(
            "silhouette edge faces",
            bytemuck::cast_slice(&edge_faces),
            wgpu::BufferUsages::STORAGE,
        );
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("silhouette params"),
            size: 32,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let flag_bytes = u64::from(words.max(1)) * 4;
        let flags = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("silhouette flags"),
            size: flag_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("silhouette flags readback"),
            size: flag_bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("silhouettes"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                storage(1, true),
                storage(2, true),
                storage(3, false),
            ],
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("silhouettes"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: planes_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: faces_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: flags.as_entire_binding(),
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("silhouettes"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("silhouettes"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("silhouettes"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("classify"),
            compilation_options: Default::default(),
            cache: None,
        });
        if let Some(e) = pollster::block_on(oom.pop()) {
            return Err(RunError::OutOfMemory(format!("silhouette buffers: {e}")));
        }
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(RunError::Internal(format!("the silhouette pipeline was refused: {e}")));
        }
        Ok(GpuSilhouettes {
            pipeline,
            group,
            params,
            flags,
            readback,
            edges,
            words,
            groups,
            row_words,
        })
    }

    /// The silhouette edges from `eye` (object space), as indices into
    /// `mesh.edges` in increasing order, as `EdgeMesh::silhouettes` gives
    /// them: the eye written, one dispatch, the flags copied back, the GPU
    /// waited for, the bits unpacked.
    pub fn classify(&self, gpu: &Gpu, eye: DVec3) -> Result<Vec<u32>, RunError> {
        let mut params = [0u8; 32];
        params[..12].copy_from_slice(bytemuck::cast_slice(&[eye.x as f32, eye.y as f32, eye.z as f32]));
        params[16..28].copy_from_slice(bytemuck::cast_slice(&[self.edges, self.words, self.row_words]));
        gpu.queue.write_buffer(&self.params, 0, &params);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("silhouettes"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.group, &[]);
            pass.dispatch_workgroups(self.groups.0, self.groups.1, 1);
        }
        encoder.copy_buffer_to_buffer(&self.flags, 0, &self.readback, 0, self.flags.size());
        gpu.queue.submit([encoder.finish()]);
        let view = self.map_readback(gpu)?;
        let mut out = Vec::new();
        for (w, &bits) in bytemuck::cast_slice::<u8, u32>(&view)
            .iter()
            .enumerate()
            .take(self.words as usize)
        {
            let mut rest = bits;
            while rest != 0 {
                out.push(w as u32 * 32 + rest.trailing_zeros());
                rest &= rest - 1;
            }
        }
        drop(view);
        self.readback.unmap();
        Ok(out)
    }

    /// The round trip of [`Self::classify`] without its dispatch: the flags
    /// copied back, the GPU waited for, the buffer mapped and unmapped.
    /// What `classify` costs beyond this is the kernel (and unpacking).
    pub fn read_back_only(&self, gpu: &Gpu) -> Result<(), RunError> {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.flags, 0, &self.readback, 0, self.flags.size());
        gpu.queue.submit([encoder.finish()]);
        drop(self.map_readback(gpu)?);
        self.readback.unmap();
        Ok(())
    }

    /// Map the read-back buffer once the GPU is done with it.
    fn map_readback(&self, gpu: &Gpu) -> Result<wgpu::BufferView, RunError> {
        let slice = self.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        crate::bench::wait_idle(gpu)?;
        rx.recv()
            .map_err(|e| RunError::Internal(format!("silhouette read-back channel closed: {e}")))?
            .map_err(|e| RunError::Internal(format!("silhouette read-back failed: {e}")))?;
        slice
            .get_mapped_range()
            .map_err(|e| RunError::Internal(format!("silhouette read-back range: {e:?}")))
    }
}
