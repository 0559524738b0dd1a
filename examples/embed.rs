//! A host application that drives an npr style itself: a winit window and
//! a wgpu surface of its own, a style compiled with the `compiler` crate, a
//! scene built in code (no TOML, no files but the style), an object and the
//! camera animated, the object's own mesh deformed (it squashes as it lands:
//! `StyleRuntime::update_mesh`), and npr's output drawn into the swapchain image inside
//! the host's own command encoder (`npr_runner::embed`).
//!
//! `cargo run --example embed [-- STYLE.npr] [--frames N] [--headless]`:
//! `--frames N` quits after N frames and prints the mean of the style's
//! output; `--headless` renders into an offscreen texture, no window
//! (tests/general/embed_example.rs runs both, the window under Xvfb).

use npr_runner::embed::{Deformed, Frame, Instance, Lights, MeshHandle, StyleRuntime, Target};
use npr_runner::scene::{primitives, Camera};
use std::sync::Arc;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

/// The host's own state: its device, its meshes, its clock.
struct Host {
    device: wgpu::Device,
    queue: wgpu::Queue,
    runtime: StyleRuntime,
    ball: MeshHandle,
    /// The ball's vertices at rest, which the host squashes each frame.
    rest: Vec<[f32; 3]>,
    ground: MeshHandle,
    frame: u32,
    frames: Option<u32>,
}

impl Host {
    /// Compile the style and register the meshes once.
    fn new(adapter: &wgpu::Adapter, style: &str) -> Result<Host, Box<dyn std::error::Error>> {
        let mut sources = npr_diag::SourceMap::new();
        let options = npr_compiler::CompileOptions {
            keep_params: true,
            ..Default::default()
        };
        let program = npr_compiler::compile_file(std::path::Path::new(style), &mut sources, &options)
            .map_err(|e| match e {
                npr_compiler::CompileError::User(d) => npr_diag::diagnostic::render(&d, &sources, false),
                other => format!("{other:?}"),
            })?
            .program();
        // Ask for what the style needs past WebGPU's defaults.
        let (required_features, required_limits) = StyleRuntime::device_needs(&program, wgpu::Limits::default());
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            required_features,
            required_limits,
            ..Default::default()
        }))?;
        let mut runtime = StyleRuntime::new(&device, &queue, program).map_err(|e| format!("{:?}", e.diagnostics()))?;
        let sphere = primitives::sphere(0.5, 48, 24);
        let rest = sphere.positions.clone();
        let ball = runtime.add_mesh(sphere);
        let ground = runtime.add_mesh(primitives::plane(6.0, 1));
        Ok(Host {
            device,
            queue,
            runtime,
            ball,
            rest,
            ground,
            frame: 0,
            frames: None,
        })
    }

    /// One frame into `view`: the ball bounces, the camera orbits.
    fn render(&mut self, view: &wgpu::TextureView) -> Result<(), Box<dyn std::error::Error>> {
        let t = self.frame as f32 / 60.0;
        let height = (t * 3.0).sin().abs();
        // The host's own deformation: squashed near the ground, its volume
        // kept. New vertices, same triangles: written over the mesh's GPU
        // buffers in place, no scene change (the runtime makes the normals).
        let squash = 1.0 - 0.3 * (1.0 - height).powi(4);
        let widen = 1.0 / squash.sqrt();
        let squashed: Vec<[f32; 3]> = self
            .rest
            .iter()
            .map(|p| [p[0] * widen, p[1] * squash, p[2] * widen])
            .collect();
        self.runtime
            .update_mesh(self.ball, Deformed::positions(&squashed))
            .map_err(|e| format!("{:?}", e.diagnostics()))?;
        let objects = [
            Instance::new(
                self.ground,
                glam::Mat4::from_translation(glam::Vec3::new(0.0, -0.5, 0.0)),
            ),
            Instance::new(
                self.ball,
                // Its bottom stays where the round ball's would be.
                glam::Mat4::from_translation(glam::Vec3::new(0.0, height - 0.5 * (1.0 - squash), 0.0)),
            ),
        ];
        let eye = glam::Vec3::new(3.0 * (t * 0.5).sin(), 1.5, 3.0 * (t * 0.5).cos());
        let camera = Camera::looking_at(eye, glam::Vec3::ZERO);
        let lights = Lights::default();
        let frame = Frame {
            camera: &camera,
            objects: &objects,
            lights: &lights,
            time_s: f64::from(t),
            frame_index: self.frame,
            eye: 0,
        };
        let mut encoder = self.device.create_command_encoder(&Default::default());
        self.runtime
            .render(&mut encoder, &frame, Target::View(view))
            .map_err(|e| format!("{:?}", e.diagnostics()))?;
        self.queue.submit([encoder.finish()]);
        self.frame += 1;
        Ok(())
    }

    /// After the last frame: the mean of the style's output, for the test.
    fn finished(&self) -> bool {
        self.frames.is_some_and(|n| self.frame >= n)
    }

    fn report(&self) -> Result<(), Box<dyn std::error::Error>> {
        let output = &self.runtime.manifest().targets[self.runtime.manifest().output].name;
        let image = self.runtime.read_target(output).map_err(|e| format!("{e}"))?;
        let texels = image.to_rgba_f32();
        let mean = texels.iter().map(|t| (t[0] + t[1] + t[2]) / 3.0).sum::<f32>() / texels.len() as f32;
        println!(
            "rendered {} frames of {}x{}; mean output {mean:.4}",
            self.frame, image.width, image.height
        );
        Ok(())
    }
}

