//! A style over Bevy's own frame (issue 47, decision 0054): a camera whose
//! style declares `input(...)` textures gets Bevy's images as those
//! inputs, each with the convention Bevy writes it in:
//!
//! | kind | Bevy's image | convention |
//! |---|---|---|
//! | `color` | the camera's main image (after tonemapping) | linear light (an sRGB view or `Rgba16Float`) |
//! | `depth` | `DepthPrepass`'s `Depth32Float` | infinite reverse-Z with the camera's near plane |
//! | `normal` | `NormalPrepass`'s `Rgb10a2Unorm` | world space (y up, as npr's), stored as n·0.5 + 0.5 |
//! | `motion` | `MotionVectorPrepass`'s `Rg16Float` | a change of UV, +y down (npr's is in pixels) |
//!
//! The runtime converts each into its own input texture (the conversion
//! draw of `npr_runner::inputs::gpu`) before any pass of the style runs,
//! so the main image it reads is copied before the style's output is drawn
//! into that same texture, in a later pass of the same encoder: no
//! ping-pong of Bevy's main textures is needed.
//!
//! What the camera cannot give is reported, and the camera left as Bevy
//! drew it: an input without its prepass, or of a kind Bevy renders no
//! image of (E0608); prepass textures that are multisampled, or a viewport
//! (E0609). Both are checked every frame, so adding the prepass (or
//! `Msaa::Off`) later makes the style draw without a restart.

use bevy::camera::CompositingSpace;
use bevy::core_pipeline::prepass::ViewPrepassTextures;
use npr_abi::manifest::{Manifest, TextureSourceManifest};
use npr_abi::InputKind;
use npr_diag::{codes, Diagnostic};
use npr_runner::embed::StyleRuntime;
use npr_runner::inputs::{ColorEncoding, DepthConvention, MotionConvention, NormalConvention, SourceConvention};

/// The codes of this module: cleared from a camera's log once every input
/// is given, so that a prepass removed again is reported again.
pub(crate) const CODES: [&str; 2] = [codes::BEVY_INPUT_NOT_PRODUCED, codes::BEVY_INPUT_UNREADABLE];

/// What a camera's view offers a style over inputs this frame.
pub(crate) struct BevyFrame<'a> {
    /// The main image (the camera's view target, as it stands).
    pub main: &'a wgpu::TextureView,
    /// How the main image stores colour.
    pub space: Option<CompositingSpace>,
    pub prepass: Option<&'a ViewPrepassTextures>,
    pub msaa_samples: u32,
    /// Whether the camera draws into a part of its target.
    pub viewport: bool,
    /// The camera's near plane (its reverse-Z depth is near / distance).
    pub near: f32,
}

/// The inputs `manifest` declares: (name, kind).
pub(crate) fn declared_inputs(manifest: &Manifest) -> Vec<(&str, InputKind)> {
    manifest
        .textures
        .iter()
        .filter_map(|t| match &t.source {
            TextureSourceManifest::Input(spec) => Some((t.name.as_str(), spec.kind)),
            _ => None,
        })
        .collect()
}

/// The prepass a kind of input comes from, by the component's name.
fn prepass_of(kind: InputKind) -> Option<&'static str> {
    match kind {
        InputKind::Depth => Some("DepthPrepass"),
        InputKind::Normal { .. } => Some("NormalPrepass"),
        InputKind::Motion => Some("MotionVectorPrepass"),
        InputKind::Color { .. } | InputKind::Id | InputKind::Image { .. } => None,
    }
}

/// Bevy's image for an input of `kind`, and its convention; `Err` the
/// diagnostic when the camera does not produce it.
fn bevy_image<'a>(
    name: &str,
    kind: InputKind,
    frame: &BevyFrame<'a>,
) -> Result<(&'a wgpu::TextureView, SourceConvention), Diagnostic> {
    let missing = |component: &str| {
        Diagnostic::error(
            codes::BEVY_INPUT_NOT_PRODUCED,
            format!(
                "the style reads input `{name}` ({}), and the camera has no `{component}`",
                kind.name()
            ),
        )
        .with_help(format!(
            "add `{component}` to the camera (bevy::core_pipeline::prepass); until then the camera shows what \
             Bevy drew"
        ))
    };
    let views = frame.prepass;
    let found = match kind {
        InputKind::Color { .. } => {
            let encoding = match frame.space {
                Some(CompositingSpace::Srgb) => ColorEncoding::Srgb,
                // An sRGB view (read as linear) or a float target.
                _ => ColorEncoding::Linear,
            };
            Some((frame.main, SourceConvention::Color(encoding)))
        }
        InputKind::Depth => views.and_then(|p| p.depth_only_view()).map(|v| {
            (
                &**v,
                SourceConvention::Depth(DepthConvention::ReverseZ { near: frame.near }),
            )
        }),
        // World-space normals, y up as npr's; the conversion decodes the
        // unorm format's n·0.5 + 0.5.
        InputKind::Normal { .. } => views
            .and_then(|p| p.normal_view())
            .map(|v| (&**v, SourceConvention::Normal(NormalConvention::World))),
        InputKind::Motion => views
            .and_then(|p| p.motion_vectors_view())
            .map(|v| (&**v, SourceConvention::Motion(MotionConvention::ScreenFraction))),
        InputKind::Id | InputKind::Image { .. } => {
            return Err(Diagnostic::error(
                codes::BEVY_INPUT_NOT_PRODUCED,
                format!(
                    "the style reads input `{name}` ({}), an image Bevy does not render",
                    kind.name()
                ),
            )
            .with_help(
                "a camera gives a style its colour, depth, normals and motion vectors; \
                 draw with a style that reads only those",
            ))
        }
    };
    found.ok_or_else(|| missing(prepass_of(kind).unwrap_or("prepass")))
}

/// Give `runtime` every input its style declares from Bevy's images of
/// this frame. The diagnostics when the camera cannot give them all: the
/// frame is then not drawn by the style.
pub(crate) fn give_inputs(runtime: &mut StyleRuntime, frame: &BevyFrame) -> Vec<Diagnostic> {
    let inputs: Vec<(String, InputKind)> = declared_inputs(runtime.manifest())
        .into_iter()
        .map(|(n, k)| (n.to_string(), k))
        .collect();
    let mut problems = Vec::new();
    if frame.viewport {
        problems.push(
            Diagnostic::error(
                codes::BEVY_INPUT_UNREADABLE,
                "the camera has a viewport; a style over Bevy's frame draws the whole target".to_string(),
            )
            .with_help("draw this style on a camera without `Camera::viewport` (its own render target)"),
        );
    }
    let reads_prepass = inputs.iter().any(|(_, k)| prepass_of(*k).is_some());
    if reads_prepass && frame.msaa_samples > 1 {
        problems.push(
            Diagnostic::error(
                codes::BEVY_INPUT_UNREADABLE,
                format!(
                    "the camera's prepass textures have {} samples per pixel (MSAA), which a style's input \
                     cannot be read from",
                    frame.msaa_samples
                ),
            )
            .with_help("add `Msaa::Off` to the camera (a style over inputs smooths its own lines)"),
        );
    }
    if !problems.is_empty() {
        return problems;
    }
    let mut given = Vec::with_capacity(inputs.len());
    for (name, kind) in &inputs {
        match bevy_image(name, *kind, frame) {
            Ok(image) => given.push((name, image)),
            Err(d) => problems.push(d),
        }
    }
    if !problems.is_empty() {
        return problems;
    }
    for (name, (view, convention)) in given {
        if let Err(e) = runtime.set_input(name, view, convention) {
            problems.extend(e.diagnostics());
        }
    }
    problems
}
