//! The paths policy (`npr_diag::paths`, docs/PATHS.md) applied to what a style
//! names, each file before it is read or even probed: a `use`d file
//! (`load`), an art-map's filter style (`load_filters`), and every
//! `image("…")` texture, an art-map's source included (`resolve`). Each
//! refusal (E0406) is at the path where the style writes it; checking
//! before probing means a refused path never says whether the file
//! outside the root exists.

use npr_diag::paths::PathPolicy;
use npr_diag::{Diagnostic, Span};
use std::path::Path;

/// E0406 at `span` when `policy` refuses the file `written` (resolved to `resolved`).
pub fn check(policy: Option<&PathPolicy>, span: Span, written: &str, resolved: &Path) -> Option<Diagnostic> {
    let refusal = policy?.check(written, resolved).err()?;
    Some(refusal.with_primary(span, "this file"))
}
