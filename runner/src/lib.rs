//! npr runner: executes a compiled style headless on wgpu.
//!
//! - [`device`]: a headless device (Vulkan, then GL), or bring your own.
//! - [`scene`]: TOML scenes with primitives, OBJ and glTF meshes, cameras, a light.
//! - [`exec`]: the [`Renderer`], which runs the passes of a manifest (one
//!   executor per pass kind).
//! - [`output`]: PNG/EXR writing (atomic), `--dump-passes` contact sheets.
//!
//! The runner depends on neither the compiler nor the stdlib: what it runs is
//! defined in the `abi` crate ([`StyleProgram`], the manifest, the frame
//! block). Golden comparison, contour ground truth and benchmarks live in the
//! `lab` crate.
//!
//! Embedding in your own wgpu application: get a [`StyleProgram`] from
//! `compiler::compile_file(..)?.program()` or [`StyleProgram::load_dir`]
//! (a directory written by `npr compile -o DIR`), load a [`scene::Scene`], then
//! `Renderer::new(&device, &queue, &program, &scene)` and call
//! [`Renderer::render`] (or [`Renderer::encode`] into your own encoder).

pub mod animation;
pub mod artmap;
pub mod artmap_cache;
pub mod device;
pub mod exec;
pub mod output;
pub mod readback;
pub mod scene;
pub mod schedule;
pub mod texgen;
pub mod texture_file;
pub mod textures;

pub use abi::StyleProgram;
pub use device::{DeviceError, Gpu};
pub use exec::{
    check_scene, check_texture_bindings, scaled_size, scene_warnings, wgpu_format, FrameSpec, Renderer, MAX_OUTPUT_SIZE,
};
pub use readback::TargetImage;

use dsl::Diagnostic;

#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// Problems with the user's input (scene, textures), as diagnostics.
    #[error("{} error(s) in the input", .0.len())]
    User(Vec<Diagnostic>),
    /// A size or resource request past a stated limit.
    #[error("limit exceeded: {0}")]
    Limit(String),
    #[error(transparent)]
    Device(#[from] DeviceError),
    /// A bug in npr.
    #[error("internal error: {0}")]
    Internal(String),
}

impl RunError {
    /// As diagnostics (user errors keep their spans).
    pub fn diagnostics(&self) -> Vec<Diagnostic> {
        match self {
            RunError::User(d) => d.clone(),
            RunError::Limit(m) => vec![Diagnostic::error(dsl::codes::LIMIT_EXCEEDED, m.clone())
                .with_help(format!("the largest image is {0}x{0}", MAX_OUTPUT_SIZE))],
            RunError::Device(e) => vec![Diagnostic::error(dsl::codes::INTERNAL, e.to_string())],
            RunError::Internal(m) => {
                vec![Diagnostic::error(dsl::codes::INTERNAL, m.clone())
                    .with_help("this is a bug in npr; please report it")]
            }
        }
    }

    pub fn is_user_error(&self) -> bool {
        matches!(self, RunError::User(_) | RunError::Limit(_))
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
