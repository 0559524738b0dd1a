//! The pass-shaped baseline of `npr bench host`: an independent wgpu
//! program whose frame runs no npr code (it reads the manifest, and the
//! style's image headers for their sizes, when it is made), that records
//! per pass of the style a pass of the same shape: the pass's colour
//! attachments (one texture per logical target of the style, in its
//! format at its scale, so a pass that reads an earlier pass's target
//! samples the texture that pass drew), a depth attachment for a render
//! pass, one vertex buffer per attribute a render pass reads, a pipeline of
//! its own per pass (as a program drawing the same targets must have), and
//! the pass's group 0 as the manifest lists it: the frame and style
//! blocks, the targets it reads (a `previous(...)` or `other_eye(...)`
//! read from a second texture of the target's shape), the style's
//! textures (one each, of the image's size, with the mip chain the style
//! asks for: wgpu tracks every level a view covers) and their samplers.
//! A render pass that reads per-object textures binds a group 1 per
//! object with them, as the style does; every other draw binds one group
//! 1 with the object's block at a dynamic offset. Then the present pass
//! samples the output into one target. A render pass binds the mesh's
//! buffers once (every object shares the mesh) and draws every object; a
//! compute pass is one dispatch of an empty shader; any other pass draws
//! a fullscreen triangle. One `write_buffer` per frame uploads the frame
//! block and every object's.
//! Its shaders do nothing a style does and read only the frame and object
//! blocks: what it measures is the API work a frame of these passes, with
//! these bindings, costs on the CPU at least, so npr's time over it is
//! npr's own work (uniforms, scene, its recording). `minimal.rs` is the
//! same with one target per pass and nothing bound but the blocks.

use super::{block_binding, block_entry, cleared, discarded_depth, target_view, uniform_group, uniform_layout};
use crate::bench_overhead::setup::{scaled, texture_format};
use npr_abi::manifest::{Binding, Manifest, PassKindManifest, PassManifest, Resource, TargetCopy};
use npr_runner::RunError;

/// Bytes between blocks (wgpu's minimum uniform offset alignment): the
/// frame block at 0, object `i`'s at `STRIDE * (1 + i)`.
const STRIDE: u64 = 256;

/// WebGPU's default `maxColorAttachments`.
const MAX_COLORS: usize = 8;

