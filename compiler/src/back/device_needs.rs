//! What each pass needs of the WebGPU device beyond its defaults
//! ([`npr_abi::manifest::DeviceNeed`], written into the manifest). Two
//! sources, each read where it is exact:
//! - the pipeline the manifest implies (`npr_abi::manifest::layout`): bind
//!   groups, bindings of each kind per shader stage, uniform block sizes,
//!   vertex buffers and attributes, colour attachments and their bytes per
//!   sample, and the optional features of 32-bit float targets;
//! - the validated shader (naga): workgroup memory used by each compute
//!   entry point, workgroup size, and the inter-stage variables between
//!   the vertex and fragment stages.
//!
//! Only values above WebGPU's defaults become needs, so most styles need
//! nothing and run on any conforming device as it comes.

use naga::valid::ModuleInfo;
use npr_abi::manifest::layout::{self, BindingType, Stage};
use npr_abi::manifest::{DeviceNeed, Feature, Limit, Manifest, PassKindManifest, PassManifest, Resource};

/// The needs of every pass of `manifest`, in pass order; `shader(pass)`
/// gives the pass's validated module.
pub fn device_needs<'m>(
    manifest: &Manifest,
    shader: impl Fn(&PassManifest) -> Option<&'m (naga::Module, ModuleInfo)>,
) -> Vec<DeviceNeed> {
    let mut out = Vec::new();
    for pass in &manifest.passes {
        for feature in features(manifest, pass) {
            out.push(DeviceNeed::Feature {
                pass: pass.name.clone(),
                feature,
            });
        }
        let mut measured = layout_limits(manifest, pass);
        if let Some((module, info)) = shader(pass) {
            measured.extend(shader_limits(pass, module, info));
        }
        // The largest value of each limit the pass needs, above the default only.
        for (limit, _, default) in Limit::ALL {
            let value = measured
                .iter()
                .filter(|(l, _)| *l == limit)
                .map(|(_, v)| *v)
                .max()
                .unwrap_or(0);
            if value > default {
                out.push(DeviceNeed::Limit {
                    pass: pass.name.clone(),
                    limit,
                    value,
                });
            }
        }
    }
    out
}

/// The optional features a pass's pipeline needs: a 32-bit float target
/// read with a filtering sampler, or blended into.
fn features(manifest: &Manifest, pass: &PassManifest) -> Vec<Feature> {
    let mut out = Vec::new();
    let filtered_float32 = pass.bindings.iter().any(|b| match &b.resource {
        Resource::Target { target, filterable, .. } => *filterable && !manifest.targets[*target].format.is_filterable(),
        _ => false,
    });
    if filtered_float32 {
        out.push(Feature::Float32Filterable);
    }
    let blended_float32 = pass
        .outputs
        .iter()
        .zip(&pass.blend)
        .any(|(t, b)| *b != npr_abi::manifest::Blend::Replace && !manifest.targets[*t].format.is_blendable());
    if blended_float32 {
        out.push(Feature::Float32Blendable);
    }
    out
}

