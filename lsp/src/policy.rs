//! The paths policy the language server applies to an open document: the
//! one `npr check` applies with no `--root` (docs/PATHS.md), so that the
//! editor reports E0406 exactly where the command line would.

use npr_diag::paths::PathPolicy;
use std::path::Path;

/// The policy for the document at `path`: its directory is the root.
pub fn for_document(path: &Path) -> Result<PathPolicy, npr_diag::Diagnostic> {
    PathPolicy::new(&PathPolicy::default_root(&[path]), &[])
}
