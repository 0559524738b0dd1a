//! Drawing built strips on the GPU (Klein et al. 2000, §5: "the lines are
//! drawn as a 2D triangle strip"): the strips' vertices in NDC with their
//! depth pulled towards the eye by the stated bias, one indexed draw,
//! blended `over` the colour target and tested (`LessEqual`, no write)
//! against a depth buffer a render pass kept, so hidden edges are not drawn.
//!
//! The bias is in NDC depth units, as a render pass's unitless
//! `depth: test(pass, bias: 0.001)`: a strip lies on the surface it outlines
//! (a silhouette's inner half on the surface just inside the rim, which is
//! nearer), so without it half a line loses the test. A slope-scaled (px)
//! bias has no meaning here: the strip's own depth barely varies across it.
//! Measured in `tests/lines_gpu.rs` (256², unit sphere and cube at distance
//! 4–6): 3e-4 keeps 52 inner-half pixels of the sphere's rim and leaks no
//! hidden crease; 1e-3 keeps 400 and leaks 7 of 512 hidden-edge samples near
//! the silhouette corners; 3e-3 keeps 460 and leaks 91. A constant NDC bias
//! also shrinks in world units with distance; a view-space bias is the
//! likely fix.
//!
//! This is the draw a `lines` pass executor records; the fragment here is a
//! flat colour from a uniform until the compiler emits the pass's own.

use wgpu::util::DeviceExt;

use super::strip::Strips;

pub use abi::lines::LineVertex;

/// How strip vertices are pulled towards the eye before the depth test.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DepthBias {
    /// Subtracted from the NDC depth (`bias: 0.001`).
    pub ndc: f64,
    /// A view-space pull (`bias: N px`): every vertex moves towards the eye
    /// along its own view ray by the share `pull` of its distance, which
    /// leaves its NDC x, y unchanged. With `eye_clip_z` the clip z of the eye
    /// (view_proj · eye; its w is 0 for a perspective camera), clip space is
    /// linear, c' = (1 − r)·c + r·E, so z'/w' = z/w + r/(1 − r)·E.z/w.
    pub pull: f64,
    pub eye_clip_z: f64,
}

impl DepthBias {
    /// The pull for `px` pixels at the vertex's own depth: one pixel spans
    /// 2/(P₁₁·H) of the view depth, so r = px·2/(P₁₁·H) (exact on the
    /// view axis, up to 1/cos of the ray's angle off it towards the edges).
    pub fn view_space_px(px: f64, focal_y: f64, height_px: f64, eye_clip_z: f64) -> DepthBias {
        DepthBias {
            ndc: 0.0,
            pull: (px * 2.0 / (focal_y * height_px)).clamp(0.0, 0.5),
            eye_clip_z,
        }
    }

    fn apply(&self, depth: f64, inv_w: f64) -> f64 {
        let pulled = depth + self.pull / (1.0 - self.pull) * self.eye_clip_z * inv_w;
        pulled - self.ndc
    }
}

/// The GPU vertices of `strips` on a `size` px viewport, depth lowered by
/// `bias` (clamped to the 0..1 range, so a line at the near plane stays).
pub fn vertices(strips: &Strips, size: [f64; 2], bias: DepthBias) -> Vec<LineVertex> {
    strips
        .vertices
        .iter()
        .map(|v| LineVertex {
            position: [
                (v.px.x / size[0] * 2.0 - 1.0) as f32,
                (1.0 - v.px.y / size[1] * 2.0) as f32,
                bias.apply(v.depth, v.inv_w).clamp(0.0, 1.0) as f32,
                v.s as f32,
            ],
            line: [v.base.x as f32, v.base.y as f32, v.across as f32, 0.0],
        })
        .collect()
}

const SHADER: &str = r#"
@group(0) @binding(0) var<uniform> ink: vec4<f32>;

@vertex
fn vs(@location(0) p: vec4<f32>) -> @builtin(position) vec4<f32> {
    return vec4<f32>(p.xyz, 1.0);
}

@fragment
fn fs() -> @location(0) vec4<f32> {
    return ink;
}
"#;

/// A pipeline drawing strips in one colour over a colour target, tested
/// against a `Depth32Float` buffer.
pub struct LinesPipeline {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

impl LinesPipeline {
    pub fn new(device: &wgpu::Device, color_format: wgpu::TextureFormat) -> LinesPipeline {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("lines"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("lines"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("lines"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("lines"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<LineVertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x4],
                })],
            },
            // Strips wind both ways along a wave: no culling.
            primitive: wgpu::PrimitiveState {
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth32Float,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::LessEqual),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: color_format,
                    blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        LinesPipeline { pipeline, layout }
    }

    /// Records the strips' draw into `color` (loaded, blended over) tested
    /// against `depth` (loaded, kept).
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        vertices: &[LineVertex],
        indices: &[u32],
        ink: [f32; 4],
    ) {
        if indices.is_empty() {
            return;
        }
        let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("lines vertices"),
            contents: bytemuck::cast_slice(vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("lines indices"),
            contents: bytemuck::cast_slice(indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("lines ink"),
            contents: bytemuck::cast_slice(&ink),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("lines"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            }],
        });
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("lines"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: color,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.set_index_buffer(index_buffer.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..indices.len() as u32, 0, 0..1);
    }
}
