//! Bevy's skinned entities as npr's posed instances (docs/decisions/0055).
//!
//! Each frame, in the extraction, a `SkinnedMesh` entity's joint matrices
//! are taken in its mesh's skin space: joint `j`'s `GlobalTransform`
//! relative to the mesh entity's, times the joint's inverse bindpose
//! (`M_j = G_mesh⁻¹ · G_joint_j · IBM_j`). Bevy skins a mesh by
//! `G_joint_j · IBM_j` in world space, ignoring the mesh entity's own
//! transform; npr places the skinned mesh by the entity's transform, as it
//! places a rigid one, so `G_mesh · M_j` is Bevy's matrix: the same pose.
//! (`AnimationPlayer` moves the joints' `Transform`s; Bevy propagates them
//! before the extraction, so the pose is the frame's.)
//!
//! In the render world the matrices become the instance's
//! [`SkinPose`], its mesh registered with its [`Skinning`]
//! (`StyleRuntime::add_skinned_mesh`): npr's GPU deformation stage then
//! skins it before the style's passes. A skinned entity whose joints are
//! missing or do not match its mesh is logged (E0612) and drawn unskinned;
//! nothing panics.

use bevy::mesh::skinning::{SkinnedMesh, SkinnedMeshInverseBindposes};
use bevy::prelude::*;
use npr_diag::{codes, Diagnostic};
use npr_runner::embed::{Instance, MeshHandle, SkinPose, Skinning, StyleRuntime};
use std::sync::Arc;

/// A skinned entity's joint matrices in its mesh's skin space, or why
/// there are none (its joint entities or inverse bindposes missing or of
/// another number).
pub(crate) fn joint_matrices(
    mesh_transform: &GlobalTransform,
    skinned: &SkinnedMesh,
    joints: &Query<&GlobalTransform>,
    bindposes: &Assets<SkinnedMeshInverseBindposes>,
) -> Result<Vec<glam::Mat4>, String> {
    let Some(inverse_bind) = bindposes.get(&skinned.inverse_bindposes) else {
        return Err("its SkinnedMesh's inverse bindposes asset is not loaded".into());
    };
    if inverse_bind.len() != skinned.joints.len() {
        return Err(format!(
            "its SkinnedMesh names {} joints and has {} inverse bindposes",
            skinned.joints.len(),
            inverse_bind.len()
        ));
    }
    let to_mesh = mesh_transform.to_matrix().inverse();
    skinned
        .joints
        .iter()
        .zip(inverse_bind.iter())
        .enumerate()
        .map(|(j, (&joint, ibm))| match joints.get(joint) {
            // Bevy's glam may be another release than npr's: by the columns.
            Ok(g) => Ok(glam::Mat4::from_cols_array(
                &(to_mesh * g.to_matrix() * *ibm).to_cols_array(),
            )),
            Err(_) => Err(format!(
                "its SkinnedMesh's joint {j}, entity {joint}, is gone (or has no GlobalTransform)"
            )),
        })
        .collect()
}

/// The pose of `entity` drawing a mesh of `skinning` with the extracted
/// `joints` (`None`: the entity has no `SkinnedMesh`): `Ok(None)` to draw
/// it unskinned, or the E0612 diagnostic saying why a skinned entity is.
pub(crate) fn pose(
    entity: Entity,
    skinning: Option<&Skinning>,
    joints: Option<&Result<Vec<glam::Mat4>, String>>,
) -> Result<Option<SkinPose>, Diagnostic> {
    let refuse = |why: String| {
        Diagnostic::error(
            codes::POSE_JOINTS,
            format!("entity {entity}: npr draws its skinned mesh unskinned: {why}"),
        )
        .with_help(
            "give a SkinnedMesh the joint entities and inverse bindposes its mesh's joint indices \
             name (a glTF scene's skin, spawned by its SceneRoot, has them)",
        )
    };
    match (joints, skinning) {
        (None, _) => Ok(None),
        (Some(Err(why)), _) => Err(refuse(why.clone())),
        (Some(Ok(_)), None) => Err(refuse(
            "its mesh has no joint indices and weights (ATTRIBUTE_JOINT_INDEX, ATTRIBUTE_JOINT_WEIGHT)".into(),
        )),
        (Some(Ok(matrices)), Some(skinning)) if matrices.len() < skinning.joint_count => Err(refuse(format!(
            "its mesh's joint indices name {} joints, and its SkinnedMesh has {}",
            skinning.joint_count,
            matrices.len()
        ))),
        (Some(Ok(matrices)), Some(skinning)) => Ok(Some(SkinPose {
            joints: matrices[..skinning.joint_count].to_vec(),
            morph_weights: Vec::new(),
        })),
    }
}

/// Registers `mesh` with `runtime`: with its `skinning` when it has one
/// (a skin that does not fit is logged, E0615, and the mesh registered
/// unskinned), else shared as it is.
pub(crate) fn register(
    runtime: &mut StyleRuntime,
    mesh: &Arc<npr_runner::scene::Mesh>,
    skinning: Option<&Skinning>,
    problems: &mut Vec<Diagnostic>,
) -> MeshHandle {
    if let Some(skinning) = skinning {
        match runtime.add_skinned_mesh((**mesh).clone(), skinning.clone()) {
            Ok(handle) => return handle,
            Err(e) => problems.extend(e.diagnostics().into_iter().map(|mut d| {
                d.message = format!("npr draws the mesh {} unskinned: {}", mesh.source, d.message);
                d
            })),
        }
    }
    runtime.add_shared_mesh(mesh.clone())
}

/// Gives `instance` (of `handle`, drawn by `entity`) its pose from the
/// extracted `joints`, when its mesh was registered skinned; a skinned
/// entity that cannot be posed is logged (E0612) and drawn unskinned.
pub(crate) fn attach_pose(
    runtime: &StyleRuntime,
    handle: MeshHandle,
    instance: &mut Instance,
    entity: Entity,
    skinning: Option<&Skinning>,
    joints: Option<&Result<Vec<glam::Mat4>, String>>,
    problems: &mut Vec<Diagnostic>,
) {
    if skinning.is_some() && runtime.skin(handle).is_none() {
        // Its skin was refused when it was registered (E0615, logged).
        return;
    }
    match pose(entity, skinning, joints) {
        Ok(pose) => instance.pose = pose,
        Err(d) => problems.push(d),
    }
}
