//! Loading the filter styles that art-maps name
//! (`artmap(image("…"), filter: "filters/hatching.npr")`): each is read and
//! parsed once, with its own `use`s, so that the pipeline can compile it as
//! a style of its own (`pipeline::compile_filters`). A filter that cannot be
//! read, or that the paths policy refuses (E0406), is reported at the path
//! in the art-map. Reading and parsing a filter file is `load.rs`'s, which
//! calls this and hands it that as `load_one`.

use npr_diag::files::FileSource;
use npr_diag::paths::PathPolicy;
use npr_diag::{codes, Diagnostic};
use npr_dsl::ast::{ExprKind, Item};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The texture sources whose `filter:` names a filter style.
pub const FILTERED_SOURCES: [&str; 2] = ["artmap", "ripmap"];

/// Every filter the items name, by the path they resolve to (the key
/// `resolve` records in the IR), each loaded by `load_one` (`None` when it
/// cannot be, its diagnostics in the vector it is given), probed in `files`.
pub fn load<Loaded>(
    files: &dyn FileSource,
    items: &[(Item, PathBuf)],
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
    mut load_one: impl FnMut(&Path, &mut Vec<Diagnostic>) -> Option<Loaded>,
) -> BTreeMap<String, Loaded> {
    let mut filters = BTreeMap::new();
    for (item, dir) in items {
        let Item::Texture(t) = item else { continue };
        if !FILTERED_SOURCES.contains(&t.source.callee.name.as_str()) {
            continue;
        }
        let Some(arg) = t
            .source
            .args
            .iter()
            .find(|a| a.name.as_ref().is_some_and(|n| n.name == "filter"))
        else {
            continue;
        };
        // `filter: "path"` or `filter: filter("path", name: value, ...)`;
        // anything else is reported by `resolve`.
        let (rel, span) = match &arg.value.kind {
            ExprKind::Str(rel) => (rel, arg.value.span),
            ExprKind::Call(c) if c.callee.name == "filter" => match c.args.first().map(|a| (&a.name, &a.value)) {
                Some((None, v)) => match &v.kind {
                    ExprKind::Str(rel) => (rel, v.span),
                    _ => continue,
                },
                _ => continue,
            },
            _ => continue,
        };
        let path = dir.join(rel);
        let key = path.display().to_string();
        if filters.contains_key(&key) {
            continue;
        }
        if let Some(d) = crate::front::paths::check(paths, span, rel, &path) {
            diags.push(d);
            continue;
        }
        if !files.is_file(&path) {
            diags.push(
                Diagnostic::error(codes::BAD_USE, format!("filter style `{rel}` not found"))
                    .with_primary(span, format!("looked for {}", path.display()))
                    .with_help("a filter is a `.npr` file of image passes, its path relative to this file"),
            );
            continue;
        }
        let mut own = Vec::new();
        if let Some(loaded) = load_one(&path, &mut own) {
            filters.insert(key, loaded);
        }
        diags.append(&mut own);
    }
    filters
}
