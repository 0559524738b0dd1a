//! The buffers of compute passes. Per pass: its per-object value buffer
//! (`vec4<f32>` slots, `objects × slots`; two copies, written by frame
//! parity, when the pass keeps state); its member table (the objects it
//! runs over: `vec4<u32>`(object index, first vertex, vertex count, first
//! element workgroup)); and for a pass over vertices, its members' vertex
//! attributes one after the other (so each stage is one dispatch over all
//! members), its partials buffer (one `vec4` per value per element
//! workgroup) and its dispatch uniform; for a pass over pixels, partials
//! per element workgroup per object (`npr_abi::manifest::pixel_workgroups` of
//! them, which depends on the ID target's size: the dispatch uniform is
//! rewritten on every new size). Made with each scene; the value buffers
//! are zeroed again whenever the history resets (a new size,
//! `restart_history`), so state restarts from its first value, and a
//! scene change copies continuing objects' rows into them
//! (`continuity.rs`).

use super::meshes::{attribute_format, GpuMesh};
use crate::gpu_count::Create;
use crate::scene::Scene;
use crate::RunError;
use npr_abi::manifest::*;
use std::collections::BTreeMap;

/// Most objects one compute pass runs over (one object-stage workgroup each,
/// in one dispatch dimension).
pub const MAX_MEMBERS: usize = 65535;

/// The buffers of one compute pass.
pub(super) struct PassBuffers {
    /// This frame's values at `copies[parity % copies.len()]`; the previous
    /// frame's at the other copy (passes with state).
    pub copies: Vec<wgpu::Buffer>,
    pub slots: u32,
    /// `vec4<u32>` per member.
    pub members: wgpu::Buffer,
    pub member_count: u32,
    /// Element workgroups of all members (passes over vertices).
    pub element_workgroups: u32,
    /// The members' vertices per attribute (passes over vertices).
    /// (The previous positions' entry is the position buffer: they follow
    /// the `pooled_vertices` current positions in it.)
    pub attributes: BTreeMap<Attribute, wgpu::Buffer>,
    /// Every member's vertices together (0 for a pass not over meshes).
    pub pooled_vertices: u64,
    /// Every member's (object, first vertex, the object's
    /// `GpuMesh::vertex_revision` its vertices here are of): a member whose
    /// vertices change (a time-varying primitive, a deformed mesh) is copied
    /// again from the object's vertex buffers before the pass runs.
    pub member_vertices: Vec<(usize, u64, u64)>,
    /// Per element workgroup, one partial per value (passes over vertices).
    pub partials: Option<wgpu::Buffer>,
    /// Passes over vertices: `vec4<u32>`(element workgroups, members, 0, 0).
    /// Passes over pixels: `vec4<u32>`(the scene's objects, element
    /// workgroups, 0, 0), written by [`write_pixel_dispatch`].
    pub dispatch: Option<wgpu::Buffer>,
    /// A pass over pixels: its ID target (an index into the manifest's targets).
    pub pixels_of: Option<usize>,
    /// The scene's objects (at least 1: the size of the value buffers).
    pub objects: u64,
    /// Reduced values per element workgroup.
    pub reduced: u64,
    /// A pass over samples: every member's samples, [`SAMPLE_WORDS`] words each.
    pub samples: Option<wgpu::Buffer>,
}

impl PassBuffers {
    /// The element workgroups of a pass over pixels at output size
    /// `width × height` (0 for other passes).
    pub fn pixel_workgroups(&self, manifest: &Manifest, width: u32, height: u32) -> u32 {
        match self.pixels_of.and_then(|t| manifest.targets.get(t)) {
            Some(target) => pixel_workgroups(
                super::sized::scaled_size(width, height, target.scale),
                self.objects,
                self.reduced,
            ),
            None => 0,
        }
    }

    /// This frame's copy (`previous: false`) or the previous frame's.
    pub fn copy(&self, parity: usize, previous: bool) -> &wgpu::Buffer {
        let n = self.copies.len();
        &self.copies[(parity + usize::from(previous)) % n]
    }
}

/// Element workgroups for `vertices` elements.
pub(super) fn element_workgroups(vertices: usize) -> u32 {
    (vertices as u64)
        .div_ceil(ELEMENTS_PER_WORKGROUP as u64)
        .min(u32::MAX as u64) as u32
}

