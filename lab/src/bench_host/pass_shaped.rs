//! The pass-shaped baseline of `npr bench host`: an independent wgpu
//! program, written with no npr code, that records per pass of the style a
//! pass of the same shape, read from the manifest as data: the pass's
//! colour attachments in their formats at the pass's scale, a depth
//! attachment for a render pass, one vertex buffer per attribute a render
//! pass reads, and a pipeline of its own per pass (as a program drawing
//! the same targets must have); then the present pass into one target.
//! A render pass binds a frame block once and each object's block at a
//! dynamic offset, binds the mesh's buffers once (every object shares the
//! mesh) and draws every object; a compute pass is one dispatch of an
//! empty shader; any other pass draws a fullscreen triangle. One
//! `write_buffer` per frame uploads the frame block and every object's.
//! Its shaders do nothing a style does: what it measures
//! is the API work a frame of these passes costs on the CPU at least, so
//! npr's time over it is npr's own work (uniforms, scene, its recording).
//! `minimal.rs` is the same with one target per pass.

use super::{cleared, discarded_depth, target_view, uniform_group, uniform_layout};
use crate::bench_overhead::setup::{scaled, texture_format};
use abi::manifest::{Manifest, PassKindManifest};

/// Bytes between blocks (wgpu's minimum uniform offset alignment): the
/// frame block at 0, object `i`'s at `STRIDE * (1 + i)`.
const STRIDE: u64 = 256;

/// WebGPU's default `maxColorAttachments`.
const MAX_COLORS: usize = 8;

