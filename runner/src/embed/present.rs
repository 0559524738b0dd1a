//! Presenting the style's output in the host's texture views: the checks
//! of a [`Target`] (E0602) and one fullscreen draw per view that copies
//! the output target's texels (`textureLoad`, no filtering) as they are,
//! so the host sees what `npr render` writes, or, for a
//! [`Target::LinearView`], decoded to linear light with the sRGB transfer
//! function, so that the host's own encoding gives them back. Pipelines
//! are made once per view format and encoding, bind groups once per
//! output texture (they change only with the size or the style).

use super::{EmbedError, Target};
use crate::gpu_count::{Create, CreateView};
use npr_diag::{codes, Diagnostic};

/// Copies a texel: in side-by-side targets the right eye's fragments are
/// `x ≥ eye width`, so `x mod width` finds the texel in both halves.
pub(crate) const PRESENT_WGSL: &str = concat!(
    crate::fullscreen::fullscreen_vertex_wgsl!(),
    crate::fullscreen::srgb_wgsl!(),
    "
@group(0) @binding(0) var source: texture_2d<f32>;

@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let size = vec2<i32>(textureDimensions(source));
    let texel = vec2<i32>(p.xy) % size;
    return textureLoad(source, texel, 0);
}

// `fs_linear` decodes with the sRGB EOTF (`srgb_to_linear`), the inverse
// of what an sRGB view's store does: a linear-light host encodes these
// back to the output's values.
@fragment
fn fs_linear(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let size = vec2<i32>(textureDimensions(source));
    let c = textureLoad(source, vec2<i32>(p.xy) % size, 0);
    return vec4<f32>(srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b), c.a);
}
"
);

/// One view a checked target draws into.
pub(super) struct PresentView<'a> {
    pub view: &'a wgpu::TextureView,
    pub format: wgpu::TextureFormat,
    /// The eye slots drawn into it, left to right: one, or two side by side.
    pub eyes: &'static [usize],
    /// Whether the host reads it as linear light ([`Target::LinearView`]).
    pub linear: bool,
}

/// A checked target: the per-eye size, and the views (one or two) with
/// the eye each shows. Nothing in it is allocated: a frame checks its target.
pub(super) struct CheckedTarget<'a> {
    pub width: u32,
    pub height: u32,
    pub views: [Option<PresentView<'a>>; 2],
}

/// The one eye slot a single view shows: the frame's eye of a stereo style.
fn single_eye(eye_slots: usize, eye: u32) -> &'static [usize] {
    if eye_slots == 2 && eye >= 1 {
        &[1]
    } else {
        &[0]
    }
}

fn target_error(message: String, help: &str) -> EmbedError {
    EmbedError::Target(Box::new(
        Diagnostic::error(codes::BAD_RENDER_TARGET, message).with_help(help.to_string()),
    ))
}

