//! What a renderer carries from one frame to the next, taken out and put
//! back: [`Renderer::save_state`] and [`Renderer::restore_state`], so a
//! path-dependent style's sequence can start mid-way from a checkpoint
//! (`crate::checkpoint`) instead of replaying from frame 0.
//!
//! A frame's image depends on earlier frames only through: both copies of
//! every history texture (per eye slot), every copy of every compute pass's
//! value buffer (`state`), the object transforms and view-projections of
//! the last two frames (`previous_model`, `previous_view_proj`, and so the
//! samples' `position.previous`), and the frame parity (`frames_begun`).
//! Everything else a frame reads is rewritten by that frame: other targets,
//! uniforms, time-varying vertices (a function of the frame's time), lines'
//! strips. So restoring these after rendering frames `0..k` gives frame `k`
//! bit for bit what the single run gives (`tests/gpu/checkpoints.rs`).

use super::frame::Motion;
use super::sized::scaled_size;
use super::Renderer;
use crate::{readback, RunError};

/// One block of GPU memory in a [`RendererState`].
#[derive(Debug, Clone, PartialEq)]
pub struct StateBlock {
    /// `texture` (a history texture) or `buffer` (a compute pass's values).
    pub kind: StateKind,
    /// Texture: the eye slot; buffer: the manifest pass index.
    pub owner: u32,
    /// Texture: the manifest's physical index; buffer: 0.
    pub index: u32,
    /// Which copy (history textures and stateful values have two).
    pub copy: u32,
    /// Texture: tightly packed rows; buffer: its bytes.
    pub bytes: Vec<u8>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StateKind {
    Texture,
    Buffer,
}

/// Transforms of one frame: per object its model matrix, per eye slot its
/// view-projection (column-major, as glam stores them).
pub type FrameTransforms = (Vec<[f32; 16]>, Vec<[f32; 16]>);

/// Everything that outlives a frame (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct RendererState {
    pub width: u32,
    pub height: u32,
    pub frames_begun: u64,
    /// The last frame's transforms and the one's before it.
    pub motion: [Option<FrameTransforms>; 2],
    pub blocks: Vec<StateBlock>,
}

fn to_arrays((models, view_projs): &(Vec<glam::Mat4>, Vec<glam::Mat4>)) -> FrameTransforms {
    (
        models.iter().map(|m| m.to_cols_array()).collect(),
        view_projs.iter().map(|m| m.to_cols_array()).collect(),
    )
}

fn to_mats((models, view_projs): &FrameTransforms) -> (Vec<glam::Mat4>, Vec<glam::Mat4>) {
    (
        models.iter().map(glam::Mat4::from_cols_array).collect(),
        view_projs.iter().map(glam::Mat4::from_cols_array).collect(),
    )
}

impl Renderer {
    /// The state the next frame depends on (read back from the GPU), after
    /// at least one frame; `RunError::Internal` before any.
    pub fn save_state(&self) -> Result<RendererState, RunError> {
        let sized = self
            .sized
            .as_ref()
            .ok_or_else(|| RunError::Internal("save_state before any frame".into()))?;
        // Values a scene change carries over are in their buffers first.
        self.submit_carried_rows();
        let mut blocks = Vec::new();
        for (slot, second) in sized.physical.second.iter().enumerate() {
            for &index in second.keys() {
                let p = &self.manifest.physical[index];
                let (w, h) = scaled_size(sized.width, sized.height, p.scale);
                for (copy, texture) in [(0, &sized.physical.slots[slot][index]), (1, &second[&index])] {
                    let img = readback::read_texture(&self.device, &self.queue, texture, w, h, p.format, "history")?;
                    blocks.push(StateBlock {
                        kind: StateKind::Texture,
                        owner: slot as u32,
                        index: index as u32,
                        copy,
                        bytes: img.bytes,
                    });
                }
            }
        }
        for (pass, buffers) in self.scene_gpu.values.iter().enumerate() {
            for (copy, buffer) in buffers.iter().flat_map(|b| b.copies.iter().enumerate()) {
                blocks.push(StateBlock {
                    kind: StateKind::Buffer,
                    owner: pass as u32,
                    index: 0,
                    copy: copy as u32,
                    bytes: readback::read_buffer(&self.device, &self.queue, buffer)?,
                });
            }
        }
        Ok(RendererState {
            width: sized.width,
            height: sized.height,
            frames_begun: self.frames_begun,
            motion: [
                self.motion.this.as_ref().map(to_arrays),
                self.motion.previous.as_ref().map(to_arrays),
            ],
            blocks,
        })
    }

