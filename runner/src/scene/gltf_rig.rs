//! Reading a glTF file's skins, morph targets and animations into a
//! [`Rig`] (the file's meshes are then its rest pose, deformed by it).
//!
//! Every problem names the file and the glTF path (`/skins/0/joints`,
//! `/meshes/1/primitives/0/attributes/WEIGHTS_0`, …) in an E0402, or an
//! E0404 for a skin past [`MAX_JOINTS`]. Skin weights are accepted when
//! their sum is within [`WEIGHT_SUM_TOLERANCE`] of 1 and renormalised
//! exactly: quantised (8- or 16-bit) weights cannot sum to 1 exactly, and
//! the spec asks only that they be as close as the type allows. Past the
//! tolerance the file is refused rather than renormalised: such weights
//! come from a broken export (a vertex bound to no bone sums to 0), and
//! renormalising would draw something the artist never saw.

use super::anim_sampler::{Interpolation, Sampler};
use super::mesh::Mesh;
use super::mesh_error::MeshLoadError;
use super::rig::{Channel, Clip, MorphTarget, Piece, Property, Rig, RigNode, Skin};
use glam::{Mat3, Mat4, Quat, Vec3};
use gltf::buffer::Data as BufferData;
use gltf::mesh::Mode;
use npr_diag::codes;

/// Most joints of one skin: the joint matrices of a GPU skinning stage fit
/// one 16 KiB uniform array (256 × 64 bytes), a quarter of WebGPU's
/// guaranteed binding size; real characters use tens to about two hundred.
pub use npr_diag::limits::MAX_JOINTS;

/// Node hierarchies deeper than this are treated as malformed (a cycle, or an
/// attempt to exhaust the stack); the rig reader and the static glTF reader
/// both walk them.
pub(super) const MAX_NODE_DEPTH: usize = 256;

/// How far a vertex's skin weights may sum from 1 and still be
/// renormalised (a 4-weight u8 set is off by at most 4 × 0.5/255 ≈ 0.008).
pub const WEIGHT_SUM_TOLERANCE: f32 = 0.01;

/// Whether the file has anything a [`Rig`] holds.
pub fn has_rig(document: &gltf::Document) -> bool {
    document.skins().len() > 0
        || document.animations().len() > 0
        || document
            .meshes()
            .any(|m| m.primitives().any(|p| p.morph_targets().len() > 0))
}

fn bad(source: &str, path: String, what: impl std::fmt::Display) -> MeshLoadError {
    MeshLoadError::unreadable(
        format!("glTF file `{source}`, at `{path}`: {what}"),
        "re-export the file (Blender: File › Export › glTF 2.0), or check it with the Khronos glTF validator",
    )
}

