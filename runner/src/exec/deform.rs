//! The GPU deformation stage (docs/decisions/0053): every object playing a
//! glTF clip, or posed by its host (`Object::pose`: the embedding API's
//! skinned meshes, Bevy's `SkinnedMesh`, docs/decisions/0055), has its
//! vertices morphed and skinned by a compute dispatch
//! (`deform.wgsl`) at the start of each encoded frame, written over the
//! object's own position, normal and tangent buffers, which every pass
//! binds (render passes, the light view, both eyes; compute passes copy
//! them again when `GpuMesh::vertex_revision` moves).
//!
//! Per file (`Rig`, shared by its objects): the rest vertices with their
//! joints, weights and morph ranges, and the morph deltas, uploaded once.
//! Per object: its joint-matrix palette and morph weights (sampled from
//! its clip, or as its host gave them), written each frame its pose moved
//! into buffers made with the scene (`queue.write_buffer`, the
//! deformed-mesh path of decision 0045), posed with vectors kept from
//! frame to frame: a steady frame creates no GPU object and allocates
//! nothing.
//!
//! The previous pose: an animated object has a previous-positions buffer
//! of its own (`Attribute::PreviousPosition`, which compute passes read for
//! `position.previous`). When its pose moved, the stage copies the
//! positions there before deforming; at its first frame, after (so the
//! previous frame is the current one, as `previous_model` is), unless it
//! continues a deformed object of the scene before a scene change (the
//! same name, docs/decisions/0046): then that object's last positions are
//! copied there before (`carry_previous`), so the first frame after the
//! change shows the true motion.

use super::meshes::GpuMesh;
use crate::gpu_count::Create;
use crate::scene::rig::{Pose, PoseScratch, Rig};
use crate::scene::{Object, Scene};
use crate::RunError;
use glam::Mat4;
use npr_abi::manifest::Attribute;
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::{Arc, OnceLock};

/// The stage's WGSL (naga-validated by `runner/tests/runner/gpu_deform.rs`).
pub const DEFORM_WGSL: &str = include_str!("deform.wgsl");

/// Vertices per workgroup (`@workgroup_size` in `deform.wgsl`).
const WORKGROUP: u32 = 64;

/// The stage's pipeline and layout: made once per renderer, at the first
/// scene with an animated object, and kept across scenes.
pub(super) struct DeformPipeline {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl DeformPipeline {
    pub fn new(device: &wgpu::Device) -> DeformPipeline {
        let entry = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..7).map(|b| entry(b, b < 4)).collect();
        let layout = device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("npr deform"),
            entries: &entries,
        });
        let pipeline_layout = device.make_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("npr deform"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = device.make_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("npr deform"),
            source: wgpu::ShaderSource::Wgsl(DEFORM_WGSL.into()),
        });
        let pipeline = device.make_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("npr deform"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("deform"),
            compilation_options: Default::default(),
            cache: None,
        });
        DeformPipeline { layout, pipeline }
    }
}

/// What one matrix of an object's palette is, fixed by its rig.
#[derive(Clone, Copy)]
enum PaletteEntry {
    /// For vertices no piece covers: they stay as they are in `bind`.
    Identity,
    /// Joint `joint` of skin `skin`: `world · inverseBind`.
    Joint { skin: usize, joint: usize },
    /// An unskinned piece's node: its world matrix.
    Node(usize),
}

/// A rig's data on the GPU and the layout of its objects' palettes and
/// morph weights; shared by the objects of one file.
struct RigGpu {
    rig: Arc<Rig>,
    palette: Vec<PaletteEntry>,
    /// Per morph weight slot: (node, target index).
    morph_slots: Vec<(usize, usize)>,
    rest: wgpu::Buffer,
    deltas: wgpu::Buffer,
}

/// `RestVertex` of `deform.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct RestVertex {
    position: [f32; 4],
    normal: [f32; 4],
    tangent: [f32; 4],
    joints: [u32; 4],
    weights: [f32; 4],
    morph: [u32; 4],
}

/// `MorphDelta` of `deform.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MorphDelta {
    position: [f32; 4],
    normal: [f32; 4],
    tangent: [f32; 4],
}

fn storage(device: &wgpu::Device, label: &str, bytes: &[u8], writable: bool) -> wgpu::Buffer {
    device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        // wgpu refuses empty buffers: 64 zero bytes (one matrix, one delta).
        contents: if bytes.is_empty() { &[0u8; 64] } else { bytes },
        usage: if writable {
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST
        } else {
            wgpu::BufferUsages::STORAGE
        },
    })
}

