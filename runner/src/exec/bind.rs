//! Bind group layouts and bind groups. Group 0 is per pass and per eye slot
//! (frame block, style block, targets, textures, samplers), rebuilt with the
//! size-dependent resources. Group 1 is the object block at a dynamic
//! offset into the one object buffer: shared by every pass, except that a
//! render pass reading per-object textures has its own layout and one group
//! per object (the object's bound image, or the declared default).

use super::Renderer;
use crate::gpu_count::{Create, CreateView};
use crate::scene::Scene;
use crate::textures::{GpuTexture, ObjectTextures};
use crate::RunError;
use npr_abi::manifest::*;

/// Every binding is visible to every stage a pass kind has (render and image
/// passes: vertex and fragment; compute passes: compute).
const ALL_STAGES: wgpu::ShaderStages = wgpu::ShaderStages::VERTEX_FRAGMENT.union(wgpu::ShaderStages::COMPUTE);

/// Group 1, binding 0: the object's uniform block at a dynamic offset.
pub(super) fn object_uniform_entry(object_uniform_size: u64) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: ALL_STAGES,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: true,
            min_binding_size: wgpu::BufferSize::new(object_uniform_size.max(16)),
        },
        count: None,
    }
}

/// The layout entry of one manifest binding (group 0, or group 1 after the object block).
pub(super) fn layout_entry(b: &Binding) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: b.binding,
        visibility: ALL_STAGES,
        ty: match &b.resource {
            Resource::FrameUniforms | Resource::StyleUniforms => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            Resource::Target { filterable, .. } => wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float {
                    filterable: *filterable,
                },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            Resource::Texture { .. } => wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            Resource::TextureSampler { .. } | Resource::LinearClampSampler => {
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)
            }
            Resource::ObjectValues { .. } => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
        },
        count: None,
    }
}

/// Group 0 layout of a pass: its manifest bindings.
pub(super) fn group0_layout(device: &wgpu::Device, pass: &PassManifest) -> wgpu::BindGroupLayout {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = pass.bindings.iter().map(layout_entry).collect();
    device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(&pass.name),
        entries: &entries,
    })
}

/// The shared group 1's layout: the object block at a dynamic offset. It
/// depends only on the style, so it lives as long as the pipelines made
/// with it, across scene changes.
pub(super) fn shared_object_layout(device: &wgpu::Device, object_uniform_size: u64) -> wgpu::BindGroupLayout {
    device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("npr object"),
        entries: &[object_uniform_entry(object_uniform_size)],
    })
}

/// The shared group 1 over the whole object buffer (made anew with the buffer).
pub(super) fn shared_object_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    buffer: &wgpu::Buffer,
    object_uniform_size: u64,
) -> wgpu::BindGroup {
    device.make_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("npr object"),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: wgpu::BufferSize::new(object_uniform_size.max(16)),
            }),
        }],
    })
}

/// What group 1 of a render pass binds: the object buffer, and the images
/// objects bind to per-object texture params.
pub(super) struct ObjectResources<'a> {
    pub scene: &'a Scene,
    pub buffer: &'a wgpu::Buffer,
    /// `Manifest::object_uniform_size`.
    pub uniform_size: u64,
    /// The style's textures (the declared defaults).
    pub textures: &'a [GpuTexture],
    pub object_textures: &'a ObjectTextures,
}

/// A pass reading per-object textures gets its own group 1 layout: the
/// shared dynamic-offset uniform at binding 0, then its textures. It
/// depends only on the pass (its `object_bindings`), never on which images
/// the objects bind, so the pipeline made with it serves every scene.
/// `None` for a pass that reads none (it uses the shared layout).
pub(super) fn pass_object_layout(
    device: &wgpu::Device,
    pass: &PassManifest,
    object_uniform_size: u64,
) -> Option<wgpu::BindGroupLayout> {
    if pass.object_bindings.is_empty() {
        return None;
    }
    let mut entries = vec![object_uniform_entry(object_uniform_size)];
    entries.extend(pass.object_bindings.iter().map(layout_entry));
    Some(device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(&pass.name),
        entries: &entries,
    }))
}

