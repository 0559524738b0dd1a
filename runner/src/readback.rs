//! Copy a GPU texture back to memory, and convert texels to floats.

use crate::gpu_count::Create;
use crate::RunError;
use npr_abi::Format;

/// A target read back from the GPU, rows tightly packed.
#[derive(Debug, Clone)]
pub struct TargetImage {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub format: Format,
    pub bytes: Vec<u8>,
}

impl TargetImage {
    /// Texel (x, y) as RGBA floats, the values a shader reads from the
    /// target (an sRGB target's colour decoded to linear); missing channels
    /// are 0 (alpha 1).
    pub fn texel(&self, x: u32, y: u32) -> [f32; 4] {
        let bpp = self.format.bytes_per_pixel() as usize;
        let i = (y as usize * self.width as usize + x as usize) * bpp;
        let b = &self.bytes[i..i + bpp];
        let channels = self.format.channels() as usize;
        let mut out = [0.0, 0.0, 0.0, 1.0];
        for (c, slot) in out.iter_mut().enumerate().take(channels) {
            *slot = match self.format {
                Format::R8unorm | Format::Rg8unorm | Format::Rgba8unorm | Format::Rgba8unormSrgb => {
                    crate::srgb::unorm8_as_read(b[c], c, self.format == Format::Rgba8unormSrgb)
                }
                Format::R16float | Format::Rg16float | Format::Rgba16float => {
                    half::f16::from_bits(u16::from_le_bytes([b[2 * c], b[2 * c + 1]])).to_f32()
                }
                Format::R32float | Format::Rg32float | Format::Rgba32float => {
                    f32::from_le_bytes([b[4 * c], b[4 * c + 1], b[4 * c + 2], b[4 * c + 3]])
                }
            };
        }
        out
    }

    /// Every texel as [`TargetImage::texel`] gives it, row-major. One match
    /// on the format for the whole image, not one per texel: the studio
    /// converts a whole frame for every image it serves.
    pub fn to_rgba_f32(&self) -> Vec<[f32; 4]> {
        match self.format {
            Format::R8unorm | Format::Rg8unorm | Format::Rgba8unorm | Format::Rgba8unormSrgb => {
                let srgb = self.format == Format::Rgba8unormSrgb;
                self.decode(1, |c, b| crate::srgb::unorm8_as_read(b[0], c, srgb))
            }
            Format::R16float | Format::Rg16float | Format::Rgba16float => self.decode(2, |_, b| {
                half::f16::from_bits(u16::from_le_bytes([b[0], b[1]])).to_f32()
            }),
            Format::R32float | Format::Rg32float | Format::Rgba32float => {
                self.decode(4, |_, b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            }
        }
    }

    /// Texels with `size`-byte channels decoded by `channel`; missing
    /// channels 0, alpha 1 (as [`TargetImage::texel`]).
    fn decode(&self, size: usize, channel: impl Fn(usize, &[u8]) -> f32) -> Vec<[f32; 4]> {
        let channels = self.format.channels() as usize;
        self.bytes
            .chunks_exact(self.format.bytes_per_pixel() as usize)
            .map(|px| {
                let mut out = [0.0, 0.0, 0.0, 1.0];
                for (c, slot) in out.iter_mut().enumerate().take(channels) {
                    *slot = channel(c, &px[c * size..]);
                }
                out
            })
            .collect()
    }

    /// 8-bit RGBA for display: unorm targets byte for byte (their values are
    /// display-referred), float targets clamped to [0, 1]. One-channel targets
    /// show as grey, two-channel as red/green.
    pub fn to_rgba8(&self) -> image::RgbaImage {
        let grey = self.format.channels() == 1;
        let px: Vec<u8> = if matches!(self.format, Format::Rgba8unorm | Format::Rgba8unormSrgb) {
            self.bytes.clone()
        } else if self.format.is_unorm() {
            // The bytes themselves: b / 255 quantized again is b.
            let bpp = self.format.bytes_per_pixel() as usize;
            self.bytes
                .chunks_exact(bpp)
                .flat_map(|b| match (grey, bpp) {
                    (true, _) => [b[0], b[0], b[0], 255],
                    (false, 2) => [b[0], b[1], 0, 255],
                    _ => [b[0], b[1], b[2], b[3]],
                })
                .collect()
        } else {
            let q = |v: f32| (if v.is_finite() { v } else { 0.0 }.clamp(0.0, 1.0) * 255.0).round() as u8;
            self.to_rgba_f32()
                .into_iter()
                .flat_map(|t| {
                    let t = if grey { [t[0], t[0], t[0], 1.0] } else { t };
                    t.map(q)
                })
                .collect()
        };
        image::RgbaImage::from_raw(self.width, self.height, px).expect("one RGBA texel per pixel")
    }

    pub fn is_float(&self) -> bool {
        !self.format.is_unorm()
    }
}

/// Read `texture` back in bands of rows, each band's buffer within the
/// device's `max_buffer_size` (a 16384² target is 1 GiB at 4 bytes per
/// pixel), inside error scopes (`gpu_error`).
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    width: u32,
    height: u32,
    format: Format,
    name: &str,
) -> Result<TargetImage, RunError> {
    let bpp = format.bytes_per_pixel();
    let unpadded = width * bpp;
    let padded = unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let band_rows = (device.limits().max_buffer_size / padded as u64).clamp(1, height.max(1) as u64) as u32;
    let mut bytes = Vec::with_capacity(unpadded as usize * height as usize);
    let mut first_row = 0;
    while first_row < height {
        let rows = band_rows.min(height - first_row);
        crate::gpu_error::scoped(
            device,
            || format!("reading back target `{name}` ({width}x{height})"),
            || {
                read_band(
                    device,
                    queue,
                    texture,
                    (width, first_row, rows),
                    (padded, unpadded),
                    &mut bytes,
                )
            },
        )?;
        first_row += rows;
    }
    Ok(TargetImage {
        name: name.to_string(),
        width,
        height,
        format,
        bytes,
    })
}

