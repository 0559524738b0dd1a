//! A glTF file's deformable content as read from it (its skins, morph
//! targets, node hierarchy and animation clips), and its evaluation: the
//! pose at a clip's time (node world matrices, joint matrices, morph
//! weights) and the mesh deformed by it, on the CPU (f32).
//!
//! The formulas are glTF 2.0's (§3.7.3 skins, §3.7.2.2 morph targets):
//! a vertex is first morphed, `p' = p + Σ_k w_k Δp_k` (normals and tangents
//! likewise), then skinned by linear blend of 4 joints,
//! `M = Σ_i w_i · world(joint_i) · inverseBind_i`, `p'' = M p'`; the skinned
//! mesh node's own transform is ignored, as the spec requires. Normals go
//! through M's cofactor matrix (the inverse transpose up to a positive
//! factor, so it stays right under non-uniform scale), tangents through M's
//! linear part, both normalised; the spec leaves these two open. A
//! primitive of an unskinned node moves rigidly with its node's (possibly
//! animated) world matrix.

use super::anim_sampler::Sampler;
use super::mesh::Mesh;
use glam::{Mat3, Mat4, Quat, Vec3, Vec4};
use std::sync::Arc;

/// A node of the file: its parent and rest transform.
#[derive(Debug, Clone, PartialEq)]
pub struct RigNode {
    pub name: String,
    pub parent: Option<usize>,
    /// The rest transform as written (a `matrix`, or T·R·S).
    pub rest: Mat4,
    /// The rest transform decomposed: what an animated property replaces.
    pub translation: Vec3,
    pub rotation: Quat,
    pub scale: Vec3,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Skin {
    /// Node indices of the joints, in the order `JOINTS_0` indexes.
    pub joints: Vec<usize>,
    /// One per joint (identity where the file has none).
    pub inverse_bind: Vec<Mat4>,
}

/// One morph target's deltas over its piece's vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct MorphTarget {
    pub positions: Vec<[f32; 3]>,
    pub normals: Option<Vec<[f32; 3]>>,
    pub tangents: Option<Vec<[f32; 3]>>,
}

/// The vertices of one drawn primitive (a node's mesh's primitive) inside
/// the merged mesh, and what moves them.
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    pub first_vertex: usize,
    pub vertex_count: usize,
    /// The node drawing the primitive: its morph weights, and its world
    /// matrix for an unskinned piece.
    pub node: usize,
    pub skin: Option<usize>,
    pub targets: Vec<MorphTarget>,
}

/// What an animation channel sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Property {
    Translation,
    Rotation,
    Scale,
    Weights,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    pub node: usize,
    pub property: Property,
    pub sampler: Sampler,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    /// The file's name for it, or `animation<i>` when it has none.
    pub name: String,
    /// The last key time of any channel, in seconds.
    pub duration: f32,
    pub channels: Vec<Channel>,
}

/// A glTF file's skins, morph targets and clips over its merged mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Rig {
    pub nodes: Vec<RigNode>,
    /// Node indices, every parent before its children.
    pub order: Vec<usize>,
    pub skins: Vec<Skin>,
    pub pieces: Vec<Piece>,
    /// Per node, its default morph weights (the node's `weights`, else its
    /// mesh's, else zeros); empty for a node without morph targets.
    pub default_weights: Vec<Vec<f32>>,
    /// The merged mesh before any node transform, skin or morph: the
    /// primitives' own attributes (indices already in the winding the rest
    /// pose draws).
    pub bind: Mesh,
    /// Per vertex of `bind`: 4 joints (indices into its piece's skin) and
    /// their weights, summing to 1 (zeros in unskinned pieces).
    pub joints: Vec<[u16; 4]>,
    pub weights: Vec<[f32; 4]>,
    pub clips: Vec<Clip>,
}

/// The per-node vectors [`Rig::pose_into`] fills before it composes the
/// world matrices, kept between frames.
#[derive(Debug, Clone, Default)]
pub struct PoseScratch {
    translation: Vec<Vec3>,
    rotation: Vec<Quat>,
    scale: Vec<Vec3>,
    animated: Vec<bool>,
}

/// A rig's state at one time: every node's world matrix and morph weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Pose {
    pub world: Vec<Mat4>,
    pub weights: Vec<Vec<f32>>,
}

/// A rig its host poses every frame (the embedding API's skinned meshes,
/// `StyleRuntime::add_skinned_mesh`; Bevy's `SkinnedMesh`), rather than
/// one of its clips: the pose is given, not sampled. Its rig is
/// [`Rig::posed_by_host`]'s, so `pose.world[j]` is joint `j`'s matrix in
/// skin space and `pose.weights[joints]` the morph weights.
#[derive(Debug, Clone)]
pub struct HostPose {
    pub rig: Arc<Rig>,
    pub pose: Pose,
    /// Bumped each time `pose` changes: the GPU stage writes a pose once.
    pub revision: u64,
}

