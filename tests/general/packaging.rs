//! Every package of the workspace can be published as it stands (issue 46):
//! the metadata a registry shows, path dependencies that carry a version,
//! and every file a package reads at compile time (`include_str!`,
//! `include_bytes!`, `include_dir!`, pest's `#[grammar]`) inside the package
//! and in the list `cargo package --list` would upload. A file outside the
//! package (`../../examples/...`) builds here and fails for every user of
//! the published crate; this catches it without a registry.

use crate::common::cargo::cargo_stdout;
use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The workspace's own packages, from `cargo metadata`.
fn workspace_packages() -> Vec<Value> {
    let out = cargo_stdout(&["metadata", "--format-version", "1", "--no-deps", "--offline"]);
    let meta: Value = serde_json::from_str(&out).expect("cargo metadata's JSON");
    let packages = meta["packages"].as_array().expect("packages").clone();
    assert!(
        packages.len() >= 12,
        "expected the 12 npr packages, found {}",
        packages.len()
    );
    packages
}

/// The files `cargo package` would put in `name`'s archive, relative to its folder.
fn packaged_files(name: &str) -> BTreeSet<String> {
    cargo_stdout(&["package", "--list", "--allow-dirty", "--offline", "-p", name])
        .lines()
        .map(str::to_string)
        .collect()
}

fn is_library(package: &Value) -> bool {
    package["targets"]
        .as_array()
        .expect("targets")
        .iter()
        .any(|t| t["kind"].as_array().expect("kind").iter().any(|k| k == "lib"))
}

#[test]
fn every_package_has_the_metadata_a_registry_shows() {
    let mut missing = Vec::new();
    for p in workspace_packages() {
        let name = p["name"].as_str().expect("name").to_string();
        let dir = Path::new(p["manifest_path"].as_str().expect("manifest_path"))
            .parent()
            .expect("folder")
            .to_path_buf();
        for field in ["description", "license", "readme", "rust_version"] {
            if p[field].as_str().is_none_or(str::is_empty) {
                missing.push(format!("{name}: no `{}`", field.replace('_', "-")));
            }
        }
        if is_library(&p) && p["documentation"].as_str().is_none() {
            missing.push(format!("{name}: no `documentation`"));
        }
        for field in ["keywords", "categories"] {
            if p[field].as_array().is_none_or(|a| a.is_empty()) {
                missing.push(format!("{name}: no `{field}`"));
            }
        }
        if let Some(readme) = p["readme"].as_str() {
            if !dir.join(readme).is_file() {
                missing.push(format!("{name}: its readme {readme} does not exist"));
            }
        }
        if !name.starts_with("npr-") && !name.starts_with("bevy_mod_") {
            missing.push(format!("{name}: not an `npr-` (or Bevy's `bevy_mod_`) name"));
        }
    }
    assert!(
        missing.is_empty(),
        "packages not ready to publish:\n  {}",
        missing.join("\n  ")
    );
}

#[test]
fn every_path_dependency_carries_a_version() {
    let mut bare = Vec::new();
    for p in workspace_packages() {
        for d in p["dependencies"].as_array().expect("dependencies") {
            // Dev-dependencies are stripped from a published package.
            if d["path"].is_string() && d["kind"] != "dev" && d["req"] == "*" {
                bare.push(format!("{} → {}", p["name"], d["name"]));
            }
        }
    }
    assert!(
        bare.is_empty(),
        "path dependencies without a version (cargo package refuses them):\n  {}",
        bare.join("\n  ")
    );
}

/// The string literal that opens `rest` (after the macro's parenthesis).
fn leading_literal(rest: &str) -> Option<&str> {
    let rest = rest.trim_start().strip_prefix('"')?;
    Some(&rest[..rest.find('"')?])
}

