//! Declared textures on the GPU: decoded image files (sRGB or linear, with an
//! optional mip chain), generated noise and halftone tone tables, each with
//! its sampler.

use crate::artmap::ArtmapBuild;
use crate::gpu_count::Create;
use crate::image_level::Level;
use crate::inputs::gpu::Converter;
use crate::scene::Scene;
use crate::texgen;
use crate::RunError;
use npr_abi::manifest::{Manifest, TextureManifest, TextureSourceManifest};
use npr_diag::Diagnostic;
use std::collections::{BTreeMap, HashMap};

#[derive(Clone)]
pub struct GpuTexture {
    pub texture: wgpu::Texture,
    pub sampler: wgpu::Sampler,
}

/// Largest texture file npr loads (the wgpu 2D limit on lavapipe and most
/// GPUs), from `npr_diag::limits`, where every limit is listed; checked by
/// `texture_file` from the file's header.
pub use npr_diag::limits::MAX_TEXTURE_SIZE;

/// Image files held in memory by their resolved path
/// ([`npr_abi::StyleProgram::files`], a bundle's); a file not in it is read
/// from disk.
pub type EmbeddedFiles = std::collections::BTreeMap<String, Vec<u8>>;

/// Every declared texture of `m`, and what building its art-maps did.
/// `input` is the level a filter style runs on (its `filter_input()`),
/// `host` the images of its `input(...)` textures by name, `files` the
/// program's embedded image files.
pub fn load_all(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    m: &Manifest,
    input: Option<&Level>,
    host: &crate::inputs::HostInputs,
    files: &EmbeddedFiles,
) -> Result<(Vec<GpuTexture>, Vec<ArtmapBuild>), RunError> {
    let mut out = Vec::new();
    let mut diags = Vec::new();
    let mut builds = Vec::new();
    let mut converter: Option<Converter> = None;
    for (i, t) in m.textures.iter().enumerate() {
        if matches!(t.source, TextureSourceManifest::Input(_)) {
            match host.get(&t.name) {
                Some(image) => {
                    let converter = converter.get_or_insert_with(|| Converter::new(device));
                    out.push(input_texture(device, queue, converter, t, image));
                }
                None => {
                    diags.push((i, missing_input(&t.name, host)));
                    out.push(placeholder(device));
                }
            }
            continue;
        }
        match load_one(device, queue, t, input, files, &mut builds) {
            Ok(g) => out.push(g),
            Err(d) => {
                diags.push((i, d));
                // Keep indices aligned; a 1×1 placeholder is never rendered since we return Err.
                out.push(placeholder(device));
            }
        }
    }
    if !diags.is_empty() {
        return Err(RunError::Textures(diags));
    }
    Ok((out, builds))
}

/// E0420: the style reads input `name`, which the host did not give.
fn missing_input(name: &str, host: &crate::inputs::HostInputs) -> Diagnostic {
    let given: Vec<&str> = host.keys().map(String::as_str).collect();
    Diagnostic::error(
        npr_diag::codes::BAD_INPUT,
        format!("the style reads input `{name}`, which was not given"),
    )
    .with_help(if given.is_empty() {
        format!("give it: `npr render STYLE --input {name}=FILE` or `--inputs FILE.exr`")
    } else {
        format!(
            "given were: {}; give `{name}` too (`--input {name}=FILE`)",
            given.join(", ")
        )
    })
}

/// The host inputs of `m` from `host` by manifest index (a renderer moving
/// on to the next frame's inputs).
pub(crate) fn host_inputs(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    m: &Manifest,
    host: &crate::inputs::HostInputs,
) -> Result<Vec<(usize, GpuTexture)>, RunError> {
    let mut out = Vec::new();
    let mut diags = Vec::new();
    let converter = Converter::new(device);
    for (i, t) in m.textures.iter().enumerate() {
        if matches!(t.source, TextureSourceManifest::Input(_)) {
            match host.get(&t.name) {
                Some(image) => out.push((i, input_texture(device, queue, &converter, t, image))),
                None => diags.push((i, missing_input(&t.name, host))),
            }
        }
    }
    if !diags.is_empty() {
        return Err(RunError::Textures(diags));
    }
    Ok(out)
}

