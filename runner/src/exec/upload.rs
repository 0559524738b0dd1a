//! A frame's uniforms go to the GPU through one mapped staging buffer:
//! the `Frame` block of each eye slot, the style parameter block and every
//! object's block are laid out in `Upload::bytes` by `prepare`, and
//! `encode` copies those bytes into a staging buffer that is already
//! mapped, then records copies from it into the uniform buffers ahead of
//! the passes (decision 0047).
//!
//! Why: `Queue::write_buffer` makes a staging buffer for every call (a
//! buffer, memory from the driver's allocator, a map), which was the
//! largest single item of a host's frame after the passes themselves
//! (docs/PERFORMANCE.md, "A host's frame"). Here the staging buffers are
//! reused: each goes back to the ring, mapped again, once the GPU has
//! copied from it (`CommandEncoder::map_buffer_on_submit`; wgpu calls back
//! on a later submit or poll). The ring holds as many buffers as frames
//! are in flight, usually one or two, and makes one only when none is back
//! yet (counted by `gpu_count`, like every buffer the runner makes). It is
//! wgpu's `util::StagingBelt` reduced to one fixed-size block per frame,
//! written here so that its buffers are counted.
//!
//! Because the copies read a staging buffer of their own, two frames
//! recorded into one encoder each read their own uniforms.

use crate::gpu_count::Create;
use std::sync::{mpsc, Mutex};

/// Staging buffers of one size, mapped for writing and ready, or on their
/// way back from the GPU.
struct StagingRing {
    device: wgpu::Device,
    size: u64,
    ready: Vec<wgpu::Buffer>,
    /// Where a buffer's map callback sends it once the GPU copied from it.
    returned: mpsc::Receiver<wgpu::Buffer>,
    send_back: mpsc::Sender<wgpu::Buffer>,
}

impl StagingRing {
    /// A mapped buffer: one that came back, or a new one.
    fn take(&mut self) -> wgpu::Buffer {
        self.ready.extend(self.returned.try_iter());
        self.ready.pop().unwrap_or_else(|| {
            self.device.make_buffer(&wgpu::BufferDescriptor {
                label: Some("npr uniforms staging"),
                size: self.size,
                usage: wgpu::BufferUsages::MAP_WRITE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: true,
            })
        })
    }

    /// A staging buffer holding `bytes`, unmapped for the copies. A buffer
    /// that cannot be written (its map failed) is dropped for a new one;
    /// `None` only if a new one cannot be written either (the device is
    /// lost, which wgpu reports through its own error handler).
    fn staged(&mut self, bytes: &[u8]) -> Option<wgpu::Buffer> {
        for _ in 0..2 {
            let buffer = self.take();
            let written = buffer
                .slice(..bytes.len() as u64)
                .get_mapped_range_mut()
                .map(|mut view| view.copy_from_slice(bytes));
            if written.is_ok() {
                buffer.unmap();
                return Some(buffer);
            }
        }
        None
    }

    /// Map `buffer` again once `encoder`'s commands ran, and take it back then.
    fn give_back_after(&self, encoder: &wgpu::CommandEncoder, buffer: wgpu::Buffer) {
        let send_back = self.send_back.clone();
        let mapped = buffer.clone();
        encoder.map_buffer_on_submit(&buffer, wgpu::MapMode::Write, .., move |result| {
            // A failed map (device lost) drops the buffer: the ring makes another.
            if result.is_ok() {
                let _ = send_back.send(mapped);
            }
        });
    }
}

/// Where each block lies in the staging bytes.
pub(super) struct Upload {
    /// `encode` takes `&self` (a host may encode from shared references).
    staging: Mutex<StagingRing>,
    /// The blocks as `prepare` wrote them, rewritten in place every frame
    /// (the style block's static parameters only when they changed).
    bytes: Vec<u8>,
    /// The image height the whole style block was last written for;
    /// `None` until it is, and after the style's parameters changed.
    style_written_for: Option<u32>,
    frame_size: usize,
    slots: usize,
    style_size: usize,
    objects_size: usize,
}

