//! Checks of a manifest read from disk, before the runner indexes anything:
//! every index in range, every size and offset inside its block, every
//! pairing the runner relies on (a target and its physical texture agree on
//! format and scale, a pass never reads what it writes). The compiler's own
//! manifests pass by construction; these checks are for files that were
//! edited, truncated, or written by another version.

use crate::formats::Format;
use crate::manifest::*;
use crate::noise::NoiseSpec;
use std::collections::BTreeSet;

mod compute;
mod lines;

/// Most colour attachments a pass may write (wgpu's default limit).
pub const MAX_PASS_OUTPUTS: usize = 8;
/// Largest pass or target scale, relative to the output size (the compiler's range).
pub const MAX_SCALE: f64 = 4.0;
/// Most per-object value slots of one compute pass (the compiler's limit).
pub const MAX_VALUE_SLOTS: usize = 64;
/// Largest uniform block (wgpu's default `max_uniform_buffer_binding_size`).
pub const MAX_UNIFORM_SIZE: u64 = 65536;
/// Binding numbers must be below this (wgpu's default `max_bindings_per_bind_group`).
pub const MAX_BINDING: u32 = 1000;
/// Largest `depth: test(..., bias: N px)` (the compiler's range).
pub const MAX_DEPTH_BIAS_PX: f64 = 64.0;

/// A manifest that is well-formed JSON but not something the runner can run:
/// `field` names the bad value as a path (`passes[2].outputs[0]`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Invalid {
    pub field: String,
    pub message: String,
}

impl std::fmt::Display for Invalid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "`{}`: {}", self.field, self.message)
    }
}

fn bad(field: impl Into<String>, message: impl Into<String>) -> Result<(), Invalid> {
    Err(Invalid {
        field: field.into(),
        message: message.into(),
    })
}

fn check_index(field: impl Into<String>, index: usize, len: usize, what: &str) -> Result<(), Invalid> {
    if index < len {
        Ok(())
    } else {
        bad(field, format!("{what} #{index} does not exist (there are {len})"))
    }
}

fn check_scale(field: impl Into<String>, scale: f64) -> Result<(), Invalid> {
    if scale.is_finite() && scale > 0.0 && scale <= MAX_SCALE {
        Ok(())
    } else {
        bad(field, format!("scale {scale} is outside (0, {MAX_SCALE}]"))
    }
}

impl Manifest {
    /// Every check of this module; the first failure comes back.
    pub fn validate(&self) -> Result<(), Invalid> {
        if self.version != MANIFEST_VERSION {
            return bad(
                "version",
                format!(
                    "manifest version {} is not supported (expected {MANIFEST_VERSION}); recompile the style",
                    self.version
                ),
            );
        }
        self.validate_textures()?;
        self.validate_targets()?;
        self.validate_params()?;
        for (i, p) in self.passes.iter().enumerate() {
            self.validate_pass(i, p)?;
        }
        for (i, need) in self.device_needs.iter().enumerate() {
            // A need names its pass for the device error (E0510).
            if !self.passes.iter().any(|p| p.name == need.pass()) {
                return bad(
                    format!("device_needs[{i}].pass"),
                    format!("no pass is named `{}`", need.pass()),
                );
            }
        }
        check_index("output", self.output, self.targets.len(), "target")
    }

    fn validate_targets(&self) -> Result<(), Invalid> {
        for (i, p) in self.physical.iter().enumerate() {
            check_scale(format!("physical[{i}].scale"), p.scale)?;
        }
        for (i, t) in self.targets.iter().enumerate() {
            let field = format!("targets[{i}]");
            check_scale(format!("{field}.scale"), t.scale)?;
            check_index(
                format!("{field}.physical"),
                t.physical,
                self.physical.len(),
                "physical texture",
            )?;
            let p = &self.physical[t.physical];
            if p.format != t.format {
                return bad(
                    format!("{field}.format"),
                    format!(
                        "target `{}` is {} but its physical texture #{} is {}",
                        t.name,
                        t.format.name(),
                        t.physical,
                        p.format.name()
                    ),
                );
            }
            if p.scale != t.scale {
                return bad(
                    format!("{field}.scale"),
                    format!(
                        "target `{}` has scale {} but its physical texture #{} has {}",
                        t.name, t.scale, t.physical, p.scale
                    ),
                );
            }
        }
        Ok(())
    }

