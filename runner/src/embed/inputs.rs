//! A host's own images as the style's inputs (issue 47):
//! [`super::StyleRuntime::set_input`] takes a texture view of the host's
//! G-buffer with the convention it was written in, and every frame the
//! runtime converts it into the style's input texture inside the host's
//! encoder, with the draw files use (`crate::inputs::gpu`), before the
//! style's passes.
//!
//! Checked when given: the name (E0604), the view's texture and the
//! convention against the input's kind (E0605). Checked every frame: every
//! input given (E0607), all of the target's size (E0606). A steady frame
//! makes nothing: the conversion's bind group is made once per host view
//! (a host that gives the same views keeps it), its uniform written only
//! when the conversion changes (normals turned into view space follow the
//! camera), the view of the input texture once per renderer texture.

use super::EmbedError;
use crate::gpu_count::CreateView;
use crate::inputs::convert::Conversion;
use crate::inputs::gpu::{Converter, UNIFORM_SIZE};
use crate::inputs::{HostImage, HostInputs, SourceConvention};
use crate::scene::CameraPose;
use npr_abi::manifest::{Manifest, TextureSourceManifest};
use npr_abi::InputKind;
use npr_diag::{codes, Diagnostic};

/// What the host gave for one input.
struct Given {
    view: wgpu::TextureView,
    source: SourceConvention,
    size: (u32, u32),
    /// A normalized-integer format: normals in it are stored as n·0.5 + 0.5.
    unorm: bool,
}

/// One input of the style, and what converting it keeps.
struct Slot {
    name: String,
    kind: InputKind,
    given: Option<Given>,
    uniform: Option<wgpu::Buffer>,
    written: Option<[u8; UNIFORM_SIZE as usize]>,
    /// The bind group reading the host's view it was made for.
    group: Option<(wgpu::TextureView, wgpu::BindGroup)>,
    /// The renderer's input texture and a view of it.
    target: Option<(wgpu::Texture, wgpu::TextureView)>,
}

/// The style's inputs as the host gives them.
pub(super) struct HostViews {
    slots: Vec<Slot>,
    converter: Option<Converter>,
    /// The size the renderer's input textures were made at.
    made_at: Option<(u32, u32)>,
}

fn error(code: &'static str, message: String, help: &str) -> EmbedError {
    EmbedError::Input(Box::new(Diagnostic::error(code, message).with_help(help.to_string())))
}

/// Whether `format` holds normalized integers (not floats, not depth).
fn is_unorm(format: wgpu::TextureFormat) -> bool {
    use wgpu::TextureFormat as F;
    !format.is_depth_stencil_format()
        && !matches!(
            format,
            F::R16Float
                | F::Rg16Float
                | F::Rgba16Float
                | F::R32Float
                | F::Rg32Float
                | F::Rgba32Float
                | F::Rg11b10Ufloat
                | F::Rgb9e5Ufloat
        )
}

impl HostViews {
    pub fn new(manifest: &Manifest) -> HostViews {
        let slots = manifest
            .textures
            .iter()
            .filter_map(|t| match &t.source {
                TextureSourceManifest::Input(spec) => Some(Slot {
                    name: t.name.clone(),
                    kind: spec.kind,
                    given: None,
                    uniform: None,
                    written: None,
                    group: None,
                    target: None,
                }),
                _ => None,
            })
            .collect();
        HostViews {
            slots,
            converter: None,
            made_at: None,
        }
    }

    /// Whether the style reads any input.
    pub fn any(&self) -> bool {
        !self.slots.is_empty()
    }

    /// Input `name` from `view`, written in `source`'s convention.
    pub fn set(&mut self, name: &str, view: &wgpu::TextureView, source: SourceConvention) -> Result<(), EmbedError> {
        let Some(slot) = self.slots.iter_mut().find(|s| s.name == name) else {
            let names: Vec<&str> = self.slots.iter().map(|s| s.name.as_str()).collect();
            let help = match npr_diag::diagnostic::did_you_mean(name, names.iter().copied()) {
                Some(s) => format!("did you mean `{s}`?"),
                None if names.is_empty() => "the style declares no `input(...)` texture".to_string(),
                None => format!("the style's inputs are: {}", names.join(", ")),
            };
            return Err(error(
                codes::UNKNOWN_HOST_INPUT,
                format!("the style has no input `{name}`"),
                &help,
            ));
        };
        let what = format!("input `{name}` ({})", slot.kind.name());
        let texture = view.texture();
        let format = texture.format();
        let bad_view = |message: String, help: &str| error(codes::BAD_HOST_INPUT, format!("{what}: {message}"), help);
        let size = texture.size();
        if texture.dimension() != wgpu::TextureDimension::D2
            || size.depth_or_array_layers != 1
            || texture.mip_level_count() != 1
            || texture.sample_count() != 1
        {
            return Err(bad_view(
                "the view's texture is not a 2D texture of one layer, one mip level and one sample".into(),
                "give a plain 2D texture (resolve a multisampled one first)",
            ));
        }
        if !texture.usage().contains(wgpu::TextureUsages::TEXTURE_BINDING) {
            return Err(bad_view(
                "the view's texture lacks TEXTURE_BINDING usage".into(),
                "create the texture with wgpu::TextureUsages::TEXTURE_BINDING",
            ));
        }
        let readable = match format.sample_type(None, None) {
            Some(wgpu::TextureSampleType::Float { .. }) => true,
            Some(wgpu::TextureSampleType::Depth) => !format.has_stencil_aspect(),
            _ => false,
        };
        if !readable {
            return Err(bad_view(
                format!("the view's format {format:?} is not read as floats"),
                "give a float, normalized or depth format (Rgba16Float, Rgba8Unorm, R32Float, Depth32Float); \
                 an integer id image must be copied into R32Float",
            ));
        }
        if let Err(m) = crate::inputs::convert::fits(slot.kind, source) {
            return Err(bad_view(m.message, m.help));
        }
        if format.is_srgb() && source == SourceConvention::Color(crate::inputs::ColorEncoding::Srgb) {
            return Err(bad_view(
                format!("the view's format {format:?} is sRGB, which the GPU decodes when it is read: its texels are linear"),
                "state SourceConvention::Color(ColorEncoding::Linear) for an sRGB texture",
            ));
        }
        slot.given = Some(Given {
            view: view.clone(),
            source,
            size: (size.width, size.height),
            unorm: is_unorm(format),
        });
        Ok(())
    }

