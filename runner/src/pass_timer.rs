//! GPU time of each pass of one frame, from timestamps written at the
//! beginning and end of every pass (`Renderer::encode_timed`). One timer per
//! renderer: the query set and buffers are made once and reused each frame.
//! `npr bench passes` takes the median over frames; `npr studio` shows the
//! times of the frame it displays.

use crate::gpu_count::Create;
use crate::{FrameSpec, Gpu, Renderer, RunError};

pub struct PassTimer {
    passes: u32,
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
}

impl PassTimer {
    /// `None` when the adapter has no timestamp queries.
    pub fn new(gpu: &Gpu, passes: usize) -> Option<PassTimer> {
        if !gpu.device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let passes = passes as u32;
        let slots = (2 * passes).max(2);
        let queries = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("npr pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: slots,
        });
        let bytes = slots as u64 * 8;
        let resolve = gpu.device.make_buffer(&wgpu::BufferDescriptor {
            label: Some("npr timestamps"),
            size: bytes,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = gpu.device.make_buffer(&wgpu::BufferDescriptor {
            label: Some("npr timestamps readback"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Some(PassTimer {
            passes,
            queries,
            resolve,
            readback,
        })
    }

    /// Render one frame of `r` (as `Renderer::render` does: prepare, record,
    /// submit, wait) with timestamps; milliseconds per pass, in manifest order.
    pub fn frame(
        &self,
        gpu: &Gpu,
        r: &mut Renderer,
        scene: &crate::scene::Scene,
        spec: &FrameSpec,
    ) -> Result<Vec<f64>, RunError> {
        r.prepare(scene, spec)?;
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        r.encode_timed(&mut encoder, &self.queries);
        let bytes = self.resolve.size();
        encoder.resolve_query_set(&self.queries, 0..2 * self.passes, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, bytes);
        gpu.queue.submit([encoder.finish()]);
        self.readback.slice(..).map_async(wgpu::MapMode::Read, |_| {});
        crate::readback::wait_idle(&gpu.device)?;
        let period_ns = gpu.queue.get_timestamp_period() as f64;
        let times = {
            let view = self
                .readback
                .slice(..)
                .get_mapped_range()
                .map_err(|e| RunError::Internal(format!("cannot map timestamps: {e}")))?;
            let ticks: &[u64] = bytemuck::cast_slice(&view);
            (0..self.passes as usize)
                .map(|p| ticks[2 * p + 1].saturating_sub(ticks[2 * p]) as f64 * period_ns * 1e-6)
                .collect()
        };
        self.readback.unmap();
        Ok(times)
    }
}