/// The size and format of one view, or why it cannot be drawn into.
/// `stated`: the format the host says the view has ([`Target::LinearView`]),
/// which makes an sRGB format fine: the host reads the view as linear light.
fn check_view(
    view: &wgpu::TextureView,
    what: &str,
    stated: Option<wgpu::TextureFormat>,
) -> Result<(u32, u32, wgpu::TextureFormat), EmbedError> {
    let texture = view.texture();
    let format = stated.unwrap_or(texture.format());
    if format.remove_srgb_suffix() != texture.format().remove_srgb_suffix() {
        return Err(target_error(
            format!(
                "the {what} view is said to have the format {format:?}, but its texture's format is {:?}",
                texture.format()
            ),
            "state the format the view was made with: its texture's format, or that format's sRGB twin",
        ));
    }
    let size = texture.size();
    if texture.dimension() != wgpu::TextureDimension::D2
        || size.depth_or_array_layers != 1
        || texture.mip_level_count() != 1
    {
        return Err(target_error(
            format!("the {what} view's texture is not a 2D texture of one layer and one mip level"),
            "render into a plain 2D texture (a surface texture, or one made with mip_level_count 1)",
        ));
    }
    if !texture.usage().contains(wgpu::TextureUsages::RENDER_ATTACHMENT) {
        return Err(target_error(
            format!("the {what} view's texture lacks RENDER_ATTACHMENT usage"),
            "create the texture with wgpu::TextureUsages::RENDER_ATTACHMENT",
        ));
    }
    if format.is_srgb() && stated.is_none() {
        return Err(target_error(
            format!(
                "the {what} view's texture has the sRGB format {format:?}, which would re-encode the style's output"
            ),
            "the style's output is display-ready: make the texture (or configure the surface) with the \
             non-sRGB twin, format.remove_srgb_suffix()",
        ));
    }
    let colour_float = matches!(
        format.sample_type(None, None),
        Some(wgpu::TextureSampleType::Float { .. })
    ) && !format.is_depth_stencil_format();
    if !colour_float {
        return Err(target_error(
            format!("the {what} view's format {format:?} is not a colour format with float or normalized channels"),
            "render into e.g. Rgba8Unorm, Bgra8Unorm or Rgba16Float",
        ));
    }
    if size.width == 0
        || size.height == 0
        || size.width > crate::MAX_OUTPUT_SIZE
        || size.height > crate::MAX_OUTPUT_SIZE
    {
        return Err(target_error(
            format!(
                "the {what} view is {}x{}, outside 1..={} on a side",
                size.width,
                size.height,
                crate::MAX_OUTPUT_SIZE
            ),
            "render into a smaller texture (docs/LIMITS.md)",
        ));
    }
    Ok((size.width, size.height, format))
}

/// Check `target` against a style with `eye_slots` eye slots (1 mono, 2
/// stereo); a single view of a stereo style shows `eye`.
pub(super) fn check_target<'a>(
    target: &Target<'a>,
    eye_slots: usize,
    eye: u32,
) -> Result<CheckedTarget<'a>, EmbedError> {
    let stereo_only = |kind: &str| {
        target_error(
            format!("a {kind} target needs a stereo style; this style renders one eye"),
            "give Target::View, or compile a stereo style (one that reads `other_eye(...)` or runs per eye)",
        )
    };
    match *target {
        Target::View(view) => {
            let (width, height, format) = check_view(view, "target", None)?;
            Ok(CheckedTarget {
                width,
                height,
                views: [
                    Some(PresentView {
                        view,
                        format,
                        eyes: single_eye(eye_slots, eye),
                        linear: false,
                    }),
                    None,
                ],
            })
        }
        Target::LinearView { view, format } => {
            let (width, height, format) = check_view(view, "target", Some(format))?;
            Ok(CheckedTarget {
                width,
                height,
                views: [
                    Some(PresentView {
                        view,
                        format,
                        eyes: single_eye(eye_slots, eye),
                        linear: true,
                    }),
                    None,
                ],
            })
        }
        Target::Eyes { left, right } => {
            if eye_slots != 2 {
                return Err(stereo_only("two-eye"));
            }
            let (w, h, lf) = check_view(left, "left eye's", None)?;
            let (w2, h2, rf) = check_view(right, "right eye's", None)?;
            if (w, h) != (w2, h2) {
                return Err(target_error(
                    format!("the left eye's view is {w}x{h} and the right eye's {w2}x{h2}"),
                    "give both eyes views of the same size",
                ));
            }
            Ok(CheckedTarget {
                width: w,
                height: h,
                views: [
                    Some(PresentView {
                        view: left,
                        format: lf,
                        eyes: &[0],
                        linear: false,
                    }),
                    Some(PresentView {
                        view: right,
                        format: rf,
                        eyes: &[1],
                        linear: false,
                    }),
                ],
            })
        }
        Target::SideBySide(view) => {
            if eye_slots != 2 {
                return Err(stereo_only("side-by-side"));
            }
            let (w, h, format) = check_view(view, "side-by-side", None)?;
            if w % 2 != 0 {
                return Err(target_error(
                    format!("the side-by-side view is {w} wide; its two halves must be equal"),
                    "give the view an even width",
                ));
            }
            Ok(CheckedTarget {
                width: w / 2,
                height: h,
                views: [
                    Some(PresentView {
                        view,
                        format,
                        eyes: &[0, 1],
                        linear: false,
                    }),
                    None,
                ],
            })
        }
    }
}

