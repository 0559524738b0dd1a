//! The wgpu objects the independent baseline builds once, each with plain
//! wgpu calls from the manifest: target and depth textures, the meshes'
//! vertex and index buffers, group 0 of a pass, the object group, and a
//! pass's render pipeline. Nothing here comes from `npr_runner::exec`.

use super::OverheadError;
use npr_abi::manifest::*;
use npr_abi::Format;
use std::collections::BTreeMap;
use wgpu::util::DeviceExt;

/// Every binding is visible to both stages of the two pass kinds drawn.
const STAGES: wgpu::ShaderStages = wgpu::ShaderStages::VERTEX_FRAGMENT;

/// A target's size at `scale` of the output (the ABI: rounded, at least 1 px).
pub fn scaled((width, height): (u32, u32), scale: f64) -> (u32, u32) {
    let s = |v: u32| ((v as f64 * scale).round() as u32).max(1);
    (s(width), s(height))
}

pub fn texture_format(f: Format) -> wgpu::TextureFormat {
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

/// A 2D texture a pass renders into: sampled by later passes and copied
/// out by the read-back, or a depth buffer.
pub fn texture(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    let usage = if format == wgpu::TextureFormat::Depth32Float {
        wgpu::TextureUsages::RENDER_ATTACHMENT
    } else {
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC
    };
    device.create_texture(&wgpu::TextureDescriptor {
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

/// One object's geometry: a vertex buffer per attribute the style reads.
pub struct Mesh {
    pub vertices: BTreeMap<Attribute, wgpu::Buffer>,
    pub index: wgpu::Buffer,
    pub index_count: u32,
}

pub fn upload_mesh(device: &wgpu::Device, mesh: &npr_runner::scene::Mesh, attributes: &[Attribute]) -> Mesh {
    let init = |label: &str, contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    let mut vertices = BTreeMap::new();
    for a in attributes {
        // `support::check` made sure every mesh has what the style reads.
        let bytes: &[u8] = match a {
            Attribute::Position => bytemuck::cast_slice(&mesh.positions),
            Attribute::Normal => bytemuck::cast_slice(&mesh.normals),
            Attribute::Uv => mesh.uvs.as_deref().map(bytemuck::cast_slice).unwrap_or_default(),
            Attribute::Tangent => mesh.tangents.as_deref().map(bytemuck::cast_slice).unwrap_or_default(),
            // `support::check` refuses styles that read patch weights.
            Attribute::PatchWeight => &[],
            // Compute passes only; the baseline draws render passes.
            Attribute::PreviousPosition => bytemuck::cast_slice(&mesh.positions),
        };
        vertices.insert(*a, init(a.name(), bytes, wgpu::BufferUsages::VERTEX));
    }
    let index = init(
        "indices",
        bytemuck::cast_slice(&mesh.indices),
        wgpu::BufferUsages::INDEX,
    );
    Mesh {
        vertices,
        index,
        index_count: mesh.indices.len() as u32,
    }
}

/// Group 1 of render passes: the object block at a dynamic offset into
/// `buffer`, `size` bytes per object.
pub fn object_group(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    size: u64,
) -> (wgpu::BindGroupLayout, wgpu::BindGroup) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("object"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: STAGES,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(size),
            },
            count: None,
        }],
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("object"),
        layout: &layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: wgpu::BufferSize::new(size),
            }),
        }],
    });
    (layout, group)
}

/// What group 0 of a pass may bind.
pub struct Group0Resources<'a> {
    pub frame: &'a wgpu::Buffer,
    pub style: Option<&'a wgpu::Buffer>,
    pub linear_clamp: &'a wgpu::Sampler,
    /// One texture per logical target.
    pub targets: &'a [wgpu::Texture],
}