/// Offsets in the staging buffer are multiples of this (wgpu's copy
/// alignment is 4; 16 keeps each block's vec4s aligned in the Vec).
const ALIGN: usize = 16;

fn aligned(n: usize) -> usize {
    n.div_ceil(ALIGN) * ALIGN
}

impl Upload {
    /// Room for `slots` frame blocks of `frame_size` bytes, a style block
    /// of `style_size` and the object blocks' `objects_size`.
    pub fn new(
        device: &wgpu::Device,
        frame_size: usize,
        slots: usize,
        style_size: usize,
        objects_size: usize,
    ) -> Upload {
        let len = aligned(frame_size) * slots + aligned(style_size) + aligned(objects_size);
        let (send_back, returned) = mpsc::channel();
        Upload {
            staging: Mutex::new(StagingRing {
                device: device.clone(),
                size: len.max(ALIGN) as u64,
                ready: Vec::new(),
                returned,
                send_back,
            }),
            bytes: vec![0; len],
            style_written_for: None,
            frame_size,
            slots,
            style_size,
            objects_size,
        }
    }

    fn style_at(&self) -> usize {
        aligned(self.frame_size) * self.slots
    }

    fn objects_at(&self) -> usize {
        self.style_at() + aligned(self.style_size)
    }

    /// Eye slot `slot`'s frame block.
    pub fn frame_mut(&mut self, slot: usize) -> &mut [u8] {
        let at = aligned(self.frame_size) * slot;
        &mut self.bytes[at..at + self.frame_size]
    }

    /// The style parameter block.
    pub fn style_mut(&mut self) -> &mut [u8] {
        let at = self.style_at();
        &mut self.bytes[at..at + self.style_size]
    }

    /// Whether the style block holds every parameter as of the last
    /// [`Upload::style_written`] for `height` (then a frame rewrites only
    /// the animated ones).
    pub fn style_current(&self, height: u32) -> bool {
        self.style_written_for == Some(height)
    }

    /// The whole style block was written for `height`.
    pub fn style_written(&mut self, height: u32) {
        self.style_written_for = Some(height);
    }

    /// The style's parameters changed: the next frame writes the whole block.
    pub fn style_changed(&mut self) {
        self.style_written_for = None;
    }

    /// Every object's block, `stride` apart.
    pub fn objects_mut(&mut self) -> &mut [u8] {
        let at = self.objects_at();
        &mut self.bytes[at..at + self.objects_size]
    }

    /// Put the blocks into a staging buffer and record the copies into the
    /// uniform buffers: each eye slot's frame block, the style block, the
    /// object blocks.
    pub fn encode_copies(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame_buffers: &[wgpu::Buffer],
        style: &wgpu::Buffer,
        objects: &wgpu::Buffer,
    ) {
        if self.bytes.is_empty() {
            return;
        }
        // A poisoned lock: a panic between `take` and `give_back_after`
        // lost at most one buffer, and the ring makes another.
        let mut ring = self.staging.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        let Some(staging) = ring.staged(&self.bytes) else {
            return;
        };
        for (slot, buffer) in frame_buffers.iter().enumerate().take(self.slots) {
            let at = (aligned(self.frame_size) * slot) as u64;
            encoder.copy_buffer_to_buffer(&staging, at, buffer, 0, self.frame_size as u64);
        }
        if self.style_size > 0 {
            encoder.copy_buffer_to_buffer(&staging, self.style_at() as u64, style, 0, self.style_size as u64);
        }
        if self.objects_size > 0 {
            encoder.copy_buffer_to_buffer(&staging, self.objects_at() as u64, objects, 0, self.objects_size as u64);
        }
        ring.give_back_after(encoder, staging);
    }
}
