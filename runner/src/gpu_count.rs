//! Every GPU object the runner creates goes through `Create` (and
//! `CreateView`), which counts it on the calling thread: what
//! `runner/tests/embed_allocations.rs` reads to show that a frame after
//! the first creates nothing. wgpu's own `Device::get_internal_counters`
//! counts live objects (with its `counters` feature), so a bind group made
//! and dropped each frame, or a staging buffer of `write_buffer`, would be
//! invisible or noise there; these count creations. The runner's
//! `clippy.toml` disallows the uncounted wgpu methods, so none is missed.
//!
//! Counts are per thread: tests run in parallel, and the runner creates
//! its objects on the thread that calls it.

#![allow(clippy::disallowed_methods)]

use std::cell::Cell;

/// GPU objects created on this thread since it began, by kind.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct GpuCreations {
    pub buffers: u64,
    pub textures: u64,
    pub texture_views: u64,
    pub samplers: u64,
    pub bind_groups: u64,
    /// Bind group layouts and pipeline layouts.
    pub layouts: u64,
    /// Render and compute pipelines.
    pub pipelines: u64,
    pub shader_modules: u64,
    /// Render bundles (a render pass's recorded draws).
    pub render_bundles: u64,
}

impl GpuCreations {
    pub fn total(&self) -> u64 {
        self.buffers
            + self.textures
            + self.texture_views
            + self.samplers
            + self.bind_groups
            + self.layouts
            + self.pipelines
            + self.shader_modules
            + self.render_bundles
    }
}

thread_local! {
    static CREATED: Cell<GpuCreations> = Cell::new(GpuCreations::default());
}

/// What the runner created on this thread so far.
pub fn created_on_this_thread() -> GpuCreations {
    CREATED.with(Cell::get)
}

fn count(add: impl FnOnce(&mut GpuCreations)) {
    CREATED.with(|c| {
        let mut n = c.get();
        add(&mut n);
        c.set(n);
    });
}

/// Counted `wgpu::Device::create_*`.
pub(crate) trait Create {
    fn make_buffer(&self, desc: &wgpu::BufferDescriptor) -> wgpu::Buffer;
    fn make_buffer_init(&self, desc: &wgpu::util::BufferInitDescriptor) -> wgpu::Buffer;
    fn make_texture(&self, desc: &wgpu::TextureDescriptor) -> wgpu::Texture;
    fn make_sampler(&self, desc: &wgpu::SamplerDescriptor) -> wgpu::Sampler;
    fn make_bind_group(&self, desc: &wgpu::BindGroupDescriptor) -> wgpu::BindGroup;
    fn make_bind_group_layout(&self, desc: &wgpu::BindGroupLayoutDescriptor) -> wgpu::BindGroupLayout;
    fn make_pipeline_layout(&self, desc: &wgpu::PipelineLayoutDescriptor) -> wgpu::PipelineLayout;
    fn make_render_pipeline(&self, desc: &wgpu::RenderPipelineDescriptor) -> wgpu::RenderPipeline;
    fn make_compute_pipeline(&self, desc: &wgpu::ComputePipelineDescriptor) -> wgpu::ComputePipeline;
    fn make_shader_module(&self, desc: wgpu::ShaderModuleDescriptor) -> wgpu::ShaderModule;
    /// Counts the bundle the encoder will finish.
    fn make_render_bundle_encoder(&self, desc: &wgpu::RenderBundleEncoderDescriptor) -> wgpu::RenderBundleEncoder<'_>;
}

impl Create for wgpu::Device {
    fn make_buffer(&self, desc: &wgpu::BufferDescriptor) -> wgpu::Buffer {
        count(|n| n.buffers += 1);
        self.create_buffer(desc)
    }
    fn make_buffer_init(&self, desc: &wgpu::util::BufferInitDescriptor) -> wgpu::Buffer {
        use wgpu::util::DeviceExt;
        count(|n| n.buffers += 1);
        self.create_buffer_init(desc)
    }
    fn make_texture(&self, desc: &wgpu::TextureDescriptor) -> wgpu::Texture {
        count(|n| n.textures += 1);
        self.create_texture(desc)
    }
    fn make_sampler(&self, desc: &wgpu::SamplerDescriptor) -> wgpu::Sampler {
        count(|n| n.samplers += 1);
        self.create_sampler(desc)
    }
    fn make_bind_group(&self, desc: &wgpu::BindGroupDescriptor) -> wgpu::BindGroup {
        count(|n| n.bind_groups += 1);
        self.create_bind_group(desc)
    }
    fn make_bind_group_layout(&self, desc: &wgpu::BindGroupLayoutDescriptor) -> wgpu::BindGroupLayout {
        count(|n| n.layouts += 1);
        self.create_bind_group_layout(desc)
    }
    fn make_pipeline_layout(&self, desc: &wgpu::PipelineLayoutDescriptor) -> wgpu::PipelineLayout {
        count(|n| n.layouts += 1);
        self.create_pipeline_layout(desc)
    }
    fn make_render_pipeline(&self, desc: &wgpu::RenderPipelineDescriptor) -> wgpu::RenderPipeline {
        count(|n| n.pipelines += 1);
        self.create_render_pipeline(desc)
    }
    fn make_compute_pipeline(&self, desc: &wgpu::ComputePipelineDescriptor) -> wgpu::ComputePipeline {
        count(|n| n.pipelines += 1);
        self.create_compute_pipeline(desc)
    }
    fn make_shader_module(&self, desc: wgpu::ShaderModuleDescriptor) -> wgpu::ShaderModule {
        count(|n| n.shader_modules += 1);
        self.create_shader_module(desc)
    }
    fn make_render_bundle_encoder(&self, desc: &wgpu::RenderBundleEncoderDescriptor) -> wgpu::RenderBundleEncoder<'_> {
        count(|n| n.render_bundles += 1);
        self.create_render_bundle_encoder(desc)
    }
}

/// Counted `wgpu::Texture::create_view`.
pub(crate) trait CreateView {
    fn make_view(&self, desc: &wgpu::TextureViewDescriptor) -> wgpu::TextureView;
}

impl CreateView for wgpu::Texture {
    fn make_view(&self, desc: &wgpu::TextureViewDescriptor) -> wgpu::TextureView {
        count(|n| n.texture_views += 1);
        self.create_view(desc)
    }
}
