//! Which files a style and a scene may read: the paths policy
//! (docs/PATHS.md), one definition for the compiler (`use`d styles,
//! `image("…")` textures) and the runner (a scene's meshes and bound
//! images).
//!
//! - A path is relative to the file that names it.
//! - Every file read must be inside the *root*: by default the deepest
//!   directory that holds both the style and the scene (the style's own
//!   directory when there is no scene), or `--root DIR`.
//! - An absolute path, or one that leaves the root (`../..`, or a symbolic
//!   link pointing out of it: paths are compared after resolving links), is
//!   E0406 naming the root, unless it is inside a directory admitted with
//!   `--allow-path DIR`.
//!
//! A file that does not exist is not refused here: the reader reports it
//! (E0004, E0401, E0402) with its own wording.
//!
//! Files held in memory (`crate::files::MemoryFiles`, the WebAssembly
//! build) follow the same rules under [`PathPolicy::in_memory`]: the root
//! is the directory the style and its files are named relative to, and
//! paths are compared on their text (memory has no links).

use crate::{codes, Diagnostic};
use std::path::{Path, PathBuf};

/// The root and the admitted directories, canonical (links resolved).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PathPolicy {
    root: PathBuf,
    allowed: Vec<PathBuf>,
    on: Storage,
}

/// Where the files the policy judges are: what a path is compared as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Storage {
    /// Canonical paths, links resolved.
    Disk,
    /// Relative paths with `.` and `..` applied to their text, the root
    /// being where they start.
    Memory,
}

impl PathPolicy {
    /// A policy with `root` and the `allowed` directories; E0502 when one
    /// of them is not a directory (they come from the command line).
    pub fn new(root: &Path, allowed: &[PathBuf]) -> Result<PathPolicy, Diagnostic> {
        let dir = |flag: &str, p: &Path| {
            p.canonicalize().ok().filter(|c| c.is_dir()).ok_or_else(|| {
                Diagnostic::error(
                    codes::BAD_ARGUMENT_VALUE,
                    format!("{flag} {}: not a directory", p.display()),
                )
                .with_help(format!("give {flag} an existing directory"))
            })
        };
        Ok(PathPolicy {
            root: dir("--root", root)?,
            allowed: allowed
                .iter()
                .map(|a| dir("--allow-path", a))
                .collect::<Result<_, _>>()?,
            on: Storage::Disk,
        })
    }

    /// The policy for files held in memory (`crate::files::MemoryFiles`):
    /// the root is the directory the style is named relative to (the
    /// empty path), and nothing outside it is admitted.
    pub fn in_memory() -> PathPolicy {
        PathPolicy {
            root: PathBuf::new(),
            allowed: Vec::new(),
            on: Storage::Memory,
        }
    }

    /// The default root for `files` (the style, and the scene when there
    /// is one): the deepest directory holding all of them.
    pub fn default_root(files: &[&Path]) -> PathBuf {
        let mut root: Option<PathBuf> = None;
        for f in files {
            // A file that does not exist (yet, or at all: a wrong
            // `--compiled` path) is taken as absolute, so that the common
            // ancestor is never the empty path.
            let canonical = f
                .canonicalize()
                .or_else(|_| std::path::absolute(f))
                .unwrap_or_else(|_| f.to_path_buf());
            let dir = canonical.parent().map(Path::to_path_buf).unwrap_or_default();
            root = Some(match root {
                None => dir,
                Some(r) => common_ancestor(&r, &dir),
            });
        }
        root.unwrap_or_else(|| PathBuf::from("."))
    }

