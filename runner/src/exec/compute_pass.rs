//! The executor of `compute` passes. Group 0 is the pass's manifest
//! bindings (as every kind); group 1 is every object's block (the object
//! buffer read as a storage array), the pass's member table and, for a
//! pass over vertices or samples, its members' vertex attributes (and, over
//! samples, the samples: triangle and barycentrics) (`values.rs`); group 2
//! is the pass's own buffers for the frame's parity.
//!
//! Each stage is one dispatch over all members: a pass over vertices
//! records the element stage (every member's ⌈vertices / 1024⌉ workgroups,
//! laid out in x and y past 65535) and then the object stage (one
//! workgroup per member); a pass over objects, ⌈members / 64⌉ workgroups.
//! WebGPU makes a dispatch's storage writes visible to the next, so the
//! object stage reads complete partials.

use super::bind;
use super::common::{EncodeContext, Timestamps};
use super::meshes::{attribute_format, GpuMesh};
use super::sized::SizedPass;
use super::values::PassBuffers;
use crate::gpu_count::Create;
use crate::RunError;
use npr_abi::manifest::*;
use std::sync::atomic::{AtomicU64, Ordering};

pub(super) struct ComputePassExec {
    name: String,
    /// The element stage (passes over vertices).
    elements: Option<wgpu::ComputePipeline>,
    objects: wgpu::ComputePipeline,
    pub(super) layout0: wgpu::BindGroupLayout,
    /// Groups 1 and 2's layouts: their entries follow from the pass alone
    /// (its attributes, domain and state), so the pipelines made with them
    /// serve every scene.
    layout1: wgpu::BindGroupLayout,
    layout2: wgpu::BindGroupLayout,
    /// What the scene gives the pass ([`ComputePassExec::bind_scene`]).
    scene: ComputeScene,
}

/// A compute pass's groups over one scene's buffers (`values.rs`) and its
/// dispatch sizes: made anew when the objects change, the pipelines kept.
#[derive(Default)]
pub(super) struct ComputeScene {
    group1: Option<wgpu::BindGroup>,
    /// Group 2 per frame parity (one when the pass keeps no state).
    own_groups: Vec<wgpu::BindGroup>,
    member_count: u32,
    element_workgroups: u32,
    /// A pass over pixels (its element workgroups depend on the size).
    over_pixels: bool,
    /// Every member's vertices per attribute, copied again when they changed.
    member_copies: Vec<MemberCopy>,
}

/// A member's vertices of one attribute in the pass's attribute buffer,
/// copied again from the object's vertex buffer whenever that buffer was
/// rewritten (`GpuMesh::vertex_revision`: a time-varying primitive at a new
/// time, a host's deformed mesh); a still member is never copied.
struct MemberCopy {
    object: usize,
    attribute: Attribute,
    pooled: wgpu::Buffer,
    offset: u64,
    bytes_per_vertex: u64,
    /// The revision the pooled vertices are of (atomic: `encode` takes `&self`).
    copied: AtomicU64,
}

fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        })
        .collect();
    device.make_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

