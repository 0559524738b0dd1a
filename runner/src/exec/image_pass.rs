//! The executor of `image` passes: one fullscreen triangle (no vertex
//! buffers, no depth, group 0 only) into the pass's targets.

use super::bind;
use super::common::{self, Timestamps};
use super::sized::SizedPass;
use crate::RunError;
use npr_abi::manifest::*;

pub(super) struct ImagePassExec {
    name: String,
    clear: wgpu::Color,
    pipeline: wgpu::RenderPipeline,
    pub(super) layout0: wgpu::BindGroupLayout,
}

impl ImagePassExec {
    pub fn build(
        device: &wgpu::Device,
        manifest: &Manifest,
        pass: &PassManifest,
        shader: common::PassShader,
    ) -> Result<ImagePassExec, RunError> {
        let layout0 = bind::group0_layout(device, pass);
        let pipeline = common::render_pipeline(device, manifest, pass, shader, &[&layout0], &[], None)?;
        Ok(ImagePassExec {
            name: pass.name.clone(),
            clear: common::clear_color(pass),
            pipeline,
            layout0,
        })
    }

    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, sized: &SizedPass, timestamps: Option<&Timestamps>) {
        let mut rp = common::begin_render_pass(encoder, &self.name, self.clear, sized, None, timestamps);
        rp.set_pipeline(&self.pipeline);
        rp.set_bind_group(0, &sized.group0, &[]);
        rp.draw(0..3, 0..1);
    }
}
