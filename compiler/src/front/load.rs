//! Loading: parse the root `.npr` file and every file it `use`s.
//!
//! Items of a used file come before the items of the file that uses it, so a
//! style can build on another's parameters and passes. `use` cycles and
//! unreadable files are reported at the `use` that caused them. Every file
//! is read through the options' [`FileSource`] (the disk, or memory in the
//! web build: `npr_diag::files`).

use npr_diag::files::{Disk, FileSource};
use npr_diag::limits::MAX_SOURCE_BYTES;
use npr_diag::paths::PathPolicy;
use npr_diag::{codes, Diagnostic, FileId, SourceMap, Span};
use npr_dsl::ast::{Ast, Item, UseTarget};
use std::path::{Path, PathBuf};

/// The parsed style: the root file's header, every item in dependency order,
/// and the directory each item's relative paths resolve against.
#[derive(Clone)]
pub struct Loaded {
    pub root: Ast,
    pub root_file: FileId,
    pub items: Vec<(Item, PathBuf)>,
    /// Names of declarations that did not parse, in every file read.
    pub broken: Vec<String>,
    /// The filter styles its art-maps name, by resolved path
    /// (`load_filters`); empty in a filter itself, which may have none.
    pub filters: std::collections::BTreeMap<String, Loaded>,
    /// Loaded as an art-map's filter (`load_filter_file`): it must read one
    /// `filter_input()` and run image passes only (`filter_checks`).
    pub is_filter: bool,
}

/// Read and parse `path` and its `use`s. `None` when the file cannot be read
/// (the diagnostic is in `diags`).
pub fn load_file(
    path: &Path,
    sources: &mut SourceMap,
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
) -> Option<Loaded> {
    load_file_from(&Disk, path, sources, paths, diags)
}

/// [`load_file`] with every file read from `files`.
pub fn load_file_from(
    files: &dyn FileSource,
    path: &Path,
    sources: &mut SourceMap,
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
) -> Option<Loaded> {
    load_file_as(files, path, sources, paths, diags, WithFilters::Yes)
}

/// Whether the art-maps' filter styles are loaded too: not for a filter,
/// which may name none (so a filter naming itself cannot recurse).
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum WithFilters {
    Yes,
    No,
}

/// [`load_file`] of a filter style: its art-maps' filters are not loaded.
pub fn load_filter_file(
    files: &dyn FileSource,
    path: &Path,
    sources: &mut SourceMap,
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
) -> Option<Loaded> {
    load_file_as(files, path, sources, paths, diags, WithFilters::No)
}

fn load_file_as(
    files: &dyn FileSource,
    path: &Path,
    sources: &mut SourceMap,
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
    with_filters: WithFilters,
) -> Option<Loaded> {
    let bytes = match files.read(path, MAX_SOURCE_BYTES as u64) {
        Ok(b) => b,
        Err(e) => {
            diags.push(
                Diagnostic::error(
                    codes::BAD_USE,
                    format!("cannot read style file `{}`: {e}", path.display()),
                )
                .with_help("check the path; style files usually end in `.npr`"),
            );
            return None;
        }
    };
    let name = path.display().to_string();
    let (file, text) = match npr_diag::text::add_utf8(sources, &name, bytes) {
        Ok(added) => added,
        Err(d) => {
            diags.push(d);
            return None;
        }
    };
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    Some(load_added(
        files,
        file,
        &name,
        &text,
        &dir,
        sources,
        paths,
        diags,
        with_filters,
    ))
}

/// Parse `text` (named `name`) and its `use`s, resolving relative paths against `dir`.
pub fn load_source(
    name: &str,
    text: &str,
    dir: &Path,
    sources: &mut SourceMap,
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
) -> Loaded {
    load_source_from(&Disk, name, text, dir, sources, paths, diags)
}

/// [`load_source`] with every file it names read from `files`.
pub fn load_source_from(
    files: &dyn FileSource,
    name: &str,
    text: &str,
    dir: &Path,
    sources: &mut SourceMap,
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
) -> Loaded {
    let file = sources.add(name, text);
    load_added(files, file, name, text, dir, sources, paths, diags, WithFilters::Yes)
}