/// The rig of a file; its bind mesh's parts are the pieces (primitives
/// drawn), numbered from 0 (`Mesh::parts`).
pub fn read_rig(document: &gltf::Document, buffers: &[BufferData], source: &str) -> Result<Rig, MeshLoadError> {
    let nodes = read_nodes(document, source)?;
    let order = parent_first_order(&nodes, source)?;
    let skins = read_skins(document, buffers, source)?;
    let mut rest_world = vec![Mat4::IDENTITY; nodes.len()];
    for &n in &order {
        rest_world[n] = nodes[n].parent.map_or(nodes[n].rest, |p| rest_world[p] * nodes[n].rest);
    }
    let mut default_weights = vec![Vec::new(); nodes.len()];
    let mut merged = Merged {
        positions: Vec::new(),
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        tangents: Some(Vec::new()),
        indices: Vec::new(),
        joints: Vec::new(),
        weights: Vec::new(),
        pieces: Vec::new(),
        parts: Vec::new(),
    };
    let roots: Vec<gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => document.nodes().filter(|n| nodes[n.index()].parent.is_none()).collect(),
    };
    // Depth-first in document order, as `gltf_file` merges rigid files.
    let mut pending: Vec<(gltf::Node, usize)> = roots.into_iter().rev().map(|n| (n, 0)).collect();
    while let Some((node, depth)) = pending.pop() {
        if depth > MAX_NODE_DEPTH {
            return Err(bad(
                source,
                format!("/nodes/{}", node.index()),
                "the hierarchy is too deep",
            ));
        }
        if let Some(mesh) = node.mesh() {
            let targets = mesh.primitives().map(|p| p.morph_targets().len()).max().unwrap_or(0);
            if targets > 0 {
                let mut w: Vec<f32> = node
                    .weights()
                    .or(mesh.weights())
                    .map(<[f32]>::to_vec)
                    .unwrap_or_default();
                w.resize(targets, 0.0);
                default_weights[node.index()] = w;
            }
            let mirrored = node.skin().is_none() && Mat3::from_mat4(rest_world[node.index()]).determinant() < 0.0;
            for primitive in mesh.primitives() {
                merged.append(&node, &mesh, &primitive, buffers, &skins, mirrored, source)?;
            }
        }
        let children: Vec<gltf::Node> = node.children().collect();
        pending.extend(children.into_iter().rev().map(|c| (c, depth + 1)));
    }
    let clips = read_clips(document, buffers, &nodes, source)?;
    let parts = merged.parts;
    let bind = Mesh::from_parts(
        merged.positions,
        merged.normals,
        merged.uvs,
        merged.tangents,
        merged.indices,
        source.to_string(),
    )
    .with_parts(parts);
    Ok(Rig {
        nodes,
        order,
        skins,
        pieces: merged.pieces,
        default_weights,
        bind,
        joints: merged.joints,
        weights: merged.weights,
        clips,
    })
}

fn read_nodes(document: &gltf::Document, source: &str) -> Result<Vec<RigNode>, MeshLoadError> {
    let mut parents: Vec<Option<usize>> = vec![None; document.nodes().len()];
    for node in document.nodes() {
        for child in node.children() {
            let slot = &mut parents[child.index()];
            if slot.is_some() || child.index() == node.index() {
                return Err(bad(
                    source,
                    format!("/nodes/{}/children", node.index()),
                    format!("node {} has two parents (the hierarchy must be a tree)", child.index()),
                ));
            }
            *slot = Some(node.index());
        }
    }
    Ok(document
        .nodes()
        .map(|node| {
            let (translation, rotation, scale) = node.transform().decomposed();
            RigNode {
                name: node
                    .name()
                    .map_or_else(|| format!("node{}", node.index()), str::to_string),
                parent: parents[node.index()],
                rest: Mat4::from_cols_array_2d(&node.transform().matrix()),
                translation: Vec3::from_array(translation),
                rotation: Quat::from_array(rotation).normalize(),
                scale: Vec3::from_array(scale),
            }
        })
        .collect())
}

/// Every node once, each after its parent; a node in a cycle is never
/// reached from a root, and is refused.
fn parent_first_order(nodes: &[RigNode], source: &str) -> Result<Vec<usize>, MeshLoadError> {
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
    for (i, n) in nodes.iter().enumerate() {
        if let Some(p) = n.parent {
            children[p].push(i);
        }
    }
    let mut order: Vec<usize> = (0..nodes.len()).filter(|&i| nodes[i].parent.is_none()).collect();
    let mut next = 0;
    while next < order.len() {
        let n = order[next];
        order.extend(children[n].iter().copied());
        next += 1;
    }
    if order.len() != nodes.len() {
        let mut reached = vec![false; nodes.len()];
        order.iter().for_each(|&n| reached[n] = true);
        let lost = reached.iter().position(|r| !r).unwrap_or(0);
        return Err(bad(
            source,
            format!("/nodes/{lost}"),
            "the node is in a cycle of children",
        ));
    }
    Ok(order)
}

