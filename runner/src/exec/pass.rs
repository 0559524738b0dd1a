//! One executor per manifest pass, by pass kind: [`PassExec`] is built once
//! from the pass's `PassKindManifest` (its pipeline and layouts live as long
//! as the renderer: they depend on the style and the device only), is given
//! each scene's part ([`PassExec::bind_scene`], [`PassExec::set_scene`]:
//! per-object groups, compute buffers' groups, line caches) and records the
//! pass for one eye slot with `encode`. A
//! new pass kind is a variant here and one file with its executor; what the
//! executors share is in `common.rs`, which they import instead of this.

use super::bind::ObjectResources;
use super::common::{pipeline_constants, EncodeContext, PassShader, Timestamps};
use super::compute_pass::{ComputePassExec, ComputeScene};
use super::image_pass::ImagePassExec;
use super::lines_pass::LinesPassExec;
use super::render_pass::{RenderPassExec, RenderScene};
use super::sized::SizedPass;
use super::sized::TiledOutputs;
use super::tiled_pass::TiledPassExec;
use crate::RunError;
use npr_abi::formats::HalfRounding;
use npr_abi::manifest::*;

pub(super) enum PassExec {
    /// `render(tag)`: draws the scene's objects (group 1: the object block).
    Render(RenderPassExec),
    /// `image`: one fullscreen triangle.
    Image(ImagePassExec),
    /// `image`, scheduled as compute over workgroup tiles.
    Tiled(TiledPassExec),
    /// `compute(domain)`: dispatches per object (groups 1 and 2 of its own).
    Compute(ComputePassExec),
    /// `lines(tag)`: strips built on the CPU per eye slot, one indexed draw
    /// (boxed: its cache makes it several times the size of the others).
    Lines(Box<LinesPassExec>),
}

/// What one scene gives a pass ([`PassExec::bind_scene`]): made for every
/// pass before any is given its own, so a scene that fails leaves the
/// passes as they were.
pub(super) enum PassScene {
    Render(RenderScene),
    Compute(ComputeScene),
    /// Image and tiled passes read no scene; a lines pass reads it per frame.
    Other,
}

impl PassExec {
    /// The pass's layouts and pipelines, which depend on the style and the
    /// device only (a render pass's group 1 layout on its per-object
    /// texture bindings, never on the images objects bind): the scene's
    /// part comes from [`PassExec::bind_scene`].
    pub fn build(
        device: &wgpu::Device,
        manifest: &Manifest,
        pass: &PassManifest,
        wgsl: &str,
        shared_object_layout: &wgpu::BindGroupLayout,
        half_rounding: Option<HalfRounding>,
    ) -> Result<PassExec, RunError> {
        let constants = pipeline_constants(pass, half_rounding)?;
        let shader = PassShader {
            wgsl,
            constants: &constants,
        };
        Ok(match &pass.kind {
            PassKindManifest::Render {
                tag, attributes, depth, ..
            } => PassExec::Render(RenderPassExec::build(
                device,
                manifest,
                pass,
                shader,
                (tag.as_ref(), attributes),
                depth,
                shared_object_layout,
            )?),
            PassKindManifest::Image { .. } => PassExec::Image(ImagePassExec::build(device, manifest, pass, shader)?),
            PassKindManifest::TiledImage { .. } => {
                PassExec::Tiled(TiledPassExec::build(device, manifest, pass, shader)?)
            }
            PassKindManifest::Compute { .. } => PassExec::Compute(ComputePassExec::build(device, pass, shader)?),
            PassKindManifest::Lines { .. } => {
                PassExec::Lines(Box::new(LinesPassExec::build(device, manifest, pass, shader)?))
            }
        })
    }