/// The shader of a pass with `outputs` colour outputs: the object's model
/// times the frame's matrix, or a fullscreen triangle; a constant colour.
fn wgsl(outputs: usize) -> String {
    let fields: String = (0..outputs)
        .map(|i| format!("@location({i}) c{i}: vec4<f32>, "))
        .collect();
    let writes: String = (0..outputs).map(|i| format!("o.c{i} = vec4<f32>(0.5); ")).collect();
    format!(
        "struct Block {{ m: mat4x4<f32> }}
@group(0) @binding(0) var<uniform> frame: Block;
@group(1) @binding(0) var<uniform> object: Block;
@vertex fn vs_object(@location(0) p: vec3<f32>) -> @builtin(position) vec4<f32> {{
    return frame.m * object.m * vec4<f32>(p, 1.0);
}}
@vertex fn vs_full(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {{
    return frame.m * vec4<f32>(f32((i << 1u) & 2u) * 2.0 - 1.0, 1.0 - f32(i & 2u) * 2.0, 0.0, 1.0);
}}
struct Out {{ {fields}}}
@fragment fn fs() -> Out {{ var o: Out; {writes}return o; }}
"
    )
}

/// A pass that draws: its pipeline, colour targets and, for a render
/// pass, its depth buffer and vertex buffer count.
struct Draw {
    pipeline: wgpu::RenderPipeline,
    colors: Vec<wgpu::TextureView>,
    depth: Option<wgpu::TextureView>,
    /// `Some(n)`: a render pass reading `n` vertex attributes.
    vertex_buffers: Option<usize>,
}

/// A drawing pass's colour formats, side and vertex buffer count
/// (`Some` for a render pass).
type DrawShape = (Vec<wgpu::TextureFormat>, u32, Option<usize>);

/// What the program records for one pass of the style.
enum Pass {
    Draw(Draw),
    /// A compute pass of the style (it writes no target): one dispatch of
    /// an empty shader.
    Dispatch(wgpu::ComputePipeline),
}

pub(super) struct PassShaped {
    passes: Vec<Pass>,
    frame_group: wgpu::BindGroup,
    object_group: wgpu::BindGroup,
    blocks_buffer: wgpu::Buffer,
    /// One copy of the mesh's positions per vertex buffer slot (a style
    /// reads each attribute from its own buffer).
    vertex: Vec<wgpu::Buffer>,
    indices: wgpu::Buffer,
    index_count: u32,
    blocks: Vec<u8>,
}

impl PassShaped {
    pub(super) fn new(
        device: &wgpu::Device,
        manifest: &Manifest,
        objects: usize,
        size: u32,
        mesh: &runner::scene::Mesh,
    ) -> PassShaped {
        use wgpu::util::DeviceExt;
        let frame_layout = uniform_layout(device, false);
        let object_layout = uniform_layout(device, true);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&frame_layout), Some(&object_layout)],
            immediate_size: 0,
        });
        let side = |scale: f64| scaled((size, size), scale).0;
        // (formats, side, vertex buffers) per pass that draws, `None` for a
        // compute pass; then the present pass.
        let mut shapes: Vec<Option<DrawShape>> = manifest
            .passes
            .iter()
            .map(|p| {
                if matches!(p.kind, PassKindManifest::Compute { .. }) {
                    return None;
                }
                let formats = p
                    .outputs
                    .iter()
                    .map(|&t| texture_format(manifest.targets[t].format))
                    .collect();
                let vertex_buffers = match &p.kind {
                    PassKindManifest::Render { attributes, .. } => Some(attributes.len().max(1)),
                    _ => None,
                };
                Some((formats, side(p.scale), vertex_buffers))
            })
            .collect();
        shapes.push(Some((vec![wgpu::TextureFormat::Rgba8Unorm], size, None)));
        let most_buffers = shapes.iter().flatten().filter_map(|s| s.2).max().unwrap_or(1);
        let compute_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: None,
            source: wgpu::ShaderSource::Wgsl("@compute @workgroup_size(1) fn cs() {}".into()),
        });
        let attributes: Vec<[wgpu::VertexAttribute; 1]> = (0..most_buffers)
            .map(|slot| {
                [wgpu::VertexAttribute {
                    format: wgpu::VertexFormat::Float32x3,
                    offset: 0,
                    shader_location: slot as u32,
                }]
            })
            .collect();
        let passes = shapes
            .into_iter()
            .map(|shape| {
                let Some((formats, side, vertex_buffers)) = shape else {
                    return Pass::Dispatch(device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: None,
                        layout: None,
                        module: &compute_module,
                        entry_point: Some("cs"),
                        compilation_options: Default::default(),
                        cache: None,
                    }));
                };
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: None,
                    source: wgpu::ShaderSource::Wgsl(wgsl(formats.len()).into()),
                });
                let buffers: Vec<Option<wgpu::VertexBufferLayout>> = attributes[..vertex_buffers.unwrap_or(0)]
                    .iter()
                    .map(|a| {
                        Some(wgpu::VertexBufferLayout {
                            array_stride: 12,
                            step_mode: wgpu::VertexStepMode::Vertex,
                            attributes: a,
                        })
                    })
                    .collect();
                let targets: Vec<Option<wgpu::ColorTargetState>> = formats.iter().map(|&f| Some(f.into())).collect();
                let depth = vertex_buffers.map(|_| wgpu::DepthStencilState {
                    format: wgpu::TextureFormat::Depth32Float,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                });
                let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: None,
                    layout: Some(&pipeline_layout),
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some(if vertex_buffers.is_some() {
                            "vs_object"
                        } else {
                            "vs_full"
                        }),
                        compilation_options: Default::default(),
                        buffers: &buffers,
                    },
                    primitive: Default::default(),
                    depth_stencil: depth,
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("fs"),
                        compilation_options: Default::default(),
                        targets: &targets,
                    }),
                    multiview_mask: None,
                    cache: None,
                });
                Pass::Draw(Draw {
                    pipeline,
                    colors: formats.iter().map(|&f| target_view(device, f, side)).collect(),
                    depth: vertex_buffers.map(|_| target_view(device, wgpu::TextureFormat::Depth32Float, side)),
                    vertex_buffers,
                })
            })
            .collect();
        let blocks_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: STRIDE * (1 + objects) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        PassShaped {
            passes,
            frame_group: uniform_group(device, &frame_layout, &blocks_buffer),
            object_group: uniform_group(device, &object_layout, &blocks_buffer),
            vertex: (0..most_buffers)
                .map(|_| {
                    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: None,
                        contents: bytemuck::cast_slice(&mesh.positions),
                        usage: wgpu::BufferUsages::VERTEX,
                    })
                })
                .collect(),
            indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
            index_count: mesh.indices.len() as u32,
            blocks_buffer,
            blocks: vec![0; (STRIDE as usize) * (1 + objects)],
        }
    }

    /// Upload the frame's and every object's block and record the passes.
    pub(super) fn frame(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        view_proj: glam::Mat4,
        models: &[glam::Mat4],
    ) {
        self.blocks[..64].copy_from_slice(bytemuck::bytes_of(&view_proj.to_cols_array()));
        for (i, m) in models.iter().enumerate() {
            let at = (1 + i) * STRIDE as usize;
            self.blocks[at..at + 64].copy_from_slice(bytemuck::bytes_of(&m.to_cols_array()));
        }
        queue.write_buffer(&self.blocks_buffer, 0, &self.blocks);
        for pass in &self.passes {
            let p = match pass {
                Pass::Draw(draw) => draw,
                Pass::Dispatch(pipeline) => {
                    let mut pass = encoder.begin_compute_pass(&Default::default());
                    pass.set_pipeline(pipeline);
                    pass.dispatch_workgroups(1, 1, 1);
                    continue;
                }
            };
            // On the stack, as a program that knows its passes writes them.
            let colors: [Option<wgpu::RenderPassColorAttachment>; MAX_COLORS] =
                std::array::from_fn(|i| p.colors.get(i).map(cleared));
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &colors[..p.colors.len()],
                depth_stencil_attachment: p.depth.as_ref().map(discarded_depth),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&p.pipeline);
            pass.set_bind_group(0, &self.frame_group, &[]);
            match p.vertex_buffers {
                Some(buffers) => {
                    for (slot, buffer) in self.vertex[..buffers].iter().enumerate() {
                        pass.set_vertex_buffer(slot as u32, buffer.slice(..));
                    }
                    pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
                    for i in 0..models.len() {
                        pass.set_bind_group(1, &self.object_group, &[((1 + i) as u64 * STRIDE) as u32]);
                        pass.draw_indexed(0..self.index_count, 0, 0..1);
                    }
                }
                None => {
                    pass.set_bind_group(1, &self.object_group, &[STRIDE as u32]);
                    pass.draw(0..3, 0..1);
                }
            }
        }
    }
}
