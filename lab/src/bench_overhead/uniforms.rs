//! The uniform blocks the independent baseline writes, filled from the ABI's
//! definitions (`npr_abi::FrameBlock`, `npr_abi::ObjectHead` and the manifest's
//! parameter slots) and the scene's CPU data (camera pose, light, model
//! matrices), without any of the runner's own uniform code.

use glam::{Mat4, Vec3};
use npr_abi::manifest::*;
use npr_abi::{FrameBlock, ObjectHead};
use npr_runner::scene::Scene;

/// The `Frame` block of a mono frame (eye 0) at `time_s`; `previous_view_proj`
/// is the previous frame's view-projection (this one's on the first frame).
pub fn frame_block(
    scene: &Scene,
    (width, height): (u32, u32),
    time_s: f64,
    frame_index: u32,
    light_view_proj: Mat4,
    previous_view_proj: Option<Mat4>,
) -> FrameBlock {
    let pose = scene.camera.pose(time_s);
    let proj = pose.projection(width as f32 / height as f32);
    let view = pose.view(0);
    let view_proj = proj * view;
    let (eye, left, right, forward) = (pose.position(0), pose.position(0), pose.position(1), pose.forward());
    let l = scene.light.direction.normalize_or_zero();
    let c = scene.light.color;
    let point = |p: Vec3| [p.x, p.y, p.z, 1.0];
    let (more_light_dir, more_light_color) = scene.more_light_frame();
    FrameBlock {
        view: view.to_cols_array_2d(),
        proj: proj.to_cols_array_2d(),
        view_proj: view_proj.to_cols_array_2d(),
        camera_pos: point(eye),
        light_dir: [l.x, l.y, l.z, scene.light.intensity],
        light_color: [c[0], c[1], c[2], 1.0],
        resolution: [width as f32, height as f32],
        time: time_s as f32,
        frame_index: frame_index as f32,
        eye: 0.0,
        near: pose.near,
        far: pose.far,
        ortho_height: 0.0,
        light_view_proj: light_view_proj.to_cols_array_2d(),
        other_view_proj: (proj * pose.view(1)).to_cols_array_2d(),
        center_view_proj: (proj * pose.center_view()).to_cols_array_2d(),
        focal: [proj.x_axis.x, proj.y_axis.y, 0.0, 0.0],
        eye_left: point(left),
        eye_right: point(right),
        camera_forward: [forward.x, forward.y, forward.z, 0.0],
        previous_view_proj: previous_view_proj.unwrap_or(view_proj).to_cols_array_2d(),
        more_light_dir,
        more_light_color,
    }
}

/// Object `index`'s head: its model, normal matrix (inverse transpose, the
/// identity where that is not finite), previous model and ids.
pub fn object_head(model: Mat4, previous_model: Option<Mat4>, index: usize, vertex_count: usize) -> ObjectHead {
    let normal = model.inverse().transpose();
    let normal = if normal.is_finite() { normal } else { Mat4::IDENTITY };
    ObjectHead {
        model: model.to_cols_array_2d(),
        normal_matrix: normal.to_cols_array_2d(),
        previous_model: previous_model.unwrap_or(model).to_cols_array_2d(),
        ids: [index as u32, index as u32 + 1, vertex_count as u32, 0],
    }
}

/// One `vec4<f32>` slot (see the manifest's uniform layout invariant).
fn slot(values: &[f64]) -> [u8; 16] {
    let mut s = [0f32; 4];
    for (v, x) in s.iter_mut().zip(values) {
        *v = *x as f32;
    }
    bytemuck::cast(s)
}

/// Up to four components as one slot's values.
fn four(values: &[f64]) -> [f64; 4] {
    let mut v = [0.0; 4];
    for (x, y) in v.iter_mut().zip(values) {
        *x = *y;
    }
    v
}

/// A parameter's value at `time_s`: its keyframes (held before the first
/// and after the last; `step`, `smooth` (3u² − 2u³) or linear between), or
/// its default.
fn value_at(p: &ParamManifest, time_s: f64) -> [f64; 4] {
    let keys = &p.keyframes;
    let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
        return four(&p.default);
    };
    if time_s <= first.0 {
        return four(&first.1);
    }
    if time_s >= last.0 {
        return four(&last.1);
    }
    let i = keys.iter().rposition(|(t, _)| *t <= time_s).unwrap_or(0);
    let ((t0, v0), (t1, v1)) = (&keys[i], &keys[i + 1]);
    let u = ((time_s - t0) / (t1 - t0).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
    let u = match p.interpolation.as_str() {
        "step" => 0.0,
        "smooth" => u * u * (3.0 - 2.0 * u),
        _ => u,
    };
    let (a, b) = (four(v0), four(v1));
    std::array::from_fn(|c| a[c] + (b[c] - a[c]) * u)
}

/// Whether the style block changes over time (some parameter in it is animated).
pub fn style_is_animated(manifest: &Manifest) -> bool {
    manifest
        .params
        .iter()
        .any(|p| p.binding == ParamBinding::Uniform && !p.keyframes.is_empty())
}

/// The style block at `time_s` into `bytes` (`style_uniform_size` long):
/// every `Uniform` parameter's slot, `%` of the height resolved for `height`.
pub fn style_block(manifest: &Manifest, time_s: f64, height: u32, bytes: &mut [u8]) {
    for p in manifest.params.iter().filter(|p| p.binding == ParamBinding::Uniform) {
        let Some(offset) = p.offset else { continue };
        let scale = if p.default_percent_of_height {
            height as f64 / 100.0
        } else {
            1.0
        };
        let v = value_at(p, time_s).map(|x| x * scale);
        bytes[offset as usize..offset as usize + 16].copy_from_slice(&slot(&v));
    }
}

/// An object's parameter slots (after the head, `object_uniform_size −
/// OBJECT_PARAMS_OFFSET` bytes): the scene's binding or the default; a
/// colour given as rgb gets alpha 1.
pub fn object_params(manifest: &Manifest, object: &npr_runner::scene::Object) -> Vec<u8> {
    let size = manifest.object_uniform_size.saturating_sub(OBJECT_PARAMS_OFFSET) as usize;
    let mut bytes = vec![0u8; size];
    for p in manifest.params.iter().filter(|p| p.binding == ParamBinding::PerObject) {
        let Some(offset) = p.offset else { continue };
        let mut v = object.params.get(&p.name).unwrap_or(&p.default).clone();
        if v.len() == 3 && p.components == 4 {
            v.push(1.0);
        }
        let at = (offset - OBJECT_PARAMS_OFFSET) as usize;
        bytes[at..at + 16].copy_from_slice(&slot(&v));
    }
    bytes
}
