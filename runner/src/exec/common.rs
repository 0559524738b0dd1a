//! What every pass executor shares, and nothing that dispatches to them:
//! the context a pass is recorded with ([`EncodeContext`], [`Timestamps`]),
//! its shader and override constants ([`PassShader`]), and the helpers the
//! render-pipeline kinds build and begin their passes with. The executors
//! (`render_pass`, `image_pass`, `tiled_pass`, `compute_pass`, `lines_pass`)
//! import this module; `pass.rs`, which dispatches to them, imports them and
//! this, so no executor imports the dispatcher.

use super::meshes::GpuMesh;
use super::sized::{wgpu_format, SizedPass};
use crate::gpu_count::Create;
use crate::RunError;
use npr_abi::formats::HalfRounding;
use npr_abi::manifest::*;

/// What a pass may read when it is recorded, besides its own state and its
/// [`SizedPass`]: the scene's meshes and the group 1 shared by passes
/// without per-object textures.
pub(super) struct EncodeContext<'a> {
    pub meshes: &'a [GpuMesh],
    pub object_group: &'a wgpu::BindGroup,
    /// Bytes between two objects' blocks (the dynamic offset step).
    pub object_stride: u64,
    /// The frame's parity (which copy of history textures and state buffers it writes).
    pub parity: usize,
}

/// GPU timestamps of one pass (benchmarks): the first eye slot writes the
/// beginning, the last the end.
pub(super) struct Timestamps<'a> {
    pub query_set: &'a wgpu::QuerySet,
    pub beginning: Option<u32>,
    pub end: Option<u32>,
}

impl Timestamps<'_> {
    pub fn compute_pass(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: self.query_set,
            beginning_of_pass_write_index: self.beginning,
            end_of_pass_write_index: self.end,
        }
    }

    pub fn render_pass(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: self.query_set,
            beginning_of_pass_write_index: self.beginning,
            end_of_pass_write_index: self.end,
        }
    }
}

pub(super) fn clear_color(pass: &PassManifest) -> wgpu::Color {
    wgpu::Color {
        r: pass.clear[0],
        g: pass.clear[1],
        b: pass.clear[2],
        a: pass.clear[3],
    }
}

/// Begin a render pass over `sized`'s colour views (cleared to `clear`) and
/// the depth attachment `depth` with its load and store operations, if any.
/// The most colour attachments a pass has: the compiler refuses a pass
/// writing more targets (`npr_diag::limits`).
const MAX_COLOR_ATTACHMENTS: usize = npr_diag::limits::MAX_TARGETS_PER_PASS;

pub(super) fn begin_render_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    clear: wgpu::Color,
    sized: &SizedPass,
    depth: Option<(&wgpu::TextureView, wgpu::Operations<f32>)>,
    timestamps: Option<&Timestamps>,
) -> wgpu::RenderPass<'e> {
    // On the stack: a frame records a dozen passes and allocates nothing for them.
    let mut attachments: [Option<wgpu::RenderPassColorAttachment>; MAX_COLOR_ATTACHMENTS] = Default::default();
    for (slot, view) in attachments.iter_mut().zip(&sized.color_views) {
        *slot = Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(clear),
                store: wgpu::StoreOp::Store,
            },
        });
    }
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &attachments[..sized.color_views.len().min(MAX_COLOR_ATTACHMENTS)],
        depth_stencil_attachment: depth.map(|(view, ops)| wgpu::RenderPassDepthStencilAttachment {
            view,
            depth_ops: Some(ops),
            stencil_ops: None,
        }),
        timestamp_writes: timestamps.map(Timestamps::render_pass),
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// The fixed-function blend of a [`Blend`] mode (`s` the fragment, `d` the
/// target): `over` is straight-alpha over, `add` s + d and `multiply` s × d
/// on every channel, alpha included; `replace` is no blending.
pub(super) fn blend_state(blend: Blend) -> Option<wgpu::BlendState> {
    use wgpu::{BlendComponent, BlendFactor, BlendOperation};
    let both = |c: BlendComponent| wgpu::BlendState { color: c, alpha: c };
    match blend {
        Blend::Replace => None,
        Blend::Over => Some(wgpu::BlendState::ALPHA_BLENDING),
        Blend::Add => Some(both(BlendComponent {
            src_factor: BlendFactor::One,
            dst_factor: BlendFactor::One,
            operation: BlendOperation::Add,
        })),
        Blend::Multiply => Some(both(BlendComponent {
            src_factor: BlendFactor::Dst,
            dst_factor: BlendFactor::Zero,
            operation: BlendOperation::Add,
        })),
    }
}