/// Write `host`'s images over the input textures among `textures` in place
/// (a sequence's next frame), so the bind groups holding them stay valid
/// and the history goes on. `false`, writing nothing, when an image is not
/// its texture's size: the textures must then be made anew
/// ([`host_inputs`]).
pub(crate) fn write_host_inputs(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    m: &Manifest,
    host: &crate::inputs::HostInputs,
    textures: &[GpuTexture],
) -> Result<bool, RunError> {
    let mut writes = Vec::new();
    for (i, t) in m.textures.iter().enumerate() {
        if matches!(t.source, TextureSourceManifest::Input(_)) {
            let image = host
                .get(&t.name)
                .ok_or_else(|| RunError::Textures(vec![(i, missing_input(&t.name, host))]))?;
            let size = textures[i].texture.size();
            if (size.width, size.height) != (image.raw.width, image.raw.height) {
                return Ok(false);
            }
            writes.push((i, image));
        }
    }
    if !writes.is_empty() {
        let converter = Converter::new(device);
        for (i, image) in writes {
            crate::inputs::gpu::convert_level(
                device,
                queue,
                &converter,
                &image.raw,
                &image.conversion,
                &textures[i].texture,
            );
        }
    }
    Ok(true)
}

/// Input `t`'s texture: `image` drawn in the language's convention by the
/// one conversion (`inputs::gpu`).
fn input_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    converter: &Converter,
    t: &TextureManifest,
    image: &crate::inputs::HostImage,
) -> GpuTexture {
    let texture = crate::inputs::gpu::input_texture(device, &t.name, image.raw.width, image.raw.height);
    crate::inputs::gpu::convert_level(device, queue, converter, &image.raw, &image.conversion, &texture);
    GpuTexture {
        texture,
        sampler: sampler(device, t),
    }
}

/// The `filter_input()` textures of a filter style's manifest for `level`,
/// by manifest index (a filter renderer moving on to its next level).
pub(crate) fn filter_inputs(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    m: &Manifest,
    level: &Level,
) -> Result<Vec<(usize, GpuTexture)>, RunError> {
    let mut out = Vec::new();
    for (i, t) in m.textures.iter().enumerate() {
        if matches!(t.source, TextureSourceManifest::FilterInput) {
            let texture = load_one(device, queue, t, Some(level), &EmbeddedFiles::new(), &mut Vec::new())
                .map_err(|d| RunError::Textures(vec![(i, d)]))?;
            out.push((i, texture));
        }
    }
    Ok(out)
}

/// The images objects bind to per-object texture params, loaded once per
/// (param, file, colour space) and shared between objects naming the same file.
pub struct ObjectTextures {
    pub images: Vec<GpuTexture>,
    /// What each of `images` was loaded from: (manifest texture index,
    /// resolved path, sRGB), the key a later scene finds it by.
    pub keys: Vec<ObjectImageKey>,
    /// Per object: manifest texture index → index into `images`. A param the
    /// object does not bind is absent: it draws with the declared default.
    pub bound: Vec<BTreeMap<usize, usize>>,
}

/// A per-object image: (manifest texture index, resolved path, sRGB).
pub type ObjectImageKey = (usize, std::path::PathBuf, bool);

/// Loads every object's image bindings (checked against the style by
/// `exec::check_scene`). The sampler options are the param's declaration's.
/// An image in `loaded` (what the renderer's previous scene bound) is
/// taken from there, not read and uploaded again.
pub fn load_object_textures(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    m: &Manifest,
    scene: &Scene,
    loaded: &HashMap<ObjectImageKey, GpuTexture>,
) -> Result<ObjectTextures, RunError> {
    let mut out = ObjectTextures {
        images: Vec::new(),
        keys: Vec::new(),
        bound: Vec::new(),
    };
    let mut cache: HashMap<ObjectImageKey, usize> = HashMap::new();
    let mut diags = Vec::new();
    for o in &scene.objects {
        let mut bound = BTreeMap::new();
        // The glTF material's base colour image, where the style declares
        // the name and the scene binds no image to it (decision 0058).
        let mut files = EmbeddedFiles::new();
        let material_image = o
            .material
            .as_ref()
            .and_then(|m| m.base_color_map.as_ref())
            .filter(|_| !o.textures.contains_key(crate::scene::gltf_material::BASE_COLOR_MAP))
            .map(|image| {
                files.insert(image.key.clone(), image.bytes.to_vec());
                let binding = crate::scene::TextureBinding {
                    path: image.key.clone(),
                    resolved: std::path::PathBuf::from(&image.key),
                    srgb: None,
                    span: o.mesh_span,
                };
                (crate::scene::gltf_material::BASE_COLOR_MAP.to_string(), binding)
            });
        for (name, b) in o.textures.iter().chain(material_image.iter().map(|(n, b)| (n, b))) {
            let Some(index) = m.textures.iter().position(|t| t.per_object && t.name == *name) else {
                continue;
            };
            let declared_srgb = match &m.textures[index].source {
                TextureSourceManifest::Image { srgb, .. } => *srgb,
                TextureSourceManifest::Artmap(spec) => spec.srgb,
                TextureSourceManifest::Noise { .. }
                | TextureSourceManifest::HalftoneTable(_)
                | TextureSourceManifest::FilterInput
                | TextureSourceManifest::Input(_) => false,
            };
            let srgb = b.srgb.unwrap_or(declared_srgb);
            let key = (index, b.resolved.clone(), srgb);
            if let Some(i) = cache.get(&key) {
                bound.insert(index, *i);
                continue;
            }
            if let Some(kept) = loaded.get(&key) {
                cache.insert(key.clone(), out.images.len());
                bound.insert(index, out.images.len());
                out.images.push(kept.clone());
                out.keys.push(key);
                continue;
            }
            let mut decl = m.textures[index].clone();
            decl.source = TextureSourceManifest::Image {
                path: b.path.clone(),
                resolved: b.resolved.display().to_string(),
                srgb,
            };
            match load_one(device, queue, &decl, None, &files, &mut Vec::new()) {
                Ok(g) => {
                    cache.insert(key.clone(), out.images.len());
                    bound.insert(index, out.images.len());
                    out.images.push(g);
                    out.keys.push(key);
                }
                // Point at the binding in the scene, not at the style.
                Err(d) => diags.push(
                    d.with_primary(b.span, format!("object `{}` binds this image", o.name))
                        .with_help("use a PNG or EXR file; image paths in a scene are relative to the scene file"),
                ),
            }
        }
        out.bound.push(bound);
    }
    if !diags.is_empty() {
        return Err(RunError::User(diags));
    }
    Ok(out)
}

