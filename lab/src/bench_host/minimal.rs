//! The minimal baseline of `npr bench host`: an independent wgpu program,
//! written with no npr code, that records the style's number of passes
//! with one target each: per render pass one pass drawing every object
//! (its block at a dynamic offset, its vertex and index buffers) into one
//! colour target and a depth buffer, per other pass and the present pass
//! one fullscreen triangle, and uploads every object's block each frame.
//! `pass_shaped.rs` is the baseline with the style's passes' shapes.

use super::{cleared, discarded_depth, target_view, uniform_group, uniform_layout};

const WGSL: &str = "
struct Object { model: mat4x4<f32> }
@group(0) @binding(0) var<uniform> object: Object;
@vertex fn vs_object(@location(0) p: vec3<f32>) -> @builtin(position) vec4<f32> {
    return object.model * vec4<f32>(p * 0.1, 1.0);
}
@vertex fn vs_full(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(f32((i << 1u) & 2u) * 2.0 - 1.0, 1.0 - f32(i & 2u) * 2.0, 0.0, 1.0);
}
@fragment fn fs() -> @location(0) vec4<f32> { return vec4<f32>(0.5, 0.5, 0.5, 1.0); }
";

/// The minimal program: its pipelines, one object buffer, one mesh.
pub(super) struct Minimal {
    object_pipeline: wgpu::RenderPipeline,
    full_pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
    objects: wgpu::Buffer,
    positions: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    depth: wgpu::TextureView,
    color: wgpu::TextureView,
    blocks: Vec<u8>,
}

/// Bytes between objects' blocks (wgpu's minimum uniform offset alignment).
const STRIDE: u64 = 256;

impl Minimal {
    pub(super) fn new(device: &wgpu::Device, objects: usize, size: u32, mesh: &npr_runner::scene::Mesh) -> Minimal {
        use wgpu::util::DeviceExt;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: None,
            source: wgpu::ShaderSource::Wgsl(WGSL.into()),
        });
        let layout = uniform_layout(device, true);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str, buffers: &[Option<wgpu::VertexBufferLayout>], depth: bool| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: None,
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: Default::default(),
                depth_stencil: depth.then(|| wgpu::DepthStencilState {
                    format: wgpu::TextureFormat::Depth32Float,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::TextureFormat::Rgba8Unorm.into())],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let attributes = [wgpu::VertexAttribute {
            format: wgpu::VertexFormat::Float32x3,
            offset: 0,
            shader_location: 0,
        }];
        let vertex = wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &attributes,
        };
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: STRIDE * objects.max(1) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let group = uniform_group(device, &layout, &buffer);
        Minimal {
            object_pipeline: pipeline("vs_object", &[Some(vertex)], true),
            full_pipeline: pipeline("vs_full", &[], false),
            group,
            objects: buffer,
            positions: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(&mesh.positions),
                usage: wgpu::BufferUsages::VERTEX,
            }),
            indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
            index_count: mesh.indices.len() as u32,
            depth: target_view(device, wgpu::TextureFormat::Depth32Float, size),
            color: target_view(device, wgpu::TextureFormat::Rgba8Unorm, size),
            blocks: vec![0; STRIDE as usize * objects.max(1)],
        }
    }

    /// Upload every object's block and record the passes: what a host's
    /// own renderer does per frame.
    pub(super) fn frame(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        models: &[glam::Mat4],
        passes: (usize, usize),
    ) {
        for (i, m) in models.iter().enumerate() {
            let at = i * STRIDE as usize;
            self.blocks[at..at + 64].copy_from_slice(bytemuck::bytes_of(&m.to_cols_array()));
        }
        queue.write_buffer(&self.objects, 0, &self.blocks);
        let (object_passes, fullscreen_passes) = passes;
        for _ in 0..object_passes {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &[Some(cleared(&self.color))],
                depth_stencil_attachment: Some(discarded_depth(&self.depth)),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.object_pipeline);
            for i in 0..models.len() {
                pass.set_bind_group(0, &self.group, &[(i as u64 * STRIDE) as u32]);
                pass.set_vertex_buffer(0, self.positions.slice(..));
                pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..self.index_count, 0, 0..1);
            }
        }
        for _ in 0..fullscreen_passes {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &[Some(cleared(&self.color))],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.full_pipeline);
            pass.set_bind_group(0, &self.group, &[0]);
            pass.draw(0..3, 0..1);
        }
    }
}