    /// Every input given, all of the target's size `size`.
    pub fn check(&self, size: (u32, u32)) -> Result<(), EmbedError> {
        for slot in &self.slots {
            let Some(given) = &slot.given else {
                return Err(error(
                    codes::MISSING_HOST_INPUT,
                    format!(
                        "the style reads input `{}` ({}), which the host has not given",
                        slot.name,
                        slot.kind.name()
                    ),
                    &format!(
                        "give it before the frame: runtime.set_input(\"{}\", &view, convention)",
                        slot.name
                    ),
                ));
            };
            if given.size != size {
                return Err(error(
                    codes::HOST_INPUT_SIZE,
                    format!(
                        "input `{}` is {}x{}, but the target is {}x{}",
                        slot.name, given.size.0, given.size.1, size.0, size.1
                    ),
                    "a style over inputs renders at their size: give inputs and target of one size",
                ));
            }
        }
        Ok(())
    }

    /// Whether the renderer's input textures are of `size`.
    pub fn made_at(&self, size: (u32, u32)) -> bool {
        self.made_at == Some(size)
    }

    /// Blank images of `size` for every input: what the renderer makes
    /// its input textures with (at its build, or when the host's size
    /// changes), to be drawn over every frame.
    pub fn blank(&self, size: (u32, u32)) -> HostInputs {
        if self.slots.is_empty() {
            return HostInputs::new();
        }
        let blank = crate::image_level::Level {
            width: size.0,
            height: size.1,
            pixels: vec![[0.0; 4]; (size.0 * size.1) as usize],
        };
        self.slots
            .iter()
            .map(|s| {
                (
                    s.name.clone(),
                    HostImage {
                        raw: blank.clone(),
                        conversion: Conversion::AS_IS,
                    },
                )
            })
            .collect()
    }

    /// The renderer's input textures are now of `size`.
    pub fn made(&mut self, size: (u32, u32)) {
        self.made_at = Some(size);
    }

    /// Record every input's conversion into `encoder` (after
    /// [`HostViews::check`]); `camera` turns normals between spaces.
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        renderer: &crate::Renderer,
        camera: &CameraPose,
    ) -> Result<(), EmbedError> {
        let converter = self.converter.get_or_insert_with(|| Converter::new(device));
        for slot in &mut self.slots {
            let Some(given) = &slot.given else { continue };
            let conversion = Conversion::resolve(slot.kind, given.source, Some(camera), given.unorm).map_err(|m| {
                error(
                    codes::BAD_HOST_INPUT,
                    format!("input `{}`: {}", slot.name, m.message),
                    m.help,
                )
            })?;
            let bytes = conversion.uniform_bytes();
            let uniform = slot.uniform.get_or_insert_with(|| converter.uniform(device));
            if slot.written != Some(bytes) {
                queue.write_buffer(uniform, 0, &bytes);
                slot.written = Some(bytes);
            }
            if slot.group.as_ref().is_none_or(|(v, _)| *v != given.view) {
                slot.group = Some((given.view.clone(), converter.bind(device, &given.view, uniform)));
            }
            let texture = renderer.input_texture(&slot.name).ok_or_else(|| {
                crate::RunError::Internal(format!("the renderer has no input texture `{}`", slot.name))
            })?;
            if slot.target.as_ref().is_none_or(|(t, _)| t != texture) {
                slot.target = Some((texture.clone(), texture.make_view(&Default::default())));
            }
            if let (Some((_, group)), Some((_, target))) = (&slot.group, &slot.target) {
                converter.encode(encoder, group, target);
            }
        }
        Ok(())
    }
}
