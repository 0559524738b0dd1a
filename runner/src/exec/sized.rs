//! The types of what depends on the output size ([`SizedResources`]: the
//! physical textures, and per parity, eye slot and pass its views and
//! bind groups) and the pure helpers that size and format them. A leaf of
//! the executor: the pass executors read these types, and `resources.rs`
//! builds them, without importing each other.

use crate::gpu_count::Create;
use npr_abi::Format;
use std::collections::BTreeMap;

/// Size of a target at `scale` of the output: at least 1 px, rounded to nearest.
pub fn scaled_size(width: u32, height: u32, scale: f64) -> (u32, u32) {
    let s = |v: u32| ((v as f64 * scale).round() as u32).max(1);
    (s(width), s(height))
}

/// A single-sample, single-mip 2D texture.
pub(super) fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.make_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

pub fn wgpu_format(f: Format) -> wgpu::TextureFormat {
    use wgpu::TextureFormat as T;
    match f {
        Format::R8unorm => T::R8Unorm,
        Format::Rg8unorm => T::Rg8Unorm,
        Format::Rgba8unorm => T::Rgba8Unorm,
        Format::Rgba8unormSrgb => T::Rgba8UnormSrgb,
        Format::R16float => T::R16Float,
        Format::Rg16float => T::Rg16Float,
        Format::Rgba16float => T::Rgba16Float,
        Format::R32float => T::R32Float,
        Format::Rg32float => T::Rg32Float,
        Format::Rgba32float => T::Rgba32Float,
    }
}

/// Every physical texture of every eye slot, and the second copy of each
/// history texture.
pub(super) struct Physical {
    /// Per eye slot: one texture per `manifest.physical` entry.
    pub slots: Vec<Vec<wgpu::Texture>>,
    /// Per eye slot: the second copy of each history texture, by physical index.
    pub second: Vec<BTreeMap<usize, wgpu::Texture>>,
}

impl Physical {
    /// The texture of physical `index` in eye `slot` that a frame of
    /// `parity` writes (`previous: false`), or binds to its previous-frame
    /// reads (`previous: true`). Textures without history have one copy.
    pub fn texture(&self, slot: usize, parity: usize, index: usize, previous: bool) -> &wgpu::Texture {
        match self.second[slot].get(&index) {
            Some(second) if (parity == 1) != previous => second,
            _ => &self.slots[slot][index],
        }
    }
}

/// Everything that depends on the output size, built once per size: the
/// physical textures, and per pass its attachment views, depth view and
/// bind group (so a frame only writes uniforms and records draws).
pub(super) struct SizedResources {
    pub width: u32,
    pub height: u32,
    pub physical: Physical,
    /// Per frame parity (two when the style has history textures, else
    /// one), per eye slot, per pass: its views and bind group.
    pub passes: Vec<Vec<Vec<SizedPass>>>,
    /// The host's depth per eye slot and tested input (`host_depth.rs`),
    /// drawn at the start of each frame.
    pub host_depths: Vec<super::host_depth::HostDepthDraw>,
    /// Which eye's textures hold the requested image (`FrameSpec::eye` for
    /// stereo styles, else 0).
    pub output_slot: usize,
}

/// One pass in one eye slot at the current size.
pub(super) struct SizedPass {
    /// The pass's outputs, in `@location` order.
    pub color_views: Vec<wgpu::TextureView>,
    /// Where the pass kind needs a depth buffer (`PassExec::needs_depth`).
    pub depth_view: Option<wgpu::TextureView>,
    /// A lines pass with a depth test: group 1, the tested pass's kept depth.
    pub tested_depth: Option<wgpu::BindGroup>,
    pub group0: wgpu::BindGroup,
    /// A compute pass over pixels: its element workgroups at this size (0 otherwise).
    pub pixel_workgroups: u32,
    /// A tiled image pass: its outputs as storage textures, and its grid.
    pub tiled_outputs: Option<TiledOutputs>,
    /// A render pass's draws for this size and scene, recorded once by
    /// `Renderer::prepare` (`render_pass.rs`); `None` until then and
    /// after the scene changed.
    pub draws: Option<wgpu::RenderBundle>,
}

/// What a tiled pass needs per eye slot and size: its output group and
/// the workgroup grid.
pub(super) struct TiledOutputs {
    pub(super) group: wgpu::BindGroup,
    pub(super) workgroups: [u32; 2],
}