    fn validate_textures(&self) -> Result<(), Invalid> {
        for (i, t) in self.textures.iter().enumerate() {
            let field = format!("textures[{i}].source");
            match &t.source {
                TextureSourceManifest::Image { resolved, .. } => {
                    if resolved.is_empty() {
                        return bad(format!("{field}.resolved"), "empty image path");
                    }
                }
                TextureSourceManifest::Noise(n) => {
                    let ranges = [
                        ("size", n.size, NoiseSpec::MAX_SIZE),
                        ("octaves", n.octaves, NoiseSpec::MAX_OCTAVES),
                        ("channels", n.channels, 4),
                        ("frequency", n.frequency, NoiseSpec::MAX_FREQUENCY),
                    ];
                    for (name, value, max) in ranges {
                        if !(1..=max).contains(&value) {
                            return bad(format!("{field}.{name}"), format!("{value} is outside 1..={max}"));
                        }
                    }
                }
                TextureSourceManifest::HalftoneTable(spec) => {
                    if !crate::HalftoneTableSpec::edge_ok(spec.edge as f64) {
                        let (lo, hi) = crate::HalftoneTableSpec::EDGE_RANGE;
                        return bad(format!("{field}.edge"), format!("{} is outside {lo}..={hi}", spec.edge));
                    }
                }
                TextureSourceManifest::Artmap(spec) => {
                    if spec.resolved.is_empty() {
                        return bad(format!("{field}.resolved"), "empty image path");
                    }
                    if let Some(n) = spec.levels {
                        if !(1..=crate::ArtmapSpec::MAX_LEVELS).contains(&n) {
                            return bad(
                                format!("{field}.levels"),
                                format!("{n} is outside 1..={}", crate::ArtmapSpec::MAX_LEVELS),
                            );
                        }
                    }
                    if t.mips == spec.rip {
                        return bad(
                            format!("textures[{i}].mips"),
                            "an art-map is a mip chain; a rip-map is one atlas level",
                        );
                    }
                    spec.filter.program().validate().map_err(|e| Invalid {
                        field: format!("{field}.filter.{}", e.field),
                        message: e.message,
                    })?;
                    spec.filter.manifest.validate_filter().map_err(|message| Invalid {
                        field: format!("{field}.filter"),
                        message,
                    })?;
                }
                TextureSourceManifest::FilterInput => {}
                TextureSourceManifest::Input(_) => {
                    // The host gives one image per input, for the whole
                    // frame: not per object, no mip chain to build.
                    if t.per_object || t.mips {
                        return bad(
                            format!("textures[{i}]"),
                            format!(
                                "input `{}` is one image from the host: neither per object nor mipmapped",
                                t.name
                            ),
                        );
                    }
                }
            }
        }
        Ok(())
    }

    fn validate_params(&self) -> Result<(), Invalid> {
        let has_render = self
            .passes
            .iter()
            .any(|p| matches!(p.kind, PassKindManifest::Render { .. }));
        let count = |b: ParamBinding| self.params.iter().filter(|p| p.binding == b).count() as u64;
        let style_size: u64 = self
            .params
            .iter()
            .filter(|p| p.binding == ParamBinding::Uniform)
            .map(|p| 16 * crate::gradient::slots_of(&p.ty) as u64)
            .sum();
        if self.style_uniform_size != style_size {
            return bad(
                "style_uniform_size",
                format!(
                    "{} bytes, but the style block holds one 16-byte slot per uniform param, a gradient's 21 ({style_size} bytes)",
                    self.style_uniform_size
                ),
            );
        }
        let object_size = if has_render {
            OBJECT_PARAMS_OFFSET + 16 * count(ParamBinding::PerObject)
        } else {
            0
        };
        if self.object_uniform_size != object_size {
            return bad(
                "object_uniform_size",
                format!(
                    "{} bytes, but the object block is {OBJECT_PARAMS_OFFSET} bytes of matrices plus one 16-byte \
                     slot per per-object param ({object_size} bytes)",
                    self.object_uniform_size
                ),
            );
        }
        if self.style_uniform_size > MAX_UNIFORM_SIZE || self.object_uniform_size > MAX_UNIFORM_SIZE {
            return bad(
                "style_uniform_size",
                format!("a uniform block is over {MAX_UNIFORM_SIZE} bytes"),
            );
        }
        for (i, p) in self.params.iter().enumerate() {
            let field = format!("params[{i}]");
            if p.components == 0 || p.components > 4 {
                return bad(
                    format!("{field}.components"),
                    format!("{} is outside 1..=4", p.components),
                );
            }
            let (start, size) = match p.binding {
                ParamBinding::Uniform => (0, self.style_uniform_size),
                ParamBinding::PerObject => (OBJECT_PARAMS_OFFSET, self.object_uniform_size),
                ParamBinding::Folded | ParamBinding::Removed => continue,
            };
            let Some(offset) = p.offset else {
                return bad(
                    format!("{field}.offset"),
                    format!("param `{}` is bound but has no offset", p.name),
                );
            };
            // A gradient takes several slots (`crate::gradient`), every other param one.
            let slots = crate::gradient::slots_of(&p.ty);
            let bytes = 16 * slots as u64;
            if offset < start || offset % 16 != 0 || offset.saturating_add(bytes) > size {
                return bad(
                    format!("{field}.offset"),
                    format!(
                        "param `{}`: offset {offset} is not the start of {slots} 16-byte slot(s) in {start}..{size} of its block",
                        p.name
                    ),
                );
            }
            if slots > 1 && (p.binding != ParamBinding::Uniform || p.default.len() != slots * 4) {
                return bad(
                    format!("{field}.default"),
                    format!(
                        "param `{}` is a {}: a style-block value of {} components",
                        p.name,
                        p.ty,
                        slots * 4
                    ),
                );
            }
            let mut last = f64::NEG_INFINITY;
            for (k, (t, _)) in p.keyframes.iter().enumerate() {
                if !t.is_finite() || *t < last {
                    return bad(
                        format!("{field}.keyframes[{k}]"),
                        format!("keyframe time {t} is not finite and in increasing order"),
                    );
                }
                last = *t;
            }
        }
        Ok(())
    }