/// Every compile-time file reference in `text`, a source file in `file_dir`
/// of a package in `package_dir`: the path it names.
fn compile_time_reads(text: &str, file_dir: &Path, package_dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for mac in ["include_str!(", "include_bytes!(", "include_dir!(", "#[grammar = "] {
        for (at, _) in text.match_indices(mac) {
            let Some(lit) = leading_literal(&text[at + mac.len()..]) else {
                continue;
            };
            let path = if let Some(rel) = lit.strip_prefix("$CARGO_MANIFEST_DIR/") {
                package_dir.join(rel)
            } else if mac == "#[grammar = " {
                // pest_derive resolves the grammar from the package's src/.
                package_dir.join("src").join(lit)
            } else {
                file_dir.join(lit)
            };
            found.push(path);
        }
    }
    found
}

/// `path` with `.` and `..` resolved lexically (the file may not exist).
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

#[test]
fn every_file_a_package_reads_at_compile_time_is_inside_it_and_packaged() {
    let mut problems = Vec::new();
    let mut checked = 0usize;
    let mut wgsl_in_stdlib = 0usize;
    for p in workspace_packages() {
        let name = p["name"].as_str().expect("name").to_string();
        let dir = normalise(
            Path::new(p["manifest_path"].as_str().expect("manifest_path"))
                .parent()
                .expect("folder"),
        );
        let listed = packaged_files(&name);
        // The code that is compiled for a user: the library, binaries and
        // build script (tests, examples and benches are not built from the
        // registry).
        let sources = listed
            .iter()
            .filter(|f| f.ends_with(".rs") && (f.starts_with("src/") || *f == "build.rs"));
        for source in sources {
            let file = dir.join(source);
            let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            for read in compile_time_reads(&text, file.parent().expect("folder"), &dir) {
                checked += 1;
                let read = normalise(&read);
                let Ok(rel) = read.strip_prefix(&dir) else {
                    problems.push(format!(
                        "{name}: {source} reads {}, outside the package",
                        read.display()
                    ));
                    continue;
                };
                let rel = rel.to_string_lossy().replace('\\', "/");
                if name == "npr-stdlib" && rel.ends_with(".wgsl") {
                    wgsl_in_stdlib += 1;
                }
                let packaged = if read.is_dir() {
                    // Every file in the folder, and at least one.
                    let on_disk = files_under(&read);
                    !on_disk.is_empty()
                        && on_disk.iter().all(|f| {
                            let f = f
                                .strip_prefix(&dir)
                                .expect("inside")
                                .to_string_lossy()
                                .replace('\\', "/");
                            listed.contains(&f)
                        })
                } else {
                    listed.contains(&rel)
                };
                if !packaged {
                    problems.push(format!(
                        "{name}: {source} reads {rel}, which `cargo package` leaves out"
                    ));
                }
            }
        }
    }
    // The scan sees what is there: the stdlib's operators are WGSL files
    // read with include_str!.
    assert!(
        wgsl_in_stdlib >= 10,
        "found only {wgsl_in_stdlib} WGSL includes in npr-stdlib"
    );
    assert!(checked >= 50, "found only {checked} compile-time reads");
    assert!(
        problems.is_empty(),
        "files a published package could not build without:\n  {}",
        problems.join("\n  ")
    );
}

fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            out.extend(files_under(&path));
        } else {
            out.push(path);
        }
    }
    out
}

/// The sweep's walking hard scene ships its mesh inside the npr-test
/// package (a package may read nothing from outside itself): that copy
/// must be the Blender script's walker, byte for byte.
#[test]
fn the_hard_scenes_walker_is_the_examples_walker() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let shipped = std::fs::read(root.join("style_tests/hard_scenes/walker.glb")).expect("the hard scenes' walker");
    let made = std::fs::read(root.join("examples/models/walker.glb")).expect("the examples' walker");
    assert!(
        shipped == made,
        "style_tests/hard_scenes/walker.glb differs from examples/models/walker.glb: copy the one \
         tests/data/blender/make_characters.py wrote over the other"
    );
}