/// The shader of a pass with `outputs` colour outputs: the object's model
/// times the frame's matrix (the frame block at group 0's `frame_binding`,
/// the identity where the pass binds none), or a fullscreen triangle; a
/// constant colour.
fn wgsl(outputs: usize, frame_binding: Option<u32>) -> String {
    let fields: String = (0..outputs)
        .map(|i| format!("@location({i}) c{i}: vec4<f32>, "))
        .collect();
    let writes: String = (0..outputs).map(|i| format!("o.c{i} = vec4<f32>(0.5); ")).collect();
    let frame = match frame_binding {
        Some(b) => format!(
            "@group(0) @binding({b}) var<uniform> frame: Block;\nfn frame_m() -> mat4x4<f32> {{ return frame.m; }}"
        ),
        None => "fn frame_m() -> mat4x4<f32> { return mat4x4<f32>(); }".to_string(),
    };
    format!(
        "struct Block {{ m: mat4x4<f32> }}
{frame}
@group(1) @binding(0) var<uniform> object: Block;
@vertex fn vs_object(@location(0) p: vec3<f32>) -> @builtin(position) vec4<f32> {{
    return frame_m() * object.m * vec4<f32>(p, 1.0);
}}
@vertex fn vs_full(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {{
    return frame_m() * vec4<f32>(f32((i << 1u) & 2u) * 2.0 - 1.0, 1.0 - f32(i & 2u) * 2.0, 0.0, 1.0);
}}
struct Out {{ {fields}}}
@fragment fn fs() -> Out {{ var o: Out; {writes}return o; }}
"
    )
}

/// A pass that draws: its pipeline, colour targets, groups and, for a
/// render pass, its depth buffer and vertex buffer count.
struct Draw {
    pipeline: wgpu::RenderPipeline,
    colors: Vec<wgpu::TextureView>,
    depth: Option<wgpu::TextureView>,
    /// `Some(n)`: a render pass reading `n` vertex attributes.
    vertex_buffers: Option<usize>,
    group0: wgpu::BindGroup,
    /// Per object, for a render pass reading per-object textures; empty
    /// otherwise (the shared group 1).
    object_groups: Vec<wgpu::BindGroup>,
}

/// What the program records for one pass of the style.
enum Pass {
    Draw(Draw),
    /// A compute pass of the style (it writes no target): one dispatch of
    /// an empty shader.
    Dispatch(wgpu::ComputePipeline),
}

/// What the passes bind besides the blocks: one texture per logical
/// target (and a second one for `previous(...)` and `other_eye(...)`
/// reads), a texture and a sampler for each of the style's textures, the
/// clamp sampler of target reads, the style block and a storage buffer
/// for compute passes' values.
struct Bound {
    targets: Vec<wgpu::Texture>,
    copies: Vec<wgpu::Texture>,
    /// Per declared texture of the style, in the manifest's order.
    textures: Vec<wgpu::Texture>,
    samplers: Vec<wgpu::Sampler>,
    /// The bilinear clamp sampler of `sample()` reads of targets.
    sampler: wgpu::Sampler,
    style: wgpu::Buffer,
    values: wgpu::Buffer,
    blocks: wgpu::Buffer,
}

/// A texture the passes draw into and sample (`bench_overhead`'s).
fn sampled_target(device: &wgpu::Device, format: wgpu::TextureFormat, side: u32) -> wgpu::Texture {
    crate::bench_overhead::setup::texture(device, "pass-shaped target", (side, side), format)
}

/// A bilinear sampler.
fn linear_sampler(device: &wgpu::Device) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

/// A declared texture of the style as a program drawing the same look
/// would hold it: the image's size (a generated noise's own), with a full
/// mip chain where the style asks for mips and an art-map's levels (wgpu
/// tracks the state of every level a bound view covers); 64², one level,
/// where the size is made at load (a rip-map's atlas, a halftone table).
/// Its texels are never written: no shader of this program reads them.
fn style_texture(device: &wgpu::Device, t: &npr_abi::manifest::TextureManifest) -> Result<wgpu::Texture, RunError> {
    use npr_abi::manifest::TextureSourceManifest as Source;
    let probe = |path: &str, resolved: &str| {
        npr_runner::texture_file::probe(std::path::Path::new(resolved))
            .map_err(|e| RunError::User(vec![e.to_diagnostic(&t.name, path)]))
    };
    // Levels to 1×1 along the longer side (abi's one definition of a chain's length).
    let full_chain = |(width, height): (u32, u32)| npr_abi::RipmapAtlas::levels(width.max(height));
    let ((width, height), mip_level_count) = match &t.source {
        Source::Image { path, resolved, .. } => {
            let size = probe(path, resolved)?;
            (size, if t.mips { full_chain(size) } else { 1 })
        }
        Source::Noise(noise) => {
            let size = (noise.size, noise.size);
            (size, if t.mips { full_chain(size) } else { 1 })
        }
        // An art-map's levels are its texture's mip chain (`levels`, or
        // the whole chain); a rip-map's are packed into one atlas level,
        // whose size is made at load.
        Source::Artmap(art) if !art.rip => {
            let size = probe(&art.path, &art.resolved)?;
            (size, art.levels.unwrap_or(full_chain(size)).min(full_chain(size)))
        }
        _ => ((64, 64), 1),
    };
    Ok(device.create_texture(&wgpu::TextureDescriptor {
        label: Some("pass-shaped style texture"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    }))
}

fn view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&Default::default())
}

/// The layout entry of a binding of the manifest, of the type the
/// manifest states for its resource.
fn layout_entry(b: &Binding) -> wgpu::BindGroupLayoutEntry {
    let texture = |filterable| wgpu::BindingType::Texture {
        sample_type: wgpu::TextureSampleType::Float { filterable },
        view_dimension: wgpu::TextureViewDimension::D2,
        multisampled: false,
    };
    let buffer = |ty| wgpu::BindingType::Buffer {
        ty,
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    wgpu::BindGroupLayoutEntry {
        binding: b.binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: match &b.resource {
            Resource::FrameUniforms | Resource::StyleUniforms => buffer(wgpu::BufferBindingType::Uniform),
            Resource::Target { filterable, .. } => texture(*filterable),
            Resource::Texture { .. } => texture(true),
            Resource::TextureSampler { .. } | Resource::LinearClampSampler => {
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)
            }
            Resource::ObjectValues { .. } => buffer(wgpu::BufferBindingType::Storage { read_only: true }),
        },
        count: None,
    }
}