/// A pass's WGSL and the values of the pipeline-overridable constants it
/// declares, as every executor builds its pipelines from them.
#[derive(Clone, Copy)]
pub(super) struct PassShader<'a> {
    pub wgsl: &'a str,
    pub constants: &'a [(&'static str, f64)],
}

impl PassShader<'_> {
    pub fn compilation_options(&self) -> wgpu::PipelineCompilationOptions<'_> {
        wgpu::PipelineCompilationOptions {
            constants: self.constants,
            ..Default::default()
        }
    }

    /// This shader as compute pipelines over one layout of `groups`: one
    /// pipeline per entry point, in order (the compute and tiled passes).
    /// The caller holds the validation scope that checks them.
    pub fn compute_pipelines(
        &self,
        device: &wgpu::Device,
        pass: &PassManifest,
        groups: &[&wgpu::BindGroupLayout],
        entries: &[&str],
    ) -> Vec<wgpu::ComputePipeline> {
        let bind_group_layouts: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().copied().map(Some).collect();
        let layout = device.make_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&pass.name),
            bind_group_layouts: &bind_group_layouts,
            immediate_size: 0,
        });
        let module = device.make_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&pass.shader),
            source: wgpu::ShaderSource::Wgsl(self.wgsl.into()),
        });
        entries
            .iter()
            .map(|entry| {
                device.make_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(&format!("{} {entry}", pass.name)),
                    layout: Some(&layout),
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: self.compilation_options(),
                    cache: None,
                })
            })
            .collect()
    }
}

/// The pipeline-overridable constants `pass`'s shader declares: the device's
/// 16-bit float store rounding when a fused read repeats such a store
/// (`npr_abi::formats::HALF_ROUNDING_OVERRIDE`). A pass that needs it without a
/// measured rounding is an internal error, never a guess.
pub(super) fn pipeline_constants(
    pass: &PassManifest,
    half_rounding: Option<HalfRounding>,
) -> Result<Vec<(&'static str, f64)>, RunError> {
    if !pass.device_half_rounding {
        return Ok(Vec::new());
    }
    let rounding = half_rounding.ok_or_else(|| {
        RunError::Internal(format!(
            "pass `{}` repeats 16-bit float stores, but the device's rounding was not measured",
            pass.name
        ))
    })?;
    Ok(vec![(
        npr_abi::formats::HALF_ROUNDING_OVERRIDE,
        rounding.override_value(),
    )])
}

/// The render pipeline of `pass` (its WGSL, its outputs' formats and blend
/// modes, no culling) with the kind's bind group layouts, vertex buffers,
/// depth state and pipeline constants; a pipeline wgpu rejects is an
/// internal error.
pub(super) fn render_pipeline(
    device: &wgpu::Device,
    manifest: &Manifest,
    pass: &PassManifest,
    shader: PassShader,
    group_layouts: &[&wgpu::BindGroupLayout],
    buffers: &[Option<wgpu::VertexBufferLayout>],
    depth_stencil: Option<wgpu::DepthStencilState>,
) -> Result<wgpu::RenderPipeline, RunError> {
    let (vertex_entry, fragment_entry) = pass
        .kind
        .raster_entries()
        .ok_or_else(|| RunError::Internal(format!("pass `{}` has no vertex and fragment entry points", pass.name)))?;
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> = group_layouts.iter().map(|l| Some(*l)).collect();
    let layout = device.make_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&pass.name),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.make_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(&pass.shader),
        source: wgpu::ShaderSource::Wgsl(shader.wgsl.into()),
    });
    // `blend` is empty (all replace) or one per output (`Manifest::validate`).
    let targets: Vec<Option<wgpu::ColorTargetState>> = pass
        .outputs
        .iter()
        .enumerate()
        .map(|(k, t)| {
            Some(wgpu::ColorTargetState {
                format: wgpu_format(manifest.targets[*t].format),
                blend: blend_state(pass.blend.get(k).copied().unwrap_or_default()),
                write_mask: wgpu::ColorWrites::ALL,
            })
        })
        .collect();
    let pipeline = device.make_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(&pass.name),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(vertex_entry),
            compilation_options: shader.compilation_options(),
            buffers,
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(fragment_entry),
            compilation_options: shader.compilation_options(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    });
    if let Some(err) = pollster::block_on(scope.pop()) {
        return Err(RunError::Internal(format!(
            "pipeline for pass `{}` rejected by wgpu: {err}",
            pass.name
        )));
    }
    Ok(pipeline)
}
