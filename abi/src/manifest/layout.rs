//! The pipeline a host builds for each pass, as the manifest implies it,
//! in WebGPU's terms: every bind group layout (not only the manifest's
//! group 0), the vertex buffers and the colour targets' byte cost. The
//! runner's executors build these layouts with wgpu (`npr_runner::exec`); the
//! compiler counts them against WebGPU's default limits
//! (`npr_compiler::back::device_needs`, written into [`Manifest::device_needs`]);
//! `tests/general/webgpu_portability.rs` builds them in a browser's WebGPU,
//! an implementation that is not wgpu. A host in another language reads
//! the same rules here.

use super::*;

/// The shader stages a binding is visible to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Visibility {
    /// Render, image and lines passes: both stages of the render pipeline.
    VertexFragment,
    /// A lines pass's kept depth, read by its vertex shader only.
    Vertex,
    /// Compute and tiled image passes.
    Compute,
}

impl Visibility {
    /// Whether a shader of stage `stage` sees the binding.
    pub fn includes(self, stage: Stage) -> bool {
        matches!(
            (self, stage),
            (Visibility::VertexFragment, Stage::Vertex | Stage::Fragment)
                | (Visibility::Vertex, Stage::Vertex)
                | (Visibility::Compute, Stage::Compute)
        )
    }
}

/// A shader stage, for WebGPU's per-stage limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    Vertex,
    Fragment,
    Compute,
}

impl Stage {
    pub const ALL: [Stage; 3] = [Stage::Vertex, Stage::Fragment, Stage::Compute];
}

/// What a layout entry binds (WebGPU's `GPUBindGroupLayoutEntry` member).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BindingType {
    /// `buffer: { type: "uniform" }`; `min_binding_size` 0 is none.
    UniformBuffer {
        dynamic_offset: bool,
        min_binding_size: u64,
    },
    /// `buffer: { type: "storage" | "read-only-storage" }`.
    StorageBuffer { read_only: bool },
    /// `texture: { sampleType: "float" | "unfilterable-float", viewDimension: "2d" }`.
    Texture { filterable: bool },
    /// `texture: { sampleType: "depth", viewDimension: "2d" }`.
    DepthTexture,
    /// `sampler: { type: "filtering" }`.
    FilteringSampler,
    /// `storageTexture: { access: "write-only", format, viewDimension: "2d" }`.
    WriteOnlyStorageTexture { format: Format },
}

/// One entry of a bind group layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LayoutEntry {
    pub binding: u32,
    pub visibility: Visibility,
    pub ty: BindingType,
}

impl PassKindManifest {
    /// Where the pass's bindings are visible: the stages of its pipeline.
    pub fn visibility(&self) -> Visibility {
        match self {
            PassKindManifest::Render { .. } | PassKindManifest::Image { .. } | PassKindManifest::Lines { .. } => {
                Visibility::VertexFragment
            }
            PassKindManifest::TiledImage { .. } | PassKindManifest::Compute { .. } => Visibility::Compute,
        }
    }
}

/// The binding type of a manifest binding (group 0, or a render pass's
/// per-object textures in group 1).
pub fn binding_type(resource: &Resource) -> BindingType {
    match resource {
        Resource::FrameUniforms | Resource::StyleUniforms => BindingType::UniformBuffer {
            dynamic_offset: false,
            min_binding_size: 0,
        },
        Resource::Target { filterable, .. } => BindingType::Texture {
            filterable: *filterable,
        },
        Resource::Texture { .. } => BindingType::Texture { filterable: true },
        Resource::TextureSampler { .. } | Resource::LinearClampSampler => BindingType::FilteringSampler,
        Resource::ObjectValues { .. } => BindingType::StorageBuffer { read_only: true },
    }
}