impl HostPose {
    /// `rig` in its bind pose: identity joint matrices, zero morph weights.
    pub fn bind(rig: Arc<Rig>) -> HostPose {
        let pose = Pose {
            world: vec![Mat4::IDENTITY; rig.nodes.len()],
            weights: rig.default_weights.clone(),
        };
        HostPose { rig, pose, revision: 0 }
    }

    /// The joint matrices (all of `pose.world` but the mesh's own node, the last).
    pub fn joints_mut(&mut self) -> &mut [Mat4] {
        let n = self.pose.world.len().saturating_sub(1);
        &mut self.pose.world[..n]
    }

    /// The morph weights of the mesh's node (empty without morph targets).
    pub fn weights_mut(&mut self) -> &mut [f32] {
        match self.pose.weights.last_mut() {
            Some(w) => w,
            None => &mut [],
        }
    }
}

impl Rig {
    /// The rig of a mesh whose host gives its joint matrices: `bind` with
    /// `joint_count` joints, whose matrices map bind-pose positions into
    /// skin space (`world · inverseBind` already multiplied, as a glTF
    /// rig's [`Rig::skin_joint_matrix`]), and `targets` over all its
    /// vertices. Its nodes are the joints, `0..joint_count` (each its own
    /// root, at rest the identity, its inverse bind the identity), then the
    /// mesh's node (identity, holding the morph weights); one piece, skinned
    /// when there are joints. The caller has checked the arrays (one entry
    /// per vertex, joints in range, weights summing to 1).
    pub fn posed_by_host(
        bind: Mesh,
        joint_count: usize,
        joints: Vec<[u16; 4]>,
        weights: Vec<[f32; 4]>,
        targets: Vec<MorphTarget>,
    ) -> Rig {
        let node = |name: String| RigNode {
            name,
            parent: None,
            rest: Mat4::IDENTITY,
            translation: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            scale: Vec3::ONE,
        };
        let mut nodes: Vec<RigNode> = (0..joint_count).map(|j| node(format!("joint {j}"))).collect();
        nodes.push(node("mesh".into()));
        let mut default_weights = vec![Vec::new(); joint_count];
        default_weights.push(vec![0.0; targets.len()]);
        let skins = if joint_count > 0 {
            vec![Skin {
                joints: (0..joint_count).collect(),
                inverse_bind: vec![Mat4::IDENTITY; joint_count],
            }]
        } else {
            Vec::new()
        };
        let (joints, weights) = if joint_count > 0 {
            (joints, weights)
        } else {
            (vec![[0; 4]; bind.vertex_count()], vec![[0.0; 4]; bind.vertex_count()])
        };
        Rig {
            order: (0..nodes.len()).collect(),
            nodes,
            skins,
            pieces: vec![Piece {
                first_vertex: 0,
                vertex_count: bind.vertex_count(),
                node: joint_count,
                skin: (joint_count > 0).then_some(0),
                targets,
            }],
            default_weights,
            bind,
            joints,
            weights,
            clips: Vec::new(),
        }
    }

    pub fn clip_index(&self, name: &str) -> Option<usize> {
        self.clips.iter().position(|c| c.name == name)
    }

    /// The pose of clip `clip` at `time_s` seconds into it (clamped to its
    /// keys), or the rest pose for `None`.
    pub fn pose(&self, clip: Option<(usize, f32)>) -> Pose {
        let mut pose = Pose {
            world: Vec::new(),
            weights: Vec::new(),
        };
        self.pose_into(clip, &mut pose, &mut PoseScratch::default());
        pose
    }

    /// [`Rig::pose`] into `pose`, reusing its vectors and `scratch`'s: once
    /// they have grown to the rig's size, a frame's pose allocates nothing
    /// (the GPU deformation stage poses every animated object every frame).
    pub fn pose_into(&self, clip: Option<(usize, f32)>, pose: &mut Pose, scratch: &mut PoseScratch) {
        let PoseScratch {
            translation,
            rotation,
            scale,
            animated,
        } = scratch;
        translation.clear();
        translation.extend(self.nodes.iter().map(|n| n.translation));
        rotation.clear();
        rotation.extend(self.nodes.iter().map(|n| n.rotation));
        scale.clear();
        scale.extend(self.nodes.iter().map(|n| n.scale));
        animated.clear();
        animated.resize(self.nodes.len(), false);
        let weights = &mut pose.weights;
        weights.clone_from(&self.default_weights);
        if let Some(clip) = clip.and_then(|(i, t)| Some((self.clips.get(i)?, t))) {
            let (clip, t) = clip;
            let mut value = [0.0f32; 4];
            for channel in &clip.channels {
                let node = channel.node;
                match channel.property {
                    Property::Weights => {
                        let w = &mut weights[node];
                        w.resize(channel.sampler.width, 0.0);
                        channel.sampler.sample(t, w);
                    }
                    Property::Translation => {
                        channel.sampler.sample(t, &mut value[..3]);
                        translation[node] = Vec3::new(value[0], value[1], value[2]);
                        animated[node] = true;
                    }
                    Property::Scale => {
                        channel.sampler.sample(t, &mut value[..3]);
                        scale[node] = Vec3::new(value[0], value[1], value[2]);
                        animated[node] = true;
                    }
                    Property::Rotation => {
                        channel.sampler.sample(t, &mut value);
                        rotation[node] = Quat::from_xyzw(value[0], value[1], value[2], value[3]).normalize();
                        animated[node] = true;
                    }
                }
            }
        }
        let world = &mut pose.world;
        world.clear();
        world.resize(self.nodes.len(), Mat4::IDENTITY);
        for &n in &self.order {
            let node = &self.nodes[n];
            let local = if animated[n] {
                Mat4::from_scale_rotation_translation(scale[n], rotation[n], translation[n])
            } else {
                node.rest
            };
            world[n] = match node.parent {
                Some(p) => world[p] * local,
                None => local,
            };
        }
    }