/// Write `levels` (linear light) over `texture`'s mips: as half floats, or
/// as 8-bit values (sRGB-encoded when `srgb`).
fn write_levels(queue: &wgpu::Queue, texture: &wgpu::Texture, levels: &[Level], srgb: bool, half_float: bool) {
    for (mip, level) in levels.iter().enumerate() {
        let (px, lw, lh) = (&level.pixels, &level.width, &level.height);
        let (bytes, bpp): (Vec<u8>, u32) = if half_float {
            let halves: Vec<u16> = px
                .iter()
                .flat_map(|p| p.map(|c| half::f16::from_f32(c).to_bits()))
                .collect();
            (bytemuck::cast_slice(&halves).to_vec(), 8)
        } else {
            let enc = |c: f32| if srgb { crate::srgb::linear_to_srgb(c) } else { c };
            (
                px.iter()
                    .flat_map(|p| {
                        [enc(p[0]), enc(p[1]), enc(p[2]), p[3]].map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
                    })
                    .collect(),
                4,
            )
        };
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: mip as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(lw * bpp),
                rows_per_image: Some(*lh),
            },
            wgpu::Extent3d {
                width: *lw,
                height: *lh,
                depth_or_array_layers: 1,
            },
        );
    }
}

/// The sampler texture `t` declares (wrap and filter).
fn sampler(device: &wgpu::Device, t: &TextureManifest) -> wgpu::Sampler {
    let address = if t.wrap_repeat {
        wgpu::AddressMode::Repeat
    } else {
        wgpu::AddressMode::ClampToEdge
    };
    let filter = if t.filter_linear {
        wgpu::FilterMode::Linear
    } else {
        wgpu::FilterMode::Nearest
    };
    device.make_sampler(&wgpu::SamplerDescriptor {
        label: Some(&t.name),
        address_mode_u: address,
        address_mode_v: address,
        address_mode_w: address,
        mag_filter: filter,
        min_filter: filter,
        mipmap_filter: if t.filter_linear {
            wgpu::MipmapFilterMode::Linear
        } else {
            wgpu::MipmapFilterMode::Nearest
        },
        ..Default::default()
    })
}

fn placeholder(device: &wgpu::Device) -> GpuTexture {
    let texture = device.make_texture(&desc(1, 1, 1, wgpu::TextureFormat::Rgba8Unorm));
    GpuTexture {
        texture,
        sampler: device.make_sampler(&Default::default()),
    }
}

fn desc(w: u32, h: u32, mips: u32, format: wgpu::TextureFormat) -> wgpu::TextureDescriptor<'static> {
    wgpu::TextureDescriptor {
        label: Some("npr texture"),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: mips,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    }
}

/// The texels of a `halftone_table(...)`, built for the edge as the shader
/// will read it back from the half-float texture (so that table and shader
/// use the same edge to the bit), in the red channel.
fn halftone_table_texels(spec: &npr_abi::HalftoneTableSpec) -> (Vec<[f32; 4]>, u32, u32) {
    use npr_abi::halftone::table::{HalftoneTable, ROWS, TONES};
    let edge = half::f16::from_f32(spec.edge).to_f64();
    let table = HalftoneTable::build(edge, spec.corrected);
    let texels = table.texels().into_iter().map(|t| [t, 0.0, 0.0, 1.0]).collect();
    (texels, TONES as u32, ROWS as u32)
}

