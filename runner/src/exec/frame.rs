//! What a frame is ([`FrameSpec`]) and the uniforms written for it each
//! frame: the `Frame` block per eye slot (camera, light, light camera, other
//! eye), the style parameter block (keyframes at the frame's time) and the
//! object blocks (see `objects.rs`). The camera's matrices
//! ([`CameraMatrices`]) and the light camera (`light_bounds.rs`) are kept
//! while what they are made from stays the same.

use super::{objects, Renderer};
use crate::scene::CameraPose;
use crate::scene::Scene;
use crate::{animation, RunError};
use glam::{Mat4, Vec3};
use npr_abi::FrameBlock;

/// Where and when to render.
#[derive(Debug, Clone, Copy)]
pub struct FrameSpec {
    pub width: u32,
    pub height: u32,
    pub time_s: f64,
    pub frame: u32,
    /// 0 = left (or mono), 1 = right.
    pub eye: u32,
}

impl FrameSpec {
    /// The frame rate `npr render` plays at unless `--fps` says otherwise,
    /// and the one tests and benchmarks animate at.
    pub const DEFAULT_FPS: f64 = 24.0;

    /// Frame `frame` of `eye` in an animation played at `fps` frames a
    /// second: at t = frame / fps, as `npr render --frames` renders it.
    pub fn animated(width: u32, height: u32, frame: u32, fps: f64, eye: u32) -> FrameSpec {
        FrameSpec {
            width,
            height,
            time_s: f64::from(frame) / fps,
            frame,
            eye,
        }
    }

    /// Frame 0 at t = 0 of `eye`, `width`×`height`: a still image.
    pub fn still(width: u32, height: u32, eye: u32) -> FrameSpec {
        FrameSpec {
            width,
            height,
            time_s: 0.0,
            frame: 0,
            eye,
        }
    }
}

/// What "the previous frame" means for `position.previous` and
/// `project_previous`: the object transforms and view-projections (per eye
/// slot) of the frame begun before the current one. On the first frame
/// after the renderer is built or resized there is none, and the current
/// frame's are used, so motion starts at zero.
#[derive(Debug, Default)]
pub(super) struct Motion {
    /// The current frame's, once its uniforms were written.
    pub(super) this: Option<(Vec<Mat4>, Vec<Mat4>)>,
    /// The previous frame's.
    pub(super) previous: Option<(Vec<Mat4>, Vec<Mat4>)>,
    /// The frame's before the previous one, whose vectors the next
    /// [`Motion::record`] refills: a frame allocates none.
    pub(super) spare: Option<(Vec<Mat4>, Vec<Mat4>)>,
    /// Objects a scene change added (`continuity.rs`): at their first
    /// frame, their previous transform is their current one.
    pub(super) new_objects: Vec<usize>,
}

impl Motion {
    /// A new frame begins: the current frame's becomes the previous one's.
    pub fn begin(&mut self) {
        if let Some(this) = self.this.take() {
            self.spare = self.previous.replace(this);
        }
    }

    /// Record the current frame's (again, for a partial re-render of it).
    fn record(&mut self, scene: &Scene, view_projs: &[Mat4]) {
        let (mut models, mut projs) = self.this.take().or_else(|| self.spare.take()).unwrap_or_default();
        models.clear();
        models.extend(scene.objects.iter().map(|o| o.model));
        projs.clear();
        projs.extend_from_slice(view_projs);
        if let Some((previous, _)) = self.previous.as_mut() {
            for &j in &self.new_objects {
                if let (Some(p), Some(m)) = (previous.get_mut(j), models.get(j)) {
                    *p = *m;
                }
            }
        }
        // Past their first frame, added objects have a previous one.
        self.new_objects.clear();
        self.this = Some((models, projs));
    }

    /// The previous frame's models and view-projections (the current
    /// ones on the first frame; empty before any was recorded).
    fn previous(&self) -> (&[Mat4], &[Mat4]) {
        self.previous
            .as_ref()
            .or(self.this.as_ref())
            .map_or((&[], &[]), |(models, projs)| (models.as_slice(), projs.as_slice()))
    }
}