fn read_skins(document: &gltf::Document, buffers: &[BufferData], source: &str) -> Result<Vec<Skin>, MeshLoadError> {
    document
        .skins()
        .map(|skin| {
            let path = format!("/skins/{}", skin.index());
            let joints: Vec<usize> = skin.joints().map(|j| j.index()).collect();
            if joints.len() > MAX_JOINTS {
                return Err(MeshLoadError {
                    code: codes::LIMIT_EXCEEDED,
                    message: format!(
                        "glTF file `{source}`, at `{path}/joints`: the skin has {} joints, more than the limit of {MAX_JOINTS}",
                        joints.len()
                    ),
                    help: "split the character into several skinned meshes, or remove helper bones before exporting"
                        .into(),
                });
            }
            if joints.is_empty() {
                return Err(bad(source, format!("{path}/joints"), "the skin has no joints"));
            }
            let inverse_bind: Vec<Mat4> = match skin.inverse_bind_matrices() {
                None => vec![Mat4::IDENTITY; joints.len()],
                Some(_) => {
                    let reader = skin.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
                    let matrices: Vec<Mat4> = reader
                        .read_inverse_bind_matrices()
                        .ok_or_else(|| {
                            bad(source, format!("{path}/inverseBindMatrices"), "the accessor cannot be read")
                        })?
                        .map(|m| Mat4::from_cols_array_2d(&m))
                        .collect();
                    if matrices.len() < joints.len() {
                        return Err(bad(
                            source,
                            format!("{path}/inverseBindMatrices"),
                            format!("{} matrices for {} joints", matrices.len(), joints.len()),
                        ));
                    }
                    matrices
                }
            };
            if inverse_bind.iter().any(|m| !m.is_finite()) {
                return Err(bad(source, format!("{path}/inverseBindMatrices"), "a matrix is not finite"));
            }
            Ok(Skin { joints, inverse_bind })
        })
        .collect()
}

/// The primitives drawn, concatenated in their own (bind) space.
struct Merged {
    positions: Vec<[f32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    uvs: Option<Vec<[f32; 2]>>,
    tangents: Option<Vec<[f32; 4]>>,
    indices: Vec<u32>,
    joints: Vec<[u16; 4]>,
    weights: Vec<[f32; 4]>,
    pieces: Vec<Piece>,
    parts: Vec<u32>,
}

impl Merged {
    #[allow(clippy::too_many_arguments)]
    fn append(
        &mut self,
        node: &gltf::Node,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
        buffers: &[BufferData],
        skins: &[Skin],
        mirrored: bool,
        source: &str,
    ) -> Result<(), MeshLoadError> {
        if primitive.mode() != Mode::Triangles {
            return Ok(());
        }
        let path = format!("/meshes/{}/primitives/{}", mesh.index(), primitive.index());
        let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let Some(positions) = reader.read_positions() else {
            return Ok(());
        };
        let first = self.positions.len();
        let first_vertex = u32::try_from(first)
            .map_err(|_| bad(source, path.clone(), "more vertices than 32-bit indices can address"))?;
        let local: Vec<[f32; 3]> = positions.collect();
        let count = local.len();
        self.positions.extend(local);
        let normals = reader
            .read_normals()
            .map(|n| n.collect::<Vec<_>>())
            .filter(|n| n.len() == count);
        merge(&mut self.normals, normals);
        let uvs = reader
            .read_tex_coords(0)
            .map(|t| t.into_f32().collect::<Vec<_>>())
            .filter(|t| t.len() == count);
        merge(&mut self.uvs, uvs);
        let tangents = reader
            .read_tangents()
            .map(|t| t.collect::<Vec<_>>())
            .filter(|t| t.len() == count);
        merge(&mut self.tangents, tangents);

        let local_indices: Vec<u32> = match reader.read_indices() {
            Some(indices) => indices.into_u32().collect(),
            None => (0..count as u32).collect(),
        };
        for t in local_indices.chunks_exact(3) {
            let ordered = if mirrored {
                [t[0], t[2], t[1]]
            } else {
                [t[0], t[1], t[2]]
            };
            self.indices
                .extend(ordered.iter().map(|i| i.saturating_add(first_vertex)));
        }
        let part = self.pieces.len() as u32;
        self.parts.resize(self.indices.len() / 3, part);

        let skin = node.skin().map(|s| s.index());
        match skin {
            Some(s) => self.append_skin(&reader, &skins[s], count, &path, source)?,
            None => {
                self.joints.resize(first + count, [0; 4]);
                self.weights.resize(first + count, [0.0; 4]);
            }
        }
        let targets = read_targets(&reader, count, &path, source)?;
        self.pieces.push(Piece {
            first_vertex: first,
            vertex_count: count,
            node: node.index(),
            skin,
            targets,
        });
        Ok(())
    }

