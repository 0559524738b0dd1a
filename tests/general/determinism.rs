//! The same style, scene and arguments give bit-identical PNGs in two runs
//! of `npr render` (two processes, so two devices, on the same backend):
//! render passes, image passes, textures, compute reductions over vertices
//! and a path-dependent style that replays its earlier frames (issue 13).

use crate::common;

use common::root;
use std::path::Path;

/// `npr render style --scene scene args -o out`, from the repository root.
fn render(style: &str, scene: &str, args: &[&str], out: &Path) {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .current_dir(root())
        .args(["render", style, "--scene", scene, "-o"])
        .arg(out)
        .args(args)
        .output()
        .expect("npr runs");
    assert!(
        run.status.success(),
        "npr render {style} failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// Render twice into `name_{a,b}.png` and compare the files byte for byte.
fn twice_identical(name: &str, style: &str, scene: &str, args: &[&str]) {
    let dir = std::env::temp_dir().join(format!("npr-determinism-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let (a, b) = (dir.join(format!("{name}_a.png")), dir.join(format!("{name}_b.png")));
    render(style, scene, args, &a);
    render(style, scene, args, &b);
    let (bytes_a, bytes_b) = (std::fs::read(&a).expect("first"), std::fs::read(&b).expect("second"));
    assert!(bytes_a.len() > 100, "{name}: the PNG is only {} bytes", bytes_a.len());
    if bytes_a != bytes_b {
        let (ia, ib) = (
            image::load_from_memory(&bytes_a).expect("png").to_rgba8(),
            image::load_from_memory(&bytes_b).expect("png").to_rgba8(),
        );
        let differing = ia.pixels().zip(ib.pixels()).filter(|(p, q)| p != q).count();
        panic!(
            "{name}: two runs differ in {differing} pixel(s) ({} and {})",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn toon_is_bit_identical_across_runs() {
    twice_identical(
        "toon",
        "examples/toon.npr",
        "examples/scenes/spot.toml",
        &["--size", "128x128"],
    );
}

#[test]
fn age_of_sail_with_textures_and_image_passes_is_bit_identical_across_runs() {
    twice_identical(
        "age_of_sail",
        "examples/age_of_sail.npr",
        "examples/scenes/age_of_sail.toml",
        &["--size", "128x128"],
    );
}

#[test]
fn compute_reductions_are_bit_identical_across_runs() {
    twice_identical(
        "object_centroids",
        "examples/object_centroids.npr",
        "examples/scenes/spheres.toml",
        &["--size", "128x128"],
    );
}

#[test]
fn a_path_dependent_style_replayed_to_a_time_is_bit_identical_across_runs() {
    // `--time 0.5` at 24 fps replays frames 0..=12 through `previous(...)`.
    twice_identical(
        "afterimage",
        "examples/afterimage.npr",
        "examples/scenes/orbit.toml",
        &["--size", "96x96", "--time", "0.5"],
    );
}

#[test]
fn the_dynamic_pattern_tracker_with_state_is_bit_identical_across_runs() {
    // Compute passes over samples with per-object state, frames replayed.
    twice_identical(
        "halftone",
        "examples/halftone.npr",
        "examples/scenes/cows.toml",
        &["--size", "96x96", "--time", "0.25"],
    );
}
