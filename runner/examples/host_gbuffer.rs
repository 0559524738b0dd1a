//! A wgpu application that renders its own G-buffer and runs an npr style
//! over it (issue 47): its colour, depth and normals become the inputs of
//! `examples/post/ink_over.npr` through `StyleRuntime::set_input`, each
//! with the convention the host wrote it in, and the inked frame is
//! written to a PNG.
//!
//! The host's renderer is a few lines of WGSL: one fullscreen draw that
//! ray-traces a sphere on a floor and writes, as a game's G-buffer pass
//! does, linear colour (`Rgba16Float`), world normals (`Rgba16Float`) and
//! infinite reverse-Z depth (`Depth32Float`, as Bevy writes it), plus the
//! distance along the view axis (`R32Float`, as Cycles' `Depth.Z`), which
//! `tests/gpu/embed_inputs.rs` also writes to files.
//!
//! `cargo run -p npr-runner --example host_gbuffer -- [OUT.png]`

#![allow(clippy::disallowed_methods)]

use npr_runner::embed::{Frame, Lights, StyleRuntime, Target};
use npr_runner::inputs::{ColorEncoding, DepthConvention, NormalConvention, SourceConvention};
use npr_runner::scene::Camera;

/// The host's own renderer, apart from npr.
pub mod gbuffer {
    use npr_runner::scene::Camera;

    /// One fullscreen triangle ray-traces a unit sphere at (0, 1, 0) on
    /// the floor y = 0 (a 6 m square), under a sun.
    const WGSL: &str = "
struct Camera {
    inverse_view: mat4x4<f32>,
    // x: tan(fov_y / 2), y: aspect, z: near, w: height in pixels
    lens: vec4<f32>,
}
@group(0) @binding(0) var<uniform> cam: Camera;

struct GBuffer {
    @location(0) colour: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) distance: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) p: vec4<f32>) -> GBuffer {
    let size = vec2<f32>(cam.lens.w * cam.lens.y, cam.lens.w);
    let ndc = vec2<f32>(p.x / size.x * 2.0 - 1.0, 1.0 - p.y / size.y * 2.0);
    let dir_view = normalize(vec3<f32>(ndc.x * cam.lens.x * cam.lens.y, ndc.y * cam.lens.x, -1.0));
    let origin = (cam.inverse_view * vec4<f32>(0.0, 0.0, 0.0, 1.0)).xyz;
    let dir = normalize((cam.inverse_view * vec4<f32>(dir_view, 0.0)).xyz);
    var t = 1e9;
    var n = vec3<f32>(0.0);
    var albedo = vec3<f32>(0.0);
    // The sphere.
    let oc = origin - vec3<f32>(0.0, 1.0, 0.0);
    let b = dot(oc, dir);
    let disc = b * b - (dot(oc, oc) - 1.0);
    if disc > 0.0 {
        let ts = -b - sqrt(disc);
        if ts > 0.0 {
            t = ts;
            n = normalize(oc + dir * ts);
            albedo = vec3<f32>(0.8, 0.25, 0.1);
        }
    }
    // The floor.
    if dir.y < 0.0 {
        let tf = -origin.y / dir.y;
        let hit = origin + dir * tf;
        if tf < t && abs(hit.x) < 3.0 && abs(hit.z) < 3.0 {
            t = tf;
            n = vec3<f32>(0.0, 1.0, 0.0);
            albedo = vec3<f32>(0.35, 0.5, 0.3);
        }
    }
    var out: GBuffer;
    if t >= 1e9 {
        out.colour = vec4<f32>(0.05, 0.07, 0.12, 1.0);
        out.normal = vec4<f32>(0.0);
        out.distance = vec4<f32>(0.0);
        out.depth = 0.0;
        return out;
    }
    let sun = normalize(vec3<f32>(0.4, 1.0, 0.3));
    out.colour = vec4<f32>(albedo * (0.15 + 0.85 * max(dot(n, sun), 0.0)), 1.0);
    out.normal = vec4<f32>(n, 1.0);
    // Along the view axis, not along the ray.
    let distance = t * -dir_view.z;
    out.distance = vec4<f32>(distance, 0.0, 0.0, 1.0);
    out.depth = cam.lens.z / distance;
    return out;
}
";

    pub const COLOUR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
    pub const NORMAL: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
    pub const DISTANCE: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
    pub const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

    /// The host's frame: what its G-buffer pass wrote.
    pub struct GBuffer {
        pub colour: wgpu::Texture,
        pub normal: wgpu::Texture,
        pub distance: wgpu::Texture,
        pub depth: wgpu::Texture,
    }

    fn target(device: &wgpu::Device, (w, h): (u32, u32), format: wgpu::TextureFormat) -> wgpu::Texture {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("host G-buffer"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    }

    /// Render the scene seen by `camera` at `size` into a new G-buffer.
    pub fn render(device: &wgpu::Device, queue: &wgpu::Queue, camera: &Camera, size: (u32, u32)) -> GBuffer {
        let g = GBuffer {
            colour: target(device, size, COLOUR),
            normal: target(device, size, NORMAL),
            distance: target(device, size, DISTANCE),
            depth: target(device, size, DEPTH),
        };
        let pose = camera.pose(0.0);
        let inverse_view = pose.center_view().inverse();
        let mut uniform = inverse_view.to_cols_array().to_vec();
        uniform.extend([
            (pose.fov_y_rad * 0.5).tan(),
            size.0 as f32 / size.1 as f32,
            pose.near,
            size.1 as f32,
        ]);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("host camera"),
            size: (uniform.len() * 4) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bytes: Vec<u8> = uniform.iter().flat_map(|f| f.to_le_bytes()).collect();
        queue.write_buffer(&buffer, 0, &bytes);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("host G-buffer"),
            source: wgpu::ShaderSource::Wgsl(WGSL.into()),
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("host G-buffer"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
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
                targets: &[COLOUR, NORMAL, DISTANCE].map(|format| {
                    Some(wgpu::ColorTargetState {
                        format,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })
                }),
            }),
            multiview_mask: None,
            cache: None,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("host camera"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        });
        let views = [&g.colour, &g.normal, &g.distance].map(|t| t.create_view(&Default::default()));
        let depth_view = g.depth.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let attachment = |view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("host G-buffer"),
                color_attachments: &[attachment(&views[0]), attachment(&views[1]), attachment(&views[2])],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
        }
        queue.submit([encoder.finish()]);
        g
    }
}