/// The present pipelines (per view format and encoding) and bind groups (per output texture).
pub(super) struct Presenter {
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    /// Per (view format, decoded to linear light): a host uses one or two,
    /// found by a scan, not a hash, every frame.
    pipelines: Vec<((wgpu::TextureFormat, bool), wgpu::RenderPipeline)>,
    /// Per output texture, `[eye slot][frame parity]`, made for the
    /// renderer's resources of `generation`.
    groups: Vec<Vec<wgpu::BindGroup>>,
    generation: u64,
}

impl Presenter {
    pub fn new(device: &wgpu::Device) -> Presenter {
        let module = device.make_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("npr present"),
            source: wgpu::ShaderSource::Wgsl(PRESENT_WGSL.into()),
        });
        let layout = device.make_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("npr present"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    // Unfilterable: textureLoad reads every float format, rgba32float included.
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.make_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("npr present"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        Presenter {
            module,
            layout,
            pipeline_layout,
            pipelines: Vec::new(),
            groups: Vec::new(),
            generation: u64::MAX,
        }
    }

    /// The pipeline for views of `format` (decoded to linear light or not),
    /// made at its first use.
    fn pipeline(&mut self, device: &wgpu::Device, format: wgpu::TextureFormat, linear: bool) -> usize {
        if let Some(k) = self.pipelines.iter().position(|(key, _)| *key == (format, linear)) {
            return k;
        }
        let (module, layout) = (&self.module, &self.pipeline_layout);
        let pipeline = device.make_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("npr present"),
            layout: Some(layout),
            vertex: wgpu::VertexState {
                module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some(if linear { "fs_linear" } else { "fs" }),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        self.pipelines.push(((format, linear), pipeline));
        self.pipelines.len() - 1
    }

    /// Record the draws of `target`: each view gets the output of its eyes.
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        renderer: &crate::Renderer,
        target: &CheckedTarget,
    ) -> Result<(), EmbedError> {
        if renderer.resources_generation() != self.generation {
            // Every eye slot and parity at once, so that no later frame makes one.
            self.groups.clear();
            for slot in 0..renderer.eye_slots() {
                let mut per_parity = Vec::new();
                for parity in 0..renderer.parities() {
                    let texture = renderer
                        .output_texture(slot, parity)
                        .ok_or_else(|| crate::RunError::Internal("present before prepare".into()))?;
                    let view = texture.make_view(&Default::default());
                    per_parity.push(device.make_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("npr present"),
                        layout: &self.layout,
                        entries: &[wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::TextureView(&view),
                        }],
                    }));
                }
                self.groups.push(per_parity);
            }
            self.generation = renderer.resources_generation();
        }
        let parity = renderer.parity_now() % renderer.parities();
        let group = |slot: usize| self.groups.get(slot).and_then(|g| g.get(parity));
        // Checked before any pass is recorded.
        if let Some(slot) = target
            .views
            .iter()
            .flatten()
            .flat_map(|v| v.eyes)
            .find(|&&s| group(s).is_none())
        {
            return Err(crate::RunError::Internal(format!("no output of eye slot {slot}")).into());
        }
        for PresentView {
            view,
            format,
            eyes,
            linear,
        } in target.views.iter().flatten()
        {
            // Made before the pass borrows the encoder.
            let pipeline = self.pipeline(device, *format, *linear);
            let pipeline = &self.pipelines[pipeline].1;
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("npr present"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            for (k, &slot) in eyes.iter().enumerate() {
                let Some(group) = self.groups.get(slot).and_then(|g| g.get(parity)) else {
                    continue;
                };
                let x = (k as u32 * target.width) as f32;
                pass.set_viewport(x, 0.0, target.width as f32, target.height as f32, 0.0, 1.0);
                pass.set_bind_group(0, group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        Ok(())
    }
}
