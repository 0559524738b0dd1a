//! What a scene change at the same size carries over (docs/decisions/0046):
//! which objects of the new scene continue objects of the old one (by
//! name, [`continuing`]), their compute state (their rows of every
//! compute pass's value buffers, copied by [`RowCopy`]s the next frame's
//! encoder records before its passes), their transforms of the last frames
//! (`previous_model`, [`Motion::remap`]) and group 0, which binds compute
//! passes' values ([`Renderer::rebind_scene_values`]). The screen-space
//! history (the history textures and the frame parity) is simply kept.

use super::frame::Motion;
use super::values::PassBuffers;
use super::Renderer;
use crate::scene::Scene;
use glam::Mat4;
use std::collections::HashMap;

/// Per object of `new`, the index of the object of the old scene (named
/// `old_names`, in order) it continues, or `None` for an object that is
/// new. An object continues the old object of the same name; where several
/// objects share a name, the k-th of the name continues the k-th (so
/// objects named by their position continue by position).
pub(super) fn continuing(old_names: &[String], new: &Scene) -> Vec<Option<usize>> {
    let mut old_by_name: HashMap<&str, std::collections::VecDeque<usize>> = HashMap::new();
    for (i, name) in old_names.iter().enumerate() {
        old_by_name.entry(name.as_str()).or_default().push_back(i);
    }
    new.objects
        .iter()
        .map(|o| old_by_name.get_mut(o.name.as_str()).and_then(|q| q.pop_front()))
        .collect()
}

/// One copy of continuing objects' value rows from an old value buffer
/// into the new one (a run of objects consecutive in both).
pub(super) struct RowCopy {
    from: wgpu::Buffer,
    from_offset: u64,
    to: wgpu::Buffer,
    to_offset: u64,
    bytes: u64,
}

impl RowCopy {
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.copy_buffer_to_buffer(&self.from, self.from_offset, &self.to, self.to_offset, self.bytes);
    }
}

/// The copies that bring every continuing object's values (its state, and
/// this frame's values) from `old` into the same slots of `new`, per pass
/// and per copy (parity): the frame parity continues, so copy `c` goes to
/// copy `c`. New objects keep the zeroed rows `values::reset` gave them,
/// which their pass reads as "no state yet" (its first values).
pub(super) fn value_rows(
    old: &[Option<PassBuffers>],
    new: &[Option<PassBuffers>],
    continuing: &[Option<usize>],
) -> Vec<RowCopy> {
    // Runs of (new index, old index, length), consecutive in both.
    let mut runs: Vec<(u64, u64, u64)> = Vec::new();
    for (j, i) in continuing.iter().enumerate() {
        let Some(i) = *i else { continue };
        match runs.last_mut() {
            Some((to, from, n)) if *to + *n == j as u64 && *from + *n == i as u64 => *n += 1,
            _ => runs.push((j as u64, i as u64, 1)),
        }
    }
    let mut copies = Vec::new();
    for (old, new) in old.iter().zip(new) {
        let (Some(old), Some(new)) = (old, new) else { continue };
        let row = u64::from(new.slots) * 16;
        for (from, to) in old.copies.iter().zip(&new.copies) {
            for &(j, i, n) in &runs {
                copies.push(RowCopy {
                    from: from.clone(),
                    from_offset: i * row,
                    to: to.clone(),
                    to_offset: j * row,
                    bytes: n * row,
                });
            }
        }
    }
    copies
}

impl Motion {
    /// The old scene's transforms, per object of the new one: a continuing
    /// object keeps its own; a new object gets its current transform as
    /// its previous one at its first frame (as every object does at a
    /// renderer's first frame): [`Motion::record`] fills them in.
    pub(super) fn remap(&mut self, continuing: &[Option<usize>]) {
        let remapped = |frame: &mut Option<(Vec<Mat4>, Vec<Mat4>)>| {
            if let Some((models, _)) = frame {
                *models = continuing
                    .iter()
                    .map(|i| i.and_then(|i| models.get(i).copied()).unwrap_or(Mat4::IDENTITY))
                    .collect();
            }
        };
        remapped(&mut self.this);
        remapped(&mut self.previous);
        self.spare = None;
        self.new_objects = continuing
            .iter()
            .enumerate()
            .filter(|(_, i)| i.is_none())
            .map(|(j, _)| j)
            .collect();
    }
}

impl Renderer {
    /// After a scene change at an unchanged size: every group 0 is made
    /// again over the kept targets, since group 0 binds buffers the scene
    /// makes (a compute pass's values, `Resource::ObjectValues`; and
    /// whatever uniform buffer `SceneGpu` holds), and passes over pixels
    /// get their element workgroups for the new number of objects.
    pub(super) fn rebind_scene_values(&mut self) {
        let Some(mut sized) = self.sized.take() else { return };
        for (parity, parity_passes) in sized.passes.iter_mut().enumerate() {
            for (slot, slot_passes) in parity_passes.iter_mut().enumerate() {
                for (pi, pass) in slot_passes.iter_mut().enumerate() {
                    pass.group0 = self.group0(pi, slot, parity, &sized.physical);
                    // Its draws bind the old group 0 and the old scene's objects.
                    pass.draws = None;
                    pass.pixel_workgroups = self.scene_gpu.values[pi]
                        .as_ref()
                        .map_or(0, |b| b.pixel_workgroups(&self.manifest, sized.width, sized.height));
                }
            }
        }
        super::values::write_pixel_dispatch(
            &self.queue,
            &self.manifest,
            &self.scene_gpu.values,
            sized.width,
            sized.height,
        );
        self.sized = Some(sized);
    }

    /// Record the value rows a scene change carries over (once: the first
    /// encode after the change takes them).
    pub(super) fn record_carried_rows(&self, encoder: &mut wgpu::CommandEncoder) {
        let carried = std::mem::take(&mut *self.carried_rows.lock().unwrap_or_else(|e| e.into_inner()));
        for copy in &carried {
            copy.record(encoder);
        }
    }

    /// Submit the carried rows now, for a read of the value buffers
    /// (`save_state`, `read_object_values`) before the next frame.
    pub(super) fn submit_carried_rows(&self) {
        let pending = !self.carried_rows.lock().unwrap_or_else(|e| e.into_inner()).is_empty();
        if pending {
            let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("npr carried values"),
            });
            self.record_carried_rows(&mut encoder);
            self.queue.submit([encoder.finish()]);
        }
    }

    /// Start the history again, as at a new size: the next frame is frame 0
    /// (`previous(...)` reads zero, compute state its first values,
    /// `previous_model` the current one), and renders what a new renderer
    /// of the same objects renders, byte for byte. The targets are made
    /// again at that frame. For a replay from frame 0 (the studio's, a
    /// sequence starting over); a scene change keeps the history.
    pub fn restart_history(&mut self) {
        self.sized = None;
        self.frames_begun = 0;
        // `make_sized` zeroes compute state (and drops the rows a scene
        // change left to copy).
        self.motion = Motion::default();
    }
}