    /// A tiled image pass stores its outputs from a compute shader: each
    /// must have a storage format, and none may blend.
    fn validate_tiled(&self, field: &str, p: &PassManifest) -> Result<(), Invalid> {
        if !matches!(p.kind, PassKindManifest::TiledImage { .. }) {
            return Ok(());
        }
        if p.blend.iter().any(|b| *b != Blend::Replace) {
            return bad(
                format!("{field}.blend"),
                format!("tiled image pass `{}` blends", p.name),
            );
        }
        for (k, t) in p.outputs.iter().enumerate() {
            let format = self.targets.get(*t).map(|t| t.format);
            if format.is_some_and(|f| !f.storage_capable()) {
                return bad(
                    format!("{field}.outputs[{k}]"),
                    format!(
                        "tiled image pass `{}` writes a target whose format is not a storage format",
                        p.name
                    ),
                );
            }
        }
        Ok(())
    }

    /// One blend mode per output (or none: all replace), and only on
    /// formats the runner can blend.
    fn validate_blend(&self, field: &str, p: &PassManifest) -> Result<(), Invalid> {
        if !p.blend.is_empty() && p.blend.len() != p.outputs.len() {
            return bad(
                format!("{field}.blend"),
                format!(
                    "pass `{}` has {} blend modes for {} outputs (one per output, or none)",
                    p.name,
                    p.blend.len(),
                    p.outputs.len()
                ),
            );
        }
        for (k, (b, t)) in p.blend.iter().zip(&p.outputs).enumerate() {
            let Some(target) = self.targets.get(*t) else {
                continue; // reported as a bad output index
            };
            if *b != Blend::Replace && !target.format.is_blendable() {
                return bad(
                    format!("{field}.blend[{k}]"),
                    format!(
                        "`{}` blending into `{}`, which is {}: that format cannot be blended",
                        b.name(),
                        target.name,
                        target.format.name()
                    ),
                );
            }
        }
        Ok(())
    }