impl RigGpu {
    fn new(device: &wgpu::Device, rig: &Arc<Rig>) -> RigGpu {
        let bind = &rig.bind;
        let extend = |v: [f32; 3], w: f32| [v[0], v[1], v[2], w];
        let mut vertices: Vec<RestVertex> = (0..bind.vertex_count())
            .map(|v| RestVertex {
                position: extend(bind.positions[v], 1.0),
                normal: extend(bind.normals[v], 0.0),
                tangent: bind.tangents.as_ref().map_or([0.0; 4], |t| t[v]),
                joints: [0; 4],
                weights: [1.0, 0.0, 0.0, 0.0],
                morph: [0; 4],
            })
            .collect();
        let mut palette = vec![PaletteEntry::Identity];
        let mut morph_slots = Vec::new();
        let mut deltas: Vec<MorphDelta> = Vec::new();
        for piece in &rig.pieces {
            let base = palette.len() as u32;
            let skin = piece.skin.and_then(|s| Some((s, rig.skins.get(s)?)));
            match skin {
                Some((s, skin)) => {
                    palette.extend((0..skin.joints.len()).map(|joint| PaletteEntry::Joint { skin: s, joint }))
                }
                None => palette.push(PaletteEntry::Node(piece.node)),
            }
            let first_weight = morph_slots.len() as u32;
            morph_slots.extend((0..piece.targets.len()).map(|k| (piece.node, k)));
            let first_delta = deltas.len() as u32;
            for target in &piece.targets {
                for local in 0..piece.vertex_count {
                    let pick = |a: &Option<Vec<[f32; 3]>>| a.as_ref().map_or([0.0; 4], |d| extend(d[local], 0.0));
                    deltas.push(MorphDelta {
                        position: extend(target.positions[local], 0.0),
                        normal: pick(&target.normals),
                        tangent: pick(&target.tangents),
                    });
                }
            }
            for local in 0..piece.vertex_count {
                let v = piece.first_vertex + local;
                let Some(r) = vertices.get_mut(v) else { break };
                match skin {
                    Some((_, skin)) => {
                        // A joint past the skin's has weight 0 (the reader
                        // refuses it otherwise): it names the skin's first.
                        r.joints = rig.joints.get(v).copied().unwrap_or([0; 4]).map(|j| {
                            base + if usize::from(j) < skin.joints.len() {
                                u32::from(j)
                            } else {
                                0
                            }
                        });
                        r.weights = rig.weights.get(v).copied().unwrap_or([1.0, 0.0, 0.0, 0.0]);
                    }
                    None => r.joints = [base; 4],
                }
                r.morph = [
                    first_weight,
                    piece.targets.len() as u32,
                    first_delta + local as u32,
                    piece.vertex_count as u32,
                ];
            }
        }
        RigGpu {
            rig: rig.clone(),
            palette,
            morph_slots,
            rest: storage(
                device,
                "npr deform rest vertices",
                bytemuck::cast_slice(&vertices),
                false,
            ),
            deltas: storage(device, "npr deform morph deltas", bytemuck::cast_slice(&deltas), false),
        }
    }
}

/// What the next encode does with an object's previous positions.
const KEEP: u8 = 0;
/// The pose moved: the positions become the previous ones before the dispatch.
const MOVED: u8 = 1;
/// The first frame: the previous positions are the current ones, after it.
const FIRST: u8 = 2;
/// The first frame after a scene change of an object that continues a
/// deformed one: the previous positions are its last deformed positions,
/// copied before the dispatch.
const CARRIED: u8 = 3;

/// Which pose an object's palette holds: a clip's time, or a host pose's
/// revision (`HostPose::revision`).
#[derive(Clone, Copy, PartialEq)]
enum PoseKey {
    Clip(f32),
    Host(u64),
}

/// The rig deforming `object`: its clip's, or its host pose's.
fn rig_of(object: &Object) -> Option<&Arc<Rig>> {
    match (&object.animation, &object.pose) {
        (Some(animation), _) => Some(&animation.rig),
        (None, Some(host)) => Some(&host.rig),
        (None, None) => None,
    }
}

/// One animated object's part of the stage.
struct DeformedObject {
    /// Its index in the scene.
    object: usize,
    rig: Arc<RigGpu>,
    palette: wgpu::Buffer,
    weights: wgpu::Buffer,
    group: wgpu::BindGroup,
    workgroups: u32,
    /// Kept from frame to frame (no allocation once grown).
    pose: Pose,
    scratch: PoseScratch,
    /// Column-major, as WGSL's `mat4x4<f32>`.
    palette_values: Vec<[f32; 16]>,
    weight_values: Vec<f32>,
    /// The pose the palette was last written for.
    posed_at: Option<PoseKey>,
    /// Its position buffer and its previous positions' (`bytes` long).
    positions: wgpu::Buffer,
    previous: wgpu::Buffer,
    bytes: u64,
    /// [`KEEP`], [`MOVED`], [`FIRST`] or [`CARRIED`], set by `prepare`,
    /// reset by `encode` (atomic: `encode` takes `&self`).
    step: AtomicU8,
    /// After a scene change, the position buffer of the deformed object
    /// of the previous scene it continues (same vertex count): its last
    /// pose, which becomes this object's previous positions at its first
    /// frame. Dropped when its pose next moves.
    carried: Option<wgpu::Buffer>,
}

