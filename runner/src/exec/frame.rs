//! What a frame is ([`FrameSpec`]) and the uniforms written for it each
//! frame: the `Frame` block per eye slot (camera, light, light camera, other
//! eye), the style parameter block (keyframes at the frame's time) and the
//! object blocks (see `objects.rs`).

use super::{objects, Renderer};
use crate::scene::Scene;
use crate::{animation, RunError};
use compiler::manifest::*;

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

impl Renderer<'_> {
    /// The `Frame` uniform block of `eye` (see `compiler::emit::wgsl`'s `struct Frame`).
    fn frame_block(&self, scene: &Scene, spec: &FrameSpec, eye: u32) -> Vec<f32> {
        let pose = scene.camera.pose(spec.time_s);
        let aspect = spec.width as f32 / spec.height as f32;
        let view = pose.view(eye);
        let proj = pose.projection(aspect);
        let view_proj = proj * view;
        let cam = pose.position(eye);
        let mut frame: Vec<f32> = Vec::with_capacity(FRAME_UNIFORM_SIZE as usize / 4);
        frame.extend_from_slice(&view.to_cols_array());
        frame.extend_from_slice(&proj.to_cols_array());
        frame.extend_from_slice(&view_proj.to_cols_array());
        frame.extend_from_slice(&[cam.x, cam.y, cam.z, 1.0]);
        let l = scene.light.direction.normalize_or_zero();
        frame.extend_from_slice(&[l.x, l.y, l.z, scene.light.intensity]);
        let c = scene.light.color;
        frame.extend_from_slice(&[c[0], c[1], c[2], 1.0]);
        frame.extend_from_slice(&[
            spec.width as f32,
            spec.height as f32,
            spec.time_s as f32,
            spec.frame as f32,
        ]);
        frame.extend_from_slice(&[eye as f32, pose.near, pose.far, 0.0]);
        let light_view_proj =
            crate::scene::light_view_proj(scene.light.direction, self.caster_bounds, self.scene_bounds);
        frame.extend_from_slice(&light_view_proj.to_cols_array());
        let other_view_proj = proj * pose.view(1 - eye.min(1));
        frame.extend_from_slice(&other_view_proj.to_cols_array());
        // Age of Sail §3.2: a single (centre) camera for T_s/B_s in stereo; §3.3 eq. 12: P₀₀, P₁₁.
        frame.extend_from_slice(&(proj * pose.center_view()).to_cols_array());
        frame.extend_from_slice(&[proj.x_axis.x, proj.y_axis.y, 0.0, 0.0]);
        let (left, right, forward) = (pose.position(0), pose.position(1), pose.forward());
        frame.extend_from_slice(&[left.x, left.y, left.z, 1.0]);
        frame.extend_from_slice(&[right.x, right.y, right.z, 1.0]);
        frame.extend_from_slice(&[forward.x, forward.y, forward.z, 0.0]);
        debug_assert_eq!(frame.len() * 4, FRAME_UNIFORM_SIZE as usize);
        frame
    }

    /// Write the per-frame, style and object uniforms for `spec`. Everything
    /// here is read from `scene` again each frame: the camera and light, and
    /// every object's transform and per-object params (bad params are
    /// `RunError::User`, and nothing is written then). Only the uniform
    /// buffers are written; meshes and bind groups stay as built.
    pub(super) fn write_uniforms(&mut self, scene: &Scene, spec: &FrameSpec) -> Result<(), RunError> {
        let objects = objects::object_blocks(&self.manifest, scene, self.object_stride)?;
        if objects::moved(&self.bounds_models, scene) {
            (self.scene_bounds, self.caster_bounds) = objects::light_bounds(&self.manifest, scene);
            self.bounds_models = scene.objects.iter().map(|o| o.model).collect();
        }
        let slots = self.frame_buffers.len() as u32;
        for slot in 0..slots {
            // A stereo style renders both eyes; otherwise the requested one.
            let eye = if slots == 2 { slot } else { spec.eye };
            let frame = self.frame_block(scene, spec, eye);
            self.queue
                .write_buffer(&self.frame_buffers[slot as usize], 0, bytemuck::cast_slice(&frame));
        }
        let style = animation::style_param_bytes(&self.manifest, spec.time_s, spec.height);
        if !style.is_empty() {
            self.queue.write_buffer(&self.style_buffer, 0, &style);
        }
        if !objects.is_empty() {
            self.queue.write_buffer(&self.object_buffer, 0, &objects);
        }
        Ok(())
    }
}
