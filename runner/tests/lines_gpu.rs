//! Strips drawn on the GPU (lavapipe) over a cube whose depth a depth-only
//! pass kept: the nine visible creases are drawn (recall and precision
//! within 1.5 px of their projection) and the three hidden ones are not
//! (Klein et al. 2000, §5: "along the 2D projection of each visible edge").

use glam::{DMat4, DVec2, DVec3};
use runner::lines::cache::{EdgeSelection, LineObject, LinesCache};
use runner::lines::draw::{vertices, DepthBias, LinesPipeline};
use runner::lines::strip::LineStyle;
use runner::scene::primitives::{cube, sphere};
use runner::scene::Mesh;
use wgpu::util::DeviceExt;

const SIZE: u32 = 256;
/// NDC depth units; see `draw.rs` for why lines need one.
const BIAS: f64 = 3e-4;

fn view_proj(eye: DVec3) -> DMat4 {
    DMat4::perspective_rh(40f64.to_radians(), 1.0, 0.1, 100.0) * DMat4::look_at_rh(eye, DVec3::ZERO, DVec3::Y)
}

fn project(vp: DMat4, p: DVec3) -> DVec2 {
    let c = vp * p.extend(1.0);
    let n = c.truncate() / c.w;
    DVec2::new((n.x + 1.0) * 0.5 * f64::from(SIZE), (1.0 - n.y) * 0.5 * f64::from(SIZE))
}

const DEPTH_SHADER: &str = r#"
@group(0) @binding(0) var<uniform> view_proj: mat4x4<f32>;
@vertex
fn vs(@location(0) p: vec3<f32>) -> @builtin(position) vec4<f32> {
    return view_proj * vec4<f32>(p, 1.0);
}
"#;

/// The cube's depth as a `depth: keep` render pass would leave it.
fn depth_prepass(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    depth: &wgpu::TextureView,
    vp: DMat4,
    mesh: &Mesh,
) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: None,
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(DEPTH_SHADER.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout: Some(&device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        })),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 12,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3],
            })],
        },
        primitive: Default::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: None,
        multiview_mask: None,
        cache: None,
    });
    let matrix: Vec<f32> = vp.as_mat4().to_cols_array().to_vec();
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&matrix),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform.as_entire_binding(),
        }],
    });
    let positions = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&mesh.positions),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&mesh.indices),
        usage: wgpu::BufferUsages::INDEX,
    });
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: None,
        color_attachments: &[],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(&pipeline);
    pass.set_bind_group(0, &group, &[]);
    pass.set_vertex_buffer(0, positions.slice(..));
    pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
    pass.draw_indexed(0..mesh.indices.len() as u32, 0, 0..1);
}

fn texture(device: &wgpu::Device, format: wgpu::TextureFormat, usage: wgpu::TextureUsages) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

fn samples(vp: DMat4, edges: &[(DVec3, DVec3)]) -> Vec<DVec2> {
    edges
        .iter()
        .flat_map(|&(a, b)| (0..=200).map(move |k| project(vp, a.lerp(b, f64::from(k) / 200.0))))
        .collect()
}

fn distance(p: DVec2, points: &[DVec2]) -> f64 {
    points.iter().map(|q| (*q - p).length()).fold(f64::INFINITY, f64::min)
}

/// The centres of the pixels the lines of `mesh` ink, seen from `eye`,
/// tested against the mesh's own depth with `bias`.
fn draw(mesh: &Mesh, eye: DVec3, selection: EdgeSelection, bias: f64) -> Vec<DVec2> {
    let gpu = runner::Gpu::headless().expect("a device (lavapipe)");
    let (device, queue) = (&gpu.device, &gpu.queue);
    let vp = view_proj(eye);
    let depth = texture(
        device,
        wgpu::TextureFormat::Depth32Float,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    let color = texture(
        device,
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let (depth_view, color_view) = (
        depth.create_view(&Default::default()),
        color.create_view(&Default::default()),
    );
    let mut cache = LinesCache::default();
    let style = LineStyle {
        width_px: 2.0,
        amplitude_px: 0.0,
        wavelength_px: 24.0,
        phase: 0.0,
        taper: 0.0,
    };
    let objects = [LineObject {
        mesh,
        model: DMat4::IDENTITY,
    }];
    let size = DVec2::splat(f64::from(SIZE));
    let strips = cache.strips(0, &objects, eye, vp, size, &style, selection).clone();
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        // Paper white, then the cube's depth, then the ink over it.
        let _clear = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::WHITE),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
    }
    depth_prepass(device, &mut encoder, &depth_view, vp, mesh);
    let pipeline = LinesPipeline::new(device, wgpu::TextureFormat::Rgba8Unorm);
    let gpu_vertices = vertices(
        &strips,
        [size.x, size.y],
        DepthBias {
            ndc: bias,
            ..Default::default()
        },
    );
    pipeline.encode(
        device,
        &mut encoder,
        &color_view,
        &depth_view,
        &gpu_vertices,
        &strips.indices,
        [0.0, 0.0, 0.0, 1.0],
    );
    queue.submit([encoder.finish()]);
    let image = runner::readback::read_texture(device, queue, &color, SIZE, SIZE, abi::Format::Rgba8unorm, "ink")
        .expect("read back");
    (0..SIZE * SIZE)
        .filter(|i| image.texel(i % SIZE, i / SIZE)[0] < 0.5)
        .map(|i| DVec2::new(f64::from(i % SIZE) + 0.5, f64::from(i / SIZE) + 0.5))
        .collect()
}

