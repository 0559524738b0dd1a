//! What the embedding tests (`embed_*.rs`) share: one headless device per
//! test binary, and the offscreen texture a host would render into.

use runner::Gpu;
use std::sync::OnceLock;

/// The device, made once per test binary; a machine without an adapter
/// fails with how to install one.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        Gpu::headless().unwrap_or_else(|e| {
            panic!("runner tests need a GPU adapter (Mesa's lavapipe: `./setup.sh --tests`, or apt-get install mesa-vulkan-drivers): {e}")
        })
    })
}

/// A host's texture of `format` that the runtime presents into and the test
/// reads back.
pub fn host_target(
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    gpu().device.create_texture(&wgpu::TextureDescriptor {
        label: Some("host target"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats,
    })
}