/// Rows `first_row..first_row + rows` of `texture`, unpadded, appended to `bytes`.
fn read_band(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    (width, first_row, rows): (u32, u32, u32),
    (padded, unpadded): (u32, u32),
    bytes: &mut Vec<u8>,
) -> Result<(), RunError> {
    let buffer = device.make_buffer(&wgpu::BufferDescriptor {
        label: Some("npr readback"),
        size: padded as u64 * rows as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("npr readback"),
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d {
                x: 0,
                y: first_row,
                z: 0,
            },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(rows),
            },
        },
        wgpu::Extent3d {
            width,
            height: rows,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    let mapped = map_read(device, &buffer)?;
    for row in 0..rows as usize {
        let start = row * padded as usize;
        bytes.extend_from_slice(&mapped[start..start + unpadded as usize]);
    }
    drop(mapped);
    buffer.unmap();
    Ok(())
}

/// Block until the GPU has finished everything submitted to `device`.
pub fn wait_idle(device: &wgpu::Device) -> Result<(), RunError> {
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map(|_| ())
        .map_err(|e| RunError::Internal(format!("GPU wait failed: {e}")))
}

/// Wait for the GPU and map `buffer` (MAP_READ) for reading.
fn map_read(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<wgpu::BufferView, RunError> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    wait_idle(device)?;
    rx.recv()
        .map_err(|e| RunError::Internal(format!("readback channel closed: {e}")))?
        .map_err(|e| RunError::Internal(format!("readback map failed: {e}")))?;
    slice
        .get_mapped_range()
        .map_err(|e| RunError::Internal(format!("readback range failed: {e:?}")))
}

/// Copy a whole storage buffer (COPY_SRC) back to the CPU.
pub fn read_buffer(device: &wgpu::Device, queue: &wgpu::Queue, source: &wgpu::Buffer) -> Result<Vec<u8>, RunError> {
    crate::gpu_error::scoped(
        device,
        || format!("reading back a {}-byte buffer", source.size()),
        || read_whole_buffer(device, queue, source),
    )
}

fn read_whole_buffer(device: &wgpu::Device, queue: &wgpu::Queue, source: &wgpu::Buffer) -> Result<Vec<u8>, RunError> {
    let buffer = device.make_buffer(&wgpu::BufferDescriptor {
        label: Some("npr buffer readback"),
        size: source.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("npr buffer readback"),
    });
    encoder.copy_buffer_to_buffer(source, 0, &buffer, 0, source.size());
    queue.submit([encoder.finish()]);
    let bytes = map_read(device, &buffer)?.to_vec();
    buffer.unmap();
    Ok(bytes)
}
