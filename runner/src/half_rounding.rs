//! Measures how the device rounds an f32 stored into a 16-bit float target
//! (`npr_abi::formats::HalfRounding`). Vulkan leaves it to the implementation:
//! to nearest even or toward zero (lavapipe truncates). A pass fused by the
//! compiler's `auto` schedule repeats the rounding of the target it skipped,
//! so it must round as this device's stores do, or it would differ from the
//! naive schedule by one binary16 step.
//!
//! The measurement renders probe values, chosen where the two modes
//! disagree (between binary16 values, ties to an odd neighbour, subnormals,
//! past 65504), into a one-row `rgba16float` target and reads them back: the
//! stored texels must equal one mode's rounding of every value exactly. A
//! device whose stores match neither cannot run a schedule that repeats
//! them: a user error (E0404) that says to compile with `--schedule naive`.

use crate::gpu_count::{Create, CreateView};
use crate::RunError;
use npr_abi::formats::{Format, HalfRounding};

/// Probe values, each an exact f32 (four per texel).
const PROBES: [f32; 20] = [
    0.35,
    0.3,
    0.6,
    -0.35,
    1.0 + 3.0 / 2048.0, // a tie whose even neighbour is above
    1.0 + 1.0 / 2048.0, // a tie whose even neighbour is below
    1.35,
    1000.3,
    -0.001_234,
    12_345.67,
    3.5e-6, // subnormal in binary16
    -3.5e-6,
    1.0e-7,
    65_519.0, // rounds to 65504 either way
    65_530.0, // infinity to nearest, 65504 toward zero
    -1.0e6,
    0.0,
    -2.0,
    0.1,
    0.7,
];

pub(crate) const SHADER: &str = concat!(
    crate::fullscreen::fullscreen_vertex_wgsl!(),
    "
@group(0) @binding(0) var<storage, read> probes: array<vec4<f32>>;

@fragment
fn fs_main(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    return probes[u32(at.x)];
}
"
);

/// The device's rounding of stores into 16-bit float targets.
pub fn measure(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<HalfRounding, RunError> {
    let stored = render_probes(device, queue)?;
    classify(&stored).ok_or_else(|| {
        let pairs: Vec<String> = PROBES
            .iter()
            .zip(&stored)
            .map(|(x, s)| format!("{x:e} → {s:e}"))
            .collect();
        RunError::User(vec![npr_diag::Diagnostic::error(
            npr_diag::codes::LIMIT_EXCEEDED,
            format!(
                "this GPU rounds values stored into 16-bit float targets neither to nearest nor toward zero ({}), \
                 so a pass fused into its reader cannot repeat the store",
                pairs.join(", ")
            ),
        )
        .with_help("compile with `--schedule naive`, which stores every target as declared")])
    })
}

/// Which mode rounds every probe exactly as the device stored it.
fn classify(stored: &[f32]) -> Option<HalfRounding> {
    [HalfRounding::TowardZero, HalfRounding::NearestEven]
        .into_iter()
        .find(|mode| {
            PROBES
                .iter()
                .zip(stored)
                .all(|(x, s)| mode.round(*x).to_bits() == s.to_bits())
        })
}

/// Renders [`PROBES`] into a `rgba16float` row and reads it back as f32.
fn render_probes(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<f32>, RunError> {
    let width = (PROBES.len() / 4) as u32;
    crate::gpu_error::scoped(
        device,
        || "measuring the device's 16-bit float rounding".to_string(),
        || {
            let module = device.make_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("npr half rounding probe"),
                source: wgpu::ShaderSource::Wgsl(SHADER.into()),
            });
            let buffer = device.make_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("npr half rounding probes"),
                contents: bytemuck::cast_slice(&PROBES),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let pipeline = device.make_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("npr half rounding probe"),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::TextureFormat::Rgba16Float.into())],
                }),
                multiview_mask: None,
                cache: None,
            });
            let group = device.make_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("npr half rounding probes"),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: buffer.as_entire_binding(),
                }],
            });
            let texture = device.make_texture(&wgpu::TextureDescriptor {
                label: Some("npr half rounding probe"),
                size: wgpu::Extent3d {
                    width,
                    height: 1,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba16Float,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            });
            let view = texture.make_view(&Default::default());
            let mut encoder = device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("npr half rounding probe"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    ..Default::default()
                });
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &group, &[]);
                pass.draw(0..3, 0..1);
            }
            queue.submit([encoder.finish()]);
            Ok(texture)
        },
    )
    .and_then(|texture| {
        let image = crate::readback::read_texture(
            device,
            queue,
            &texture,
            width,
            1,
            Format::Rgba16float,
            "half rounding probe",
        )?;
        Ok(image.to_rgba_f32().into_iter().flatten().collect())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_probes_tell_the_two_modes_apart() {
        let near: Vec<f32> = PROBES.iter().map(|x| HalfRounding::NearestEven.round(*x)).collect();
        let zero: Vec<f32> = PROBES.iter().map(|x| HalfRounding::TowardZero.round(*x)).collect();
        assert_eq!(classify(&near), Some(HalfRounding::NearestEven));
        assert_eq!(classify(&zero), Some(HalfRounding::TowardZero));
        let differ = near
            .iter()
            .zip(&zero)
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert!(differ >= 12, "{differ} of {} probes tell the modes apart", PROBES.len());
        // A device that flushes binary16 subnormals matches neither.
        let mut flushed = zero.clone();
        flushed[10] = 0.0;
        assert_eq!(classify(&flushed), None);
    }
}