    /// The pass's part of a scene: `objects` and, for a compute pass, its
    /// `buffers` (`values.rs`), bound with the layouts of its pipelines.
    pub fn bind_scene(
        &self,
        device: &wgpu::Device,
        pass: &PassManifest,
        objects: &ObjectResources,
        buffers: Option<&super::values::PassBuffers>,
    ) -> Result<PassScene, RunError> {
        Ok(match self {
            PassExec::Render(p) => PassScene::Render(p.bind_scene(device, pass, objects)?),
            PassExec::Compute(p) => {
                let buffers = buffers
                    .ok_or_else(|| RunError::Internal(format!("compute pass `{}` has no buffers", pass.name)))?;
                PassScene::Compute(p.bind_scene(device, pass, objects.buffer, buffers)?)
            }
            PassExec::Image(_) | PassExec::Tiled(_) | PassExec::Lines(_) => PassScene::Other,
        })
    }

    /// Take the part [`PassExec::bind_scene`] made (a lines pass forgets
    /// its cached strips).
    pub fn set_scene(&mut self, scene: PassScene) {
        match (self, scene) {
            (PassExec::Render(p), PassScene::Render(scene)) => p.set_scene(scene),
            (PassExec::Compute(p), PassScene::Compute(scene)) => p.set_scene(scene),
            (PassExec::Lines(p), _) => p.set_scene(),
            _ => {}
        }
    }

    /// The layout of the pass's group 0 (built per size in `bind.rs`).
    pub fn layout0(&self) -> &wgpu::BindGroupLayout {
        match self {
            PassExec::Render(p) => &p.layout0,
            PassExec::Image(p) => &p.layout0,
            PassExec::Tiled(p) => &p.layout0,
            PassExec::Compute(p) => &p.layout0,
            PassExec::Lines(p) => &p.layout0,
        }
    }

    /// Whether the pass's [`SizedPass`] gets a depth buffer.
    pub fn needs_depth(&self) -> bool {
        match self {
            PassExec::Render(_) => true,
            // Lines test in their shader (`tested_depth_group`), with no attachment.
            PassExec::Image(_) | PassExec::Tiled(_) | PassExec::Compute(_) | PassExec::Lines(_) => false,
        }
    }

    /// A lines pass with a depth test: its group 1 over `kept`, the tested
    /// pass's depth texture; `None` for every other pass.
    pub fn tested_depth_group(&self, device: &wgpu::Device, kept: &wgpu::TextureView) -> Option<wgpu::BindGroup> {
        match self {
            PassExec::Lines(p) => p.tested_depth_group(device, kept),
            _ => None,
        }
    }

    /// A tiled pass: its output group over `outputs` (one eye slot's views)
    /// at `size`; `None` for every other pass.
    pub fn tiled_outputs(
        &self,
        device: &wgpu::Device,
        outputs: &[wgpu::TextureView],
        size: (u32, u32),
    ) -> Option<TiledOutputs> {
        match self {
            PassExec::Tiled(p) => Some(p.outputs(device, outputs, size)),
            _ => None,
        }
    }

    /// A render pass's draws for `sized` and the current scene, recorded
    /// once for the frames that follow (`render_pass.rs`); `None` for
    /// other kinds, which record theirs every frame.
    pub fn record_draws(
        &self,
        device: &wgpu::Device,
        sized: &SizedPass,
        ctx: &EncodeContext,
    ) -> Option<wgpu::RenderBundle> {
        match self {
            PassExec::Render(p) => Some(p.record_draws(device, sized, ctx)),
            _ => None,
        }
    }

    /// Record the pass for eye slot `slot`.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        (sized, slot): (&SizedPass, usize),
        ctx: &EncodeContext,
        timestamps: Option<&Timestamps>,
    ) {
        match self {
            PassExec::Render(p) => p.encode(encoder, sized, ctx, timestamps),
            PassExec::Image(p) => p.encode(encoder, sized, timestamps),
            // `make_sized` gives every tiled pass its outputs.
            PassExec::Tiled(p) => {
                if let Some(outputs) = &sized.tiled_outputs {
                    p.encode(encoder, sized, outputs, timestamps)
                }
            }
            PassExec::Compute(p) => p.encode(encoder, sized, ctx, timestamps),
            PassExec::Lines(p) => p.encode(encoder, sized, slot, timestamps),
        }
    }

    /// Whether the pass runs once per eye slot (render and image passes) or
    /// once per frame (compute passes: per-object values have no eye).
    pub fn per_eye(&self) -> bool {
        !matches!(self, PassExec::Compute(_))
    }
}