impl Bound {
    /// The views of the textures `bindings` read, in their order (`None`
    /// for a buffer or sampler): made first, so that the entries can
    /// borrow them.
    fn views(&self, bindings: &[Binding]) -> Vec<Option<wgpu::TextureView>> {
        bindings
            .iter()
            .map(|b| match &b.resource {
                Resource::Target { target, copy, .. } => Some(view(match copy {
                    TargetCopy::This => &self.targets[*target],
                    TargetCopy::OtherEye | TargetCopy::Previous => &self.copies[*target],
                })),
                Resource::Texture { texture } => Some(view(&self.textures[*texture])),
                _ => None,
            })
            .collect()
    }

    /// The resource of a binding of the manifest (`view` from [`Bound::views`]).
    fn resource<'a>(&'a self, b: &Binding, view: Option<&'a wgpu::TextureView>) -> wgpu::BindingResource<'a> {
        let buffer = |buffer| {
            wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: None,
            })
        };
        match (&b.resource, view) {
            // The frame block's slot of the blocks buffer (the whole buffer
            // passes a uniform binding's size limit at 1,000 objects).
            (Resource::FrameUniforms, _) => wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: &self.blocks,
                offset: 0,
                size: wgpu::BufferSize::new(STRIDE),
            }),
            (Resource::StyleUniforms, _) => buffer(&self.style),
            (Resource::ObjectValues { .. }, _) => buffer(&self.values),
            (Resource::TextureSampler { texture }, _) => wgpu::BindingResource::Sampler(&self.samplers[*texture]),
            (Resource::LinearClampSampler, _) => wgpu::BindingResource::Sampler(&self.sampler),
            (_, Some(view)) => wgpu::BindingResource::TextureView(view),
            (_, None) => unreachable!("`views` makes a view for every texture binding"),
        }
    }

    /// A group of `layout` binding `bindings`, after `first` (group 1's
    /// object block) when given.
    fn group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        bindings: &[Binding],
        first: Option<wgpu::BindGroupEntry>,
    ) -> wgpu::BindGroup {
        let views = self.views(bindings);
        let entries: Vec<wgpu::BindGroupEntry> = first
            .into_iter()
            .chain(bindings.iter().zip(&views).map(|(b, v)| wgpu::BindGroupEntry {
                binding: b.binding,
                resource: self.resource(b, v.as_ref()),
            }))
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout,
            entries: &entries,
        })
    }
}

/// What every drawing pass is built from.
struct Builder<'a> {
    device: &'a wgpu::Device,
    bound: &'a Bound,
    shared_object_layout: &'a wgpu::BindGroupLayout,
    /// One position attribute per vertex buffer slot.
    attributes: &'a [[wgpu::VertexAttribute; 1]],
    objects: usize,
}