impl ComputePassExec {
    /// The pass's layouts and pipelines (no scene: [`ComputePassExec::bind_scene`]).
    pub fn build(
        device: &wgpu::Device,
        pass: &PassManifest,
        shader: super::common::PassShader,
    ) -> Result<ComputePassExec, RunError> {
        let PassKindManifest::Compute {
            domain,
            attributes,
            history,
            elements_entry,
            objects_entry,
            ..
        } = &pass.kind
        else {
            return Err(RunError::Internal(format!(
                "pass `{}` is not a compute pass",
                pass.name
            )));
        };
        // Group 1: the objects, the members, the members' attributes, the
        // samples (a pass over samples: `values::create` makes them).
        let bound = attributes.iter().filter(|a| a.has_compute_binding()).count();
        let group1_len = 2 + bound + usize::from(*domain == ComputeDomain::Samples);
        let storage = group1_len
            + if elements_entry.is_some() || *history { 2 } else { 1 }
            + pass
                .bindings
                .iter()
                .filter(|b| matches!(b.resource, Resource::ObjectValues { .. }))
                .count();
        let limit = device.limits().max_storage_buffers_per_shader_stage as usize;
        if storage > limit {
            return Err(RunError::Limit(format!(
                "compute pass `{}` binds {storage} storage buffers; this device allows {limit} per stage \
                 (read fewer other passes' values, or fewer vertex attributes, in it)",
                pass.name
            )));
        }
        let over_vertices = elements_entry.is_some();
        // Everything wgpu creates below is checked in this validation scope
        // (a manifest from disk may disagree with its WGSL); nothing returns
        // before it is popped.
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout0 = bind::group0_layout(device, pass);
        let entries1: Vec<wgpu::BindGroupLayoutEntry> =
            (0..group1_len).map(|i| storage_entry(i as u32, true)).collect();
        let layout1 = device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{} objects", pass.name)),
            entries: &entries1,
        });
        // Group 2: this frame's values, then the partials and the dispatch
        // uniform (over vertices) or the previous frame's values (state).
        let mut entries2 = vec![storage_entry(0, false)];
        if over_vertices {
            entries2.push(storage_entry(1, false));
            entries2.push(wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            });
        } else if *history {
            entries2.push(storage_entry(1, true));
        }
        let layout2 = device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{} buffers", pass.name)),
            entries: &entries2,
        });
        // The objects' entry point first, then the elements' (over vertices).
        let entries: Vec<&str> = std::iter::once(objects_entry.as_str())
            .chain(elements_entry.as_deref())
            .collect();
        let pipelines = shader.compute_pipelines(device, pass, &[&layout0, &layout1, &layout2], &entries);
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RunError::Internal(format!(
                "compute pipelines for pass `{}` rejected by wgpu: {err}",
                pass.name
            )));
        }
        let mut pipelines = pipelines.into_iter();
        let (Some(objects_pipeline), elements) = (pipelines.next(), pipelines.next()) else {
            return Err(RunError::Internal(format!("pass `{}` built no pipeline", pass.name)));
        };
        Ok(ComputePassExec {
            name: pass.name.clone(),
            elements,
            objects: objects_pipeline,
            layout0,
            layout1,
            layout2,
            scene: ComputeScene::default(),
        })
    }

    /// The pass's groups 1 and 2 over one scene's `object_buffer` and
    /// `buffers`, made with the layouts its pipelines were built with.
    pub fn bind_scene(
        &self,
        device: &wgpu::Device,
        pass: &PassManifest,
        object_buffer: &wgpu::Buffer,
        buffers: &PassBuffers,
    ) -> Result<ComputeScene, RunError> {
        let PassKindManifest::Compute {
            attributes,
            history,
            elements_entry,
            ..
        } = &pass.kind
        else {
            return Err(RunError::Internal(format!(
                "pass `{}` is not a compute pass",
                pass.name
            )));
        };
        let mut group1_buffers = vec![object_buffer, &buffers.members];
        for a in attributes.iter().filter(|a| a.has_compute_binding()) {
            group1_buffers.push(buffers.attributes.get(a).ok_or_else(|| {
                RunError::Internal(format!(
                    "pass `{}` has no `{}` buffer of its members",
                    pass.name,
                    a.name()
                ))
            })?);
        }
        // Passes over vertices and over pixels: an element stage, with
        // partials and a dispatch uniform.
        if let Some(samples) = &buffers.samples {
            group1_buffers.push(samples);
        }
        let over_vertices = elements_entry.is_some();
        if over_vertices && (buffers.partials.is_none() || buffers.dispatch.is_none()) {
            return Err(RunError::Internal(format!(
                "pass `{}` has no partials buffer",
                pass.name
            )));
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let group1 = group(
            device,
            &format!("{} objects", pass.name),
            &self.layout1,
            &group1_buffers,
        );
        let parities = if *history { 2 } else { 1 };
        let mut own_groups = Vec::new();
        for parity in 0..parities {
            let this = buffers.copy(parity, false);
            let own: Vec<&wgpu::Buffer> = match (&buffers.partials, &buffers.dispatch) {
                (Some(partials), Some(dispatch)) if over_vertices => vec![this, partials, dispatch],
                _ if *history => vec![this, buffers.copy(parity, true)],
                _ => vec![this],
            };
            own_groups.push(group(
                device,
                &format!("{} buffers, parity {parity}", pass.name),
                &self.layout2,
                &own,
            ));
        }
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RunError::Internal(format!(
                "the groups of compute pass `{}` rejected by wgpu: {err}",
                pass.name
            )));
        }
        let mut member_copies = Vec::new();
        for &(object, first, revision) in &buffers.member_vertices {
            for (a, pooled) in &buffers.attributes {
                let bytes_per_vertex = attribute_format(*a).1;
                // Previous positions follow every member's current ones.
                let base = if *a == Attribute::PreviousPosition {
                    buffers.pooled_vertices
                } else {
                    0
                };
                member_copies.push(MemberCopy {
                    object,
                    attribute: *a,
                    pooled: pooled.clone(),
                    offset: (base + first) * bytes_per_vertex,
                    bytes_per_vertex,
                    copied: AtomicU64::new(revision),
                });
            }
        }
        Ok(ComputeScene {
            group1: Some(group1),
            own_groups,
            member_count: buffers.member_count,
            element_workgroups: buffers.element_workgroups,
            over_pixels: buffers.pixels_of.is_some(),
            member_copies,
        })
    }

    /// Take the groups [`ComputePassExec::bind_scene`] made.
    pub fn set_scene(&mut self, scene: ComputeScene) {
        self.scene = scene;
    }

    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        sized: &SizedPass,
        ctx: &EncodeContext,
        timestamps: Option<&Timestamps>,
    ) {
        self.copy_changed_members(encoder, ctx.meshes);
        let mut cp = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&self.name),
            timestamp_writes: timestamps.map(Timestamps::compute_pass),
        });
        cp.set_bind_group(0, &sized.group0, &[]);
        // `bind_scene` made the groups before any frame (`Renderer::build`).
        let (Some(group1), Some(own)) = (
            &self.scene.group1,
            self.scene
                .own_groups
                .get(ctx.parity % self.scene.own_groups.len().max(1)),
        ) else {
            return;
        };
        cp.set_bind_group(1, group1, &[]);
        cp.set_bind_group(2, own, &[]);
        if self.scene.member_count == 0 {
            return;
        }
        match &self.elements {
            Some(elements) if self.scene.over_pixels => {
                // `sized.pixel_workgroups` is what the dispatch uniform says
                // (both from `PassBuffers::pixel_workgroups` at this size).
                cp.set_pipeline(elements);
                cp.dispatch_workgroups(sized.pixel_workgroups, 1, 1);
                cp.set_pipeline(&self.objects);
                cp.dispatch_workgroups(self.scene.member_count, 1, 1);
            }
            Some(elements) => {
                let n = self.scene.element_workgroups;
                if n > 0 {
                    cp.set_pipeline(elements);
                    // The shader numbers workgroups `x + y × 65535`.
                    cp.dispatch_workgroups(n.min(65535), n.div_ceil(65535), 1);
                }
                cp.set_pipeline(&self.objects);
                cp.dispatch_workgroups(self.scene.member_count, 1, 1);
            }
            None => {
                cp.set_pipeline(&self.objects);
                cp.dispatch_workgroups(self.scene.member_count.div_ceil(OBJECT_WORKGROUP), 1, 1);
            }
        }
    }

    /// Members whose vertex buffers were rewritten since the pass last
    /// copied them (a time-varying primitive, a deformed mesh): copy them
    /// into the pass's attribute buffers.
    fn copy_changed_members(&self, encoder: &mut wgpu::CommandEncoder, meshes: &[GpuMesh]) {
        for m in &self.scene.member_copies {
            let Some(mesh) = meshes.get(m.object) else { continue };
            if m.copied.load(Ordering::Relaxed) == mesh.vertex_revision {
                continue;
            }
            if let Some(source) = mesh.buffers.get(&m.attribute) {
                let bytes = mesh.vertex_count as u64 * m.bytes_per_vertex;
                encoder.copy_buffer_to_buffer(source, 0, &m.pooled, m.offset, bytes);
            }
            m.copied.store(mesh.vertex_revision, Ordering::Relaxed);
        }
    }
}
