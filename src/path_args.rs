//! `--root` and `--allow-path` made into the paths policy
//! (`npr_diag::paths::PathPolicy`, docs/PATHS.md) for a style and its scene.

use crate::cli::PathArgs;
use npr_diag::paths::PathPolicy;
use npr_diag::Diagnostic;
use std::path::Path;

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
