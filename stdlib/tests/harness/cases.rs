//! The generic GPU runner of the operators' data cases (`npr_stdlib::ops::Case`):
//! each call is built from the operator's signature (a number argument is a
//! slot of a storage buffer, read as the parameter's WGSL type; a uv is the
//! pixel's; a texture is bound with its sampler), and every call runs in a
//! fragment shader, one cell of pixels per call, so operators that take
//! screen derivatives run too. The reference sees exactly the f32 values
//! the GPU sees.

use super::{gpu, Lcg, TexIn};
use npr_stdlib::ops::{Arg, Case, OpDef, TexFormat, Tol, Val, Value};
use npr_stdlib::reference::ImageF64;
use npr_stdlib::{Operator, Ty};

/// The operator's WGSL with its snippets and (transitive) dependencies, as the emitter assembles it.
pub fn with_deps(op: &Operator) -> String {
    let mut ops: Vec<&Operator> = Vec::new();
    let mut todo = vec![op];
    while let Some(o) = todo.pop() {
        if ops.iter().any(|x| x.name == o.name) {
            continue;
        }
        ops.push(o);
        todo.extend(o.depends.iter().map(|d| npr_stdlib::find(d).expect("dependency")));
    }
    let mut snippets: Vec<&str> = Vec::new();
    for o in &ops {
        for s in o.snippets {
            if !snippets.contains(s) {
                snippets.push(s);
            }
        }
    }
    let mut src: Vec<&str> = snippets
        .iter()
        .map(|s| npr_stdlib::snippets::find(s).expect("snippet"))
        .collect();
    src.extend(ops.iter().rev().map(|o| o.wgsl));
    src.join("\n")
}

fn q(v: Value) -> Value {
    v.map(|x| x as f32 as f64)
}

fn seed(name: &str, case: usize, arg: usize) -> u64 {
    let mut h = 0xcbf29ce484222325u64;
    for b in name.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x100000001b3);
    }
    h ^ ((case as u64) << 32 | arg as u64)
}

/// The texels the GPU holds, in f64.
fn stored(image: ImageF64, format: TexFormat) -> ImageF64 {
    let round = |c: f64| match format {
        TexFormat::Rgba8Unorm => (c.clamp(0.0, 1.0) * 255.0).round() / 255.0,
        TexFormat::Rgba32Float => c as f32 as f64,
    };
    ImageF64 {
        pixels: image.pixels.iter().map(|p| p.map(round)).collect(),
        ..image
    }
}

fn lit(x: f64) -> String {
    format!("{:?}", x as f32)
}

fn vec2_lit(v: [f64; 2]) -> String {
    format!("vec2<f32>({}, {})", lit(v[0]), lit(v[1]))
}