impl Builder<'_> {
    /// A pass drawing into `colors` (of `formats`, `side`²) with
    /// `vertex_buffers` for a render pass, binding `bindings` in group 0
    /// and, with `object_bindings`, a group 1 per object.
    fn draw(
        &self,
        (colors, formats, side): (Vec<wgpu::TextureView>, Vec<wgpu::TextureFormat>, u32),
        vertex_buffers: Option<usize>,
        (bindings, object_bindings): (&[Binding], &[Binding]),
    ) -> Pass {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings.iter().map(layout_entry).collect();
        let layout0 = self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: None,
            entries: &entries,
        });
        // A pass reading per-object textures: its own group 1 layout
        // (the object block, then its textures), one group per object.
        let own_object_layout = (!object_bindings.is_empty()).then(|| {
            let mut entries = vec![block_entry(true)];
            entries.extend(object_bindings.iter().map(layout_entry));
            self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: None,
                entries: &entries,
            })
        });
        let object_layout = own_object_layout.as_ref().unwrap_or(self.shared_object_layout);
        let object_groups = match &own_object_layout {
            Some(layout) => (0..self.objects)
                .map(|_| {
                    let block = block_binding(&self.bound.blocks);
                    self.bound.group(self.device, layout, object_bindings, Some(block))
                })
                .collect(),
            None => Vec::new(),
        };
        let pipeline_layout = self.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&layout0), Some(object_layout)],
            immediate_size: 0,
        });
        let frame_binding = bindings
            .iter()
            .find(|b| matches!(b.resource, Resource::FrameUniforms))
            .map(|b| b.binding);
        let module = self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: None,
            source: wgpu::ShaderSource::Wgsl(wgsl(formats.len(), frame_binding).into()),
        });
        let buffers: Vec<Option<wgpu::VertexBufferLayout>> = self.attributes[..vertex_buffers.unwrap_or(0)]
            .iter()
            .map(|a| {
                Some(wgpu::VertexBufferLayout {
                    array_stride: 12,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: a,
                })
            })
            .collect();
        let targets: Vec<Option<wgpu::ColorTargetState>> = formats.iter().map(|&f| Some(f.into())).collect();
        let depth = vertex_buffers.map(|_| wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        });
        let pipeline = self.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: None,
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(if vertex_buffers.is_some() {
                    "vs_object"
                } else {
                    "vs_full"
                }),
                compilation_options: Default::default(),
                buffers: &buffers,
            },
            primitive: Default::default(),
            depth_stencil: depth,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        });
        Pass::Draw(Draw {
            pipeline,
            colors,
            depth: vertex_buffers.map(|_| target_view(self.device, wgpu::TextureFormat::Depth32Float, side)),
            vertex_buffers,
            group0: self.bound.group(self.device, &layout0, bindings, None),
            object_groups,
        })
    }
}

pub(super) struct PassShaped {
    passes: Vec<Pass>,
    object_group: wgpu::BindGroup,
    blocks_buffer: wgpu::Buffer,
    /// One copy of the mesh's positions per vertex buffer slot (a style
    /// reads each attribute from its own buffer).
    vertex: Vec<wgpu::Buffer>,
    indices: wgpu::Buffer,
    index_count: u32,
    blocks: Vec<u8>,
}

/// The present pass's bindings: the frame block and the style's output.
fn present_bindings(manifest: &Manifest) -> Vec<Binding> {
    vec![
        Binding {
            binding: 0,
            resource: Resource::FrameUniforms,
        },
        Binding {
            binding: 1,
            resource: Resource::Target {
                target: manifest.output,
                filterable: false,
                copy: TargetCopy::This,
            },
        },
    ]
}

