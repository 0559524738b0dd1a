//! Watching the files a style depends on (the style, what it `use`s, the
//! scene, textures and meshes) for `npr watch` and `npr studio`.
//!
//! Their *directories* are watched, not the files: an editor that saves by
//! writing a temporary file and renaming it over the original replaces the
//! inode, which a watch on the file itself would lose. Events are filtered
//! down to changes (created, written, renamed, removed: not a read, or the
//! build reading the files would trigger the next build) of the files of
//! interest, so a build writing into the same folder does not trigger one
//! either, and then debounced: one save is one rebuild. The set of files
//! changes with every build (a new `use`, a new texture) and is replaced
//! with [`FileWatcher::set_files`].
//!
//! The debounce is our own, on notify's raw events, and trails the burst:
//! a change is reported [`QUIET`] after the last event of interest, so a
//! save costs QUIET and no more. notify-debouncer-full, used before, reports
//! an event when it is older than its timeout, checked on a tick (a quarter
//! of it): its 60 ms timeout made a save wait 60–75 ms, most of the studio's
//! save → image overhead (docs/PERFORMANCE.md), while what it adds (file
//! ids to stitch renames together, event kinds kept) is not used here: any
//! change to a watched path means "build again". The debounce thread
//! sleeps on a channel, so an idle watcher wakes nothing.

use notify::{EventKind, RecommendedWatcher, RecursiveMode, Watcher};
use npr_diag::{codes, Diagnostic};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// How long the watched files must be left alone before a change is
/// reported. A save's events (the temporary written, then renamed over the
/// file; or the file truncated and written in place) come within a
/// millisecond or two of each other; 10 ms still holds a save written in a
/// few chunks together, and no one saves twice within it.
pub const QUIET: Duration = Duration::from_millis(10);

pub struct FileWatcher {
    watcher: RecommendedWatcher,
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
    /// renamed over or deleted), once per burst of changes, on a thread of
    /// the watcher's own.
    pub fn new(on_change: impl Fn(Vec<PathBuf>) + Send + 'static) -> Result<FileWatcher, String> {
        let files: Arc<Mutex<BTreeSet<PathBuf>>> = Arc::default();
        let watched = files.clone();
        let (changes, burst) = channel::<Vec<PathBuf>>();
        let watcher = notify::recommended_watcher(move |result: notify::Result<notify::Event>| {
            let Ok(event) = result else { return };
            let files = watched.lock().unwrap_or_else(|e| e.into_inner());
            let changed: Vec<PathBuf> = if event.need_rescan() {
                // The kernel dropped events: any watched file may have changed.
                files.iter().cloned().collect()
            } else if matches!(
                event.kind,
                EventKind::Create(_) | EventKind::Modify(_) | EventKind::Remove(_)
            ) {
                event.paths.into_iter().filter(|p| files.contains(p)).collect()
            } else {
                Vec::new()
            };
            drop(files);
            if !changed.is_empty() {
                // The debounce thread is gone only when the watcher is.
                let _ = changes.send(changed);
            }
        })
        .map_err(|e| format!("cannot watch files: {e}"))?;
        std::thread::Builder::new()
            .name("npr file watch".into())
            .spawn(move || {
                // Ends when the watcher, which holds the sender, is dropped.
                while let Ok(first) = burst.recv() {
                    let mut changed: BTreeSet<PathBuf> = first.into_iter().collect();
                    loop {
                        match burst.recv_timeout(QUIET) {
                            Ok(more) => changed.extend(more),
                            Err(RecvTimeoutError::Timeout) => break,
                            Err(RecvTimeoutError::Disconnected) => return,
                        }
                    }
                    on_change(changed.into_iter().collect());
                }
            })
            .map_err(|e| format!("cannot watch files: {e}"))?;
        Ok(FileWatcher {
            watcher,
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
            let _ = self.watcher.unwatch(gone);
        }
        let mut watching = BTreeSet::new();
        for dir in &dirs {
            if self.dirs.contains(dir) || self.watcher.watch(dir, RecursiveMode::NonRecursive).is_ok() {
                watching.insert(dir.clone());
            }
        }
        self.dirs = watching;
        *self.files.lock().unwrap_or_else(|e| e.into_inner()) = files;
    }
}

/// The watcher could not start or stopped: E0507.
pub fn cannot_watch(e: String) -> Diagnostic {
    Diagnostic::error(codes::CANNOT_SERVE, e)
        .with_help("on Linux, raise fs.inotify.max_user_watches if it is exhausted (sysctl)")
}
