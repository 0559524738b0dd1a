//! Watching the files a style depends on (the style, what it `use`s, the
//! scene, textures and meshes) for `npr watch` and `npr studio`.
//!
//! Their *directories* are watched, not the files: an editor that saves by
//! writing a temporary file and renaming it over the original replaces the
//! inode, which a watch on the file itself would lose. Events are debounced
//! (notify-debouncer-full, which keeps each event's kind), so one save is
//! one rebuild, and filtered down to changes (created, written, renamed,
//! removed: not a read, or the build reading the files would trigger the
//! next build) of the files of interest, so a build writing into the same
//! folder does not trigger one either. The set of files changes with every build (a new `use`, a
//! new texture) and is replaced with [`FileWatcher::set_files`].

use notify_debouncer_full::notify::{EventKind, RecommendedWatcher, RecursiveMode};
use notify_debouncer_full::{new_debouncer, DebounceEventResult, Debouncer, RecommendedCache};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// How long the debouncer waits for a burst of events to settle.
pub const DEBOUNCE: Duration = Duration::from_millis(60);

pub struct FileWatcher {
    debouncer: Debouncer<RecommendedWatcher, RecommendedCache>,
    files: Arc<Mutex<BTreeSet<PathBuf>>>,
    dirs: BTreeSet<PathBuf>,
}

/// `path` made absolute with `.` and `..` removed (lexically, not
/// canonically: a symlinked file is matched by the path it was named by,
/// which is the path notify reports for the folder it was asked to watch).
pub fn absolute(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut out = PathBuf::new();
    for c in abs.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

impl FileWatcher {
    /// `on_change` gets the watched files that changed (created, written,
    /// renamed over or deleted), once per debounced burst.
    pub fn new(on_change: impl Fn(Vec<PathBuf>) + Send + 'static) -> Result<FileWatcher, String> {
        let files: Arc<Mutex<BTreeSet<PathBuf>>> = Arc::default();
        let watched = files.clone();
        let debouncer = new_debouncer(DEBOUNCE, None, move |result: DebounceEventResult| {
            let Ok(events) = result else { return };
            let files = watched.lock().unwrap_or_else(|e| e.into_inner());
            let mut changed: Vec<PathBuf> = events
                .into_iter()
                .filter(|e| {
                    matches!(
                        e.kind,
                        EventKind::Create(_) | EventKind::Modify(_) | EventKind::Remove(_)
                    )
                })
                .flat_map(|e| e.event.paths)
                .filter(|p| files.contains(p))
                .collect();
            drop(files);
            changed.sort();
            changed.dedup();
            if !changed.is_empty() {
                on_change(changed);
            }
        })
        .map_err(|e| format!("cannot watch files: {e}"))?;
        Ok(FileWatcher {
            debouncer,
            files,
            dirs: BTreeSet::new(),
        })
    }

    /// Watch exactly these files (through their directories) from now on.
    /// A directory that does not exist (yet) is skipped; its file's absence
    /// is reported by the build that needs it.
    pub fn set_files(&mut self, files: impl IntoIterator<Item = PathBuf>) {
        let files: BTreeSet<PathBuf> = files.into_iter().map(|f| absolute(&f)).collect();
        let dirs: BTreeSet<PathBuf> = files.iter().filter_map(|f| f.parent().map(Path::to_path_buf)).collect();
        for gone in self.dirs.difference(&dirs) {
            let _ = self.debouncer.unwatch(gone);
        }
        let mut watching = BTreeSet::new();
        for dir in &dirs {
            if self.dirs.contains(dir) || self.debouncer.watch(dir, RecursiveMode::NonRecursive).is_ok() {
                watching.insert(dir.clone());
            }
        }
        self.dirs = watching;
        *self.files.lock().unwrap_or_else(|e| e.into_inner()) = files;
    }
}
