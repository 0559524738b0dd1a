//! The executor of tiled image passes (`PassKindManifest::TiledImage`): one
//! compute dispatch of `TILE_SIZE`² workgroups over the pass's pixels.
//! Group 0 as an image pass; group 1 holds the outputs as write-only
//! storage textures, one group per eye slot and size (`storage_group`),
//! since the outputs are the slot's textures.

use super::bind;
use super::common::{PassShader, Timestamps};
use super::sized::{wgpu_format, SizedPass, TiledOutputs};
use crate::gpu_count::Create;
use crate::RunError;
use npr_abi::manifest::*;

pub(super) struct TiledPassExec {
    name: String,
    pipeline: wgpu::ComputePipeline,
    pub(super) layout0: wgpu::BindGroupLayout,
    layout1: wgpu::BindGroupLayout,
}

impl TiledPassExec {
    pub fn build(
        device: &wgpu::Device,
        manifest: &Manifest,
        pass: &PassManifest,
        shader: PassShader,
    ) -> Result<TiledPassExec, RunError> {
        let PassKindManifest::TiledImage { entry } = &pass.kind else {
            return Err(RunError::Internal(format!(
                "pass `{}` is not a tiled image pass",
                pass.name
            )));
        };
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout0 = bind::group0_layout(device, pass);
        let entries: Vec<wgpu::BindGroupLayoutEntry> = pass
            .outputs
            .iter()
            .enumerate()
            .map(|(k, t)| wgpu::BindGroupLayoutEntry {
                binding: k as u32,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::StorageTexture {
                    access: wgpu::StorageTextureAccess::WriteOnly,
                    format: wgpu_format(manifest.targets[*t].format),
                    view_dimension: wgpu::TextureViewDimension::D2,
                },
                count: None,
            })
            .collect();
        let layout1 = device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{} outputs", pass.name)),
            entries: &entries,
        });
        let pipeline = shader
            .compute_pipelines(device, pass, &[&layout0, &layout1], &[entry])
            .pop();
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RunError::Internal(format!(
                "tiled pipeline for pass `{}` rejected by wgpu: {err}",
                pass.name
            )));
        }
        let Some(pipeline) = pipeline else {
            return Err(RunError::Internal(format!("pass `{}` built no pipeline", pass.name)));
        };
        Ok(TiledPassExec {
            name: pass.name.clone(),
            pipeline,
            layout0,
            layout1,
        })
    }

    /// Group 1 over `outputs` (the views of one eye slot's output
    /// textures) and the workgroups that cover a `width`×`height` output.
    pub fn outputs(
        &self,
        device: &wgpu::Device,
        outputs: &[wgpu::TextureView],
        (width, height): (u32, u32),
    ) -> TiledOutputs {
        let entries: Vec<wgpu::BindGroupEntry> = outputs
            .iter()
            .enumerate()
            .map(|(k, v)| wgpu::BindGroupEntry {
                binding: k as u32,
                resource: wgpu::BindingResource::TextureView(v),
            })
            .collect();
        let group = device.make_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("{} outputs", self.name)),
            layout: &self.layout1,
            entries: &entries,
        });
        TiledOutputs {
            group,
            workgroups: [width.div_ceil(TILE_SIZE), height.div_ceil(TILE_SIZE)],
        }
    }

    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        sized: &SizedPass,
        outputs: &TiledOutputs,
        timestamps: Option<&Timestamps>,
    ) {
        let mut cp = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&self.name),
            timestamp_writes: timestamps.map(Timestamps::compute_pass),
        });
        cp.set_pipeline(&self.pipeline);
        cp.set_bind_group(0, &sized.group0, &[]);
        cp.set_bind_group(1, &outputs.group, &[]);
        cp.dispatch_workgroups(outputs.workgroups[0], outputs.workgroups[1], 1);
    }
}