    fn append_skin<'a, 's, F>(
        &mut self,
        reader: &gltf::mesh::Reader<'a, 's, F>,
        skin: &Skin,
        count: usize,
        path: &str,
        source: &str,
    ) -> Result<(), MeshLoadError>
    where
        F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
    {
        let joints: Vec<[u16; 4]> = reader
            .read_joints(0)
            .ok_or_else(|| {
                bad(
                    source,
                    format!("{path}/attributes"),
                    "a skinned primitive has no JOINTS_0",
                )
            })?
            .into_u16()
            .collect();
        let weights: Vec<[f32; 4]> = reader
            .read_weights(0)
            .ok_or_else(|| {
                bad(
                    source,
                    format!("{path}/attributes"),
                    "a skinned primitive has no WEIGHTS_0",
                )
            })?
            .into_f32()
            .collect();
        if joints.len() != count || weights.len() != count {
            return Err(bad(
                source,
                format!("{path}/attributes"),
                format!(
                    "JOINTS_0 has {} and WEIGHTS_0 {} entries for {count} vertices",
                    joints.len(),
                    weights.len()
                ),
            ));
        }
        for (v, (j, w)) in joints.iter().zip(&weights).enumerate() {
            let sum: f32 = w.iter().sum();
            if w.iter().any(|x| !(x.is_finite() && *x >= 0.0)) || (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE {
                return Err(bad(
                    source,
                    format!("{path}/attributes/WEIGHTS_0"),
                    format!(
                        "vertex {v}'s weights {w:?} sum to {sum}, not 1 (within {WEIGHT_SUM_TOLERANCE}): every vertex must be bound to its bones"
                    ),
                ));
            }
            if let Some(k) = (0..4).find(|&k| w[k] > 0.0 && j[k] as usize >= skin.joints.len()) {
                return Err(bad(
                    source,
                    format!("{path}/attributes/JOINTS_0"),
                    format!("vertex {v} uses joint {} of a skin of {}", j[k], skin.joints.len()),
                ));
            }
            self.joints.push(*j);
            self.weights.push(w.map(|x| x / sum));
        }
        Ok(())
    }
}

/// Appends a primitive's attribute; it becomes `None` as soon as one
/// primitive lacks it (the mesh then computes it).
fn merge<T>(merged: &mut Option<Vec<T>>, part: Option<Vec<T>>) {
    match (merged.as_mut(), part) {
        (Some(all), Some(part)) => all.extend(part),
        _ => *merged = None,
    }
}

fn read_targets<'a, 's, F>(
    reader: &gltf::mesh::Reader<'a, 's, F>,
    count: usize,
    path: &str,
    source: &str,
) -> Result<Vec<MorphTarget>, MeshLoadError>
where
    F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
{
    reader
        .read_morph_targets()
        .enumerate()
        .map(|(k, (positions, normals, tangents))| {
            let at = format!("{path}/targets/{k}");
            let check = |len: usize, what: &str| {
                if len == count {
                    Ok(())
                } else {
                    Err(bad(
                        source,
                        format!("{at}/{what}"),
                        format!("{len} deltas for {count} vertices"),
                    ))
                }
            };
            let positions: Vec<[f32; 3]> = match positions {
                Some(p) => p.collect(),
                None => vec![[0.0; 3]; count],
            };
            check(positions.len(), "POSITION")?;
            let normals: Option<Vec<[f32; 3]>> = normals.map(Iterator::collect);
            if let Some(n) = &normals {
                check(n.len(), "NORMAL")?;
            }
            let tangents: Option<Vec<[f32; 3]>> = tangents.map(Iterator::collect);
            if let Some(t) = &tangents {
                check(t.len(), "TANGENT")?;
            }
            Ok(MorphTarget {
                positions,
                normals,
                tangents,
            })
        })
        .collect()
}

fn read_clips(
    document: &gltf::Document,
    buffers: &[BufferData],
    nodes: &[RigNode],
    source: &str,
) -> Result<Vec<Clip>, MeshLoadError> {
    let mut clips = Vec::new();
    for animation in document.animations() {
        let mut channels = Vec::new();
        let mut duration = 0.0f32;
        for channel in animation.channels() {
            let sampler_path = format!(
                "/animations/{}/samplers/{}",
                animation.index(),
                channel.sampler().index()
            );
            let channel_path = format!("/animations/{}/channels/{}", animation.index(), channel.index());
            let node = channel.target().node().index();
            if node >= nodes.len() {
                return Err(bad(source, format!("{channel_path}/target/node"), "no such node"));
            }
            let reader = channel.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
            let times: Vec<f32> = reader
                .read_inputs()
                .ok_or_else(|| bad(source, format!("{sampler_path}/input"), "the accessor cannot be read"))?
                .collect();
            if times.is_empty() {
                return Err(bad(source, format!("{sampler_path}/input"), "the sampler has no keys"));
            }
            if times.iter().any(|t| !t.is_finite()) || times.windows(2).any(|w| w[0] >= w[1]) {
                return Err(bad(
                    source,
                    format!("{sampler_path}/input"),
                    "key times must be finite and strictly increasing",
                ));
            }
            let outputs = reader
                .read_outputs()
                .ok_or_else(|| bad(source, format!("{sampler_path}/output"), "the accessor cannot be read"))?;
            use gltf::animation::util::ReadOutputs;
            let (property, values): (Property, Vec<f32>) = match outputs {
                ReadOutputs::Translations(t) => (Property::Translation, t.flatten().collect()),
                ReadOutputs::Scales(s) => (Property::Scale, s.flatten().collect()),
                ReadOutputs::Rotations(r) => (Property::Rotation, r.into_f32().flatten().collect()),
                ReadOutputs::MorphTargetWeights(w) => (Property::Weights, w.into_f32().collect()),
            };
            let interpolation = match channel.sampler().interpolation() {
                gltf::animation::Interpolation::Step => Interpolation::Step,
                gltf::animation::Interpolation::Linear => Interpolation::Linear,
                gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
            };
            let width = match property {
                Property::Translation | Property::Scale => 3,
                Property::Rotation => 4,
                Property::Weights => {
                    let targets = channel.target().node().mesh().map_or(0, |m| {
                        m.primitives().map(|p| p.morph_targets().len()).max().unwrap_or(0)
                    });
                    if targets == 0 {
                        return Err(bad(
                            source,
                            format!("{channel_path}/target"),
                            format!("the channel animates morph weights of node {node}, which has no morph targets"),
                        ));
                    }
                    targets
                }
            };
            let sampler = Sampler {
                interpolation,
                times,
                values,
                width,
                rotation: property == Property::Rotation,
            };
            if sampler.values.len() != sampler.values_expected() || sampler.values.iter().any(|v| !v.is_finite()) {
                return Err(bad(
                    source,
                    format!("{sampler_path}/output"),
                    format!(
                        "{} finite values expected ({} keys of {} for {:?} {:?}), {} found",
                        sampler.values_expected(),
                        sampler.times.len(),
                        width,
                        interpolation,
                        property,
                        sampler.values.len()
                    ),
                ));
            }
            duration = duration.max(*sampler.times.last().unwrap_or(&0.0));
            channels.push(Channel {
                node,
                property,
                sampler,
            });
        }
        clips.push(Clip {
            name: animation
                .name()
                .map_or_else(|| format!("animation{}", animation.index()), str::to_string),
            duration,
            channels,
        });
    }
    Ok(clips)
}