    /// The root, canonical.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// Whether the file `written` in a style or scene, which resolves to
    /// `resolved` (joined to the naming file's directory), may be read. The
    /// refusal has no span: the caller labels the path where it is written.
    pub fn check(&self, written: &str, resolved: &Path) -> Result<(), Diagnostic> {
        if self.on == Storage::Memory {
            return self.check_in_memory(written, resolved);
        }
        let canonical = canonical_even_if_missing(resolved);
        let admitted = self.allowed.iter().any(|a| canonical.starts_with(a));
        if admitted {
            return Ok(());
        }
        let root = self.root.display();
        if Path::new(written).is_absolute() {
            return Err(Diagnostic::error(
                codes::PATH_OUTSIDE_ROOT,
                format!("`{written}` is an absolute path; files are named relative to the file that names them"),
            )
            .with_note(format!("the root is {root}"))
            .with_help(format!(
                "write the path relative to this file, inside {root}, or admit its directory with --allow-path DIR"
            )));
        }
        if canonical.starts_with(&self.root) {
            return Ok(());
        }
        let through_link = lexically_inside(resolved, &self.root);
        Err(Diagnostic::error(
            codes::PATH_OUTSIDE_ROOT,
            if through_link {
                format!(
                    "`{written}` leaves the root {root} through a symbolic link (it is {})",
                    canonical.display()
                )
            } else {
                format!("`{written}` leaves the root {root} (it is {})", canonical.display())
            },
        )
        .with_note(
            "the root is the deepest directory holding both the style and the scene, unless --root DIR gives another",
        )
        .with_help("move the file inside the root, or give --root DIR or --allow-path DIR to admit it"))
    }
}

impl PathPolicy {
    /// [`PathPolicy::check`] of a file held in memory: the same refusals,
    /// on the path's text.
    fn check_in_memory(&self, written: &str, resolved: &Path) -> Result<(), Diagnostic> {
        let root = "the directory of the style given in memory";
        let note = "files given in memory are named relative to the style, inside its directory";
        if Path::new(written).is_absolute() {
            return Err(Diagnostic::error(
                codes::PATH_OUTSIDE_ROOT,
                format!("`{written}` is an absolute path; files are named relative to the file that names them"),
            )
            .with_note(format!("the root is {root}"))
            .with_help(note));
        }
        let normalized = crate::files::lexical(resolved);
        if crate::files::lexically_inside_root(&normalized) {
            return Ok(());
        }
        Err(Diagnostic::error(
            codes::PATH_OUTSIDE_ROOT,
            format!("`{written}` leaves the root, {root} (it is {})", normalized.display()),
        )
        .with_note(note)
        .with_help("give the file in memory under a path inside the style's directory, and name it so"))
    }
}

/// `path` with links resolved as far as it exists, and the rest (which
/// does not exist) with `.` and `..` applied to its text: so a file that is
/// missing is judged by where it would be, and a refused path never says
/// whether the file outside the root exists.
fn canonical_even_if_missing(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    for existing in absolute.ancestors() {
        if let (Ok(base), Ok(rest)) = (existing.canonicalize(), absolute.strip_prefix(existing)) {
            return join_lexically(base, rest.components());
        }
    }
    // Not even the filesystem root resolves: the text is all there is.
    join_lexically(PathBuf::new(), absolute.components())
}

/// `base` with `parts` appended to its text alone (no links followed): `.`
/// dropped, `..` taking off the last part.
fn join_lexically<'a>(mut base: PathBuf, parts: impl IntoIterator<Item = std::path::Component<'a>>) -> PathBuf {
    for part in parts {
        match part {
            std::path::Component::ParentDir => {
                base.pop();
            }
            std::path::Component::CurDir => {}
            other => base.push(other),
        }
    }
    base
}

/// The deepest directory that is an ancestor of (or equal to) both.
fn common_ancestor(a: &Path, b: &Path) -> PathBuf {
    a.components()
        .zip(b.components())
        .take_while(|(x, y)| x == y)
        .map(|(x, _)| x)
        .collect()
}