/// The camera's matrices for a frame's blocks, kept while the camera's
/// pose and the image's size stay the same: a host's still camera (most
/// frames) costs a pose and a comparison, not the look-at and perspective
/// matrices of both eyes again (docs/PERFORMANCE.md, "host path"). What is
/// kept is what [`CameraPose`]'s functions give, so the blocks' bytes are
/// the same as when they were computed every frame.
#[derive(Debug, Default)]
pub(super) struct CameraMatrices {
    /// The bits of the pose and the size these were made for (bits, so
    /// that −0 and 0, which may give different matrices, differ, and a
    /// NaN pose is made anew every frame).
    key: Option<[u32; 17]>,
    proj: Mat4,
    center_view_proj: Mat4,
    forward: Vec3,
    /// Per eye (0 left or mono, 1 right): view, `proj × view`, position.
    eyes: [(Mat4, Mat4, Vec3); 2],
    near: f32,
    far: f32,
    /// 0 for a perspective camera (`Frame::ortho_height`).
    ortho_height_m: f32,
}

fn pose_key(pose: &CameraPose, width: u32, height: u32) -> [u32; 17] {
    let v = |v: Vec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
    let [e0, e1, e2] = v(pose.eye);
    let [t0, t1, t2] = v(pose.target);
    let [u0, u1, u2] = v(pose.up);
    [
        e0,
        e1,
        e2,
        t0,
        t1,
        t2,
        u0,
        u1,
        u2,
        pose.fov_y_rad.to_bits(),
        pose.near.to_bits(),
        pose.far.to_bits(),
        u32::from(pose.ipd_m.is_some()),
        pose.ipd_m.map_or(0, f32::to_bits),
        pose.ortho_height_m.map_or(0, f32::to_bits),
        width,
        height,
    ]
}

impl CameraMatrices {
    /// Bring the matrices to `scene`'s camera at `spec`'s time and size.
    fn update(&mut self, scene: &Scene, spec: &FrameSpec) {
        let pose = scene.camera.pose(spec.time_s);
        let key = pose_key(&pose, spec.width, spec.height);
        if self.key == Some(key) {
            return;
        }
        let proj = pose.projection(spec.width as f32 / spec.height as f32);
        // Eye indices past 1 are the right eye (`CameraPose::view`'s rule).
        let eye = |e: u32| {
            let view = pose.view(e);
            (view, proj * view, pose.position(e))
        };
        *self = CameraMatrices {
            key: Some(key),
            proj,
            center_view_proj: proj * pose.center_view(),
            forward: pose.forward(),
            eyes: [eye(0), eye(1)],
            near: pose.near,
            far: pose.far,
            ortho_height_m: pose.ortho_height_m.unwrap_or(0.0),
        };
    }

    /// Eye `eye`'s view, view-projection and position.
    fn eye(&self, eye: u32) -> &(Mat4, Mat4, Vec3) {
        &self.eyes[eye.min(1) as usize]
    }
}

impl Renderer {
    /// The `Frame` uniform block of `eye` (`npr_abi::FrameBlock`, `struct Frame`
    /// in WGSL), from the camera's matrices ([`CameraMatrices::update`]d for
    /// `spec`) and the light camera.
    fn frame_block(
        &self,
        scene: &Scene,
        spec: &FrameSpec,
        eye: u32,
        (previous_view_proj, light_view_proj): (Mat4, Mat4),
    ) -> FrameBlock {
        let camera = &self.camera;
        let (view, view_proj, cam) = *camera.eye(eye);
        let proj = camera.proj;
        let l = scene.light.direction.normalize_or_zero();
        let c = scene.light.color;
        let other_view_proj = camera.eye(1 - eye.min(1)).1;
        let (left, right, forward) = (camera.eyes[0].2, camera.eyes[1].2, camera.forward);
        let (more_light_dir, more_light_color) = scene.more_light_frame();
        FrameBlock {
            view: view.to_cols_array_2d(),
            proj: proj.to_cols_array_2d(),
            view_proj: view_proj.to_cols_array_2d(),
            camera_pos: [cam.x, cam.y, cam.z, 1.0],
            light_dir: [l.x, l.y, l.z, scene.light.intensity],
            light_color: [c[0], c[1], c[2], 1.0],
            resolution: [spec.width as f32, spec.height as f32],
            time: spec.time_s as f32,
            frame_index: spec.frame as f32,
            eye: eye as f32,
            near: camera.near,
            far: camera.far,
            ortho_height: camera.ortho_height_m,
            light_view_proj: light_view_proj.to_cols_array_2d(),
            other_view_proj: other_view_proj.to_cols_array_2d(),
            // Age of Sail §3.2: a single (centre) camera for T_s/B_s in stereo; §3.3 eq. 12: P₀₀, P₁₁.
            center_view_proj: camera.center_view_proj.to_cols_array_2d(),
            focal: [proj.x_axis.x, proj.y_axis.y, 0.0, 0.0],
            eye_left: [left.x, left.y, left.z, 1.0],
            eye_right: [right.x, right.y, right.z, 1.0],
            camera_forward: [forward.x, forward.y, forward.z, 0.0],
            previous_view_proj: previous_view_proj.to_cols_array_2d(),
            more_light_dir,
            more_light_color,
        }
    }

