//! An independent f64 reference of glTF 2.0 skinning and morphing (not the
//! runner's `scene::rig`): reads the file with the `gltf` crate, samples
//! STEP and LINEAR channels (slerp for rotations), composes the node
//! hierarchy in f64 and deforms every drawn primitive: morph first, then
//! `Σ w_i · world(joint_i) · inverseBind_i` (or the node's world matrix for
//! an unskinned primitive). Normals go through the inverse transpose.
//! Vertices come out in the order the runner merges primitives (depth
//! first over the default scene, document order).

use glam::{DMat3, DMat4, DQuat, DVec3};
use std::collections::HashMap;
use std::path::Path;

pub struct Deformed {
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub indices: Vec<u32>,
}

fn sample(times: &[f64], values: &[Vec<f64>], step: bool, rotation: bool, t: f64) -> Vec<f64> {
    if t <= times[0] {
        return values[0].clone();
    }
    let n = times.len();
    if t >= times[n - 1] {
        return values[n - 1].clone();
    }
    let k = (0..n - 1)
        .find(|&k| times[k] <= t && t < times[k + 1])
        .expect("a segment");
    if step {
        return values[k].clone();
    }
    let s = (t - times[k]) / (times[k + 1] - times[k]);
    if rotation {
        let a = DQuat::from_xyzw(values[k][0], values[k][1], values[k][2], values[k][3]).normalize();
        let b = DQuat::from_xyzw(values[k + 1][0], values[k + 1][1], values[k + 1][2], values[k + 1][3]).normalize();
        // glam's slerp takes the shorter arc, as the spec's Appendix C does.
        let q = a.slerp(b, s);
        return vec![q.x, q.y, q.z, q.w];
    }
    values[k]
        .iter()
        .zip(&values[k + 1])
        .map(|(a, b)| a + (b - a) * s)
        .collect()
}

