//! [`EmbedError`]: what a host application did wrong, or what went wrong
//! on the GPU, as values with a diagnostic code (never a panic).

use super::MeshHandle;
use crate::RunError;
use npr_diag::{codes, Diagnostic};

/// Why a call of the embedding API failed. Every variant has a code
/// ([`EmbedError::code`]) from `npr_diag::codes`, explained by `npr explain`.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EmbedError {
    /// A mesh handle that was removed, or that another runtime gave out (E0601).
    #[error("mesh handle #{} (generation {}) does not name a mesh of this runtime: it was removed, or another runtime gave it out", .0.index, .0.generation)]
    UnknownMesh(MeshHandle),
    /// A style parameter that does not exist, or a value of the wrong type,
    /// unit or outside its declared range: the codes `--set` gives (E0101,
    /// E0201, E0202, E0203, E0502).
    #[error("{}", .0.message)]
    Param(Box<Diagnostic>),
    /// A texture view the runtime cannot render into: the wrong format,
    /// size or usage (E0602).
    #[error("{}", .0.message)]
    Target(Box<Diagnostic>),
    /// Vertices [`super::StyleRuntime::update_mesh`] cannot write over the
    /// mesh: another vertex count, a non-finite number, tangents for a mesh
    /// without UVs, or a mesh whose vertices the runtime derives itself (an
    /// animated primitive, a patch) (E0603).
    #[error("{}", .0.message)]
    MeshUpdate(Box<Diagnostic>),
    /// A host input the runtime cannot use: a name the style does not
    /// declare (E0604), a view or convention it cannot be read from
    /// (E0605), a size other than the target's (E0606), or one not given
    /// before a frame (E0607).
    #[error("{}", .0.message)]
    Input(Box<Diagnostic>),
    /// A frame's camera whose projection cannot be drawn with: a field of
    /// view outside (0, π), a near plane not past the eye, a far plane not
    /// past the near one (E0616).
    #[error("{}", .0.message)]
    Camera(Box<Diagnostic>),
    /// A skin that does not fit its mesh (E0615), or a pose that does not
    /// fit its mesh's skin: joint matrices (E0612), morph weights (E0614),
    /// a number that is not finite (E0613).
    #[error("{}", .0.message)]
    Skin(Box<Diagnostic>),
    /// What the runner reports: a device lacking a feature or limit the
    /// style needs (E0510), objects the style cannot draw (E0403, E0405),
    /// out of memory (E0508), a lost device (E0509), a bug (E9001).
    #[error(transparent)]
    Run(#[from] RunError),
}

impl EmbedError {
    /// The diagnostic code of the (first) error.
    pub fn code(&self) -> &'static str {
        match self {
            EmbedError::UnknownMesh(_) => codes::UNKNOWN_MESH,
            EmbedError::Param(d)
            | EmbedError::Target(d)
            | EmbedError::MeshUpdate(d)
            | EmbedError::Input(d)
            | EmbedError::Camera(d)
            | EmbedError::Skin(d) => d.code,
            EmbedError::Run(e) => e.diagnostics().first().map_or(codes::INTERNAL, |d| d.code),
        }
    }

    /// As diagnostics (no spans: a host's call has no source text), to
    /// render with `npr_diag::diagnostic::render` or log.
    pub fn diagnostics(&self) -> Vec<Diagnostic> {
        match self {
            EmbedError::UnknownMesh(_) => {
                vec![Diagnostic::error(codes::UNKNOWN_MESH, self.to_string()).with_help(
                    "register the mesh with `StyleRuntime::add_mesh`, use the handle it returns, and \
                         remove it only after the last frame that draws it",
                )]
            }
            EmbedError::Param(d)
            | EmbedError::Target(d)
            | EmbedError::MeshUpdate(d)
            | EmbedError::Input(d)
            | EmbedError::Camera(d)
            | EmbedError::Skin(d) => {
                vec![(**d).clone()]
            }
            EmbedError::Run(e) => e.diagnostics(),
        }
    }
}