/// The limits the pass's pipeline layout, vertex buffers and colour
/// attachments count against (one value per limit, any order).
fn layout_limits(manifest: &Manifest, pass: &PassManifest) -> Vec<(Limit, u64)> {
    let groups = layout::bind_group_layouts(manifest, pass);
    let entries = || groups.iter().flatten();
    let mut out = vec![
        (Limit::MaxBindGroups, groups.len() as u64),
        (
            Limit::MaxBindingsPerBindGroup,
            entries().map(|e| u64::from(e.binding) + 1).max().unwrap_or(0),
        ),
        (
            Limit::MaxDynamicUniformBuffersPerPipelineLayout,
            entries()
                .filter(|e| {
                    matches!(
                        e.ty,
                        BindingType::UniformBuffer {
                            dynamic_offset: true,
                            ..
                        }
                    )
                })
                .count() as u64,
        ),
    ];
    // Per-stage limits: the most any one stage sees.
    let per_stage = |limit: Limit, kind: fn(&BindingType) -> bool| {
        let most = Stage::ALL
            .iter()
            .map(|s| entries().filter(|e| e.visibility.includes(*s) && kind(&e.ty)).count())
            .max()
            .unwrap_or(0);
        (limit, most as u64)
    };
    out.extend([
        per_stage(Limit::MaxSampledTexturesPerShaderStage, |t| {
            matches!(t, BindingType::Texture { .. } | BindingType::DepthTexture)
        }),
        per_stage(Limit::MaxSamplersPerShaderStage, |t| {
            matches!(t, BindingType::FilteringSampler)
        }),
        per_stage(Limit::MaxStorageBuffersPerShaderStage, |t| {
            matches!(t, BindingType::StorageBuffer { .. })
        }),
        per_stage(Limit::MaxStorageTexturesPerShaderStage, |t| {
            matches!(t, BindingType::WriteOnlyStorageTexture { .. })
        }),
        per_stage(Limit::MaxUniformBuffersPerShaderStage, |t| {
            matches!(t, BindingType::UniformBuffer { .. })
        }),
    ]);
    // Uniform blocks bound whole: the frame's, the style's, one object's.
    let mut uniform_bytes = pass
        .bindings
        .iter()
        .map(|b| match b.resource {
            Resource::FrameUniforms => npr_abi::FRAME_UNIFORM_SIZE,
            Resource::StyleUniforms => manifest.style_uniform_size,
            _ => 0,
        })
        .max()
        .unwrap_or(0);
    if matches!(pass.kind, PassKindManifest::Render { .. }) {
        uniform_bytes = uniform_bytes.max(manifest.object_uniform_size);
    }
    out.push((Limit::MaxUniformBufferBindingSize, uniform_bytes));
    let buffers = layout::vertex_buffers(pass);
    out.push((Limit::MaxVertexBuffers, buffers.len() as u64));
    out.push((
        Limit::MaxVertexAttributes,
        buffers.iter().map(|b| b.attributes.len() as u64).sum(),
    ));
    if pass.kind.raster_entries().is_some() {
        let formats = pass.outputs.iter().map(|t| manifest.targets[*t].format);
        out.push((Limit::MaxColorAttachments, pass.outputs.len() as u64));
        out.push((
            Limit::MaxColorAttachmentBytesPerSample,
            layout::color_attachment_bytes_per_sample(formats),
        ));
    }
    out
}

/// The limits the pass's entry points count against in its shader.
fn shader_limits(pass: &PassManifest, module: &naga::Module, info: &ModuleInfo) -> Vec<(Limit, u64)> {
    let mut layouter = naga::proc::Layouter::default();
    // The module passed validation, so its types lay out; if not, no size is known.
    let laid_out = layouter.update(module.to_ctx()).is_ok();
    let mut out = Vec::new();
    let entries = pass.kind.entries();
    for (index, ep) in module.entry_points.iter().enumerate() {
        if !entries.iter().any(|(_, name)| *name == ep.name) {
            continue;
        }
        match ep.stage {
            naga::ShaderStage::Compute => {
                let [x, y, z] = ep.workgroup_size.map(u64::from);
                out.extend([
                    (Limit::MaxComputeWorkgroupSizeX, x),
                    (Limit::MaxComputeWorkgroupSizeY, y),
                    (Limit::MaxComputeWorkgroupSizeZ, z),
                    (Limit::MaxComputeInvocationsPerWorkgroup, x * y * z),
                ]);
                if laid_out {
                    // WebGPU's rule: each workgroup variable the entry point
                    // uses, its size rounded up to 16 bytes.
                    let uses = info.get_entry_point(index);
                    let bytes: u64 = module
                        .global_variables
                        .iter()
                        .filter(|(h, g)| g.space == naga::AddressSpace::WorkGroup && !uses[*h].is_empty())
                        .map(|(_, g)| u64::from(layouter[g.ty].size).next_multiple_of(16))
                        .sum();
                    out.push((Limit::MaxComputeWorkgroupStorageSize, bytes));
                }
            }
            naga::ShaderStage::Vertex => {
                let locations = ep
                    .function
                    .result
                    .as_ref()
                    .map(|r| binding_locations(module, r.ty, r.binding.as_ref()))
                    .unwrap_or_default();
                out.push((
                    Limit::MaxInterStageShaderVariables,
                    locations.iter().map(|l| u64::from(*l) + 1).max().unwrap_or(0),
                ));
            }
            _ => {}
        }
    }
    out
}

/// The `@location`s of a value of type `ty` with `binding` (a struct's
/// members when it has none of its own).
fn binding_locations(module: &naga::Module, ty: naga::Handle<naga::Type>, binding: Option<&naga::Binding>) -> Vec<u32> {
    match binding {
        Some(naga::Binding::Location { location, .. }) => vec![*location],
        Some(naga::Binding::BuiltIn(_)) => Vec::new(),
        None => match &module.types[ty].inner {
            naga::TypeInner::Struct { members, .. } => members
                .iter()
                .flat_map(|m| binding_locations(module, m.ty, m.binding.as_ref()))
                .collect(),
            _ => Vec::new(),
        },
    }
}