/// Run one case of `def` on the GPU against its reference; returns the number of calls compared.
pub fn run_case(def: &OpDef, index: usize, case: &Case) -> usize {
    let op = &def.op;
    let label = format!("{} case {index} ({})", op.name, case.what);
    assert_eq!(case.args.len(), op.params.len(), "{label}: one argument per parameter");
    let (w, h) = case.pixels;
    // Textures, per argument; the values of each factor, per argument.
    let mut images: Vec<Option<ImageF64>> = Vec::new();
    let mut textures: Vec<TexIn> = Vec::new();
    let mut levels: Vec<Vec<ImageF64>> = Vec::new();
    let mut factors: Vec<(usize, Vec<Value>)> = Vec::new();
    for (k, a) in case.args.iter().enumerate() {
        images.push(None);
        match a {
            Arg::Texture(t) => {
                let image = stored((t.image)(), t.format);
                textures.push(TexIn {
                    image: image.clone(),
                    format: match t.format {
                        TexFormat::Rgba8Unorm => wgpu::TextureFormat::Rgba8Unorm,
                        TexFormat::Rgba32Float => wgpu::TextureFormat::Rgba32Float,
                    },
                });
                let count = 32 - image.width.max(image.height).leading_zeros();
                levels.push(match t.levels {
                    Some(f) => (1..count).map(f).collect(),
                    None => Vec::new(),
                });
                images[k] = Some(image);
            }
            Arg::Each(vs) => factors.push((k, vs.iter().map(|v| q(*v)).collect())),
            Arg::Random { lo, hi, n } => {
                let mut g = Lcg(seed(op.name, index, k));
                let vs = (0..*n)
                    .map(|_| q(std::array::from_fn(|c| g.range(lo[c], hi[c]))))
                    .collect();
                factors.push((k, vs));
            }
            _ => {}
        }
    }
    let calls: usize = factors.iter().map(|(_, v)| v.len()).product();
    assert!(calls > 0, "{label}: no calls");
    // Screen derivatives are taken over 2×2 quads: they must not straddle two calls.
    let prelude = with_deps(op);
    if calls > 1
        && ["dpdx", "dpdy", "fwidth", "textureSample(", "textureSampleBias("]
            .iter()
            .any(|f| prelude.contains(f))
    {
        assert!(
            w % 2 == 0 && h % 2 == 0,
            "{label}: an operator that takes derivatives needs an even grid"
        );
    }
    // The value of argument k in call j (factors in mixed radix, the first fastest).
    let value = |j: usize, k: usize| -> Value {
        let mut rest = j;
        for (fk, vs) in &factors {
            let v = vs[rest % vs.len()];
            rest /= vs.len();
            if *fk == k {
                return v;
            }
        }
        match case.args[k] {
            Arg::Const(v) => q(v),
            _ => unreachable!(),
        }
    };
    let value = |j: usize, k: usize| -> Value {
        match case.args[k] {
            Arg::From { arg, f } => q(f(value(j, arg))),
            _ => value(j, k),
        }
    };
    let slots: Vec<usize> = (0..case.args.len())
        .filter(|k| {
            matches!(
                case.args[*k],
                Arg::Const(_) | Arg::Each(_) | Arg::Random { .. } | Arg::From { .. }
            )
        })
        .collect();
    let cols = (256 / w as usize).clamp(1, calls);
    let rows = calls.div_ceil(cols);
    let size = (w * cols as u32, h * rows as u32);
    assert!(
        size.0 <= 8192 && size.1 <= 8192,
        "{label}: {calls} calls of {w}×{h} pixels are too many"
    );

    // The call, from the signature.
    let mut args: Vec<String> = Vec::new();
    let mut t = 0;
    for (k, (p, a)) in op.params.iter().zip(case.args).enumerate() {
        let s = match a {
            Arg::Uv => "uv".to_string(),
            Arg::ScreenUv { origin, dx, dy } => format!(
                "({} + centre.x * {} + centre.y * {})",
                vec2_lit(*origin),
                vec2_lit(*dx),
                vec2_lit(*dy)
            ),
            Arg::Texture(tx) => {
                t += 1;
                match p.ty {
                    Ty::Texture => format!("t{}", t - 1),
                    Ty::SampledTexture if tx.repeat => format!("t{}, samp_repeat", t - 1),
                    Ty::SampledTexture => format!("t{}, samp_clamp", t - 1),
                    _ => panic!("{label}: `{}` is not a texture parameter", p.name),
                }
            }
            _ => {
                let slot = slots.iter().position(|s| *s == k).expect("slot");
                let v = format!("inputs[base + {slot}u]");
                match p.ty {
                    Ty::Float => format!("{v}.x"),
                    Ty::Int | Ty::Enum(_) => format!("i32({v}.x)"),
                    Ty::Bool => format!("({v}.x != 0.0)"),
                    Ty::Vec2 => format!("{v}.xy"),
                    Ty::Vec3 => format!("{v}.xyz"),
                    Ty::Vec4 | Ty::Color => v,
                    Ty::Texture | Ty::SampledTexture => panic!("{label}: `{}` needs a texture", p.name),
                }
            }
        };
        args.push(s);
    }
    let call = format!("npr_{}({})", op.name, args.join(", "));
    let (wrapped, channels) = match op.returns {
        Ty::Float | Ty::Int | Ty::Bool | Ty::Enum(_) => (format!("vec4<f32>(f32({call}), 0.0, 0.0, 0.0)"), 1),
        Ty::Vec2 => (format!("vec4<f32>({call}, 0.0, 0.0)"), 2),
        Ty::Vec3 => (format!("vec4<f32>({call}, 0.0)"), 3),
        _ => (call.clone(), 4),
    };
    let n_slots = slots.len();
    let mut decl = String::new();
    if n_slots > 0 {
        decl.push_str("@group(0) @binding(0) var<storage, read> inputs: array<vec4<f32>>;\n");
    }
    decl.push_str("@group(0) @binding(1) var samp_clamp: sampler;\n@group(0) @binding(2) var samp_repeat: sampler;\n");
    for i in 0..textures.len() {
        decl.push_str(&format!("@group(0) @binding({}) var t{i}: texture_2d<f32>;\n", 3 + i));
    }
    let src = format!(
        "{decl}\n{prelude}\n
@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {{
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}}

@fragment
fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {{
    let px = vec2<u32>(pos.xy);
    let cell = vec2<u32>(px.x % {w}u, px.y % {h}u);
    let j = min((px.y / {h}u) * {cols}u + px.x / {w}u, {last}u);
    let base = j * {n_slots}u;
    let centre = vec2<f32>(cell) + vec2<f32>(0.5);
    let uv = centre / vec2<f32>({w}.0, {h}.0);
    return {wrapped};
}}
",
        last = calls - 1,
    );
    let mut inputs: Vec<[f32; 4]> = Vec::new();
    for j in 0..calls {
        for k in &slots {
            inputs.push(value(j, *k).map(|x| x as f32));
        }
    }
    let out = render(&label, &src, &inputs, size, (&textures, &levels), &call);

    // The reference, call by call and pixel by pixel.
    let (mut compared, mut skipped, mut max) = (0usize, 0usize, 0.0f64);
    for j in 0..calls {
        for y in 0..h {
            for x in 0..w {
                let centre = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                let vals: Vec<Val> = case
                    .args
                    .iter()
                    .enumerate()
                    .map(|(k, a)| match a {
                        Arg::Texture(_) => Val::Tex(images[k].as_ref().expect("texture")),
                        Arg::Uv => Val::Uv {
                            uv: [
                                ((x as f32 + 0.5) / w as f32) as f64,
                                ((y as f32 + 0.5) / h as f32) as f64,
                            ],
                            dx: [1.0 / f64::from(w), 0.0],
                            dy: [0.0, 1.0 / f64::from(h)],
                        },
                        Arg::ScreenUv { origin, dx, dy } => {
                            let f = |c: usize| {
                                (origin[c] as f32 + centre[0] as f32 * dx[c] as f32 + centre[1] as f32 * dy[c] as f32)
                                    as f64
                            };
                            Val::Uv {
                                uv: [f(0), f(1)],
                                dx: [dx[0] as f32 as f64, dx[1] as f32 as f64],
                                dy: [dy[0] as f32 as f64, dy[1] as f32 as f64],
                            }
                        }
                        _ => Val::Num(value(j, k)),
                    })
                    .collect();
                let r = (def.eval)(&vals);
                let (px, py) = ((j % cols) as u32 * w + x, (j / cols) as u32 * h + y);
                let g = out[(py * size.0 + px) as usize];
                if r[..channels].iter().any(|v| v.is_nan()) {
                    skipped += 1;
                    continue;
                }
                compared += 1;
                for c in 0..channels {
                    let (bound, scale) = match case.tol {
                        Tol::Abs(t) => (t, 1.0),
                        Tol::Rel(t) => (t, r[c].abs().max(1.0)),
                    };
                    let e = (g[c] as f64 - r[c]).abs() / scale;
                    assert!(
                        g[c].is_finite() && e <= bound,
                        "{label}: call {j} pixel ({x}, {y}) channel {c}: gpu {} vs reference {} (error {e:e} > {bound:e}); arguments {:?}",
                        g[c],
                        r[c],
                        vals.iter().map(|v| match v { Val::Tex(_) => "texture".to_string(), v => format!("{:?}", v.v4()) }).collect::<Vec<_>>()
                    );
                    max = max.max(e);
                }
            }
        }
    }
    let all = compared + skipped;
    assert!(
        skipped as f64 <= case.max_skipped * all as f64,
        "{label}: {skipped} of {all} references undefined (at most {} allowed)",
        case.max_skipped
    );
    println!(
        "{label}: {compared} compared, {skipped} skipped, max error {max:.3e} ({:?})",
        case.tol
    );
    compared
}