    /// The eye that eye slot `slot` renders: a stereo style renders both eyes,
    /// a mono one the requested eye.
    pub(super) fn eye_of_slot(&self, spec: &FrameSpec, slot: u32) -> u32 {
        if self.frame_buffers.len() == 2 {
            slot
        } else {
            spec.eye
        }
    }

    /// The view-projection of `eye` for `spec` (as `frame_block` computes it).
    pub(super) fn view_proj(&self, scene: &Scene, spec: &FrameSpec, eye: u32) -> Mat4 {
        let pose = scene.camera.pose(spec.time_s);
        pose.projection(spec.width as f32 / spec.height as f32) * pose.view(eye)
    }

    /// Write the per-frame, style and object uniforms for `spec` (into the
    /// blocks `encode` uploads: `upload.rs`). Everything
    /// here is read from `scene` again each frame: the camera and light, and
    /// every object's transform and per-object params (bad params are
    /// `RunError::User`, and nothing is written then). Only the uniform
    /// buffers are written; meshes and bind groups stay as built.
    pub(super) fn write_uniforms(&mut self, scene: &Scene, spec: &FrameSpec) -> Result<(), RunError> {
        let slots = self.frame_buffers.len();
        self.camera.update(scene, spec);
        // At most two eye slots (stereo): no allocation for them.
        let mut view_projs = [Mat4::IDENTITY; 2];
        for (s, vp) in view_projs.iter_mut().enumerate().take(slots) {
            *vp = self.camera.eye(self.eye_of_slot(spec, s as u32)).1;
        }
        self.motion.record(scene, &view_projs[..slots]);
        let (previous_models, previous_projs) = self.motion.previous();
        objects::write_object_blocks(
            (&self.manifest, &self.object_params),
            scene,
            self.object_stride,
            (previous_models, &self.scene_gpu.vertex_counts),
            self.scene_gpu.upload.objects_mut(),
        )?;
        let mut previous_view_projs = view_projs;
        for (p, previous) in previous_view_projs.iter_mut().zip(previous_projs) {
            *p = *previous;
        }
        self.scene_gpu.light_bounds.update(scene);
        let light_view_proj = self.scene_gpu.light_bounds.light_view_proj(scene.light.direction);
        for (slot, previous) in previous_view_projs.iter().enumerate().take(slots) {
            let eye = self.eye_of_slot(spec, slot as u32);
            let frame = self.frame_block(scene, spec, eye, (*previous, light_view_proj));
            self.scene_gpu
                .upload
                .frame_mut(slot)
                .copy_from_slice(bytemuck::bytes_of(&frame));
        }
        // The whole style block when the parameters or the height changed
        // since it was last written whole; otherwise only the animated ones.
        let upload = &mut self.scene_gpu.upload;
        if upload.style_current(spec.height) {
            animation::write_style_params_at(
                &self.manifest,
                &self.animated_style_params,
                spec.time_s,
                spec.height,
                upload.style_mut(),
            );
        } else {
            animation::write_style_params(&self.manifest, spec.time_s, spec.height, upload.style_mut());
            self.animated_style_params = animation::animated_style_param_indices(&self.manifest);
            upload.style_written(spec.height);
        }
        // `encode` puts the blocks into a staging buffer and copies them into their buffers.
        Ok(())
    }
}
