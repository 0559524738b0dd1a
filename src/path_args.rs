//! `--root` and `--allow-path`, the arguments every command that reads a
//! style has, and their paths policy
//! (`npr_diag::paths::PathPolicy`, docs/PATHS.md) for a style and its scene.

use npr_diag::paths::{PathChoice, PathPolicy};
use npr_diag::Diagnostic;
use std::path::{Path, PathBuf};

/// Which files a style and its scene may read (docs/PATHS.md): every
/// command that reads a style or a scene has these.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct PathArgs {
    /// Every file the style and the scene name (`use`, textures, meshes)
    /// must be inside DIR. Default: the deepest directory holding both the
    /// style and the scene.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Also admit files inside DIR, even by an absolute path or outside the
    /// root. Repeatable.
    #[arg(long = "allow-path", value_name = "DIR")]
    pub allow_path: Vec<PathBuf>,
}

impl PathArgs {
    /// The choice as the libraries take it (`npr_diag::paths::PathChoice`).
    pub fn choice(&self) -> PathChoice {
        PathChoice {
            root: self.root.clone(),
            allowed: self.allow_path.clone(),
        }
    }

    /// The policy for `style` (and `scene`, when there is one):
    /// [`PathChoice::policy`].
    pub fn policy(&self, style: &Path, scene: Option<&Path>) -> Result<PathPolicy, Diagnostic> {
        self.choice().policy(style, scene)
    }
}