/// Whether `path`, with `.` and `..` applied to its text alone (no links
/// followed), is inside `root`: if it is, but its canonical form is not, a
/// link took it out.
fn lexically_inside(path: &Path, root: &Path) -> bool {
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().unwrap_or_default().join(path)
    };
    let out = join_lexically(PathBuf::new(), absolute.components());
    // The root is canonical; compare against the cwd's own spelling too.
    out.starts_with(root)
        || std::env::current_dir()
            .ok()
            .and_then(|cwd| cwd.canonicalize().ok().map(|c| (cwd, c)))
            .and_then(|(cwd, c)| out.strip_prefix(&cwd).ok().map(|rest| c.join(rest)))
            .is_some_and(|p| p.starts_with(root))
}

/// The paths a user chose for a command (`--root`, `--allow-path`) before
/// the style and the scene are known; [`PathChoice::policy`] makes the
/// policy once they are. The CLI's arguments and a test file's runner
/// (`npr-test`) both hold one.
#[derive(Debug, Clone, Default)]
pub struct PathChoice {
    /// Every file must be inside this directory; `None`: the deepest
    /// directory holding both the style and the scene.
    pub root: Option<PathBuf>,
    /// Directories also admitted, even by an absolute path or outside the root.
    pub allowed: Vec<PathBuf>,
}

impl PathChoice {
    /// The policy for `style` (and `scene`, when there is one): the chosen
    /// root, or the deepest directory holding both; E0502 for a root or an
    /// allowed path that is not a directory.
    pub fn policy(&self, style: &Path, scene: Option<&Path>) -> Result<PathPolicy, Diagnostic> {
        let root = match &self.root {
            Some(r) => r.clone(),
            None => {
                let mut files = vec![style];
                files.extend(scene);
                PathPolicy::default_root(&files)
            }
        };
        PathPolicy::new(&root, &self.allowed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_common_ancestor_is_the_deepest_shared_directory() {
        assert_eq!(
            common_ancestor(Path::new("/a/b/c"), Path::new("/a/b/d/e")),
            PathBuf::from("/a/b")
        );
        assert_eq!(common_ancestor(Path::new("/a"), Path::new("/b")), PathBuf::from("/"));
    }

    #[test]
    fn a_missing_file_is_judged_by_where_it_would_be() {
        let root = std::env::temp_dir().join(format!("npr-paths-missing-{}", std::process::id()));
        let inside = root.join("style");
        std::fs::create_dir_all(&inside).expect("a scratch directory");
        let policy = PathPolicy::new(&inside, &[]).expect("a policy");
        // Inside the root, missing: the reader reports it, not the policy.
        assert!(policy.check("gone.png", &inside.join("gone.png")).is_ok());
        assert!(policy.check("a/b/../gone.png", &inside.join("a/b/../gone.png")).is_ok());
        // Outside, missing or not: refused, so a refusal says nothing of existence.
        for written in ["../gone.png", "nowhere/../../gone.png"] {
            let refusal = policy.check(written, &inside.join(written)).expect_err(written);
            assert_eq!(refusal.code, codes::PATH_OUTSIDE_ROOT, "{written}");
        }
        let canonical_root = root.canonicalize().expect("exists");
        assert_eq!(
            canonical_even_if_missing(&inside.join("x/../../y/z.png")),
            canonical_root.join("y/z.png")
        );
        std::fs::remove_dir_all(&root).ok();
    }

    #[test]
    fn in_memory_the_root_is_where_the_style_is_named_from() {
        let policy = PathPolicy::in_memory();
        for (written, resolved) in [
            ("lib/a.npr", "lib/a.npr"),
            ("../a.npr", "lib/../a.npr"),
            ("x/../y.png", "styles/x/../y.png"),
        ] {
            assert!(policy.check(written, Path::new(resolved)).is_ok(), "{resolved}");
        }
        for (written, resolved) in [
            ("../a.npr", "../a.npr"),
            ("../../a.npr", "lib/../../a.npr"),
            ("/etc/passwd", "/etc/passwd"),
        ] {
            let refusal = policy.check(written, Path::new(resolved)).expect_err(resolved);
            assert_eq!(refusal.code, codes::PATH_OUTSIDE_ROOT, "{resolved}");
        }
    }
}