    /// A depth test reads the kept depth of an earlier render pass of the
    /// same size and view; the runner binds that pass's depth texture. A
    /// `lines` pass sees the scene through the camera, so it tests a camera
    /// view's depth.
    fn validate_depth(&self, i: usize, field: &str, p: &PassManifest) -> Result<(), Invalid> {
        let (pass, bias_px, light_view) = match &p.kind {
            PassKindManifest::Render {
                depth: DepthMode::Test { pass, bias_px },
                light_view,
                ..
            } => (pass, bias_px, *light_view),
            PassKindManifest::Lines {
                depth: DepthMode::Test { pass, bias_px },
                ..
            } => (pass, bias_px, false),
            PassKindManifest::Render {
                depth: DepthMode::TestInput { input, bias_px },
                light_view,
                ..
            } => return self.validate_input_depth(field, p, (*input, *bias_px), *light_view),
            PassKindManifest::Lines {
                depth: DepthMode::TestInput { input, bias_px },
                ..
            } => return self.validate_input_depth(field, p, (*input, *bias_px), false),
            PassKindManifest::Lines {
                depth: DepthMode::Keep, ..
            } => {
                return bad(
                    format!("{field}.kind.depth"),
                    format!("lines pass `{}` cannot keep a depth: it has none of its own", p.name),
                )
            }
            _ => return Ok(()),
        };
        let f = format!("{field}.kind.depth");
        if *pass >= i {
            return bad(
                format!("{f}.pass"),
                format!(
                    "pass `{}` tests the depth of pass #{pass}, which does not run before it",
                    p.name
                ),
            );
        }
        let tested = &self.passes[*pass];
        let PassKindManifest::Render {
            depth: DepthMode::Keep,
            light_view: tested_light,
            ..
        } = &tested.kind
        else {
            return bad(
                format!("{f}.pass"),
                format!(
                    "pass `{}` tests the depth of `{}`, which keeps none",
                    p.name, tested.name
                ),
            );
        };
        if tested.scale != p.scale || *tested_light != light_view {
            return bad(
                format!("{f}.pass"),
                format!(
                    "pass `{}` tests the depth of `{}`, which has another scale or view",
                    p.name, tested.name
                ),
            );
        }
        if !(0.0..=MAX_DEPTH_BIAS_PX).contains(bias_px) {
            return bad(
                format!("{f}.bias_px"),
                format!("{bias_px} is outside 0..={MAX_DEPTH_BIAS_PX}"),
            );
        }
        Ok(())
    }

    /// A depth test against the host's depth reads an `input(depth)`
    /// texture, which has the output's size and the camera's view: the
    /// pass renders at scale 1 through the camera.
    fn validate_input_depth(
        &self,
        field: &str,
        p: &PassManifest,
        (input, bias_px): (usize, f64),
        light_view: bool,
    ) -> Result<(), Invalid> {
        let f = format!("{field}.kind.depth");
        let is_depth_input = self.textures.get(input).is_some_and(|t| {
            matches!(
                t.source,
                TextureSourceManifest::Input(crate::input::InputSpec {
                    kind: crate::input::InputKind::Depth
                })
            )
        });
        if !is_depth_input {
            return bad(
                format!("{f}.input"),
                format!(
                    "pass `{}` tests against texture #{input}, which is not an `input(depth)`",
                    p.name
                ),
            );
        }
        if p.scale != 1.0 || light_view {
            return bad(
                format!("{f}.input"),
                format!(
                    "pass `{}` tests against the host's depth from another scale or view than the camera's",
                    p.name
                ),
            );
        }
        if !(0.0..=MAX_DEPTH_BIAS_PX).contains(&bias_px) {
            return bad(
                format!("{f}.bias_px"),
                format!("{bias_px} is outside 0..={MAX_DEPTH_BIAS_PX}"),
            );
        }
        Ok(())
    }

