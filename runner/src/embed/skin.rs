//! A host's skinned and morphing meshes (docs/decisions/0055): the
//! [`Skinning`] a host registers with its mesh
//! (`StyleRuntime::add_skinned_mesh`), checked (E0615) and made into the
//! mesh's rig ([`Rig::posed_by_host`]), and the [`SkinPose`] an instance
//! carries each frame, checked (E0612, E0613, E0614) and copied into its
//! object's [`HostPose`] in place. The renderer deforms such an object
//! with the GPU stage that deforms a scene file's clips
//! (`exec/deform.rs`): one data flow whatever the source.

use super::meshes::Entry;
use super::{EmbedError, MeshHandle};
use crate::scene::gltf_rig::{MAX_JOINTS, WEIGHT_SUM_TOLERANCE};
use crate::scene::rig::{HostPose, MorphTarget, Rig};
use crate::scene::Mesh;
use glam::Mat4;
use npr_diag::{codes, Diagnostic};
use std::sync::Arc;

/// What deforms a host's mesh, per vertex: up to 4 joints of its skin with
/// their weights (glTF's `JOINTS_0`/`WEIGHTS_0`, Bevy's
/// `ATTRIBUTE_JOINT_INDEX`/`ATTRIBUTE_JOINT_WEIGHT`), and its morph
/// targets (glTF 2.0 §3.7.2.2: per target, a delta per vertex).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Skinning {
    /// How many joint matrices a pose gives (0: a mesh that only morphs).
    pub joint_count: usize,
    /// Per vertex, 4 indices into the pose's joint matrices (empty when
    /// `joint_count` is 0). An index with weight 0 is not read.
    pub joints: Vec<[u16; 4]>,
    /// Per vertex, the 4 joints' weights: finite, not negative, summing to
    /// 1 within [`WEIGHT_SUM_TOLERANCE`] (then renormalised, as for a glTF
    /// file's quantised weights).
    pub weights: Vec<[f32; 4]>,
    /// Morph targets, each with one position delta per vertex (and normal
    /// and tangent deltas, if given, one per vertex).
    pub morph_targets: Vec<MorphTarget>,
}

/// One instance's pose this frame, in the mesh's skin space: joint `j`'s
/// matrix maps a bind-pose position into the mesh's object space (a
/// glTF skin's `world(joint) · inverseBind`, with `world` relative to
/// the skinned mesh's own node; Bevy's joint `GlobalTransform` times its
/// inverse bindpose, relative to the mesh entity), so the instance's
/// transform then places the skinned mesh as it places a rigid one.
/// Identity matrices and zero weights are the bind pose.
///
/// A host keeps its instances from frame to frame and writes new values
/// into these vectors in place: a frame then allocates nothing.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SkinPose {
    /// One matrix per joint of the mesh's [`Skinning`], finite.
    pub joints: Vec<Mat4>,
    /// One weight per morph target of the mesh, finite.
    pub morph_weights: Vec<f32>,
}

impl SkinPose {
    /// The bind pose of a mesh of `joint_count` joints and `targets` morph
    /// targets: identity matrices, zero weights.
    pub fn bind(joint_count: usize, targets: usize) -> SkinPose {
        SkinPose {
            joints: vec![Mat4::IDENTITY; joint_count],
            morph_weights: vec![0.0; targets],
        }
    }
}

/// An error of `code` with `message` and `help`.
fn refuse(code: &'static str, message: String, help: &str) -> EmbedError {
    EmbedError::Skin(Box::new(Diagnostic::error(code, message).with_help(help.to_string())))
}

