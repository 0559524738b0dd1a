//! The window's GPU: a wgpu instance that knows the display, the window's
//! surface, and a device on an adapter that can present to it.
//!
//! The device is asked for what any style may need (every limit at what
//! the adapter allows, and each WebGPU feature npr's styles use where the
//! adapter has it), as `Gpu::headless` is, because a save may change the
//! style's needs; a style the device cannot run is refused by
//! `StyleRuntime::new` (E0510). The surface is viewed in the non-sRGB twin
//! of its format: the style's output is display-ready, written as is, like
//! `npr render`'s PNG.

use npr_diag::{codes, Diagnostic};
use std::sync::Arc;
use winit::window::Window;

pub struct WindowGpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub watch: npr_runner::DeviceWatch,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The format the style's output is drawn in (the surface's, without sRGB).
    view_format: wgpu::TextureFormat,
    pub adapter: String,
}

fn no_device(message: String) -> Diagnostic {
    Diagnostic::error(codes::NO_DEVICE, message).with_help(
        "on Debian/Ubuntu install a Vulkan driver (`sudo apt-get install -y mesa-vulkan-drivers`, or ./setup.sh) \
         and run under a display (X11 or Wayland; `xvfb-run` gives a virtual one)",
    )
}

impl WindowGpu {
    /// A device that presents to `window`, at the window's current size.
    pub fn new(
        window: Arc<Window>,
        display: winit::event_loop::OwnedDisplayHandle,
        vsync: bool,
    ) -> Result<WindowGpu, Diagnostic> {
        let mut desc = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(display));
        desc.backends = wgpu::Backends::VULKAN | wgpu::Backends::GL;
        let instance = wgpu::Instance::new(desc);
        let size = window.inner_size();
        let surface = instance
            .create_surface(window)
            .map_err(|e| no_device(format!("cannot make a surface for the window: {e}")))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .map_err(|e| no_device(format!("no GPU adapter can present to the window: {e}")))?;
        let features = npr_abi::manifest::Feature::ALL
            .into_iter()
            .map(npr_runner::device_needs::wgpu_feature)
            .fold(wgpu::Features::empty(), |a, b| a | b)
            & adapter.features();
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("npr view"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| no_device(format!("the adapter `{}` refused a device: {e}", info.name)))?;
        let watch = npr_runner::DeviceWatch::install(&device);
        let caps = surface.get_capabilities(&adapter);
        // A non-sRGB format where the surface has one: the runtime checks
        // the texture's format, and a view in another one (the non-sRGB
        // twin of an sRGB surface) is refused (E0602).
        let format = *caps
            .formats
            .iter()
            .find(|f| !f.is_srgb() && matches!(f, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm))
            .or_else(|| caps.formats.iter().find(|f| !f.is_srgb()))
            .or(caps.formats.first())
            .ok_or_else(|| no_device(format!("the adapter `{}` cannot present to this window", info.name)))?;
        let view_format = format.remove_srgb_suffix();
        let present_mode = if vsync {
            wgpu::PresentMode::AutoVsync
        } else {
            wgpu::PresentMode::AutoNoVsync
        };
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: if view_format == format {
                vec![]
            } else {
                vec![view_format]
            },
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&device, &config);
        Ok(WindowGpu {
            device,
            queue,
            watch,
            surface,
            config,
            view_format,
            adapter: format!("{} ({:?})", info.name, info.backend),
        })
    }

    /// The window's inner size changed.
    pub fn resize(&mut self, width: u32, height: u32) {
        if width > 0 && height > 0 && (width, height) != (self.config.width, self.config.height) {
            self.config.width = width;
            self.config.height = height;
            self.surface.configure(&self.device, &self.config);
        }
    }

    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// The next image to draw, and a view of it in the output's format;
    /// `None` when there is none to draw this time (the window is hidden,
    /// or the surface was reconfigured and the next frame will have one).
    pub fn next_image(&mut self) -> Option<(wgpu::SurfaceTexture, wgpu::TextureView)> {
        let texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) => t,
            wgpu::CurrentSurfaceTexture::Suboptimal(t) => {
                // Drawn this time; the surface is made anew for the next.
                self.surface.configure(&self.device, &self.config);
                t
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                return None;
            }
            wgpu::CurrentSurfaceTexture::Timeout
            | wgpu::CurrentSurfaceTexture::Occluded
            | wgpu::CurrentSurfaceTexture::Validation => return None,
        };
        let view = texture.texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(self.view_format),
            ..Default::default()
        });
        Some((texture, view))
    }
}