/// Group 0 of `pass`, layout and group, as its manifest bindings list it
/// (`support::check` refused every other resource).
pub fn group0(
    device: &wgpu::Device,
    pass: &PassManifest,
    r: &Group0Resources,
) -> Result<(wgpu::BindGroupLayout, wgpu::BindGroup), OverheadError> {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = pass
        .bindings
        .iter()
        .map(|b| wgpu::BindGroupLayoutEntry {
            binding: b.binding,
            visibility: STAGES,
            ty: match &b.resource {
                Resource::Target { filterable, .. } => wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float {
                        filterable: *filterable,
                    },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                Resource::LinearClampSampler => wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                _ => wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
            },
            count: None,
        })
        .collect();
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(&pass.name),
        entries: &entries,
    });
    let views: Vec<Option<wgpu::TextureView>> = pass
        .bindings
        .iter()
        .map(|b| match &b.resource {
            Resource::Target { target, .. } => Some(r.targets[*target].create_view(&Default::default())),
            _ => None,
        })
        .collect();
    let mut entries = Vec::new();
    for (b, view) in pass.bindings.iter().zip(&views) {
        let resource = match (&b.resource, view, r.style) {
            (Resource::FrameUniforms, _, _) => r.frame.as_entire_binding(),
            (Resource::StyleUniforms, _, Some(style)) => style.as_entire_binding(),
            (Resource::LinearClampSampler, _, _) => wgpu::BindingResource::Sampler(r.linear_clamp),
            (Resource::Target { .. }, Some(view), _) => wgpu::BindingResource::TextureView(view),
            _ => {
                return Err(OverheadError::Unsupported(format!(
                    "binding {} of pass `{}`",
                    b.binding, pass.name
                )))
            }
        };
        entries.push(wgpu::BindGroupEntry {
            binding: b.binding,
            resource,
        });
    }
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(&pass.name),
        layout: &layout,
        entries: &entries,
    });
    Ok((layout, group))
}

fn vertex_format(a: Attribute) -> (wgpu::VertexFormat, u64) {
    match a {
        Attribute::Position | Attribute::Normal | Attribute::PreviousPosition => (wgpu::VertexFormat::Float32x3, 12),
        Attribute::Uv => (wgpu::VertexFormat::Float32x2, 8),
        Attribute::Tangent => (wgpu::VertexFormat::Float32x4, 16),
        Attribute::PatchWeight => (wgpu::VertexFormat::Float32, 4),
    }
}

/// The render pipeline of `pass`: its WGSL, one colour target per output
/// (no blending), no culling; with `attributes` (a render pass) one vertex
/// buffer per attribute and a depth test (less, written), without (an image
/// pass) neither.
pub fn pipeline(
    device: &wgpu::Device,
    manifest: &Manifest,
    pass: &PassManifest,
    wgsl: &str,
    group_layouts: &[Option<&wgpu::BindGroupLayout>],
    attributes: Option<&[Attribute]>,
) -> Result<wgpu::RenderPipeline, OverheadError> {
    let (vertex_entry, fragment_entry) = pass
        .kind
        .raster_entries()
        .ok_or_else(|| OverheadError::Unsupported(format!("pass `{}` is not drawn", pass.name)))?;
    let attributes = attributes.unwrap_or_default();
    let vertex_attributes: Vec<[wgpu::VertexAttribute; 1]> = attributes
        .iter()
        .enumerate()
        .map(|(location, a)| {
            [wgpu::VertexAttribute {
                format: vertex_format(*a).0,
                offset: 0,
                shader_location: location as u32,
            }]
        })
        .collect();
    let vertex_buffers: Vec<Option<wgpu::VertexBufferLayout>> = attributes
        .iter()
        .zip(&vertex_attributes)
        .map(|(a, attrs)| {
            Some(wgpu::VertexBufferLayout {
                array_stride: vertex_format(*a).1,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: attrs,
            })
        })
        .collect();
    let depth_stencil = matches!(pass.kind, PassKindManifest::Render { .. }).then_some(wgpu::DepthStencilState {
        format: wgpu::TextureFormat::Depth32Float,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias: Default::default(),
    });
    let color_targets: Vec<Option<wgpu::ColorTargetState>> = pass
        .outputs
        .iter()
        .map(|t| {
            Some(wgpu::ColorTargetState {
                format: texture_format(manifest.targets[*t].format),
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })
        })
        .collect();
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(&pass.shader),
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&pass.name),
        bind_group_layouts: group_layouts,
        immediate_size: 0,
    });
    Ok(device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(&pass.name),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(vertex_entry),
            compilation_options: Default::default(),
            buffers: &vertex_buffers,
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(fragment_entry),
            compilation_options: Default::default(),
            targets: &color_targets,
        }),
        multiview_mask: None,
        cache: None,
    }))
}