    /// Put `state` back (from [`Renderer::save_state`] of a renderer of the
    /// same program and scene): the next frame continues the sequence it
    /// was saved from. A state that does not fit this renderer's textures
    /// and buffers (another style) is `RunError::Internal`; the file's
    /// identity check (`crate::checkpoint`) refuses those first.
    pub fn restore_state(&mut self, state: &RendererState) -> Result<(), RunError> {
        // Fresh textures at the state's size (this also resets what the
        // state does not hold to its frame-0 value, and drops the value
        // rows a scene change left to copy: the state replaces them).
        self.sized = None;
        self.ensure_size(state.width, state.height)?;
        let sized = self
            .sized
            .as_ref()
            .ok_or_else(|| RunError::Internal("no textures".into()))?;
        let wrong = |what: String| RunError::Internal(format!("the saved state does not fit this renderer: {what}"));
        let expected_textures: usize = sized.physical.second.iter().map(|s| 2 * s.len()).sum();
        let expected_buffers: usize = self.scene_gpu.values.iter().flatten().map(|b| b.copies.len()).sum();
        let count = |k: StateKind| state.blocks.iter().filter(|b| b.kind == k).count();
        if count(StateKind::Texture) != expected_textures || count(StateKind::Buffer) != expected_buffers {
            return Err(wrong(format!(
                "{} history textures and {} value buffers saved, {expected_textures} and {expected_buffers} here",
                count(StateKind::Texture),
                count(StateKind::Buffer)
            )));
        }
        for block in &state.blocks {
            match block.kind {
                StateKind::Texture => {
                    let (slot, index) = (block.owner as usize, block.index as usize);
                    let second = sized
                        .physical
                        .second
                        .get(slot)
                        .and_then(|s| s.get(&index))
                        .ok_or_else(|| wrong(format!("no history texture #{index} in eye slot {slot}")))?;
                    let texture = if block.copy == 0 {
                        &sized.physical.slots[slot][index]
                    } else {
                        second
                    };
                    let p = &self.manifest.physical[index];
                    let (w, h) = scaled_size(state.width, state.height, p.scale);
                    let row = w * p.format.bytes_per_pixel();
                    if block.bytes.len() != (row * h) as usize {
                        return Err(wrong(format!(
                            "history texture #{index} has {} bytes",
                            block.bytes.len()
                        )));
                    }
                    self.queue.write_texture(
                        texture.as_image_copy(),
                        &block.bytes,
                        wgpu::TexelCopyBufferLayout {
                            offset: 0,
                            bytes_per_row: Some(row),
                            rows_per_image: Some(h),
                        },
                        wgpu::Extent3d {
                            width: w,
                            height: h,
                            depth_or_array_layers: 1,
                        },
                    );
                }
                StateKind::Buffer => {
                    let buffer = self
                        .scene_gpu
                        .values
                        .get(block.owner as usize)
                        .and_then(|b| b.as_ref())
                        .and_then(|b| b.copies.get(block.copy as usize))
                        .ok_or_else(|| wrong(format!("no value buffer of pass #{}", block.owner)))?;
                    if block.bytes.len() as u64 != buffer.size() {
                        return Err(wrong(format!(
                            "pass #{}'s values have {} bytes",
                            block.owner,
                            block.bytes.len()
                        )));
                    }
                    self.queue.write_buffer(buffer, 0, &block.bytes);
                }
            }
        }
        self.frames_begun = state.frames_begun;
        self.motion = Motion {
            this: state.motion[0].as_ref().map(to_mats),
            previous: state.motion[1].as_ref().map(to_mats),
            spare: None,
            new_objects: Vec::new(),
        };
        self.queue.submit([]);
        Ok(())
    }
}
