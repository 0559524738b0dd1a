//! A style whose files are held in memory (`npr_diag::files::MemoryFiles`
//! under `PathPolicy::in_memory`, as the WebAssembly build compiles them)
//! compiles to what the same files on disk give, and the same paths rules
//! refuse the same paths: absolute, or leaving the style's directory.

use npr_compiler::{CompileError, CompileOptions, Compiled};
use npr_diag::files::{Files, MemoryFiles};
use npr_diag::paths::PathPolicy;
use npr_diag::{codes, SourceMap};
use std::path::{Path, PathBuf};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples")
        .canonicalize()
        .expect("examples/")
}

/// Every file under `examples/` a style there may name: its libraries,
/// filters and textures, named relative to `examples/`.
fn example_files() -> MemoryFiles {
    let root = examples();
    let mut files = MemoryFiles::new();
    for dir in ["lib", "filters", "textures"] {
        for entry in std::fs::read_dir(root.join(dir)).expect("an examples folder") {
            let path = entry.expect("an entry").path();
            let name = path.strip_prefix(&root).expect("inside").to_string_lossy().into_owned();
            files
                .insert(&name, std::fs::read(&path).expect("readable"))
                .expect("inside the root");
        }
    }
    files
}

fn in_memory(name: &str, text: &str, files: MemoryFiles) -> Result<Compiled, (Vec<npr_diag::Diagnostic>, SourceMap)> {
    let opts = CompileOptions {
        paths: Some(PathPolicy::in_memory()),
        files: Files::new(files),
        ..Default::default()
    };
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source(name, text, Path::new(""), &mut sources, &opts) {
        Ok(c) => Ok(c),
        Err(CompileError::User(d)) => Err((d, sources)),
        Err(CompileError::Internal(e)) => panic!("{e}"),
    }
}

#[test]
fn a_style_in_memory_compiles_as_it_does_on_disk() {
    let root = examples();
    // `use` (halftone), images, art-maps and their filter styles (artmap_gallery).
    for name in ["halftone.npr", "artmap_gallery.npr", "age_of_sail.npr"] {
        let text = std::fs::read_to_string(root.join(name)).expect("an example");
        let memory = in_memory(name, &text, example_files())
            .unwrap_or_else(|(d, s)| panic!("{name}: {}", npr_diag::diagnostic::render(&d, &s, false)));
        let opts = CompileOptions {
            paths: Some(PathPolicy::new(&root, &[]).expect("a root")),
            ..Default::default()
        };
        let mut sources = SourceMap::new();
        let disk = npr_compiler::compile_source(name, &text, &root, &mut sources, &opts)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(memory.shaders, disk.shaders, "{name}");
        // On disk a texture's `resolved` path starts at the root's own path.
        let disk_manifest = serde_json::to_string_pretty(&disk.manifest)
            .expect("JSON")
            .replace(&format!("{}/", root.display()), "");
        let memory_manifest = serde_json::to_string_pretty(&memory.manifest).expect("JSON");
        assert_eq!(memory_manifest, disk_manifest, "{name}");
    }
}

#[test]
fn memory_refuses_what_the_disk_refuses() {
    let mut files = MemoryFiles::new();
    files
        .insert("lib/a.npr", "style \"A\"\nparam a: float = 1\n")
        .expect("inside");
    files
        .insert("lib/loop.npr", "style \"L\"\nuse \"../main.npr\"\n")
        .expect("inside");
    let header = "style \"S\"\n";
    let cases = [
        ("use \"../outside.npr\"\n", codes::PATH_OUTSIDE_ROOT, "leaves the root"),
        ("use \"/etc/passwd\"\n", codes::PATH_OUTSIDE_ROOT, "absolute path"),
        ("use \"lib/../../a.npr\"\n", codes::PATH_OUTSIDE_ROOT, "leaves the root"),
        (
            "use \"lib/missing.npr\"\n",
            codes::BAD_USE,
            "no such file among the files given with the style",
        ),
        ("use \"lib/loop.npr\"\n", codes::BAD_USE, "`use` cycle"),
        (
            "texture t = image(\"textures/none.png\", srgb)\n",
            codes::MISSING_TEXTURE,
            "not found",
        ),
        (
            "texture t = image(\"../x.png\", srgb)\n",
            codes::PATH_OUTSIDE_ROOT,
            "leaves the root",
        ),
    ];
    for (line, code, says) in cases {
        let text = format!("{header}{line}pass final: image() {{ out color: rgba8unorm = vec4(1.0, 1.0, 1.0, 1.0) }}\noutput final.color\n");
        let (diags, sources) = in_memory("main.npr", &text, files.clone()).expect_err(line);
        let rendered = npr_diag::diagnostic::render(&diags, &sources, false);
        let first = diags.iter().find(|d| d.is_error()).expect("an error");
        assert_eq!(first.code, code, "{line}{rendered}");
        assert!(rendered.contains(says), "{line}: {rendered}");
        assert!(first.primary_span().is_some(), "{line}: no span: {rendered}");
    }
    // Through a `use`d file, the library's own `use` resolves against its folder.
    let text = format!("{header}use \"lib/a.npr\"\npass final: image() {{ out color: rgba8unorm = vec4(a, a, a, 1.0) }}\noutput final.color\n");
    in_memory("main.npr", &text, files)
        .unwrap_or_else(|(d, s)| panic!("{}", npr_diag::diagnostic::render(&d, &s, false)));
}