/// An image file decoded to linear RGBA, and the file's bytes: from
/// `files` when it holds the file (a bundle's), else from disk.
fn decode_image(
    t: &TextureManifest,
    path: &str,
    resolved: &str,
    srgb: bool,
    files: &EmbeddedFiles,
) -> Result<(Level, Vec<u8>), Diagnostic> {
    let file = std::path::Path::new(resolved);
    // One read of the file: the art-map cache keys on the same bytes.
    let bytes = match files.get(resolved) {
        Some(bytes) => bytes.clone(),
        None => std::fs::read(file)
            .map_err(|e| crate::texture_file::TextureFileError::Unreadable(e).to_diagnostic(&t.name, path))?,
    };
    let img = crate::texture_file::read_bytes(&bytes, file).map_err(|e| e.to_diagnostic(&t.name, path))?;
    let rgba = img.to_rgba32f();
    let (width, height) = rgba.dimensions();
    let mut pixels: Vec<[f32; 4]> = rgba.pixels().map(|p| p.0).collect();
    if srgb {
        for p in &mut pixels {
            for c in &mut p[..3] {
                *c = crate::srgb::srgb_to_linear(*c);
            }
        }
    }
    Ok((Level { width, height, pixels }, bytes))
}

fn load_one(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    t: &TextureManifest,
    input: Option<&Level>,
    files: &EmbeddedFiles,
    builds: &mut Vec<ArtmapBuild>,
) -> Result<GpuTexture, Diagnostic> {
    // Linear-light levels (one, or a mip chain) plus how they are stored.
    let (levels, srgb, half_float): (Vec<Level>, bool, bool) = match &t.source {
        TextureSourceManifest::Image { path, resolved, srgb } => {
            let (base, _) = decode_image(t, path, resolved, *srgb, files)?;
            let count = if t.mips { u32::MAX } else { 1 };
            (crate::image_level::mip_chain(base, count), *srgb, false)
        }
        TextureSourceManifest::Noise(spec) => {
            let img = texgen::generate(spec);
            let base = Level {
                width: img.size,
                height: img.size,
                pixels: img.pixels,
            };
            let count = if t.mips { u32::MAX } else { 1 };
            (crate::image_level::mip_chain(base, count), false, true)
        }
        TextureSourceManifest::HalftoneTable(spec) => {
            let (pixels, width, height) = halftone_table_texels(spec);
            (vec![Level { width, height, pixels }], false, true)
        }
        TextureSourceManifest::Artmap(spec) => {
            let (base, bytes) = decode_image(t, &spec.path, &spec.resolved, spec.srgb, files)?;
            let (levels, build) = crate::artmap::build(device, queue, &t.name, spec, &bytes, base).map_err(|e| {
                let first = e.diagnostics().into_iter().next().unwrap_or_else(|| {
                    Diagnostic::error(
                        npr_diag::codes::INTERNAL,
                        format!("art-map `{}` failed with no diagnostic", t.name),
                    )
                });
                first.with_note(format!(
                    "while filtering art-map `{}` with `{}`",
                    t.name, spec.filter.path
                ))
            })?;
            builds.push(build);
            // Half floats: a filter's output is linear and may leave [0, 1].
            ((*levels).clone(), false, true)
        }
        TextureSourceManifest::Input(_) => {
            // Converted by `input_texture`, never loaded as a file.
            return Err(Diagnostic::error(
                npr_diag::codes::INTERNAL,
                format!("texture `{}` is a host input, loaded as a file", t.name),
            ));
        }
        TextureSourceManifest::FilterInput => {
            let level = input.ok_or_else(|| {
                Diagnostic::error(
                    npr_diag::codes::INTERNAL,
                    format!("texture `{}` is a filter's input, but no level was given", t.name),
                )
            })?;
            (vec![level.clone()], false, true)
        }
    };
    let format = if half_float {
        wgpu::TextureFormat::Rgba16Float
    } else if srgb {
        wgpu::TextureFormat::Rgba8UnormSrgb
    } else {
        wgpu::TextureFormat::Rgba8Unorm
    };
    let texture = device.make_texture(&desc(levels[0].width, levels[0].height, levels.len() as u32, format));
    write_levels(queue, &texture, &levels, srgb, half_float);
    let sampler = sampler(device, t);
    Ok(GpuTexture { texture, sampler })
}