/// Render `src`'s `vs`/`fs` into an rgba32float target of `size` and read it back.
fn render(
    label: &str,
    src: &str,
    inputs: &[[f32; 4]],
    size: (u32, u32),
    (textures, levels): (&[TexIn], &[Vec<ImageF64>]),
    call: &str,
) -> Vec<[f32; 4]> {
    use wgpu::util::DeviceExt;
    let g = gpu();
    let scope = g.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = g.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let format = wgpu::TextureFormat::Rgba32Float;
    let pipeline = g.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
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
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let sampler = |mode| {
        g.device.create_sampler(&wgpu::SamplerDescriptor {
            address_mode_u: mode,
            address_mode_v: mode,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        })
    };
    let (clamp, repeat) = (
        sampler(wgpu::AddressMode::ClampToEdge),
        sampler(wgpu::AddressMode::Repeat),
    );
    let buffer = g.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(if inputs.is_empty() { &[[0.0f32; 4]] } else { inputs }),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let views: Vec<wgpu::TextureView> = textures.iter().zip(levels).map(|(t, l)| upload(g, t, l)).collect();
    // Auto layouts hold only what the shader uses.
    let mut entries = Vec::new();
    if !inputs.is_empty() {
        entries.push(wgpu::BindGroupEntry {
            binding: 0,
            resource: buffer.as_entire_binding(),
        });
    }
    if call.contains("samp_clamp") {
        entries.push(wgpu::BindGroupEntry {
            binding: 1,
            resource: wgpu::BindingResource::Sampler(&clamp),
        });
    }
    if call.contains("samp_repeat") {
        entries.push(wgpu::BindGroupEntry {
            binding: 2,
            resource: wgpu::BindingResource::Sampler(&repeat),
        });
    }
    for (i, v) in views.iter().enumerate() {
        entries.push(wgpu::BindGroupEntry {
            binding: 3 + i as u32,
            resource: wgpu::BindingResource::TextureView(v),
        });
    }
    let group = g.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    let target = g.device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let row = (size.0 * 16).div_ceil(256) * 256;
    let staging = g.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(row * size.1),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let view = target.create_view(&Default::default());
    let mut enc = g.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
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
    enc.copy_texture_to_buffer(
        target.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &staging,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: None,
            },
        },
        wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
    );
    g.queue.submit([enc.finish()]);
    if let Some(e) = pollster::block_on(scope.pop()) {
        panic!("{label}: {e}\n{src}");
    }
    let slice = staging.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    g.device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let data = slice.get_mapped_range().expect("mapped");
    let mut out = Vec::with_capacity((size.0 * size.1) as usize);
    for y in 0..size.1 {
        let start = (y * row) as usize;
        let texels: &[[f32; 4]] = bytemuck::cast_slice(&data[start..start + (size.0 * 16) as usize]);
        out.extend_from_slice(texels);
    }
    drop(data);
    staging.unmap();
    out
}

/// A texture with level 0 from `t` and the levels after it from `levels`.
fn upload(g: &super::Gpu, t: &TexIn, levels: &[ImageF64]) -> wgpu::TextureView {
    let bytes = |image: &ImageF64| super::texel_bytes(t.format, image);
    let texture = g.device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: t.image.width,
            height: t.image.height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1 + levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: t.format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (mip, image) in std::iter::once(&t.image).chain(levels).enumerate() {
        let (data, bpp) = bytes(image);
        let (w, h) = ((t.image.width >> mip).max(1), (t.image.height >> mip).max(1));
        assert_eq!((image.width, image.height), (w, h), "mip level {mip} is {w}×{h}");
        g.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: mip as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &data,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(w * bpp),
                rows_per_image: Some(h),
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
    }
    texture.create_view(&Default::default())
}
