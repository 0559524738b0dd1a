//! Helpers shared by the integration tests in `tests/`: one headless GPU per
//! test binary (failing, never skipping, when there is none) and the
//! repository root.

// Each test binary uses its own subset of these.
#![allow(dead_code)]

pub mod artmaps;
pub mod cargo;
pub mod chromium;
pub mod cli;
pub mod fuzz;
pub mod http;
pub mod lines;
pub mod live;
pub mod lsa;
pub mod patch_strip;
pub mod xvfb;

use npr_runner::Gpu;
use std::path::Path;
use std::sync::OnceLock;

/// The headless device of this test binary.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        Gpu::headless().unwrap_or_else(|e| {
            panic!("this test needs a GPU adapter: {e} (install one with ./setup.sh: mesa-vulkan-drivers)")
        })
    })
}

/// A style given as text, compiled with paths relative to the repository
/// root; a user or internal error fails the test with its rendered message.
pub fn compile_text(text: &str) -> npr_runner::StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    match npr_compiler::compile_source("case.npr", text, root(), &mut sources, &Default::default()) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    }
}

/// The repository root (where `examples/` and `tests/` are).
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Render `style` on `scene` at 48×48 (style and scene relative to the
/// repository root, or absolute) with `npr render` twice: frames 0..7 as a
/// sequence, and frame 6 alone (`--time 0.25` at 24 fps, which a
/// path-dependent style replays). Returns (frame 6 of the sequence, frame 6
/// alone, frame 0 of the sequence) as RGBA bytes, after checking that the
/// lone render said it replayed.
pub fn sequence_and_alone(style: &str, scene: &str, scratch: &Path) -> (Vec<u8>, Vec<u8>, Vec<u8>) {
    std::fs::create_dir_all(scratch).expect("scratch dir");
    let npr = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
            .current_dir(root())
            .args(["render", style, "--scene", scene, "--size", "48x48"])
            .args(args)
            .output()
            .expect("npr runs");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let seq = scratch.join("seq_{frame}.png");
    npr(&["--frames", "0..7", "-o", seq.to_str().expect("utf-8 path")]);
    let alone = scratch.join("alone.png");
    let log = npr(&["--time", "0.25", "-o", alone.to_str().expect("utf-8 path")]);
    assert!(log.contains("replaying 6 frame(s)"), "{log}");
    let read = |p: std::path::PathBuf| image::open(&p).expect("a rendered frame").to_rgba8().into_raw();
    let frames = (
        read(scratch.join("seq_0006.png")),
        read(alone),
        read(scratch.join("seq_0000.png")),
    );
    let _ = std::fs::remove_dir_all(scratch);
    frames
}