/// `mesh` with `skinning` as a rig, or why not (E0615).
pub(super) fn rig_of(mesh: Mesh, skinning: Skinning) -> Result<Rig, EmbedError> {
    let count = mesh.vertex_count();
    let bad = |message: String, help: &str| refuse(codes::BAD_SKIN, message, help);
    let per_vertex = "give one entry per vertex of the mesh, in its order";
    let Skinning {
        joint_count,
        joints,
        mut weights,
        morph_targets,
    } = skinning;
    if joint_count > MAX_JOINTS {
        return Err(bad(
            format!("the skin has {joint_count} joints, more than the limit of {MAX_JOINTS}"),
            "split the character into meshes of fewer joints each",
        ));
    }
    if joint_count > 0 {
        for (what, len) in [("joint index sets", joints.len()), ("weight sets", weights.len())] {
            if len != count {
                return Err(bad(format!("{len} {what} for a mesh of {count} vertices"), per_vertex));
            }
        }
        for (v, (j, w)) in joints.iter().zip(weights.iter_mut()).enumerate() {
            let sum: f32 = w.iter().sum();
            if w.iter().any(|x| !(x.is_finite() && *x >= 0.0)) || (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE {
                return Err(bad(
                    format!("vertex {v}'s weights {w:?} sum to {sum}, not 1 (within {WEIGHT_SUM_TOLERANCE})"),
                    "every vertex must be bound to its joints: finite weights, none negative, summing to 1",
                ));
            }
            if let Some(k) = (0..4).find(|&k| w[k] > 0.0 && usize::from(j[k]) >= joint_count) {
                return Err(bad(
                    format!("vertex {v} uses joint {} of a skin of {joint_count}", j[k]),
                    "joint indices count from 0 and stay below the skin's joint count",
                ));
            }
            *w = w.map(|x| x / sum);
        }
    } else if !joints.is_empty() || !weights.is_empty() {
        return Err(bad(
            format!(
                "joint indices or weights for a skin of no joints ({} and {} sets)",
                joints.len(),
                weights.len()
            ),
            "give `joint_count`, or leave `joints` and `weights` empty for a mesh that only morphs",
        ));
    }
    if joint_count == 0 && morph_targets.is_empty() {
        return Err(bad(
            "a skinned mesh with no joints and no morph targets".into(),
            "register a mesh nothing deforms with `add_mesh`",
        ));
    }
    for (k, target) in morph_targets.iter().enumerate() {
        let lengths = [
            ("position", Some(target.positions.len())),
            ("normal", target.normals.as_ref().map(Vec::len)),
            ("tangent", target.tangents.as_ref().map(Vec::len)),
        ];
        for (what, len) in lengths {
            if let Some(len) = len.filter(|&len| len != count) {
                return Err(bad(
                    format!("morph target {k} has {len} {what} deltas for a mesh of {count} vertices"),
                    per_vertex,
                ));
            }
        }
        if target.tangents.is_some() && mesh.tangents.is_none() {
            return Err(bad(
                format!("morph target {k} has tangent deltas for a mesh without tangents"),
                "leave the tangent deltas out for a mesh without UVs",
            ));
        }
        let deltas = [
            Some(&target.positions),
            target.normals.as_ref(),
            target.tangents.as_ref(),
        ];
        if let Some(v) = deltas
            .into_iter()
            .flatten()
            .find_map(|d| d.iter().position(|x| x.iter().any(|c| !c.is_finite())))
        {
            return Err(bad(
                format!("morph target {k} has a delta at vertex {v} that is not a finite number"),
                "a morph target's deltas must be finite numbers",
            ));
        }
    }
    Ok(Rig::posed_by_host(mesh, joint_count, joints, weights, morph_targets))
}

/// The joint count and morph target count of `rig` (a host's rig).
pub(super) fn sizes(rig: &Rig) -> (usize, usize) {
    (
        rig.skins.first().map_or(0, |s| s.joints.len()),
        rig.pieces.first().map_or(0, |p| p.targets.len()),
    )
}

/// Whether `pose` fits `entry`'s mesh (E0612, E0613, E0614); `name`
/// names the instance (`object 3`, `entity 7`) in the messages (made only
/// for one: a frame allocates nothing).
pub(super) fn check_pose(
    name: impl Fn() -> String,
    handle: MeshHandle,
    entry: &Entry,
    pose: &SkinPose,
) -> Result<(), EmbedError> {
    let fits = entry.extras.rig.as_ref().is_some_and(|rig| {
        sizes(rig) == (pose.joints.len(), pose.morph_weights.len())
            && pose.joints.iter().all(Mat4::is_finite)
            && pose.morph_weights.iter().all(|w| w.is_finite())
    });
    if fits {
        return Ok(());
    }
    let object = name();
    let mesh = format!("mesh handle #{}", handle.index);
    let Some(rig) = &entry.extras.rig else {
        return Err(refuse(
            codes::POSE_JOINTS,
            format!("{object} has a pose, and its {mesh} has no skin"),
            "register a skinned mesh with `add_skinned_mesh(mesh, skinning)`; an instance of a mesh \
             from `add_mesh` has no pose",
        ));
    };
    let (joints, targets) = sizes(rig);
    if pose.joints.len() != joints {
        return Err(refuse(
            codes::POSE_JOINTS,
            format!(
                "{object} gives {} joint matrices, and its {mesh}'s skin has {joints} joints",
                pose.joints.len()
            ),
            "give one matrix per joint of the mesh's `Skinning`, in the order its joint indices name them",
        ));
    }
    if pose.morph_weights.len() != targets {
        return Err(refuse(
            codes::POSE_MORPH_WEIGHTS,
            format!(
                "{object} gives {} morph weights, and its {mesh} has {targets} morph targets",
                pose.morph_weights.len()
            ),
            "give one weight per morph target of the mesh's `Skinning`, in its order",
        ));
    }
    let finite_help = "a pose must be finite numbers: check the animation for a division by zero or \
                       a scale of zero inverted";
    if let Some(j) = pose.joints.iter().position(|m| !m.is_finite()) {
        return Err(refuse(
            codes::NON_FINITE_POSE,
            format!("joint matrix {j} of {object}'s pose is not finite"),
            finite_help,
        ));
    }
    if let Some(k) = pose.morph_weights.iter().position(|w| !w.is_finite()) {
        return Err(refuse(
            codes::NON_FINITE_POSE,
            format!("morph weight {k} of {object}'s pose is not finite"),
            finite_help,
        ));
    }
    Err(EmbedError::Run(crate::RunError::Internal(format!(
        "{object}'s pose was refused for no reason found"
    ))))
}

/// The object's pose for `entry`'s rig, as `pose` gives it (checked).
pub(super) fn host_pose(rig: &Arc<Rig>, pose: &SkinPose) -> HostPose {
    let mut host = HostPose::bind(rig.clone());
    copy_pose(&mut host, pose);
    host
}

/// `pose` into `host` in place (no allocation: the sizes are checked to be
/// the rig's); its revision bumped when a value changed.
pub(super) fn copy_pose(host: &mut HostPose, pose: &SkinPose) {
    let mut changed = false;
    let joints = host.joints_mut();
    if joints != pose.joints.as_slice() {
        joints.copy_from_slice(&pose.joints);
        changed = true;
    }
    let weights = host.weights_mut();
    if weights != pose.morph_weights.as_slice() {
        weights.copy_from_slice(&pose.morph_weights);
        changed = true;
    }
    if changed {
        host.revision += 1;
    }
}
