//! Where the files a style names come from (`use`d styles, art-maps'
//! filter styles, `image("…")` textures): the disk, natively the default,
//! or a set of files held in memory (the WebAssembly build, whose page has
//! no file system: decision 0052). The compiler reads and probes every
//! file through a [`FileSource`], so both follow one code path and the
//! same paths policy ([`crate::paths`], docs/PATHS.md): a memory source
//! goes with [`PathPolicy::in_memory`](crate::paths::PathPolicy::in_memory),
//! whose root is the directory the files are named relative to, and which
//! refuses an absolute path or one that leaves that root as the disk's does.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

/// What the compiler asks of the files a style names.
pub trait FileSource: Send + Sync + std::fmt::Debug {
    /// The bytes of `path`, but never more than `max_bytes` + 1 of them (so
    /// that a caller can tell a file past its limit from one at it).
    fn read(&self, path: &Path, max_bytes: u64) -> std::io::Result<Vec<u8>>;
    /// Whether `path` names a file (not a directory) that can be read.
    fn is_file(&self, path: &Path) -> bool;
    /// What identifies the file at `path` (a `use` cycle is the same file
    /// twice): on disk the canonical path, links resolved; in memory the
    /// path with `.` and `..` applied to its text.
    fn identity(&self, path: &Path) -> PathBuf;
}

/// The files on disk, through `std::fs`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Disk;

impl FileSource for Disk {
    fn read(&self, path: &Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
        let mut bytes = Vec::new();
        std::fs::File::open(path)?
            .take(max_bytes.saturating_add(1))
            .read_to_end(&mut bytes)?;
        Ok(bytes)
    }

    fn is_file(&self, path: &Path) -> bool {
        path.is_file()
    }

    fn identity(&self, path: &Path) -> PathBuf {
        path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
    }
}

/// Files held in memory, each under a path relative to the in-memory root
/// (`lib/shared.npr`, `textures/paper.png`), written with `/`.
#[derive(Debug, Clone, Default)]
pub struct MemoryFiles {
    files: BTreeMap<PathBuf, Vec<u8>>,
}

impl MemoryFiles {
    pub fn new() -> MemoryFiles {
        MemoryFiles::default()
    }

    /// Add `bytes` as the file `path`. `Err` with the reason when the path
    /// is not one a style could name inside the root: empty, absolute, or
    /// leaving the root through `..`.
    pub fn insert(&mut self, path: &str, bytes: impl Into<Vec<u8>>) -> Result<(), String> {
        let key = lexical(Path::new(path));
        if path.is_empty() || key.as_os_str().is_empty() {
            return Err(format!("`{path}` names no file"));
        }
        if !lexically_inside_root(&key) {
            return Err(format!(
                "`{path}` is not inside the root: a file given in memory is named relative to the style, without leaving its directory"
            ));
        }
        self.files.insert(key, bytes.into());
        Ok(())
    }

    /// The paths held, as given (normalized).
    pub fn paths(&self) -> impl Iterator<Item = &Path> {
        self.files.keys().map(PathBuf::as_path)
    }
}

impl FileSource for MemoryFiles {
    fn read(&self, path: &Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
        let bytes = self.files.get(&lexical(path)).ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::NotFound,
                "no such file among the files given with the style",
            )
        })?;
        let end = bytes
            .len()
            .min(usize::try_from(max_bytes.saturating_add(1)).unwrap_or(usize::MAX));
        Ok(bytes[..end].to_vec())
    }

    fn is_file(&self, path: &Path) -> bool {
        self.files.contains_key(&lexical(path))
    }

    fn identity(&self, path: &Path) -> PathBuf {
        lexical(path)
    }
}

/// A shared [`FileSource`]: what `CompileOptions` holds. The default is
/// the [`Disk`].
#[derive(Debug, Clone)]
pub struct Files(Arc<dyn FileSource>);

impl Files {
    pub fn new(source: impl FileSource + 'static) -> Files {
        Files(Arc::new(source))
    }

    pub fn source(&self) -> &dyn FileSource {
        &*self.0
    }
}

impl Default for Files {
    fn default() -> Files {
        Files::new(Disk)
    }
}

/// `path` with `.` dropped and each `..` taking off the part before it,
/// on its text alone; a `..` with nothing before it to take off is kept
/// (the path leaves where it starts).
pub fn lexical(path: &Path) -> PathBuf {
    let mut parts: Vec<Component> = Vec::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir => match parts.last() {
                Some(Component::Normal(_)) => {
                    parts.pop();
                }
                Some(Component::RootDir | Component::Prefix(_)) => {}
                _ => parts.push(part),
            },
            other => parts.push(other),
        }
    }
    parts.iter().collect()
}

/// Whether the normalized `path` is relative and stays below where it
/// starts (no leading `..`).
pub fn lexically_inside_root(normalized: &Path) -> bool {
    normalized
        .components()
        .all(|c| matches!(c, Component::Normal(_) | Component::CurDir))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lexical_paths_keep_what_leaves_their_start() {
        assert_eq!(lexical(Path::new("a/./b/../c.npr")), PathBuf::from("a/c.npr"));
        assert_eq!(lexical(Path::new("a/../../c.npr")), PathBuf::from("../c.npr"));
        assert_eq!(lexical(Path::new("/../c.npr")), PathBuf::from("/c.npr"));
        assert!(lexically_inside_root(&lexical(Path::new("lib/../x.npr"))));
        assert!(!lexically_inside_root(&lexical(Path::new("lib/../../x.npr"))));
        assert!(!lexically_inside_root(&lexical(Path::new("/x.npr"))));
    }

    #[test]
    fn memory_files_are_found_by_any_spelling_inside_the_root() {
        let mut files = MemoryFiles::new();
        files.insert("lib/shared.npr", "style \"S\"").expect("inside");
        assert!(files.is_file(Path::new("lib/./shared.npr")));
        assert!(files.is_file(Path::new("textures/../lib/shared.npr")));
        assert!(!files.is_file(Path::new("lib")));
        assert_eq!(files.read(Path::new("lib/shared.npr"), 3).expect("held"), b"styl");
        assert!(files.read(Path::new("gone.npr"), 100).is_err());
        assert!(files.insert("../outside.npr", "").is_err());
        assert!(files.insert("/etc/passwd", "").is_err());
        assert!(files.insert("", "").is_err());
    }
}
