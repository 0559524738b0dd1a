//! `cargo run -p bevy_mod_npr --example toon` runs in a real window under
//! Xvfb (winit, a wgpu surface on lavapipe): the log says the camera is
//! drawn with the toon style, and a screenshot of the window at frame 40
//! has the style's clear colour (#202020) in its corner, not Bevy's, and
//! the style's shading bands. `cargo test` builds the example; this finds
//! it beside the test binary, building it when a filtered run did not.

use std::path::PathBuf;
use std::process::Command;

fn example() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    // target/<profile>/deps/example-… → target/<profile>/examples/toon
    let dir = exe.parent().and_then(|d| d.parent()).expect("target dir");
    let path = dir
        .join("examples")
        .join(format!("toon{}", std::env::consts::EXE_SUFFIX));
    if !path.exists() {
        let status = Command::new(env!("CARGO"))
            .args(["build", "-p", "bevy_mod_npr", "--example", "toon"])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .status()
            .expect("run cargo build --example toon");
        assert!(status.success(), "cargo build -p bevy_mod_npr --example toon failed");
    }
    assert!(path.exists(), "no example binary at {}", path.display());
    path
}

#[test]
fn the_toon_example_draws_its_window_with_the_style() {
    let binary = example();
    assert!(
        Command::new("xvfb-run").arg("--help").output().is_ok(),
        "xvfb-run is not installed: the example's window needs an X server (./setup.sh --tests installs xvfb)"
    );
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1024x768x24"])
        .arg(&binary)
        .args(["--frames", "40"])
        // Bevy reads assets relative to the package (../examples/toon.npr).
        .env("BEVY_ASSET_ROOT", env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .env("RUST_LOG", "info")
        .output()
        .expect("run the example under xvfb-run");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "the example failed ({}):\n{stdout}\n{stderr}",
        out.status
    );
    let log = format!("{stdout}\n{stderr}");
    assert!(
        log.contains("drawn with the style \"Toon\""),
        "the camera was not drawn with the style:\n{log}"
    );
    // Bevy's own errors (wgpu's probing of EGL, which the Vulkan adapter
    // does not need, is not one of them).
    let bevy_errors: Vec<&str> = log
        .lines()
        .filter(|l| l.contains("ERROR") && l.contains("bevy"))
        .collect();
    assert!(
        bevy_errors.is_empty(),
        "Bevy logged errors:\n{}",
        bevy_errors.join("\n")
    );
    let line = stdout
        .lines()
        .find(|l| l.starts_with("screenshot 640x480"))
        .unwrap_or_else(|| panic!("no screenshot line:\n{log}"));
    // The corner is the style's clear colour #202020 (the same in RGBA and BGRA).
    assert!(line.contains("corner [32, 32, 32, 255]"), "{line}");
    let colours: usize = line
        .rsplit(", ")
        .next()
        .and_then(|c| c.trim_end_matches(" colours").parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    assert!(colours >= 6, "the style's bands and rim: {line}");
}
