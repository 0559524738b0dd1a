//! The small scene Blender (Cycles, CPU, headless) renders into a
//! multi-layer EXR of passes (`tests/data/blender/render_passes.py`), and
//! the same scene written as an npr scene: what the tests of styles over a
//! host's frame run on (`host_inputs.rs`, `post_examples.rs`). Blender runs
//! once per test run (about 3 s here) rather than from a committed EXR, so
//! the tests check what this Blender writes, and nothing binary is
//! committed.

use npr_runner::inputs::files::ExrChannels;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Blender's passes and the mirrored scene, rendered once per test run.
pub fn blender() -> &'static (PathBuf, PathBuf) {
    static ONCE: OnceLock<(PathBuf, PathBuf)> = OnceLock::new();
    ONCE.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("host_inputs");
        std::fs::create_dir_all(&dir).expect("scratch dir");
        let (exr, toml) = (dir.join("blender_passes.exr"), dir.join("blender_scene.toml"));
        assert!(
            Path::new("/usr/bin/blender").exists(),
            "Blender is not installed: run `./setup.sh --tests` (apt-get install -y blender python3-numpy)"
        );
        // The system PATH: Blender's Python finds Debian's numpy there.
        let out = Command::new("/usr/bin/blender")
            .env("PATH", "/usr/bin:/bin")
            .args(["-b", "--factory-startup", "-P"])
            .arg(root().join("tests/data/blender/render_passes.py"))
            .arg("--")
            .args([&exr, &toml])
            .output()
            .expect("run blender");
        assert!(
            out.status.success() && exr.is_file() && toml.is_file(),
            "blender failed:\n{}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        (exr, toml)
    })
}

pub fn npr(args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(args)
        .current_dir(root())
        .env("XDG_RUNTIME_DIR", "/tmp/npr-xdg-runtime")
        .output()
        .expect("run npr");
    assert!(
        out.status.success(),
        "npr {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

pub fn scratch(name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("host_inputs").join(name)
}

pub fn channel<'a>(exr: &'a ExrChannels, name: &str) -> &'a [f32] {
    exr.channels
        .get(name)
        .unwrap_or_else(|| panic!("no channel {name}: {:?}", exr.channels.keys().collect::<Vec<_>>()))
}
