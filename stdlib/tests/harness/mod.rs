//! The harness of the GPU-against-reference tests: a shared wgpu device, a
//! compute shader that runs operator WGSL once per input, texture inputs,
//! comparisons with absolute and relative tolerances, and deterministic test
//! inputs. Each test binary uses part of it.
#![allow(dead_code)]

pub mod cases;

use npr_stdlib::reference::ImageF64;
use std::sync::OnceLock;
use wgpu::util::DeviceExt;

pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::VULKAN | wgpu::Backends::GL;
        let instance = wgpu::Instance::new(desc);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default())).unwrap_or_else(|e| {
            panic!("no GPU adapter ({e}); install the software Vulkan driver: `sudo apt-get install -y mesa-vulkan-drivers` (or ./setup.sh)")
        });
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor::default())).expect("device");
        Gpu { device, queue }
    })
}

/// A texture input: size, RGBA texels, format (Rgba32Float or Rgba8Unorm).
pub struct TexIn {
    pub image: ImageF64,
    pub format: wgpu::TextureFormat,
}

/// Run `body` (WGSL statements that set `result: vec4<f32>` from `a`, `b`, `c`,
/// `uv`, and textures `t0`, `t1`) once per output, after `prelude` (operator code).
pub fn run(prelude: &str, body: &str, inputs: &[[f32; 4]], out_size: (u32, u32), textures: &[TexIn]) -> Vec<[f32; 4]> {
    let g = gpu();
    let n = (out_size.0 * out_size.1) as usize;
    let mut decl = String::from(
        "@group(0) @binding(0) var<storage, read> inputs: array<vec4<f32>>;\n@group(0) @binding(1) var<storage, read_write> outputs: array<vec4<f32>>;\n@group(0) @binding(2) var samp: sampler;\n@group(0) @binding(3) var samp_repeat: sampler;\n",
    );
    for i in 0..textures.len() {
        decl.push_str(&format!("@group(0) @binding({}) var t{i}: texture_2d<f32>;\n", 4 + i));
    }
    let src = format!(
        "{decl}\n{prelude}\n@compute @workgroup_size(64)\nfn main(@builtin(global_invocation_id) id: vec3<u32>) {{\n    let i = id.x;\n    if (i >= {n}u) {{ return; }}\n    let a = inputs[i * 3u];\n    let b = inputs[i * 3u + 1u];\n    let c = inputs[i * 3u + 2u];\n    let uv = (vec2<f32>(f32(i % {w}u), f32(i / {w}u)) + vec2<f32>(0.5)) / vec2<f32>({w}.0, {h}.0);\n    var result = vec4<f32>(0.0);\n    {body}\n    outputs[i] = result;\n}}\n",
        w = out_size.0,
        h = out_size.1
    );
    let module = g.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let mut input_data: Vec<[f32; 4]> = inputs.to_vec();
    input_data.resize(n * 3, [0.0; 4]);
    let input = g.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&input_data),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (n * 16) as u64;
    let output = g.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let staging = g.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let sampler = g.device.create_sampler(&wgpu::SamplerDescriptor {
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let views: Vec<wgpu::TextureView> = textures
        .iter()
        .map(|t| {
            let (bytes, _) = texel_bytes(t.format, &t.image);
            let tex = g.device.create_texture_with_data(
                &g.queue,
                &wgpu::TextureDescriptor {
                    label: None,
                    size: wgpu::Extent3d {
                        width: t.image.width,
                        height: t.image.height,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: t.format,
                    usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                    view_formats: &[],
                },
                wgpu::util::TextureDataOrder::LayerMajor,
                &bytes,
            );
            tex.create_view(&Default::default())
        })
        .collect();
    let pipeline = g.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: None,
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let layout = pipeline.get_bind_group_layout(0);
    let mut entries = vec![
        wgpu::BindGroupEntry {
            binding: 0,
            resource: input.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 1,
            resource: output.as_entire_binding(),
        },
    ];
    // Auto layouts only contain what the shader uses.
    if body.contains(", samp,") {
        entries.push(wgpu::BindGroupEntry {
            binding: 2,
            resource: wgpu::BindingResource::Sampler(&sampler),
        });
    }
    let repeat = g.device.create_sampler(&wgpu::SamplerDescriptor {
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    if body.contains("samp_repeat") {
        entries.push(wgpu::BindGroupEntry {
            binding: 3,
            resource: wgpu::BindingResource::Sampler(&repeat),
        });
    }
    for (i, v) in views.iter().enumerate() {
        if body.contains(&format!("t{i}")) {
            entries.push(wgpu::BindGroupEntry {
                binding: 4 + i as u32,
                resource: wgpu::BindingResource::TextureView(v),
            });
        }
    }
    let group = g.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layout,
        entries: &entries,
    });
    let mut enc = g.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups((n as u32).div_ceil(64), 1, 1);
    }
    enc.copy_buffer_to_buffer(&output, 0, &staging, 0, size);
    g.queue.submit([enc.finish()]);
    let slice = staging.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    g.device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let data = slice.get_mapped_range().expect("mapped");
    let out: Vec<[f32; 4]> = bytemuck::cast_slice(&data).to_vec();
    drop(data);
    staging.unmap();
    out
}

pub fn op_wgsl(names: &[&str]) -> String {
    let mut snippets: Vec<&str> = Vec::new();
    for n in names {
        for s in npr_stdlib::find(n).expect("operator").snippets {
            if !snippets.contains(s) {
                snippets.push(s);
            }
        }
    }
    let mut src: Vec<&str> = snippets
        .iter()
        .map(|s| npr_stdlib::snippets::find(s).expect("snippet"))
        .collect();
    src.extend(names.iter().map(|n| npr_stdlib::find(n).expect("operator").wgsl));
    src.join("\n")
}

/// Compare GPU and reference, assert finiteness and the bound; returns the max error.
pub fn compare(name: &str, gpu: &[[f32; 4]], reference: &[[f64; 4]], channels: usize, tol: f64) -> f64 {
    let mut max = 0.0f64;
    for (i, (g, r)) in gpu.iter().zip(reference).enumerate() {
        for c in 0..channels {
            assert!(g[c].is_finite(), "{name}: case {i} channel {c} is {}", g[c]);
            let e = (g[c] as f64 - r[c]).abs();
            max = max.max(e);
            assert!(
                e <= tol,
                "{name}: case {i} channel {c}: gpu {} vs reference {} (error {e:e} > {tol:e})",
                g[c],
                r[c]
            );
        }
    }
    println!(
        "{name}: {} cases, max abs error {max:.3e} (tolerance {tol:.0e})",
        gpu.len()
    );
    max
}

/// A small deterministic generator (64-bit LCG) for test inputs.
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

pub fn f32v(v: [f64; 4]) -> [f32; 4] {
    v.map(|x| x as f32)
}

/// Round-trip through f32 so the reference sees exactly what the GPU sees.
pub fn q(v: [f64; 4]) -> [f64; 4] {
    v.map(|x| x as f32 as f64)
}

pub fn vectors(seed: u64, count: usize) -> Vec<[f64; 4]> {
    let mut g = Lcg(seed);
    let mut v: Vec<[f64; 4]> = (0..count)
        .map(|_| {
            q([
                g.range(-1.0, 1.0),
                g.range(-1.0, 1.0),
                g.range(-1.0, 1.0),
                g.range(0.0, 1.0),
            ])
        })
        .collect();
    // Hard cases: zero vectors, tiny and huge magnitudes, exact opposites.
    v.extend([
        [0.0; 4],
        [1e-20, 0.0, 0.0, 0.0],
        [1e18, -1e18, 0.0, 1.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0, 0.0],
    ]);
    v
}

/// Deterministic test patterns, including steps (hard for blurs) and noise.
pub fn pattern(kind: u32, w: u32, h: u32, seed: u64) -> ImageF64 {
    let mut g = Lcg(seed);
    let noise: Vec<f64> = (0..w * h * 4).map(|_| g.next()).collect();
    ImageF64::new(w, h, |x, y| {
        let i = ((y * w + x) * 4) as usize;
        let v = match kind {
            0 => [x as f64 / w as f64, y as f64 / h as f64, 0.5, 1.0],
            1 => {
                let s = if (x / 3 + y / 3) % 2 == 0 { 1.0 } else { 0.0 };
                [s, 1.0 - s, s * 0.5, 1.0]
            }
            _ => [noise[i], noise[i + 1], noise[i + 2], noise[i + 3]],
        };
        q(v)
    })
}

pub fn pixels_ref(out: (u32, u32), f: impl Fn([f64; 2]) -> [f64; 4]) -> Vec<[f64; 4]> {
    let mut v = Vec::new();
    for y in 0..out.1 {
        for x in 0..out.0 {
            // The same uv the shader computes, rounded through f32.
            let uv = [
                ((x as f32 + 0.5) / out.0 as f32) as f64,
                ((y as f32 + 0.5) / out.1 as f32) as f64,
            ];
            v.push(f(uv));
        }
    }
    v
}

/// Compare with a tolerance relative to the reference's magnitude, |g − r| ≤ tol·max(1, |r|).
pub fn compare_rel(name: &str, gpu: &[[f32; 4]], reference: &[[f64; 4]], channels: usize, tol: f64) {
    let mut max = 0.0f64;
    for (i, (g, r)) in gpu.iter().zip(reference).enumerate() {
        for c in 0..channels {
            assert!(g[c].is_finite(), "{name}: case {i} channel {c} is {}", g[c]);
            let e = (g[c] as f64 - r[c]).abs() / r[c].abs().max(1.0);
            max = max.max(e);
            assert!(
                e <= tol,
                "{name}: case {i} channel {c}: gpu {} vs reference {} (relative error {e:e} > {tol:e})",
                g[c],
                r[c]
            );
        }
    }
    println!(
        "{name}: {} cases, max relative error {max:.3e} (tolerance {tol:.0e})",
        gpu.len()
    );
}

pub fn one(name: &str, body: &str, cases: &[[[f64; 4]; 3]], textures: &[TexIn]) -> Vec<[f32; 4]> {
    let inputs: Vec<[f32; 4]> = cases.iter().flat_map(|c| c.map(f32v)).collect();
    run(&op_wgsl(&[name]), body, &inputs, (cases.len() as u32, 1), textures)
}

/// The bytes of `image` as texels of `format` (`Rgba8Unorm`, else
/// `Rgba32Float`), and the bytes a texel takes. 8-bit channels are clamped
/// to [0, 1] and rounded (a saturating cast would give the same bytes).
pub fn texel_bytes(format: wgpu::TextureFormat, image: &ImageF64) -> (Vec<u8>, u32) {
    match format {
        wgpu::TextureFormat::Rgba8Unorm => (
            image
                .pixels
                .iter()
                .flat_map(|p| p.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8))
                .collect(),
            4,
        ),
        _ => (
            image
                .pixels
                .iter()
                .flat_map(|p| p.map(|c| c as f32))
                .flat_map(f32::to_le_bytes)
                .collect(),
            16,
        ),
    }
}
