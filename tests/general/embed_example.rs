//! `examples/embed.rs`, the host application of `npr_runner::embed`, runs: headless
//! (an offscreen texture) and in a real window under Xvfb (a wgpu surface on
//! lavapipe, presented), each for 30 frames; both print the mean of the
//! style's output after the last frame, which is the same frame (the
//! animation follows the frame count), so the two must agree, and it is not
//! black. `cargo test` builds the example; this finds it beside the test
//! binary, building it when a filtered run did not.

use std::path::PathBuf;
use std::process::Command;

fn example() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    // target/<profile>/deps/general-… → target/<profile>/examples/embed
    let dir = exe.parent().and_then(|d| d.parent()).expect("target dir");
    let path = dir
        .join("examples")
        .join(format!("embed{}", std::env::consts::EXE_SUFFIX));
    if !path.exists() {
        let status = Command::new(env!("CARGO"))
            .args(["build", "--example", "embed"])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .status()
            .expect("run cargo build --example embed");
        assert!(status.success(), "cargo build --example embed failed");
    }
    assert!(path.exists(), "no example binary at {}", path.display());
    path
}

/// The mean the example printed: "rendered 30 frames of 512x384; mean output 0.1234".
fn mean(stdout: &str, what: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("rendered 30 frames of 512x384"))
        .unwrap_or_else(|| panic!("{what}: no report line in:\n{stdout}"));
    line.rsplit(' ')
        .next()
        .and_then(|m| m.parse().ok())
        .unwrap_or_else(|| panic!("{what}: {line}"))
}

fn run(command: &mut Command, what: &str) -> f64 {
    // Mesa's window-system probing wants a runtime directory.
    let out = command
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    mean(&stdout, what)
}

#[test]
fn the_embed_example_renders_headless_and_in_a_window() {
    let binary = example();
    let headless = run(
        Command::new(&binary).args(["--headless", "--frames", "30"]),
        "examples/embed --headless",
    );
    assert!(headless > 0.02, "the style's output is black: mean {headless}");
    let xvfb = Command::new("xvfb-run").arg("--help").output();
    assert!(
        xvfb.is_ok(),
        "xvfb-run is not installed: the window test needs an X server (apt-get install xvfb)"
    );
    let windowed = run(
        Command::new("xvfb-run")
            .args(["-a", "-s", "-screen 0 1024x768x24"])
            .arg(&binary)
            .args(["--frames", "30"]),
        "examples/embed in a window under Xvfb",
    );
    assert!(
        (windowed - headless).abs() < 1e-4,
        "the window's last frame differs from the headless one: {windowed} vs {headless}"
    );
}
