//! A frame's uniforms go to the GPU in one `Queue::write_buffer`: the
//! `Frame` block of each eye slot, the style parameter block and every
//! object's block are laid out in one staging buffer, written once, and
//! copied into their uniform buffers by commands recorded ahead of the
//! passes (`Renderer::encode`).
//!
//! Why: wgpu makes a staging buffer for every `write_buffer` call (a
//! memory allocation in the driver's allocator, whose cost grows with the
//! device's other allocations: about 20 µs at 100 objects on lavapipe),
//! while a copy command costs about a microsecond. A frame writing three
//! blocks separately spent a fifth of its CPU time there (docs/PERFORMANCE.md,
//! "host path"). The copies are in the encoder, after the queue's write
//! (wgpu performs a submit's queue writes before its command buffers), so
//! the passes read what the frame wrote, as they did before.

use crate::gpu_count::Create;

/// Where each block lies in the staging bytes.
pub(super) struct Upload {
    staging: wgpu::Buffer,
    /// The staging buffer's contents, rewritten in place every frame.
    bytes: Vec<u8>,
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
        Upload {
            staging: device.make_buffer(&wgpu::BufferDescriptor {
                label: Some("npr uniforms staging"),
                size: len.max(ALIGN) as u64,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            bytes: vec![0; len],
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

    /// Every object's block, `stride` apart.
    pub fn objects_mut(&mut self) -> &mut [u8] {
        let at = self.objects_at();
        &mut self.bytes[at..at + self.objects_size]
    }

    /// The frame's one write (into the staging buffer).
    pub fn write(&self, queue: &wgpu::Queue) {
        if !self.bytes.is_empty() {
            queue.write_buffer(&self.staging, 0, &self.bytes);
        }
    }

    /// Record the copies into the uniform buffers: each eye slot's frame
    /// block, the style block, the object blocks.
    pub fn encode_copies(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame_buffers: &[wgpu::Buffer],
        style: &wgpu::Buffer,
        objects: &wgpu::Buffer,
    ) {
        for (slot, buffer) in frame_buffers.iter().enumerate().take(self.slots) {
            let at = (aligned(self.frame_size) * slot) as u64;
            encoder.copy_buffer_to_buffer(&self.staging, at, buffer, 0, self.frame_size as u64);
        }
        if self.style_size > 0 {
            encoder.copy_buffer_to_buffer(&self.staging, self.style_at() as u64, style, 0, self.style_size as u64);
        }
        if self.objects_size > 0 {
            encoder.copy_buffer_to_buffer(
                &self.staging,
                self.objects_at() as u64,
                objects,
                0,
                self.objects_size as u64,
            );
        }
    }
}