/// `pose`'s joint matrices (column-major) and morph weights in the order
/// of `rig`'s palette and morph slots, into vectors kept between frames.
fn write_palette(rig: &RigGpu, pose: &Pose, palette: &mut Vec<[f32; 16]>, weights: &mut Vec<f32>) {
    palette.clear();
    palette.extend(rig.palette.iter().map(|entry| {
        match *entry {
            PaletteEntry::Identity => Mat4::IDENTITY,
            PaletteEntry::Joint { skin, joint } => rig.rig.skin_joint_matrix(skin, joint, pose),
            PaletteEntry::Node(node) => pose.world.get(node).copied().unwrap_or(Mat4::IDENTITY),
        }
        .to_cols_array()
    }));
    weights.clear();
    weights.extend(
        rig.morph_slots
            .iter()
            .map(|&(node, k)| pose.weights.get(node).and_then(|w| w.get(k)).copied().unwrap_or(0.0)),
    );
}

/// The stage over one scene's animated objects (none: it does nothing).
#[derive(Default)]
pub(super) struct DeformStage {
    objects: Vec<DeformedObject>,
}

impl DeformStage {
    /// The stage for `scene`'s objects playing a clip or posed by their
    /// host, over their buffers
    /// in `meshes`; the pipeline is made at the first scene that needs it.
    pub fn new(
        device: &wgpu::Device,
        pipeline: &OnceLock<DeformPipeline>,
        scene: &Scene,
        meshes: &[GpuMesh],
    ) -> Result<DeformStage, RunError> {
        let mut rigs: Vec<Arc<RigGpu>> = Vec::new();
        let mut objects = Vec::new();
        for (index, (object, mesh)) in scene.objects.iter().zip(meshes).enumerate() {
            let Some(object_rig) = rig_of(object) else { continue };
            if mesh.vertex_count != object_rig.bind.vertex_count() {
                return Err(RunError::Internal(format!(
                    "object `{}` is deformed by a rig of {} vertices over a mesh of {}",
                    object.name,
                    object_rig.bind.vertex_count(),
                    mesh.vertex_count
                )));
            }
            let rig = match rigs.iter().find(|r| Arc::ptr_eq(&r.rig, object_rig)) {
                Some(r) => r.clone(),
                None => {
                    let r = Arc::new(RigGpu::new(device, object_rig));
                    rigs.push(r.clone());
                    r
                }
            };
            let pipeline = pipeline.get_or_init(|| DeformPipeline::new(device));
            let palette = storage(device, "npr deform palette", &vec![0u8; 64 * rig.palette.len()], true);
            let weights = storage(
                device,
                "npr deform morph weights",
                &vec![0u8; 4 * rig.morph_slots.len()],
                true,
            );
            let empty = || storage(device, "npr deform no tangents", &[0u8; 16], true);
            let tangents = mesh.buffers.get(&Attribute::Tangent).cloned().unwrap_or_else(empty);
            let (Some(positions), Some(normals), Some(previous)) = (
                mesh.buffers.get(&Attribute::Position),
                mesh.buffers.get(&Attribute::Normal),
                mesh.buffers.get(&Attribute::PreviousPosition),
            ) else {
                return Err(RunError::Internal(format!(
                    "object `{}` has no position, normal or previous-position buffer to deform",
                    object.name
                )));
            };
            let buffers = [
                &rig.rest,
                &rig.deltas,
                &palette,
                &weights,
                positions,
                normals,
                &tangents,
            ];
            let entries: Vec<wgpu::BindGroupEntry> = buffers
                .iter()
                .enumerate()
                .map(|(i, b)| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource: b.as_entire_binding(),
                })
                .collect();
            let group = device.make_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("npr deform"),
                layout: &pipeline.layout,
                entries: &entries,
            });
            objects.push(DeformedObject {
                object: index,
                workgroups: (mesh.vertex_count as u32).div_ceil(WORKGROUP),
                palette_values: Vec::with_capacity(rig.palette.len()),
                weight_values: Vec::with_capacity(rig.morph_slots.len()),
                rig,
                palette,
                weights,
                group,
                pose: Pose {
                    world: Vec::new(),
                    weights: Vec::new(),
                },
                scratch: PoseScratch::default(),
                posed_at: None,
                positions: positions.clone(),
                previous: previous.clone(),
                bytes: 12 * mesh.vertex_count as u64,
                step: AtomicU8::new(KEEP),
                carried: None,
            });
        }
        Ok(DeformStage { objects })
    }

    /// Poses every animated object of `scene` at scene time `time_s` (a
    /// host-posed one as its host gave it) and writes its palette and morph
    /// weights; an object whose pose moved has its `vertex_revision` bumped
    /// (compute passes copy its vertices again after the stage has run).
    pub fn prepare(&mut self, queue: &wgpu::Queue, scene: &Scene, time_s: f64, meshes: &mut [GpuMesh]) {
        for o in &mut self.objects {
            let Some(object) = scene.objects.get(o.object) else {
                continue;
            };
            let (key, pose) = match (&object.animation, &object.pose) {
                (Some(animation), _) => {
                    let clip_time = animation.clip_time(time_s);
                    if o.posed_at == Some(PoseKey::Clip(clip_time)) {
                        continue;
                    }
                    let rig = &o.rig.rig;
                    rig.pose_into(Some((animation.clip, clip_time)), &mut o.pose, &mut o.scratch);
                    (PoseKey::Clip(clip_time), &o.pose)
                }
                (None, Some(host)) => {
                    if o.posed_at == Some(PoseKey::Host(host.revision)) {
                        continue;
                    }
                    (PoseKey::Host(host.revision), &host.pose)
                }
                (None, None) => continue,
            };
            write_palette(&o.rig, pose, &mut o.palette_values, &mut o.weight_values);
            let first = o.posed_at.is_none();
            queue.write_buffer(&o.palette, 0, bytemuck::cast_slice(&o.palette_values));
            if !o.weight_values.is_empty() {
                queue.write_buffer(&o.weights, 0, bytemuck::cast_slice(&o.weight_values));
            }
            let step = match (first, &o.carried) {
                (true, Some(_)) => CARRIED,
                (true, None) => FIRST,
                (false, _) => {
                    o.carried = None;
                    MOVED
                }
            };
            o.step.store(step, Ordering::Relaxed);
            o.posed_at = Some(key);
            if let Some(mesh) = meshes.get_mut(o.object) {
                mesh.vertex_revision += 1;
            }
        }
    }

    /// After a scene change: each deformed object that continues a
    /// deformed object of `old` (`continuing`, by index; the same vertex
    /// count) takes its last deformed positions as its previous ones at
    /// its first frame, so `position.previous` shows the true motion
    /// across the change instead of none.
    pub fn carry_previous(&mut self, old: &DeformStage, continuing: &[Option<usize>]) {
        for o in &mut self.objects {
            let Some(Some(from)) = continuing.get(o.object) else {
                continue;
            };
            if let Some(before) = old.objects.iter().find(|b| b.object == *from) {
                if before.bytes == o.bytes && before.posed_at.is_some() {
                    o.carried = Some(before.positions.clone());
                }
            }
        }
    }

    /// Records the stage: one dispatch per animated object, before any pass.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, pipeline: &OnceLock<DeformPipeline>) {
        let (Some(pipeline), false) = (pipeline.get(), self.objects.is_empty()) else {
            return;
        };
        // The pose moved: this frame's previous positions are the last
        // deformed ones (after a scene change, those of the object it continues).
        for o in &self.objects {
            match (o.step.load(Ordering::Relaxed), &o.carried) {
                (MOVED, _) if o.bytes > 0 => encoder.copy_buffer_to_buffer(&o.positions, 0, &o.previous, 0, o.bytes),
                (CARRIED, Some(old)) if o.bytes > 0 => encoder.copy_buffer_to_buffer(old, 0, &o.previous, 0, o.bytes),
                _ => {}
            }
        }
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("npr deform"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&pipeline.pipeline);
            for o in &self.objects {
                if o.workgroups == 0 {
                    continue;
                }
                pass.set_bind_group(0, &o.group, &[]);
                // `deform.wgsl` numbers workgroups `x + y × 65535`.
                pass.dispatch_workgroups(o.workgroups.min(65535), o.workgroups.div_ceil(65535), 1);
            }
        }
        // The first frame: no motion yet. Either way, done until the next pose.
        for o in &self.objects {
            if o.step.swap(KEEP, Ordering::Relaxed) == FIRST && o.bytes > 0 {
                encoder.copy_buffer_to_buffer(&o.positions, 0, &o.previous, 0, o.bytes);
            }
        }
    }
}
