//! Each frame, before the passes are recorded: every `lines` pass builds
//! its strips for each eye slot (`lines_pass.rs` holds the executor; this is
//! the renderer's side, which finds the lines passes among its executors).

use super::lines_pass::{LinesEye, LinesFrame};
use super::pass::PassExec;
use crate::RunError;

impl super::Renderer {
    /// Per lines pass (by name): how many times its strips were built since
    /// the renderer was made (each eye slot counts).
    pub fn lines_rebuilds(&self) -> Vec<(String, u64)> {
        self.passes
            .iter()
            .zip(&self.manifest.passes)
            .filter_map(|(exec, pass)| match exec {
                PassExec::Lines(l) => Some((pass.name.clone(), l.rebuilds())),
                _ => None,
            })
            .collect()
    }

    /// Every lines pass's strips for this frame, per eye slot (after the
    /// uniforms are written; `scene` is posed at the frame's time).
    pub(super) fn prepare_lines(
        &mut self,
        scene: &crate::scene::Scene,
        spec: &super::FrameSpec,
    ) -> Result<(), RunError> {
        if !self.has_lines {
            return Ok(());
        }
        let meshes: Vec<std::sync::Arc<crate::scene::Mesh>> = scene
            .objects
            .iter()
            .map(|o| match &o.time_varying {
                Some(primitive) => std::sync::Arc::new(primitive.build_at(spec.time_s)),
                None => o.mesh.clone(),
            })
            .collect();
        let frame = LinesFrame {
            manifest: &self.manifest,
            scene,
            meshes: &meshes,
            time_s: spec.time_s,
            width: spec.width,
            height: spec.height,
        };
        let pose = scene.camera.pose(spec.time_s);
        let focal_y = f64::from(pose.projection(spec.width as f32 / spec.height as f32).y_axis.y);
        let eyes: Vec<LinesEye> = (0..self.frame_buffers.len())
            .map(|slot| {
                let eye = self.eye_of_slot(spec, slot as u32);
                LinesEye {
                    slot,
                    eye,
                    position: crate::lines::viewpoint::Viewpoint(pose.homogeneous_eye(eye).as_dvec4()),
                    view_proj: self.view_proj(scene, spec, eye).as_dmat4(),
                    focal_y,
                }
            })
            .collect();
        for (pi, exec) in self.passes.iter_mut().enumerate() {
            let PassExec::Lines(lines) = exec else {
                continue;
            };
            for eye in &eyes {
                lines.prepare(&self.device, &self.queue, &frame, eye, self.manifest.passes[pi].scale)?;
            }
        }
        Ok(())
    }
}
