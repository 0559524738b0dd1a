//! The files of `examples/` that npr's own commands read (the demos of
//! `npr doc`, the scenes, meshes, textures, filters and default styles of
//! `npr bench`) and docs/PERFORMANCE.md, built into the binary, so that an
//! installed `npr` works from any directory.
//!
//! A path under `examples/` that does not exist where npr runs is read from
//! a copy of the bundled files, written once per build of npr into the
//! system's temporary directory (atomically: a directory renamed into
//! place), because scenes name their meshes by relative path and the
//! runner reads files. Goldens are not bundled: no command reads them.

use include_dir::{include_dir, Dir};
use std::path::{Component, Path, PathBuf};

static SCENES: Dir = include_dir!("$CARGO_MANIFEST_DIR/examples/scenes");
static MODELS: Dir = include_dir!("$CARGO_MANIFEST_DIR/examples/models");
static TEXTURES: Dir = include_dir!("$CARGO_MANIFEST_DIR/examples/textures");
static FILTERS: Dir = include_dir!("$CARGO_MANIFEST_DIR/examples/filters");
static LIB: Dir = include_dir!("$CARGO_MANIFEST_DIR/examples/lib");

/// The styles at the top of `examples/` that `npr bench` names by default.
const STYLES: &[(&str, &str)] = &[
    ("toon.npr", include_str!("../examples/toon.npr")),
    ("rounded_shadows.npr", include_str!("../examples/rounded_shadows.npr")),
    ("age_of_sail.npr", include_str!("../examples/age_of_sail.npr")),
];

/// The dynamic 2D pattern tracker the examples `use`, which `npr bench
/// patterns` measures.
pub const TRACKER: &str = include_str!("../examples/lib/dynamic_pattern.npr");

/// docs/PERFORMANCE.md as built: the committed `npr bench ops` table
/// `npr doc` shows.
pub const PERFORMANCE_MD: &str = include_str!("../docs/PERFORMANCE.md");

/// `path` itself when it exists, or, for a relative path under `examples/`
/// that does not exist here, the same file in the bundled copy.
pub fn resolve(path: &Path) -> std::io::Result<PathBuf> {
    if path.exists() {
        return Ok(path.to_path_buf());
    }
    let parts: Vec<Component> = path.components().filter(|c| *c != Component::CurDir).collect();
    match parts.split_first() {
        Some((Component::Normal(first), rest)) if *first == "examples" => {
            Ok(examples_dir()?.join(rest.iter().collect::<PathBuf>()))
        }
        _ => Ok(path.to_path_buf()),
    }
}

/// The bundled `examples/`, written on first use.
fn examples_dir() -> std::io::Result<PathBuf> {
    let dirs: [(&str, &Dir); 5] = [
        ("scenes", &SCENES),
        ("models", &MODELS),
        ("textures", &TEXTURES),
        ("filters", &FILTERS),
        ("lib", &LIB),
    ];
    let mut files: Vec<(PathBuf, &[u8])> = STYLES.iter().map(|(n, t)| (PathBuf::from(n), t.as_bytes())).collect();
    for (name, dir) in dirs {
        collect(dir, Path::new(name), &mut files);
    }
    // One directory per content: a newer npr never reads an older copy.
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for (path, bytes) in &files {
        for b in path.to_string_lossy().bytes().chain(bytes.iter().copied()) {
            hash = (hash ^ b as u64).wrapping_mul(0x100_0000_01b3);
        }
    }
    let dir = std::env::temp_dir().join(format!("npr-examples-{}-{hash:016x}", env!("CARGO_PKG_VERSION")));
    if dir.is_dir() {
        return Ok(dir);
    }
    let partial = std::env::temp_dir().join(format!("npr-examples-{hash:016x}.{}.partial", std::process::id()));
    let _ = std::fs::remove_dir_all(&partial);
    for (path, bytes) in &files {
        let target = partial.join(path);
        if let Some(parent) = target.parent() {
            std::fs::create_dir_all(parent)?;
        }
        std::fs::write(&target, bytes)?;
    }
    match std::fs::rename(&partial, &dir) {
        Ok(()) => Ok(dir),
        // Another npr placed the same copy first.
        Err(_) if dir.is_dir() => {
            let _ = std::fs::remove_dir_all(&partial);
            Ok(dir)
        }
        Err(e) => Err(e),
    }
}

fn collect<'a>(dir: &'a Dir<'a>, prefix: &Path, out: &mut Vec<(PathBuf, &'a [u8])>) {
    for f in dir.files() {
        out.push((prefix.join(f.path().file_name().unwrap_or_default()), f.contents()));
    }
    for d in dir.dirs() {
        collect(d, &prefix.join(d.path().file_name().unwrap_or_default()), out);
    }
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    /// Every file a benchmark reads by default is in the bundled copy, so
    /// `npr bench <any>` runs outside the repository (`bench host`'s
    /// `age_of_sail.npr` once was not).
    #[test]
    fn every_default_file_of_npr_bench_is_bundled() {
        let cli = crate::cli::Cli::command();
        let bench = cli.find_subcommand("bench").expect("npr has a bench command");
        let dir = super::examples_dir().expect("the bundled examples can be written");
        let mut checked = Vec::new();
        for command in bench.get_subcommands() {
            for default in command.get_arguments().flat_map(|a| a.get_default_values()) {
                let default = default.to_string_lossy();
                if let Some(rest) = default.strip_prefix("examples/") {
                    assert!(
                        dir.join(rest).is_file(),
                        "`npr bench {}` reads {default} by default, which is not bundled (src/bundled.rs)",
                        command.get_name()
                    );
                    checked.push(default.into_owned());
                }
            }
        }
        assert!(
            checked.iter().any(|p| p.ends_with("age_of_sail.npr")) && checked.len() >= 5,
            "the defaults were not found: {checked:?}"
        );
    }
}
