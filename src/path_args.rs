//! `--root` and `--allow-path`, the arguments every command that reads a
//! style has, and their paths policy
//! (`npr_diag::paths::PathPolicy`, docs/PATHS.md) for a style and its scene.

use npr_diag::paths::PathPolicy;
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
    /// The policy for `style` (and `scene`, when there is one): `--root`,
    /// or the deepest directory holding both; E0502 for a `--root` or
    /// `--allow-path` that is not a directory.
    pub fn policy(&self, style: &Path, scene: Option<&Path>) -> Result<PathPolicy, Diagnostic> {
        let root = match &self.root {
            Some(r) => r.clone(),
            None => {
                let mut files = vec![style];
                files.extend(scene);
                PathPolicy::default_root(&files)
            }
        };
        PathPolicy::new(&root, &self.allow_path)
    }
}