/// Every bind group layout of `pass`'s pipeline, group by group:
/// - group 0: the manifest's `bindings`, for every kind;
/// - render: group 1 is the object block (binding 0, a uniform at a
///   dynamic offset, at least 16 bytes) and then `object_bindings`;
/// - tiled image: group 1 is the outputs as write-only storage textures;
/// - compute: group 1 is the objects, the members, one array per vertex
///   attribute and (over samples) the samples, all read-only storage;
///   group 2 this frame's values, then the partials and the dispatch
///   uniform (with an element stage) or the previous frame's values
///   (with state);
/// - lines with a depth test: group 1 is the kept depth (vertex stage).
pub fn bind_group_layouts(manifest: &Manifest, pass: &PassManifest) -> Vec<Vec<LayoutEntry>> {
    let visibility = pass.kind.visibility();
    let entry = |binding: u32, ty: BindingType| LayoutEntry {
        binding,
        visibility,
        ty,
    };
    let group0: Vec<LayoutEntry> = pass
        .bindings
        .iter()
        .map(|b| entry(b.binding, binding_type(&b.resource)))
        .collect();
    let storage = |binding: u32, read_only: bool| entry(binding, BindingType::StorageBuffer { read_only });
    let mut groups = vec![group0];
    match &pass.kind {
        PassKindManifest::Render { .. } => {
            let mut group1 = vec![entry(
                0,
                BindingType::UniformBuffer {
                    dynamic_offset: true,
                    min_binding_size: manifest.object_uniform_size.max(16),
                },
            )];
            group1.extend(
                pass.object_bindings
                    .iter()
                    .map(|b| entry(b.binding, binding_type(&b.resource))),
            );
            groups.push(group1);
        }
        PassKindManifest::Image { .. } => {}
        PassKindManifest::TiledImage { .. } => groups.push(
            pass.outputs
                .iter()
                .enumerate()
                .map(|(k, t)| {
                    entry(
                        k as u32,
                        BindingType::WriteOnlyStorageTexture {
                            format: manifest.targets[*t].format,
                        },
                    )
                })
                .collect(),
        ),
        PassKindManifest::Compute {
            domain,
            attributes,
            history,
            elements_entry,
            ..
        } => {
            let bound = attributes.iter().filter(|a| a.has_compute_binding()).count();
            let inputs = 2 + bound + usize::from(*domain == ComputeDomain::Samples);
            groups.push((0..inputs as u32).map(|b| storage(b, true)).collect());
            let mut own = vec![storage(0, false)];
            if elements_entry.is_some() {
                own.push(storage(1, false));
                own.push(entry(
                    2,
                    BindingType::UniformBuffer {
                        dynamic_offset: false,
                        min_binding_size: 0,
                    },
                ));
            } else if *history {
                own.push(storage(1, true));
            }
            groups.push(own);
        }
        PassKindManifest::Lines { depth, .. } => {
            if depth.is_test() {
                groups.push(vec![LayoutEntry {
                    binding: 0,
                    visibility: Visibility::Vertex,
                    ty: BindingType::DepthTexture,
                }]);
            }
        }
    }
    groups
}

/// One vertex attribute: `components` f32s at `offset` in its buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VertexAttributeLayout {
    pub location: u32,
    pub offset: u64,
    /// 1 to 4: WebGPU's `float32`, `float32x2`, `float32x3`, `float32x4`.
    pub components: u32,
}

/// One vertex buffer (stepped per vertex).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VertexBufferLayout {
    pub array_stride: u64,
    pub attributes: Vec<VertexAttributeLayout>,
}

/// The vertex buffers of `pass`'s render pipeline: a render pass has one
/// tightly packed buffer per attribute (location = index); a lines pass
/// one buffer of [`crate::lines::LineVertex`]; the other kinds none.
pub fn vertex_buffers(pass: &PassManifest) -> Vec<VertexBufferLayout> {
    match &pass.kind {
        PassKindManifest::Render { attributes, .. } => attributes
            .iter()
            .enumerate()
            .map(|(location, a)| VertexBufferLayout {
                array_stride: 4 * u64::from(a.components()),
                attributes: vec![VertexAttributeLayout {
                    location: location as u32,
                    offset: 0,
                    components: a.components(),
                }],
            })
            .collect(),
        PassKindManifest::Lines { .. } => vec![VertexBufferLayout {
            array_stride: std::mem::size_of::<crate::lines::LineVertex>() as u64,
            attributes: crate::lines::LINE_VERTEX_ATTRIBUTES
                .iter()
                .enumerate()
                .map(|(location, &(offset, components))| VertexAttributeLayout {
                    location: location as u32,
                    offset,
                    components,
                })
                .collect(),
        }],
        PassKindManifest::Image { .. } | PassKindManifest::TiledImage { .. } | PassKindManifest::Compute { .. } => {
            Vec::new()
        }
    }
}

/// The bytes per sample of `formats` as colour attachments, by WebGPU's
/// rule: each attachment is aligned to its component alignment, then adds
/// its render-target pixel byte cost (checked against
/// `maxColorAttachmentBytesPerSample`).
pub fn color_attachment_bytes_per_sample(formats: impl IntoIterator<Item = Format>) -> u64 {
    formats.into_iter().fold(0, |total, f| {
        let (cost, alignment) = f.render_target_cost_and_alignment();
        total.next_multiple_of(alignment) + cost
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn color_attachment_bytes_follow_webgpus_alignment_rule() {
        // The spec's example: r8unorm, then rgba32float aligned to 4.
        assert_eq!(
            color_attachment_bytes_per_sample([Format::R8unorm, Format::Rgba32float]),
            4 + 16
        );
        // rgba8unorm costs 8 (WebGPU's table), so four of them fill the default 32.
        assert_eq!(color_attachment_bytes_per_sample([Format::Rgba8unorm; 4]), 32);
        assert_eq!(color_attachment_bytes_per_sample([Format::Rgba32float; 8]), 128);
    }
}