/// The file at `path` deformed by clip `clip` (by name) at `t` seconds, or
/// its rest pose for `None`.
pub fn deform(path: &Path, clip: Option<(&str, f64)>) -> Deformed {
    let (document, buffers, _) = gltf::import(path).expect("reference reads the file");
    let get = |b: gltf::Buffer| buffers.get(b.index()).map(|d| &d.0[..]);
    let count = document.nodes().len();
    let mut t: Vec<DVec3> = Vec::with_capacity(count);
    let mut r: Vec<DQuat> = Vec::with_capacity(count);
    let mut s: Vec<DVec3> = Vec::with_capacity(count);
    for node in document.nodes() {
        let (tt, rr, ss) = node.transform().decomposed();
        t.push(DVec3::from_array(tt.map(f64::from)));
        r.push(DQuat::from_array(rr.map(f64::from)).normalize());
        s.push(DVec3::from_array(ss.map(f64::from)));
    }
    let mut weights: HashMap<usize, Vec<f64>> = HashMap::new();
    for node in document.nodes() {
        if let Some(mesh) = node.mesh() {
            if let Some(w) = node.weights().or(mesh.weights()) {
                weights.insert(node.index(), w.iter().map(|&x| f64::from(x)).collect());
            }
        }
    }
    if let Some((name, time)) = clip {
        let animation = document
            .animations()
            .find(|a| a.name() == Some(name))
            .expect("clip in the file");
        for channel in animation.channels() {
            let reader = channel.reader(get);
            let times: Vec<f64> = reader.read_inputs().expect("inputs").map(f64::from).collect();
            let step = channel.sampler().interpolation() == gltf::animation::Interpolation::Step;
            assert!(
                step || channel.sampler().interpolation() == gltf::animation::Interpolation::Linear,
                "the reference samples STEP and LINEAR only"
            );
            let node = channel.target().node().index();
            use gltf::animation::util::ReadOutputs;
            match reader.read_outputs().expect("outputs") {
                ReadOutputs::Translations(v) => {
                    let v: Vec<Vec<f64>> = v.map(|x| x.map(f64::from).to_vec()).collect();
                    t[node] = DVec3::from_slice(&sample(&times, &v, step, false, time));
                }
                ReadOutputs::Scales(v) => {
                    let v: Vec<Vec<f64>> = v.map(|x| x.map(f64::from).to_vec()).collect();
                    s[node] = DVec3::from_slice(&sample(&times, &v, step, false, time));
                }
                ReadOutputs::Rotations(v) => {
                    let v: Vec<Vec<f64>> = v.into_f32().map(|x| x.map(f64::from).to_vec()).collect();
                    let q = sample(&times, &v, step, true, time);
                    r[node] = DQuat::from_xyzw(q[0], q[1], q[2], q[3]).normalize();
                }
                ReadOutputs::MorphTargetWeights(v) => {
                    let flat: Vec<f64> = v.into_f32().map(f64::from).collect();
                    let width = flat.len() / times.len();
                    let v: Vec<Vec<f64>> = flat.chunks(width).map(<[f64]>::to_vec).collect();
                    weights.insert(node, sample(&times, &v, step, false, time));
                }
            }
        }
    }
    // World matrices, depth first from the default scene's roots.
    let mut world = vec![DMat4::IDENTITY; count];
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .expect("a scene");
    let mut drawn = Vec::new();
    let mut stack: Vec<(gltf::Node, DMat4)> = scene.nodes().map(|n| (n, DMat4::IDENTITY)).collect();
    stack.reverse();
    while let Some((node, parent)) = stack.pop() {
        let i = node.index();
        world[i] = parent * DMat4::from_scale_rotation_translation(s[i], r[i], t[i]);
        if node.mesh().is_some() {
            drawn.push(node.clone());
        }
        let children: Vec<gltf::Node> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|c| (c, world[i])));
    }
    let mut out = Deformed {
        positions: Vec::new(),
        normals: Vec::new(),
        indices: Vec::new(),
    };
    for node in drawn {
        let mesh = node.mesh().expect("drawn");
        let skin = node.skin().map(|skin| {
            let ibm: Vec<DMat4> = skin
                .reader(get)
                .read_inverse_bind_matrices()
                .map(|m| {
                    m.map(|c| DMat4::from_cols_array_2d(&c.map(|r| r.map(f64::from))))
                        .collect()
                })
                .unwrap_or_else(|| vec![DMat4::IDENTITY; skin.joints().count()]);
            skin.joints()
                .zip(ibm)
                .map(|(j, m)| world[j.index()] * m)
                .collect::<Vec<_>>()
        });
        let morph = weights.get(&node.index()).cloned().unwrap_or_default();
        for primitive in mesh.primitives() {
            let reader = primitive.reader(get);
            let base = out.positions.len() as u32;
            let mut p: Vec<DVec3> = reader
                .read_positions()
                .expect("positions")
                .map(|v| DVec3::from_array(v.map(f64::from)))
                .collect();
            let mut n: Vec<DVec3> = reader
                .read_normals()
                .expect("normals")
                .map(|v| DVec3::from_array(v.map(f64::from)))
                .collect();
            for (k, (dp, dn, _)) in reader.read_morph_targets().enumerate() {
                let w = morph.get(k).copied().unwrap_or(0.0);
                if let Some(dp) = dp {
                    for (p, d) in p.iter_mut().zip(dp) {
                        *p += w * DVec3::from_array(d.map(f64::from));
                    }
                }
                if let Some(dn) = dn {
                    for (n, d) in n.iter_mut().zip(dn) {
                        *n += w * DVec3::from_array(d.map(f64::from));
                    }
                }
            }
            let matrices: Vec<DMat4> = match &skin {
                Some(joints) => {
                    let j: Vec<[u16; 4]> = reader.read_joints(0).expect("joints").into_u16().collect();
                    let w: Vec<[f32; 4]> = reader.read_weights(0).expect("weights").into_f32().collect();
                    j.iter()
                        .zip(&w)
                        .map(|(j, w)| {
                            let sum: f64 = w.iter().map(|&x| f64::from(x)).sum();
                            (0..4).fold(DMat4::ZERO, |m, i| m + joints[j[i] as usize] * (f64::from(w[i]) / sum))
                        })
                        .collect()
                }
                None => vec![world[node.index()]; p.len()],
            };
            for ((p, n), m) in p.iter().zip(&n).zip(&matrices) {
                out.positions.push(m.transform_point3(*p));
                let normal_matrix = DMat3::from_mat4(*m).inverse().transpose();
                out.normals.push((normal_matrix * *n).normalize());
            }
            let indices: Vec<u32> = match reader.read_indices() {
                Some(i) => i.into_u32().collect(),
                None => (0..p.len() as u32).collect(),
            };
            out.indices.extend(indices.iter().map(|i| i + base));
        }
    }
    out
}