/// One group 1 per object of a pass with its own `layout`
/// ([`pass_object_layout`]); empty for a pass without one.
pub(super) fn pass_object_groups(
    device: &wgpu::Device,
    pass: &PassManifest,
    layout: Option<&wgpu::BindGroupLayout>,
    objects: &ObjectResources,
) -> Result<Vec<wgpu::BindGroup>, RunError> {
    let Some(layout) = layout else {
        return Ok(Vec::new());
    };
    // One group 1 per object: the object's bound image where it binds one,
    // the declared default otherwise. Objects binding the same images share
    // one group (the block is chosen by the dynamic offset), which wgpu
    // records faster than as many distinct groups.
    let object_size = wgpu::BufferSize::new(objects.uniform_size.max(16));
    let mut groups: Vec<wgpu::BindGroup> = Vec::new();
    let mut made: std::collections::HashMap<&std::collections::BTreeMap<usize, usize>, usize> =
        std::collections::HashMap::new();
    for (oi, o) in objects.scene.objects.iter().enumerate() {
        let bound = &objects.object_textures.bound[oi];
        if let Some(first) = made.get(bound) {
            groups.push(groups[*first].clone());
            continue;
        }
        made.insert(bound, oi);
        let gpu = |texture: usize| match objects.object_textures.bound[oi].get(&texture) {
            Some(i) => &objects.object_textures.images[*i],
            None => &objects.textures[texture],
        };
        let views: Vec<Option<wgpu::TextureView>> = pass
            .object_bindings
            .iter()
            .map(|b| match b.resource {
                Resource::Texture { texture } => Some(gpu(texture).texture.make_view(&Default::default())),
                _ => None,
            })
            .collect();
        let mut entries = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: objects.buffer,
                offset: 0,
                size: object_size,
            }),
        }];
        for (b, view) in pass.object_bindings.iter().zip(&views) {
            let resource = match (&b.resource, view) {
                (Resource::TextureSampler { texture }, _) => wgpu::BindingResource::Sampler(&gpu(*texture).sampler),
                (Resource::Texture { .. }, Some(view)) => wgpu::BindingResource::TextureView(view),
                _ => {
                    return Err(RunError::Internal(format!(
                        "pass `{}`: group 1 binding {} is not a per-object texture or sampler",
                        pass.name, b.binding
                    )))
                }
            };
            entries.push(wgpu::BindGroupEntry {
                binding: b.binding,
                resource,
            });
        }
        groups.push(device.make_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("{} / {}", pass.name, o.name)),
            layout,
            entries: &entries,
        }));
    }
    Ok(groups)
}

impl Renderer {
    /// Group 0 of pass `pi` in eye `slot` for frames of `parity`, over
    /// `physical` (every slot's physical textures): an `other_eye` target is
    /// bound to the other slot's texture, a `previous` one to the copy this
    /// parity does not write.
    pub(super) fn group0(
        &self,
        pi: usize,
        slot: usize,
        parity: usize,
        physical: &super::sized::Physical,
    ) -> wgpu::BindGroup {
        let pass = &self.manifest.passes[pi];
        let slots = physical.slots.len();
        let views: Vec<(u32, wgpu::TextureView)> = pass
            .bindings
            .iter()
            .filter_map(|b| match &b.resource {
                Resource::Target { target, copy, .. } => {
                    let index = self.manifest.targets[*target].physical;
                    let texture = match copy {
                        TargetCopy::This => physical.texture(slot, parity, index, false),
                        // The other eye's copy lives in the other slot (stereo styles only).
                        TargetCopy::OtherEye => physical.texture((slot + 1) % slots, parity, index, false),
                        TargetCopy::Previous => physical.texture(slot, parity, index, true),
                    };
                    Some((b.binding, texture.make_view(&Default::default())))
                }
                Resource::Texture { texture } => Some((
                    b.binding,
                    self.textures[*texture].texture.make_view(&Default::default()),
                )),
                _ => None,
            })
            .collect();
        let entries: Vec<wgpu::BindGroupEntry> = pass
            .bindings
            .iter()
            .filter_map(|b| {
                let resource = match &b.resource {
                    Resource::FrameUniforms => self.frame_buffers[slot].as_entire_binding(),
                    Resource::StyleUniforms => self.style_buffer.as_entire_binding(),
                    Resource::Target { .. } | Resource::Texture { .. } => {
                        wgpu::BindingResource::TextureView(views.iter().find(|(n, _)| *n == b.binding).map(|(_, v)| v)?)
                    }
                    Resource::TextureSampler { texture } => {
                        wgpu::BindingResource::Sampler(&self.textures[*texture].sampler)
                    }
                    Resource::LinearClampSampler => wgpu::BindingResource::Sampler(&self.linear_clamp),
                    // This frame's values of an earlier compute pass (validated: a compute pass).
                    Resource::ObjectValues { pass } => self.scene_gpu.values[*pass]
                        .as_ref()?
                        .copy(parity, false)
                        .as_entire_binding(),
                };
                Some(wgpu::BindGroupEntry {
                    binding: b.binding,
                    resource,
                })
            })
            .collect();
        self.device.make_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&pass.name),
            layout: self.passes[pi].layout0(),
            entries: &entries,
        })
    }
}