/// The host's camera: npr's, so that the style turns the host's world
/// normals into the view space it reads with the pose that rendered them.
pub fn camera() -> Camera {
    Camera::looking_at(glam::Vec3::new(2.2, 2.4, 4.5), glam::Vec3::new(0.0, 0.7, 0.0))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "host_gbuffer.png".into());
    let size = (320, 240);
    let gpu = npr_runner::Gpu::headless()?;
    let camera = camera();

    // The host's frame, rendered as the host renders it.
    let g = gbuffer::render(&gpu.device, &gpu.queue, &camera, size);

    // The style, compiled here (a shipped host would load a bundle).
    let style = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/post/ink_over.npr");
    let mut sources = npr_diag::SourceMap::new();
    let compiled = npr_compiler::compile_file(&style, &mut sources, &Default::default())
        .map_err(|e| format!("{}: {e:?}", style.display()))?;
    let mut runtime = StyleRuntime::new(&gpu.device, &gpu.queue, compiled.program())?;

    // Each input with the convention the host wrote it in.
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    let near = camera.pose(0.0).near;
    runtime.set_input(
        "color_in",
        &view(&g.colour),
        SourceConvention::Color(ColorEncoding::Linear),
    )?;
    runtime.set_input(
        "depth_in",
        &view(&g.depth),
        SourceConvention::Depth(DepthConvention::ReverseZ { near }),
    )?;
    runtime.set_input(
        "normal_in",
        &view(&g.normal),
        SourceConvention::Normal(NormalConvention::World),
    )?;

    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("inked"),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let lights = Lights::default();
    let frame = Frame {
        camera: &camera,
        objects: &[],
        lights: &lights,
        time_s: 0.0,
        frame_index: 0,
        eye: 0,
    };
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    runtime.render(&mut encoder, &frame, Target::View(&view(&texture)))?;
    gpu.queue.submit([encoder.finish()]);

    let image = npr_runner::readback::read_texture(
        &gpu.device,
        &gpu.queue,
        &texture,
        size.0,
        size.1,
        npr_abi::Format::Rgba8unorm,
        "inked",
    )?;
    image.to_rgba8().save(&out)?;
    println!("wrote {out} ({}x{}, {})", size.0, size.1, gpu.describe());
    Ok(())
}