    fn validate_pass(&self, i: usize, p: &PassManifest) -> Result<(), Invalid> {
        let field = format!("passes[{i}]");
        let file_name_ok =
            !p.shader.is_empty() && p.shader != "." && p.shader != ".." && !p.shader.contains(['/', '\\', ':', '\0']);
        if !file_name_ok {
            return bad(
                format!("{field}.shader"),
                format!("`{}` is not a file name beside the manifest", p.shader),
            );
        }
        {
            for (name, entry) in p.kind.entries() {
                let identifier = entry
                    .chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                    && entry.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
                if !identifier {
                    return bad(
                        format!("{field}.kind.{name}"),
                        format!("`{entry}` is not a WGSL entry-point name"),
                    );
                }
            }
        }
        check_scale(format!("{field}.scale"), p.scale)?;
        // A pass kept only for its depth (a later pass tests against it) may
        // write no colour target.
        let depth_only = matches!(
            p.kind,
            PassKindManifest::Render {
                depth: DepthMode::Keep,
                ..
            }
        );
        if let PassKindManifest::Compute { .. } = &p.kind {
            self.validate_compute(&field, p)?;
        } else if (p.outputs.is_empty() && !depth_only) || p.outputs.len() > MAX_PASS_OUTPUTS {
            return bad(
                format!("{field}.outputs"),
                format!(
                    "pass `{}` writes {} targets; 1..={MAX_PASS_OUTPUTS} are allowed",
                    p.name,
                    p.outputs.len()
                ),
            );
        }
        self.validate_blend(&field, p)?;
        self.validate_tiled(&field, p)?;
        self.validate_depth(i, &field, p)?;
        self.validate_lines(&field, p)?;
        if !p.clear.iter().all(|c| c.is_finite()) {
            return bad(format!("{field}.clear"), "clear colour is not finite");
        }
        let mut written = BTreeSet::new();
        for (k, &t) in p.outputs.iter().enumerate() {
            let f = format!("{field}.outputs[{k}]");
            check_index(&f, t, self.targets.len(), "target")?;
            let target = &self.targets[t];
            if !written.insert(target.physical) {
                return bad(
                    f,
                    format!("pass `{}` writes physical texture #{} twice", p.name, target.physical),
                );
            }
            if target.scale != p.scale {
                return bad(
                    f,
                    format!(
                        "target `{}` has scale {} but pass `{}` renders at {}",
                        target.name, target.scale, p.name, p.scale
                    ),
                );
            }
        }
        let mut numbers = BTreeSet::new();
        for (k, b) in p.bindings.iter().enumerate() {
            let f = format!("{field}.bindings[{k}]");
            if !numbers.insert(b.binding) {
                return bad(format!("{f}.binding"), format!("binding {} appears twice", b.binding));
            }
            if b.binding >= MAX_BINDING {
                return bad(
                    format!("{f}.binding"),
                    format!("binding {} is not below {MAX_BINDING}", b.binding),
                );
            }
            match &b.resource {
                Resource::Target {
                    target,
                    filterable,
                    copy,
                } => {
                    check_index(format!("{f}.resource.target"), *target, self.targets.len(), "target")?;
                    let t = &self.targets[*target];
                    if *filterable && !t.format.is_filterable() {
                        return bad(
                            format!("{f}.resource.filterable"),
                            format!("target `{}` is {}, which is not filterable", t.name, t.format.name()),
                        );
                    }
                    // A previous-frame read binds the history texture's other
                    // copy, so it needs one; the other eye's copy is another
                    // slot's texture.
                    if *copy == TargetCopy::Previous && !self.physical[t.physical].history {
                        return bad(
                            format!("{f}.resource.copy"),
                            format!(
                                "pass `{}` reads the previous frame of `{}`, whose physical texture #{} is not `history`",
                                p.name, t.name, t.physical
                            ),
                        );
                    }
                    if *copy == TargetCopy::This && written.contains(&t.physical) {
                        return bad(
                            format!("{f}.resource.target"),
                            format!(
                                "pass `{}` reads target `{}`, whose texture it also writes",
                                p.name, t.name
                            ),
                        );
                    }
                }
                Resource::Texture { texture } | Resource::TextureSampler { texture } => {
                    check_index(
                        format!("{f}.resource.texture"),
                        *texture,
                        self.textures.len(),
                        "texture",
                    )?;
                }
                Resource::ObjectValues { pass } => {
                    let f = format!("{f}.resource.pass");
                    check_index(&f, *pass, i, "earlier pass")?;
                    if !matches!(self.passes[*pass].kind, PassKindManifest::Compute { .. }) {
                        return bad(f, format!("pass `{}` is not a compute pass", self.passes[*pass].name));
                    }
                    if p.kind.is_image() || matches!(p.kind, PassKindManifest::Lines { .. }) {
                        return bad(
                            f,
                            format!("pass `{}` has no object to read per-object values for", p.name),
                        );
                    }
                }
                Resource::FrameUniforms | Resource::StyleUniforms | Resource::LinearClampSampler => {}
            }
        }
        let is_render = matches!(p.kind, PassKindManifest::Render { .. });
        if !p.object_bindings.is_empty() && !is_render {
            return bad(
                format!("{field}.object_bindings"),
                format!("image pass `{}` has per-object bindings", p.name),
            );
        }
        let mut numbers = BTreeSet::from([0]);
        for (k, b) in p.object_bindings.iter().enumerate() {
            let f = format!("{field}.object_bindings[{k}]");
            if !numbers.insert(b.binding) {
                return bad(
                    format!("{f}.binding"),
                    format!("binding {} appears twice (0 is the object block)", b.binding),
                );
            }
            if b.binding >= MAX_BINDING {
                return bad(
                    format!("{f}.binding"),
                    format!("binding {} is not below {MAX_BINDING}", b.binding),
                );
            }
            match &b.resource {
                Resource::Texture { texture } | Resource::TextureSampler { texture } => {
                    check_index(
                        format!("{f}.resource.texture"),
                        *texture,
                        self.textures.len(),
                        "texture",
                    )?;
                }
                _ => {
                    return bad(
                        format!("{f}.resource"),
                        "group 1 holds only per-object textures and samplers",
                    )
                }
            }
        }
        Ok(())
    }
}
