//! The conversions of host inputs, on the GPU: the one definition of each
//! (`convert.rs` resolves a source's convention into a [`Conversion`],
//! this draws it). A fullscreen draw reads the source texel by texel
//! (`textureLoad`, no filtering) and writes the language's convention into
//! the style's input texture (half floats). Both paths run it: a file's
//! image uploaded as 32-bit floats ([`convert_level`]), and a host's own
//! texture view, converted inside the host's encoder every frame
//! (`embed::inputs`), so one image gives the same texels either way.

use super::convert::Conversion;
use crate::gpu_count::{Create, CreateView};
use crate::image_level::Level;

/// What every input texture is: linear half floats, as a filter's level
/// (depth keeps 11 significant bits, 5 mm at 10 m; an id is exact up to
/// 2048), drawn into by the conversion and copied out by tests.
pub const INPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The draw. `c.mode.x`: 0 as it is, 1 colour, 2 depth as a view
/// distance with a background sentinel, 3 reverse-Z depth, 4 normals, 5
/// motion in fractions of the image (scaled to pixels by its size);
/// `c.mode.y`: colour 1 decodes sRGB, 2 encodes it; `c.mode.z`: normals
/// stored as n·0.5 + 0.5 (a normalized-integer texture); `c.param.x`: the
/// depth sentinel or near plane; `c.m0..m2`: the normals' matrix columns.
pub(crate) const CONVERT_WGSL: &str = concat!(
    crate::fullscreen::fullscreen_vertex_wgsl!(),
    crate::fullscreen::srgb_wgsl!(),
    "
struct Conversion {
    m0: vec4<f32>,
    m1: vec4<f32>,
    m2: vec4<f32>,
    param: vec4<f32>,
    mode: vec4<u32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var<uniform> c: Conversion;

@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let v = textureLoad(source, vec2<i32>(p.xy), 0);
    switch c.mode.x {
        case 1u: {
            if c.mode.y == 1u {
                return vec4<f32>(srgb_to_linear(v.r), srgb_to_linear(v.g), srgb_to_linear(v.b), v.a);
            }
            if c.mode.y == 2u {
                return vec4<f32>(linear_to_srgb(v.r), linear_to_srgb(v.g), linear_to_srgb(v.b), v.a);
            }
            return v;
        }
        case 2u: {
            // A distance along the view axis; the sentinel and beyond: nothing hit.
            return vec4<f32>(select(v.r, 0.0, v.r >= c.param.x), 0.0, 0.0, 1.0);
        }
        case 3u: {
            // Infinite reverse-Z: ndc = near / distance, 0 where nothing was hit.
            return vec4<f32>(select(c.param.x / v.r, 0.0, v.r == 0.0), 0.0, 0.0, 1.0);
        }
        case 4u: {
            var n = v.xyz;
            if c.mode.z == 1u {
                n = n * 2.0 - 1.0;
            }
            return vec4<f32>(mat3x3<f32>(c.m0.xyz, c.m1.xyz, c.m2.xyz) * n, 1.0);
        }
        case 5u: {
            // A change of UV (Bevy's motion vectors) in pixels of this image.
            return vec4<f32>(v.xy * vec2<f32>(textureDimensions(source)), 0.0, 1.0);
        }
        default: {
            return v;
        }
    }
}
"
);

/// The size of the `Conversion` uniform block.
pub const UNIFORM_SIZE: u64 = 80;

impl Conversion {
    /// The `Conversion` block of the shader.
    pub fn uniform_bytes(&self) -> [u8; UNIFORM_SIZE as usize] {
        let m = self.normal_matrix.to_cols_array();
        let floats: [f32; 16] = [
            m[0], m[1], m[2], 0.0, m[3], m[4], m[5], 0.0, m[6], m[7], m[8], 0.0, self.param, 0.0, 0.0, 0.0,
        ];
        let mut out = [0u8; UNIFORM_SIZE as usize];
        out[..64].copy_from_slice(bytemuck::cast_slice(&floats));
        let mode: [u32; 4] = [self.mode, self.colour, u32::from(self.encoded_normals), 0];
        out[64..].copy_from_slice(bytemuck::cast_slice(&mode));
        out
    }
}

/// The conversion pipeline, made once per renderer or runtime.
pub struct Converter {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

impl Converter {
    pub fn new(device: &wgpu::Device) -> Converter {
        let module = device.make_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("npr input conversion"),
            source: wgpu::ShaderSource::Wgsl(CONVERT_WGSL.into()),
        });
        let layout = device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("npr input conversion"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        // Unfilterable: textureLoad reads every float format,
                        // 32-bit floats and a depth texture's depth included.
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(UNIFORM_SIZE),
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.make_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("npr input conversion"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.make_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("npr input conversion"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: INPUT_FORMAT,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Converter { pipeline, layout }
    }

    /// A uniform buffer for one input's [`Conversion`].
    pub fn uniform(&self, device: &wgpu::Device) -> wgpu::Buffer {
        device.make_buffer(&wgpu::BufferDescriptor {
            label: Some("npr input conversion"),
            size: UNIFORM_SIZE,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// The bind group reading `source` with the conversion in `uniform`.
    pub fn bind(&self, device: &wgpu::Device, source: &wgpu::TextureView, uniform: &wgpu::Buffer) -> wgpu::BindGroup {
        device.make_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("npr input conversion"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(source),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: uniform.as_entire_binding(),
                },
            ],
        })
    }

    /// Record the conversion of `group`'s source into `target` (a view of
    /// an input texture of the source's size).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, group: &wgpu::BindGroup, target: &wgpu::TextureView) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("npr input conversion"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// An input texture of `width`×`height`: sampled by the style, drawn into
/// by the conversion, copied out to read it back.
pub fn input_texture(device: &wgpu::Device, name: &str, width: u32, height: u32) -> wgpu::Texture {
    device.make_texture(&wgpu::TextureDescriptor {
        label: Some(name),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: INPUT_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// `raw` (a file's image as it was written) converted by `conversion` into
/// `target`, an input texture of its size: uploaded as 32-bit floats, so
/// the draw reads the file's values exactly, and submitted now.
pub fn convert_level(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    converter: &Converter,
    raw: &Level,
    conversion: &Conversion,
    target: &wgpu::Texture,
) {
    let size = wgpu::Extent3d {
        width: raw.width,
        height: raw.height,
        depth_or_array_layers: 1,
    };
    let source = device.make_texture(&wgpu::TextureDescriptor {
        label: Some("npr input as read"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: &source,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        bytemuck::cast_slice(&raw.pixels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(raw.width * 16),
            rows_per_image: Some(raw.height),
        },
        size,
    );
    let uniform = converter.uniform(device);
    queue.write_buffer(&uniform, 0, &conversion.uniform_bytes());
    let group = converter.bind(device, &source.make_view(&Default::default()), &uniform);
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("npr input conversion"),
    });
    converter.encode(&mut encoder, &group, &target.make_view(&Default::default()));
    queue.submit([encoder.finish()]);
}