/// [`load_source`] of a file already in `sources`.
#[allow(clippy::too_many_arguments)] // each is a separate input of one load; a struct would only rename them
fn load_added(
    files: &dyn FileSource,
    file: FileId,
    name: &str,
    text: &str,
    dir: &Path,
    sources: &mut SourceMap,
    paths: Option<&PathPolicy>,
    diags: &mut Vec<Diagnostic>,
    with_filters: WithFilters,
) -> Loaded {
    let (ast, mut parse_diags) = npr_dsl::parse(file, text);
    diags.append(&mut parse_diags);
    let mut items = Vec::new();
    let own = Path::new(name)
        .file_name()
        .map(|f| dir.join(f))
        .unwrap_or_else(|| dir.to_path_buf());
    let mut stack = vec![files.identity(&own)];
    let mut broken = ast.broken.clone();
    let mut reader = Reader {
        files,
        sources,
        diags,
        paths,
    };
    expand_uses(&ast, dir, &mut reader, &mut items, &mut stack, &mut broken);
    let filters = match with_filters {
        WithFilters::Yes => crate::front::load_filters::load(files, &items, paths, diags, |path, diags| {
            load_filter_file(files, path, sources, paths, diags)
        }),
        WithFilters::No => Default::default(),
    };
    Loaded {
        root: ast,
        root_file: file,
        items,
        broken,
        filters,
        is_filter: with_filters == WithFilters::No,
    }
}

/// Depth limit for nested `use`, far above any real style.
const MAX_USE_DEPTH: usize = 32;

/// What reading `use`d files needs: where they are, the run's sources,
/// its diagnostics, and the paths policy.
struct Reader<'a> {
    files: &'a dyn FileSource,
    sources: &'a mut SourceMap,
    diags: &'a mut Vec<Diagnostic>,
    paths: Option<&'a PathPolicy>,
}

fn expand_uses(
    ast: &Ast,
    dir: &Path,
    reader: &mut Reader,
    items: &mut Vec<(Item, PathBuf)>,
    stack: &mut Vec<PathBuf>,
    broken: &mut Vec<String>,
) {
    for item in &ast.items {
        let Reader {
            files,
            sources,
            diags,
            paths,
        } = reader;
        let Item::Use(u) = item else {
            items.push((item.clone(), dir.to_path_buf()));
            continue;
        };
        match &u.target {
            UseTarget::Module(path) => {
                let joined: Vec<&str> = path.iter().map(|p| p.name.as_str()).collect();
                diags.push(
                    Diagnostic::error(codes::BAD_USE, format!("unknown module `{}`", joined.join("::")))
                        .with_primary(u.span, "no such module")
                        .with_help(
                            "stdlib operators are available without `use`; to share declarations, \
                         `use \"other.npr\"` with a path relative to this file",
                        ),
                );
            }
            UseTarget::File(rel) => {
                let path = dir.join(rel);
                let key = files.identity(&path);
                if stack.contains(&key) {
                    diags.push(
                        Diagnostic::error(codes::BAD_USE, format!("`use` cycle through `{rel}`"))
                            .with_primary(u.span, "this file is already being loaded")
                            .with_help("remove one of the `use` lines that form the cycle"),
                    );
                    continue;
                }
                if stack.len() >= MAX_USE_DEPTH {
                    diags.push(
                        Diagnostic::error(codes::LIMIT_EXCEEDED, "`use` nested too deeply")
                            .with_primary(u.span, format!("more than {MAX_USE_DEPTH} levels")),
                    );
                    continue;
                }
                if let Some(d) = crate::front::paths::check(*paths, u.span, rel, &path) {
                    diags.push(d);
                    continue;
                }
                let bytes = match files.read(&path, MAX_SOURCE_BYTES as u64) {
                    Ok(b) => b,
                    Err(e) => {
                        diags.push(use_error(u.span, rel, &e.to_string()));
                        continue;
                    }
                };
                let (file, text) = match npr_diag::text::add_utf8(sources, &path.display().to_string(), bytes) {
                    Ok(added) => added,
                    Err(d) => {
                        diags.push(d.with_secondary(u.span, "used here"));
                        continue;
                    }
                };
                let (used, mut d) = npr_dsl::parse(file, &text);
                diags.append(&mut d);
                broken.extend(used.broken.iter().cloned());
                let sub_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
                stack.push(key);
                expand_uses(&used, &sub_dir, reader, items, stack, broken);
                stack.pop();
            }
        }
    }
}

fn use_error(span: Span, rel: &str, err: &str) -> Diagnostic {
    Diagnostic::error(codes::BAD_USE, format!("cannot read `{rel}`: {err}"))
        .with_primary(span, "used here")
        .with_help("paths in `use` are relative to the file that contains the `use`")
}
