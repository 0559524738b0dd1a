//! The host's depth as a depth buffer (`depth: test(input)`, issue 47): a
//! pass of npr's own that draws over a host's frame is hidden where the
//! host's surfaces are nearer. The `input(depth)` texture holds the
//! language's convention (a view distance in metres, 0 where nothing was
//! hit, converted at the edge by `crate::inputs`); each frame, before the
//! passes, a fullscreen draw turns it into window depth through the frame
//! camera's projection (`Frame::proj`, the matrix npr's own passes project
//! with, so both depths are of one projection) and writes `frag_depth`
//! into a `Depth32Float` texture per eye slot and input. A render pass
//! loads that texture as its attachment and a lines pass reads it in its
//! shader, exactly as a depth an earlier pass kept. The pipeline is made
//! once per renderer, the textures and bind groups once per size
//! (`resources.rs`): a frame records the draw and allocates nothing.

use crate::gpu_count::Create;
use npr_abi::manifest::{DepthMode, Manifest, PassKindManifest};

/// The draw. `frame.proj` maps a view-space point (0, 0, −d) to clip space;
/// its z/w is the window depth npr's own rasteriser gives a surface at view
/// distance d (x and y do not change it in a perspective or orthographic
/// projection). Nothing hit (0) is the far plane.
pub(crate) fn host_depth_wgsl() -> String {
    format!(
        "{frame}
@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var host_depth: texture_2d<f32>;

{vertex}
@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @builtin(frag_depth) f32 {{
    let d = textureLoad(host_depth, vec2<i32>(p.xy), 0).r;
    if d <= 0.0 {{
        return 1.0;
    }}
    let clip = frame.proj * vec4<f32>(0.0, 0.0, -d, 1.0);
    return clamp(clip.z / clip.w, 0.0, 1.0);
}}
",
        frame = npr_abi::FRAME_WGSL,
        vertex = crate::fullscreen::fullscreen_vertex_wgsl!()
    )
}

/// The input textures (indices into `Manifest::textures`) some pass tests
/// its depth against, each once, in index order.
pub(super) fn tested_inputs(manifest: &Manifest) -> Vec<usize> {
    let mut inputs: Vec<usize> = manifest
        .passes
        .iter()
        .filter_map(|p| match &p.kind {
            PassKindManifest::Render {
                depth: DepthMode::TestInput { input, .. },
                ..
            }
            | PassKindManifest::Lines {
                depth: DepthMode::TestInput { input, .. },
                ..
            } => Some(*input),
            _ => None,
        })
        .collect();
    inputs.sort_unstable();
    inputs.dedup();
    inputs
}

/// The pipeline that writes the host's depth, made when a pass tests
/// against it.
pub(super) struct HostDepthPipeline {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

/// One host depth buffer of one eye slot at the current size: its view
/// (the passes' attachment) and the draw's bind group (the slot's frame
/// block, the input texture).
pub(super) struct HostDepthDraw {
    pub view: wgpu::TextureView,
    pub group: wgpu::BindGroup,
}

impl HostDepthPipeline {
    pub fn new(device: &wgpu::Device) -> HostDepthPipeline {
        let module = device.make_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("npr host depth"),
            source: wgpu::ShaderSource::Wgsl(host_depth_wgsl().into()),
        });
        let layout = device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("npr host depth"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(npr_abi::FRAME_UNIFORM_SIZE),
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.make_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("npr host depth"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.make_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("npr host depth"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth32Float,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[],
            }),
            multiview_mask: None,
            cache: None,
        });
        HostDepthPipeline { pipeline, layout }
    }

    /// The bind group of one eye slot's draw.
    pub fn bind(&self, device: &wgpu::Device, frame: &wgpu::Buffer, input: &wgpu::TextureView) -> wgpu::BindGroup {
        device.make_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("npr host depth"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: frame.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(input),
                },
            ],
        })
    }

    /// Record the draws: every host depth buffer written from its input
    /// for this frame (after the frame blocks are copied, before any pass).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, draws: &[HostDepthDraw]) {
        for draw in draws {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("npr host depth"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &draw.view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &draw.group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}