/// The window, its surface, and the host.
struct App {
    style: String,
    frames: Option<u32>,
    window: Option<(Arc<Window>, wgpu::Surface<'static>, wgpu::SurfaceConfiguration, Host)>,
    error: Option<Box<dyn std::error::Error>>,
}

impl App {
    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<(), Box<dyn std::error::Error>> {
        let attributes = Window::default_attributes()
            .with_title("npr embed")
            .with_inner_size(winit::dpi::PhysicalSize::new(512, 384));
        let window = Arc::new(event_loop.create_window(attributes)?);
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle(Box::new(
            event_loop.owned_display_handle(),
        )));
        let surface = instance.create_surface(window.clone())?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))?;
        let mut host = Host::new(&adapter, &self.style)?;
        host.frames = self.frames;
        let size = window.inner_size();
        // npr writes display-ready values: a surface format without sRGB encoding.
        let caps = surface.get_capabilities(&adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .ok_or("the surface has no non-sRGB format")?;
        let mut config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .ok_or("surface unsupported")?;
        config.format = format;
        surface.configure(&host.device, &config);
        window.request_redraw();
        self.window = Some((window, surface, config, host));
        Ok(())
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) -> Result<(), Box<dyn std::error::Error>> {
        let Some((window, surface, config, host)) = &mut self.window else {
            return Ok(());
        };
        let frame = match surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f) | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            _ => {
                surface.configure(&host.device, config);
                window.request_redraw();
                return Ok(());
            }
        };
        host.render(&frame.texture.create_view(&Default::default()))?;
        window.pre_present_notify();
        host.queue.present(frame);
        if host.finished() {
            host.report()?;
            event_loop.exit();
        }
        window.request_redraw();
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none() {
            if let Err(e) = self.open(event_loop) {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some((_, surface, config, host)) = &mut self.window {
                    (config.width, config.height) = (size.width.max(1), size.height.max(1));
                    surface.configure(&host.device, config);
                }
            }
            _ => {}
        }
        let redraw = matches!(event, WindowEvent::RedrawRequested);
        if let Err(e) = if redraw { self.redraw(event_loop) } else { Ok(()) } {
            self.error = Some(e);
            event_loop.exit();
        }
    }
}

/// No window: the same host, into an offscreen texture.
fn headless(style: &str, frames: u32) -> Result<(), Box<dyn std::error::Error>> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
    let mut host = Host::new(&adapter, style)?;
    let size = wgpu::Extent3d {
        width: 512,
        height: 384,
        depth_or_array_layers: 1,
    };
    let texture = host.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("offscreen"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    for _ in 0..frames {
        host.render(&view)?;
    }
    host.report()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| args.iter().position(|a| a == flag).and_then(|i| args.get(i + 1));
    let frames = value("--frames").map(|n| n.parse::<u32>()).transpose()?;
    let style = args
        .iter()
        .find(|a| a.ends_with(".npr"))
        .cloned()
        .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/examples/toon.npr").to_string());
    if args.iter().any(|a| a == "--headless") {
        return headless(&style, frames.unwrap_or(60));
    }
    let mut app = App {
        style,
        frames,
        window: None,
        error: None,
    };
    EventLoop::new()?.run_app(&mut app)?;
    app.error.map_or(Ok(()), Err)
}