/// The CPU data of attribute `a` of `mesh`, as bytes.
fn attribute_data(mesh: &crate::scene::Mesh, a: Attribute) -> Option<&[u8]> {
    Some(match a {
        // At the first frame the previous position is the current one.
        Attribute::Position | Attribute::PreviousPosition => bytemuck::cast_slice(&mesh.positions),
        Attribute::Normal => bytemuck::cast_slice(&mesh.normals),
        Attribute::Uv => bytemuck::cast_slice(mesh.uvs.as_ref()?),
        Attribute::Tangent => bytemuck::cast_slice(mesh.tangents.as_ref()?),
        // `npr_abi::validate` refuses it in compute passes.
        Attribute::PatchWeight => return None,
    })
}

/// The buffers of every manifest pass (`None` for passes that are not compute).
pub(super) fn create(
    device: &wgpu::Device,
    manifest: &Manifest,
    scene: &Scene,
    meshes: &[GpuMesh],
) -> Result<Vec<Option<PassBuffers>>, RunError> {
    let objects = scene.objects.len().max(1) as u64;
    let mut all = Vec::new();
    // Samples drawn per (object, count, seed): two passes that sample the
    // same objects alike (the pattern tracker's two) share one draw.
    let mut drawn_samples: BTreeMap<(usize, u32, u64), crate::scene::samples::Samples> = BTreeMap::new();
    for p in &manifest.passes {
        let PassKindManifest::Compute {
            domain,
            tag,
            attributes,
            values,
            history,
            ..
        } = &p.kind
        else {
            all.push(None);
            continue;
        };
        let slots = values.len() as u32 + u32::from(*history);
        let value_buffer = |copy: usize| {
            device.make_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("npr values of `{}` #{copy}", p.name)),
                size: objects * slots as u64 * 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let copies = (0..if *history { 2 } else { 1 }).map(value_buffer).collect();
        let members: Vec<usize> = (0..scene.objects.len())
            .filter(|o| tag.as_ref().is_none_or(|t| scene.objects[*o].has_tag(t)))
            .collect();
        if members.len() > MAX_MEMBERS {
            return Err(RunError::Limit(format!(
                "compute pass `{}` runs over {} objects; at most {MAX_MEMBERS} are supported",
                p.name,
                members.len()
            )));
        }
        let (pixels_of, sample_spec) = match &p.kind {
            PassKindManifest::Compute { pixels_of, samples, .. } => (*pixels_of, *samples),
            _ => (None, None),
        };
        // The member table: where each member's elements start, how many it
        // has and its first element workgroup; and where its vertices start
        // in the pooled attributes (the same as its elements over vertices).
        let (mut table, mut first_element, mut first_workgroup) = (Vec::new(), 0u64, 0u64);
        let (mut vertex_starts, mut first_vertex) = (Vec::new(), 0u64);
        let mut sample_words: Vec<u32> = Vec::new();
        for &o in &members {
            let n = match (*domain, sample_spec) {
                (ComputeDomain::Vertices, _) => meshes[o].vertex_count as u64,
                (ComputeDomain::Samples, Some(spec)) => {
                    // Breslav et al. 2007 §3.1: stratified, stored as a
                    // triangle (pooled vertex indices) and barycentrics.
                    let seed = crate::scene::samples::object_seed(spec.seed, o);
                    let drawn = drawn_samples.entry((o, spec.count, seed)).or_insert_with(|| {
                        crate::scene::samples::stratified(&scene.objects[o].mesh, spec.count as usize, seed)
                    });
                    for x in &drawn.samples {
                        sample_words.extend(x.triangle.map(|i| i + first_vertex as u32));
                        sample_words.extend([x.b1.to_bits(), x.b2.to_bits(), drawn.spacing.to_bits()]);
                    }
                    drawn.samples.len() as u64
                }
                _ => 0,
            };
            table.push([o as u32, first_element as u32, n as u32, first_workgroup as u32]);
            vertex_starts.push(first_vertex);
            first_element += n;
            if domain.on_meshes() {
                first_vertex += meshes[o].vertex_count as u64;
            }
            first_workgroup += element_workgroups(n as usize) as u64;
        }
        if first_element > u32::MAX as u64 / 8 || first_vertex > u32::MAX as u64 / 4 || first_workgroup > 65535 * 65535
        {
            return Err(RunError::Limit(format!(
                "compute pass `{}` runs over {first_element} elements of {first_vertex} vertices, past what one dispatch addresses",
                p.name
            )));
        }
        let samples = (*domain == ComputeDomain::Samples).then(|| {
            if sample_words.is_empty() {
                sample_words.resize(SAMPLE_WORDS as usize, 0);
            }
            device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("npr samples of `{}`'s members", p.name)),
                contents: bytemuck::cast_slice(&sample_words),
                usage: wgpu::BufferUsages::STORAGE,
            })
        });
        let member_buffer = device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&format!("npr members of `{}`", p.name)),
            contents: if table.is_empty() {
                &[0u8; 16]
            } else {
                bytemuck::cast_slice(&table)
            },
            usage: wgpu::BufferUsages::STORAGE,
        });
        let mut pooled = BTreeMap::new();
        let mut member_vertices = Vec::new();
        if domain.on_meshes() {
            // The previous positions are pooled in the position's buffer,
            // after every member's current ones (`Attribute::has_compute_binding`).
            let previous = attributes.contains(&Attribute::PreviousPosition);
            for a in attributes.iter().filter(|a| a.has_compute_binding()) {
                let mut bytes = Vec::with_capacity((first_vertex * attribute_format(*a).1) as usize);
                let pooled_with = if previous && *a == Attribute::Position {
                    &[Attribute::Position, Attribute::PreviousPosition][..]
                } else {
                    std::slice::from_ref(a)
                };
                for a in pooled_with {
                    for &o in &members {
                        let data = attribute_data(&scene.objects[o].mesh, *a).ok_or_else(|| {
                            RunError::Internal(format!("object #{o} has no `{}` for pass `{}`", a.name(), p.name))
                        })?;
                        bytes.extend_from_slice(data);
                    }
                }
                if bytes.is_empty() {
                    bytes.resize(16, 0);
                }
                let buffer = device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(&format!("npr `{}` of `{}`'s members", a.name(), p.name)),
                    contents: &bytes,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                });
                if previous && *a == Attribute::Position {
                    pooled.insert(Attribute::PreviousPosition, buffer.clone());
                }
                pooled.insert(*a, buffer);
            }
            member_vertices = table
                .iter()
                .zip(&vertex_starts)
                .map(|(m, first)| (m[0] as usize, *first, meshes[m[0] as usize].vertex_revision))
                .collect();
        }
        let reduced = values.len().max(1) as u64;
        let (partials, dispatch) = if pixels_of.is_some() {
            // The most workgroups any size gets (the budget bounds them).
            let most = pixel_workgroups((u32::MAX, u32::MAX), objects, reduced) as u64;
            let partials = device.make_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("npr partials of `{}`", p.name)),
                size: most * objects * reduced * 16,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            });
            let dispatch = device.make_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("npr dispatch of `{}`", p.name)),
                size: 16,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            (Some(partials), Some(dispatch))
        } else if domain.on_meshes() {
            let partials = device.make_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("npr partials of `{}`", p.name)),
                size: first_workgroup.max(1) * values.len().max(1) as u64 * 16,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            });
            let dispatch = device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("npr dispatch of `{}`", p.name)),
                contents: bytemuck::cast_slice(&[first_workgroup as u32, members.len() as u32, 0, 0]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            (Some(partials), Some(dispatch))
        } else {
            (None, None)
        };
        all.push(Some(PassBuffers {
            copies,
            slots,
            members: member_buffer,
            member_count: members.len() as u32,
            element_workgroups: first_workgroup as u32,
            attributes: pooled,
            pooled_vertices: if domain.on_meshes() { first_vertex } else { 0 },
            member_vertices,
            partials,
            dispatch,
            pixels_of,
            objects,
            reduced,
            samples,
        }));
    }
    Ok(all)
}

/// The dispatch uniform of every pass over pixels for output size
/// `width × height`: the scene's objects and the element workgroups.
pub(super) fn write_pixel_dispatch(
    queue: &wgpu::Queue,
    manifest: &Manifest,
    buffers: &[Option<PassBuffers>],
    width: u32,
    height: u32,
) {
    for b in buffers.iter().flatten() {
        if let (Some(_), Some(dispatch)) = (b.pixels_of, &b.dispatch) {
            let workgroups = b.pixel_workgroups(manifest, width, height);
            queue.write_buffer(dispatch, 0, bytemuck::cast_slice(&[b.objects as u32, workgroups, 0, 0]));
        }
    }
}

/// Zero every value buffer: state restarts from its first value.
pub(super) fn reset(queue: &wgpu::Queue, buffers: &[Option<PassBuffers>]) {
    for b in buffers.iter().flatten() {
        for c in &b.copies {
            queue.write_buffer(c, 0, &vec![0u8; c.size() as usize]);
        }
    }
}
