//! npr runner: executes a compiled style headless on wgpu.
//!
//! - [`device`]: a headless device (Vulkan, then GL), or bring your own.
//! - [`scene`]: TOML scenes with primitives, OBJ and glTF meshes, cameras, a light.
//! - [`exec`]: the [`Renderer`], which runs the passes of a manifest (one
//!   executor per pass kind).
//! - [`inputs`]: host inputs (`input(...)` textures), read from files and
//!   converted to the language's conventions.
//! - [`output`]: PNG/EXR writing (atomic), `--dump-passes` contact sheets.
//! - [`embed`]: [`embed::StyleRuntime`], the runtime a host application drives.
//! - [`gpu_count`]: every GPU object the runner creates, counted.
//! - [`pass_timer`]: each pass's GPU time in a frame, from timestamp queries.
//! - `fullscreen`: the vertex stage and sRGB functions the runner's own
//!   fullscreen draws share (host depth, input conversion, presenting).
//!
//! The runner depends on neither the compiler, the stdlib nor the parser
//! (`dsl`, pest); its errors are `diag` diagnostics, and what it runs is
//! defined in the `abi` crate ([`StyleProgram`], the manifest, the frame
//! block). Golden comparison, contour ground truth and benchmarks live in the
//! `lab` crate.
//!
//! Embedding in your own wgpu application: [`embed::StyleRuntime`], which
//! the host drives frame by frame with its own meshes, camera, command
//! encoder and texture views (see the module's docs and
//! `examples/embed.rs`).

pub mod animation;
pub mod artmap;
pub mod artmap_cache;
pub mod checkpoint;
pub mod device;
pub mod device_needs;
pub mod embed;
pub mod exec;
pub mod exr_layers;
mod fullscreen;
pub mod gpu_count;
pub mod gpu_error;
pub mod half_rounding;
pub mod image_level;
pub mod inputs;
pub mod lines;
pub mod output;
pub mod own_shaders;
pub mod pass_timer;
pub mod readback;
pub mod scene;
pub mod schedule;
pub mod srgb;
pub mod texgen;
pub mod texture_file;
pub mod textures;

pub use device::{DeviceError, Gpu};
pub use exec::{
    check_scene, check_texture_bindings, scaled_size, scene_warnings, wgpu_format, FrameSpec, Renderer, MAX_OUTPUT_SIZE,
};
pub use gpu_error::DeviceWatch;
pub use npr_abi::StyleProgram;
pub use readback::TargetImage;

use npr_diag::Diagnostic;

#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// Problems with the user's input (scene, textures), as diagnostics.
    #[error("{} error(s) in the input", .0.len())]
    User(Vec<Diagnostic>),
    /// Texture files of the style that cannot be used, each with its
    /// manifest texture index, so that a caller holding the style's spans
    /// points at the `image("…")` naming the file ([`RunError::at_texture_spans`]).
    #[error("{} texture file(s) cannot be used", .0.len())]
    Textures(Vec<(usize, Diagnostic)>),
    /// A size or resource request past a stated limit.
    #[error("limit exceeded: {0}")]
    Limit(String),
    #[error(transparent)]
    Device(#[from] DeviceError),
    /// The GPU could not allocate what the frame needs (E0508).
    #[error("{0}")]
    OutOfMemory(String),
    /// The device was lost while npr used it (E0509).
    #[error("the GPU device was lost: {0}")]
    DeviceLost(String),
    /// A bug in npr.
    #[error("internal error: {0}")]
    Internal(String),
}

impl RunError {
    /// As diagnostics (user errors keep their spans).
    pub fn diagnostics(&self) -> Vec<Diagnostic> {
        match self {
            RunError::User(d) => d.clone(),
            RunError::Textures(d) => d.iter().map(|(_, d)| d.clone()).collect(),
            RunError::Limit(m) => vec![Diagnostic::error(npr_diag::codes::LIMIT_EXCEEDED, m.clone())
                .with_help(format!(
                    "the largest image is {0}x{0} (docs/LIMITS.md), and a GPU adapter may allow less",
                    MAX_OUTPUT_SIZE
                ))],
            RunError::Device(e) => e.diagnostics(),
            RunError::OutOfMemory(m) => vec![Diagnostic::error(npr_diag::codes::GPU_OUT_OF_MEMORY, m.clone()).with_help(
                "render at a smaller --size, give wide targets a narrower format (rgba16float instead of \
                 rgba32float) or a smaller `scale`, or use a GPU with more memory",
            )],
            RunError::DeviceLost(m) => vec![Diagnostic::error(
                npr_diag::codes::DEVICE_LOST,
                format!("the GPU device was lost: {m}"),
            )
            .with_help("the driver reset or the GPU went away; run the command again (`npr studio` makes a new device by itself)")],
            RunError::Internal(m) => {
                vec![Diagnostic::error(npr_diag::codes::INTERNAL, m.clone())
                    .with_help("this is a bug in npr; please report it")]
            }
        }
    }

    /// Texture errors pointed at `spans[index]` (the style's `image("…")`
    /// per manifest texture, `npr_compiler::Compiled::texture_spans`); other
    /// errors unchanged.
    pub fn at_texture_spans(self, spans: &[npr_diag::Span]) -> RunError {
        match self {
            RunError::Textures(d) => RunError::User(
                d.into_iter()
                    .map(|(i, d)| match spans.get(i) {
                        Some(span) => d.with_primary(*span, "this file"),
                        None => d,
                    })
                    .collect(),
            ),
            other => other,
        }
    }

    /// Whether the error exits 1 (the input, its size, or the machine),
    /// not 2 (a bug in npr).
    pub fn is_user_error(&self) -> bool {
        matches!(
            self,
            RunError::User(_)
                | RunError::Textures(_)
                | RunError::Limit(_)
                | RunError::OutOfMemory(_)
                | RunError::DeviceLost(_)
                | RunError::Device(_)
        )
    }
}

/// Render one frame and read back the output target.
pub fn render_frame(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &scene::Scene,
    spec: &FrameSpec,
) -> Result<TargetImage, RunError> {
    let mut r = Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    r.render(scene, spec)?;
    r.read_output()
}