#[test]
fn visible_creases_are_drawn_and_hidden_ones_are_not() {
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let vp = view_proj(eye);
    let selection = EdgeSelection {
        silhouettes: false,
        crease_deg: Some(40.0),
    };
    let drawn = draw(&cube(2.0), eye, selection, BIAS);
    // Truth: the cube's edges on its three front faces (+X, +Y, +Z from this
    // eye) and the three at the far corner (−1, −1, −1).
    let c = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let far = c(-1.0, -1.0, -1.0);
    let hidden = [
        (far, c(1.0, -1.0, -1.0)),
        (far, c(-1.0, 1.0, -1.0)),
        (far, c(-1.0, -1.0, 1.0)),
    ];
    let mut visible = Vec::new();
    for (i, axis) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
        let (u, v) = ([DVec3::Y, DVec3::Z, DVec3::X][i], [DVec3::Z, DVec3::X, DVec3::Y][i]);
        for (a, b) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)]
            .windows(2)
            .map(|w| (axis + u * w[0].0 + v * w[0].1, axis + u * w[1].0 + v * w[1].1))
        {
            visible.push((a, b));
        }
    }
    let visible = samples(vp, &visible);
    let found = visible
        .iter()
        .filter(|t| drawn.iter().any(|p| (*p - **t).length() <= 1.5))
        .count();
    let near = drawn.iter().filter(|p| distance(**p, &visible) <= 1.0 + 1.5).count();
    let (recall, precision) = (found as f64 / visible.len() as f64, near as f64 / drawn.len() as f64);
    // Hidden edges, away from where they meet the visible ones at the
    // silhouette (6 px): no ink within 1 px.
    let hidden: Vec<DVec2> = samples(vp, &hidden)
        .into_iter()
        .filter(|h| distance(*h, &visible) > 6.0)
        .collect();
    let leaked = hidden
        .iter()
        .filter(|h| drawn.iter().any(|p| (*p - **h).length() <= 1.0))
        .count();
    eprintln!(
        "cube creases on the GPU: recall {recall:.4}, precision {precision:.4}, hidden samples {} with ink {leaked}",
        hidden.len()
    );
    assert!(
        hidden.len() > 300,
        "the hidden edges are mostly away from the visible ones"
    );
    assert_eq!(leaked, 0, "hidden creases drawn");
    assert!(
        recall >= 0.99 && precision >= 0.99,
        "recall {recall}, precision {precision}"
    );
}

#[test]
fn a_sphere_silhouette_needs_the_bias_to_keep_its_inner_half() {
    let eye = DVec3::new(0.0, 0.0, 4.0);
    let vp = view_proj(eye);
    let selection = EdgeSelection {
        silhouettes: true,
        crease_deg: None,
    };
    // Truth: the circle p·ê = 1/d of radius √(1 − 1/d²) (see lines_pixels.rs).
    let d = eye.length();
    let truth: Vec<DVec2> = (0..=1024)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / 1024.0;
            project(
                vp,
                DVec3::new(a.cos(), a.sin(), 0.0) * (1.0 - 1.0 / (d * d)).sqrt() + DVec3::Z / d,
            )
        })
        .collect();
    let centre = project(vp, DVec3::Z / d);
    let radius = (truth[0] - centre).length();
    // Pixels on the inner half of the 2 px line: inside the circle.
    let inner = |drawn: &[DVec2]| drawn.iter().filter(|p| (**p - centre).length() < radius - 0.25).count();
    let with_bias = draw(&sphere(1.0, 64, 32), eye, selection, BIAS);
    let without = draw(&sphere(1.0, 64, 32), eye, selection, 0.0);
    let found = truth
        .iter()
        .filter(|t| with_bias.iter().any(|p| (*p - **t).length() <= 1.5))
        .count();
    let recall = found as f64 / truth.len() as f64;
    let near = with_bias.iter().filter(|p| distance(**p, &truth) <= 2.5).count();
    let precision = near as f64 / with_bias.len() as f64;
    eprintln!(
        "sphere silhouette on the GPU: recall {recall:.4}, precision {precision:.4}; inner-half pixels {} with bias {BIAS}, {} without",
        inner(&with_bias),
        inner(&without)
    );
    assert!(
        recall >= 0.99 && precision >= 0.99,
        "recall {recall}, precision {precision}"
    );
    assert!(
        inner(&without) < inner(&with_bias),
        "without a bias the surface inside the rim hides the line"
    );
}
