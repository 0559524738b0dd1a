//! The executor of `compute` passes. Group 0 is the pass's manifest
//! bindings (as every kind); group 1 is the object block at a dynamic
//! offset plus, for a pass over vertices, the object's vertex attributes as
//! read-only storage buffers (one group per object); group 2 is the pass's
//! own buffers (`values.rs`) for the frame's parity.
//!
//! A pass over vertices records, per object with the pass's tag, one
//! dispatch of the element stage (⌈vertices / 1024⌉ workgroups), then one
//! workgroup of the object stage per object; a pass over objects, one
//! single-invocation dispatch per object. WebGPU makes each dispatch's
//! storage writes visible to the next, so the object stage reads complete
//! partials.

use super::bind::{self, ObjectResources};
use super::meshes::GpuMesh;
use super::pass::{EncodeContext, Timestamps};
use super::resources::SizedPass;
use super::values::{element_workgroups, PassBuffers};
use crate::RunError;
use abi::manifest::*;

pub(super) struct ComputePassExec {
    name: String,
    /// The element stage (passes over vertices).
    elements: Option<wgpu::ComputePipeline>,
    objects: wgpu::ComputePipeline,
    pub(super) layout0: wgpu::BindGroupLayout,
    /// Per object: its group 1, or `None` when the pass's tag excludes it.
    object_groups: Vec<Option<wgpu::BindGroup>>,
    /// Per object: element-stage workgroups.
    workgroups: Vec<u32>,
    /// Group 2 per frame parity (one when the pass keeps no state).
    own_groups: Vec<wgpu::BindGroup>,
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

impl ComputePassExec {
    pub fn build(
        device: &wgpu::Device,
        pass: &PassManifest,
        wgsl: &str,
        objects: &ObjectResources,
        meshes: &[GpuMesh],
        buffers: &PassBuffers,
    ) -> Result<ComputePassExec, RunError> {
        let PassKindManifest::Compute {
            tag,
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
        let layout0 = bind::group0_layout(device, pass);
        // Group 1: the object block, then the attributes.
        let mut entries1 = vec![bind::object_uniform_entry(objects.uniform_size)];
        entries1.extend((0..attributes.len()).map(|i| storage_entry(i as u32 + 1, true)));
        let layout1 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{} objects", pass.name)),
            entries: &entries1,
        });
        let mut object_groups = Vec::new();
        for (o, (object, mesh)) in objects.scene.objects.iter().zip(meshes).enumerate() {
            if tag.as_ref().is_some_and(|t| !object.tags.contains(t)) {
                object_groups.push(None);
                continue;
            }
            let mut entries = vec![wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: objects.buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(objects.uniform_size.max(16)),
                }),
            }];
            for (i, a) in attributes.iter().enumerate() {
                let buffer = mesh.buffers.get(a).ok_or_else(|| {
                    RunError::Internal(format!(
                        "object #{o} has no `{}` buffer for pass `{}`",
                        a.name(),
                        pass.name
                    ))
                })?;
                entries.push(wgpu::BindGroupEntry {
                    binding: i as u32 + 1,
                    resource: buffer.as_entire_binding(),
                });
            }
            object_groups.push(Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&format!("{} object #{o}", pass.name)),
                layout: &layout1,
                entries: &entries,
            })));
        }
        // Group 2: this frame's values, then the partials and the dispatch
        // uniform (over vertices) or the previous frame's values (state).
        let over_vertices = elements_entry.is_some();
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
        let layout2 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{} buffers", pass.name)),
            entries: &entries2,
        });
        let parities = if *history { 2 } else { 1 };
        let mut own_groups = Vec::new();
        for parity in 0..parities {
            let mut entries = vec![wgpu::BindGroupEntry {
                binding: 0,
                resource: buffers.copy(parity, false).as_entire_binding(),
            }];
            match (&buffers.partials, &buffers.dispatch) {
                (Some(partials), Some(dispatch)) if over_vertices => {
                    entries.push(wgpu::BindGroupEntry {
                        binding: 1,
                        resource: partials.as_entire_binding(),
                    });
                    entries.push(wgpu::BindGroupEntry {
                        binding: 2,
                        resource: dispatch.as_entire_binding(),
                    });
                }
                _ if over_vertices => {
                    return Err(RunError::Internal(format!(
                        "pass `{}` has no partials buffer",
                        pass.name
                    )))
                }
                _ if *history => entries.push(wgpu::BindGroupEntry {
                    binding: 1,
                    resource: buffers.copy(parity, true).as_entire_binding(),
                }),
                _ => {}
            }
            own_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&format!("{} buffers, parity {parity}", pass.name)),
                layout: &layout2,
                entries: &entries,
            }));
        }
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&pass.name),
            bind_group_layouts: &[Some(&layout0), Some(&layout1), Some(&layout2)],
            immediate_size: 0,
        });
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&pass.shader),
            source: wgpu::ShaderSource::Wgsl(wgsl.into()),
        });
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&format!("{} {entry}", pass.name)),
                layout: Some(&layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let elements = elements_entry.as_deref().map(pipeline);
        let objects_pipeline = pipeline(objects_entry);
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RunError::Internal(format!(
                "compute pipelines for pass `{}` rejected by wgpu: {err}",
                pass.name
            )));
        }
        Ok(ComputePassExec {
            name: pass.name.clone(),
            elements,
            objects: objects_pipeline,
            layout0,
            object_groups,
            workgroups: meshes.iter().map(|m| element_workgroups(m.vertex_count)).collect(),
            own_groups,
        })
    }

    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        sized: &SizedPass,
        ctx: &EncodeContext,
        timestamps: Option<&Timestamps>,
    ) {
        let mut cp = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&self.name),
            timestamp_writes: timestamps.map(|t| wgpu::ComputePassTimestampWrites {
                query_set: t.query_set,
                beginning_of_pass_write_index: t.beginning,
                end_of_pass_write_index: t.end,
            }),
        });
        cp.set_bind_group(0, &sized.group0, &[]);
        cp.set_bind_group(2, &self.own_groups[ctx.parity % self.own_groups.len()], &[]);
        let offset = |o: usize| (o as u64 * ctx.object_stride) as u32;
        if let Some(elements) = &self.elements {
            cp.set_pipeline(elements);
            for (o, group) in self.object_groups.iter().enumerate() {
                if let (Some(group), n) = (group, self.workgroups[o]) {
                    if n > 0 {
                        cp.set_bind_group(1, group, &[offset(o)]);
                        cp.dispatch_workgroups(n, 1, 1);
                    }
                }
            }
        }
        cp.set_pipeline(&self.objects);
        for (o, group) in self.object_groups.iter().enumerate() {
            if let Some(group) = group {
                cp.set_bind_group(1, group, &[offset(o)]);
                cp.dispatch_workgroups(1, 1, 1);
            }
        }
    }
}