    /// Joint `joint` of skin `skin` in `pose`: `world(joint's node) ·
    /// inverseBind` (glTF §3.7.3); zero for a joint the skin lacks, as
    /// [`Rig::deform`] takes it.
    pub fn skin_joint_matrix(&self, skin: usize, joint: usize, pose: &Pose) -> Mat4 {
        match self.skins.get(skin) {
            Some(s) => match (s.joints.get(joint), s.inverse_bind.get(joint)) {
                (Some(&j), Some(ibm)) => pose.world[j] * *ibm,
                _ => Mat4::ZERO,
            },
            None => Mat4::ZERO,
        }
    }

    /// `bind` morphed and skinned (or moved rigidly) by `pose`.
    pub fn deform(&self, pose: &Pose) -> Mesh {
        let mut mesh = self.bind.clone();
        for piece in &self.pieces {
            self.deform_piece(piece, pose, &mut mesh);
        }
        mesh
    }

    fn deform_piece(&self, piece: &Piece, pose: &Pose, mesh: &mut Mesh) {
        let range = piece.first_vertex..piece.first_vertex + piece.vertex_count;
        let weights = pose.weights.get(piece.node).map_or(&[][..], Vec::as_slice);
        let joint_matrices: Vec<Mat4> = match piece.skin.and_then(|s| self.skins.get(s)) {
            Some(skin) => skin
                .joints
                .iter()
                .zip(&skin.inverse_bind)
                .map(|(&j, ibm)| pose.world[j] * *ibm)
                .collect(),
            None => Vec::new(),
        };
        let rigid = pose.world.get(piece.node).copied().unwrap_or(Mat4::IDENTITY);
        for (local, v) in range.enumerate() {
            let mut p = Vec3::from_array(self.bind.positions[v]);
            let mut n = Vec3::from_array(self.bind.normals[v]);
            let mut t = self.bind.tangents.as_ref().map(|t| Vec4::from_array(t[v]));
            for (target, &w) in piece.targets.iter().zip(weights) {
                if w == 0.0 {
                    continue;
                }
                p += w * Vec3::from_array(target.positions[local]);
                if let Some(dn) = &target.normals {
                    n += w * Vec3::from_array(dn[local]);
                }
                if let (Some(t), Some(dt)) = (t.as_mut(), &target.tangents) {
                    *t += (w * Vec3::from_array(dt[local])).extend(0.0);
                }
            }
            let m = if joint_matrices.is_empty() {
                rigid
            } else {
                let (j, w) = (self.joints[v], self.weights[v]);
                let pick = |i: usize| joint_matrices.get(j[i] as usize).copied().unwrap_or(Mat4::ZERO);
                pick(0) * w[0] + pick(1) * w[1] + pick(2) * w[2] + pick(3) * w[3]
            };
            mesh.positions[v] = m.transform_point3(p).to_array();
            let linear = Mat3::from_mat4(m);
            // A mirroring matrix's cofactor turns normals inside out.
            let sign = if linear.determinant() < 0.0 { -1.0 } else { 1.0 };
            mesh.normals[v] = (sign * (cofactor(linear) * n)).normalize_or_zero().to_array();
            if let (Some(t), Some(out)) = (t, mesh.tangents.as_mut()) {
                let handedness = if linear.determinant() < 0.0 { -t.w } else { t.w };
                out[v] = (linear * t.truncate())
                    .normalize_or_zero()
                    .extend(handedness)
                    .to_array();
            }
        }
    }
}

/// The cofactor matrix of `m`, `det(m) · m⁻ᵀ`: normals transform by it
/// (up to a factor the normalisation removes), and it exists even where `m`
/// is singular.
fn cofactor(m: Mat3) -> Mat3 {
    Mat3::from_cols(
        m.y_axis.cross(m.z_axis),
        m.z_axis.cross(m.x_axis),
        m.x_axis.cross(m.y_axis),
    )
}