impl PassShaped {
    pub(super) fn new(
        device: &wgpu::Device,
        manifest: &Manifest,
        objects: usize,
        size: u32,
        mesh: &npr_runner::scene::Mesh,
    ) -> Result<PassShaped, RunError> {
        use wgpu::util::DeviceExt;
        let side = |scale: f64| scaled((size, size), scale).0;
        let target =
            |t: &npr_abi::manifest::TargetManifest| sampled_target(device, texture_format(t.format), side(t.scale));
        let blocks_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: STRIDE * (1 + objects) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let buffer = |size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: size.max(16).next_multiple_of(16),
                usage,
                mapped_at_creation: false,
            })
        };
        let bound = Bound {
            targets: manifest.targets.iter().map(target).collect(),
            copies: manifest.targets.iter().map(target).collect(),
            textures: manifest
                .textures
                .iter()
                .map(|t| style_texture(device, t))
                .collect::<Result<_, _>>()?,
            samplers: manifest.textures.iter().map(|_| linear_sampler(device)).collect(),
            sampler: linear_sampler(device),
            style: buffer(manifest.style_uniform_size, wgpu::BufferUsages::UNIFORM),
            values: buffer(16 * objects as u64, wgpu::BufferUsages::STORAGE),
            blocks: blocks_buffer.clone(),
        };
        let shared_object_layout = uniform_layout(device, true);
        let compute_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: None,
            source: wgpu::ShaderSource::Wgsl("@compute @workgroup_size(1) fn cs() {}".into()),
        });
        let most_buffers = manifest
            .passes
            .iter()
            .filter_map(|p| match &p.kind {
                PassKindManifest::Render { attributes, .. } => Some(attributes.len().max(1)),
                _ => None,
            })
            .max()
            .unwrap_or(1);
        let attributes: Vec<[wgpu::VertexAttribute; 1]> = (0..most_buffers)
            .map(|slot| {
                [wgpu::VertexAttribute {
                    format: wgpu::VertexFormat::Float32x3,
                    offset: 0,
                    shader_location: slot as u32,
                }]
            })
            .collect();
        let builder = Builder {
            device,
            bound: &bound,
            shared_object_layout: &shared_object_layout,
            attributes: &attributes,
            objects,
        };
        let mut passes: Vec<Pass> = manifest
            .passes
            .iter()
            .map(|p: &PassManifest| {
                if matches!(p.kind, PassKindManifest::Compute { .. }) {
                    return Pass::Dispatch(device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: None,
                        layout: None,
                        module: &compute_module,
                        entry_point: Some("cs"),
                        compilation_options: Default::default(),
                        cache: None,
                    }));
                }
                let vertex_buffers = match &p.kind {
                    PassKindManifest::Render { attributes, .. } => Some(attributes.len().max(1)),
                    _ => None,
                };
                let colors = p.outputs.iter().map(|&t| view(&bound.targets[t])).collect();
                let formats = p
                    .outputs
                    .iter()
                    .map(|&t| texture_format(manifest.targets[t].format))
                    .collect();
                builder.draw(
                    (colors, formats, side(p.scale)),
                    vertex_buffers,
                    (&p.bindings, &p.object_bindings),
                )
            })
            .collect();
        let presented = sampled_target(device, wgpu::TextureFormat::Rgba8Unorm, size);
        passes.push(builder.draw(
            (vec![view(&presented)], vec![wgpu::TextureFormat::Rgba8Unorm], size),
            None,
            (&present_bindings(manifest), &[]),
        ));
        Ok(PassShaped {
            passes,
            object_group: uniform_group(device, &shared_object_layout, &blocks_buffer),
            vertex: (0..most_buffers)
                .map(|_| {
                    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: None,
                        contents: bytemuck::cast_slice(&mesh.positions),
                        usage: wgpu::BufferUsages::VERTEX,
                    })
                })
                .collect(),
            indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
            index_count: mesh.indices.len() as u32,
            blocks_buffer,
            blocks: vec![0; (STRIDE as usize) * (1 + objects)],
        })
    }

    /// Upload the frame's and every object's block and record the passes.
    pub(super) fn frame(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        view_proj: glam::Mat4,
        models: &[glam::Mat4],
    ) {
        self.blocks[..64].copy_from_slice(bytemuck::bytes_of(&view_proj.to_cols_array()));
        for (i, m) in models.iter().enumerate() {
            let at = (1 + i) * STRIDE as usize;
            self.blocks[at..at + 64].copy_from_slice(bytemuck::bytes_of(&m.to_cols_array()));
        }
        queue.write_buffer(&self.blocks_buffer, 0, &self.blocks);
        for pass in &self.passes {
            let p = match pass {
                Pass::Draw(draw) => draw,
                Pass::Dispatch(pipeline) => {
                    let mut pass = encoder.begin_compute_pass(&Default::default());
                    pass.set_pipeline(pipeline);
                    pass.dispatch_workgroups(1, 1, 1);
                    continue;
                }
            };
            // On the stack, as a program that knows its passes writes them.
            let colors: [Option<wgpu::RenderPassColorAttachment>; MAX_COLORS] =
                std::array::from_fn(|i| p.colors.get(i).map(cleared));
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &colors[..p.colors.len()],
                depth_stencil_attachment: p.depth.as_ref().map(discarded_depth),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&p.pipeline);
            pass.set_bind_group(0, &p.group0, &[]);
            match p.vertex_buffers {
                Some(buffers) => {
                    for (slot, buffer) in self.vertex[..buffers].iter().enumerate() {
                        pass.set_vertex_buffer(slot as u32, buffer.slice(..));
                    }
                    pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
                    for i in 0..models.len() {
                        let group = p.object_groups.get(i).unwrap_or(&self.object_group);
                        pass.set_bind_group(1, group, &[((1 + i) as u64 * STRIDE) as u32]);
                        pass.draw_indexed(0..self.index_count, 0, 0..1);
                    }
                }
                None => {
                    pass.set_bind_group(1, &self.object_group, &[STRIDE as u32]);
                    pass.draw(0..3, 0..1);
                }
            }
        }
    }
}
