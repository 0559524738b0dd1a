//! The paths policy (`dsl::paths`, docs/PATHS.md) applied to what a style
//! names: a `use`d file before it is read (`load`), and every
//! `image("…")` texture (an art-map's source included) after resolve, each refusal (E0406) at the path
//! where the style writes it.

use crate::ir::{Ir, TextureSource};
use dsl::paths::PathPolicy;
use dsl::{Diagnostic, SourceMap, Span};
use std::path::Path;

/// E0406 at `span` when `policy` refuses the `use` of `written` (resolved to `resolved`).
pub fn check_use(policy: Option<&PathPolicy>, span: Span, written: &str, resolved: &Path) -> Option<Diagnostic> {
    let refusal = policy?.check(written, resolved).err()?;
    Some(refusal.with_primary(span, "this file"))
}

/// E0406 for each image texture of `ir` whose file `policy` refuses, at
/// the path in its `image("…")`.
pub fn check_textures(ir: &Ir, sources: &SourceMap, policy: Option<&PathPolicy>) -> Vec<Diagnostic> {
    let Some(policy) = policy else { return Vec::new() };
    let spans = crate::texture_spans::texture_spans(ir, sources);
    ir.textures
        .iter()
        .zip(spans)
        .filter_map(|(t, span)| {
            let (TextureSource::Image { path, resolved, .. } | TextureSource::Artmap { path, resolved, .. }) =
                &t.source
            else {
                return None;
            };
            let refusal = policy.check(path, Path::new(resolved)).err()?;
            Some(refusal.with_primary(span, "this file"))
        })
        .collect()
}
