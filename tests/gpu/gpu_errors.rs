//! GPU and device errors become `RunError`s with a code, never a panic or
//! an abort (issue 13), on the real device:
//! - targets too large for memory: E0508 (exit 1), forced by running `npr
//!   render` under an address-space limit, so the driver's allocation
//!   fails as it would on a GPU with less memory;
//! - a target past the adapter's 2D texture limit: E0404, before any
//!   texture is made;
//! - a lost device (`Device::destroy`, which loses it as a driver reset
//!   does): E0509 through `Gpu::watch`, and a renderer on a new device works;
//! - a read-back larger than one buffer may be (16384 × 4097 × 4 bytes is
//!   over the 256 MiB `max_buffer_size` of downlevel limits) is read in bands.
//! - a format the adapter cannot create: E0404 with an install hint
//!   (`gpu_error::check_target_formats`; lavapipe renders every target
//!   format npr has, so a usage no adapter has for a format, storage on
//!   sRGB, stands in for GL's missing `r32float` rendering).

use crate::common;

use common::{compile_text, root};
use npr_runner::{FrameSpec, Gpu, Renderer, RunError};
use std::process::Command;

/// Eight rgba32float targets: 4 GiB each at 16384².
const WIDE: &str = "style \"Wide\"
pass p: image() {
  out a: rgba32float = vec4(screen_uv, 0.0, 1.0)
  out b: rgba32float = vec4(screen_uv, 1.0, 1.0)
  out c: rgba32float = vec4(screen_uv, 0.5, 1.0)
  out d: rgba32float = vec4(screen_uv, 0.25, 1.0)
  out e: rgba32float = vec4(screen_uv, 0.75, 1.0)
  out f: rgba32float = vec4(screen_uv, 0.125, 1.0)
  out g: rgba32float = vec4(screen_uv, 0.625, 1.0)
  out h: rgba32float = vec4(screen_uv, 0.875, 1.0)
}
pass q: image(p) {
  out o: rgba8unorm = p.a + p.b + p.c + p.d + p.e + p.f + p.g + p.h
}
output q.o
";

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("gpu-errors")
        .join(name);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// `npr render` of `style_text` on spot, under an address-space limit of
/// `limit_kib` (the shell's `ulimit -v`): (exit code, stderr).
fn render_limited(name: &str, style_text: &str, size: &str, limit_kib: u64) -> (Option<i32>, String) {
    let dir = scratch(name);
    let style = dir.join("style.npr");
    std::fs::write(&style, style_text).expect("write style");
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {limit_kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_npr"))
        .args(["render"])
        .arg(&style)
        // Naive: every declared target is allocated (`auto` would fuse the
        // wide pass into its reader and need none of them).
        .args([
            "--schedule",
            "naive",
            "--scene",
            "examples/scenes/spot.toml",
            "--size",
            size,
            "-o",
        ])
        .arg(dir.join("out.png"))
        .current_dir(root())
        .output()
        .expect("npr runs");
    (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn targets_too_large_for_memory_are_e0508_and_exit_1() {
    // 32 GiB of targets in a 12 GB address space.
    let (code, stderr) = render_limited("oom", WIDE, "16384x16384", 12_000_000);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("error[E0508]: the GPU ran out of memory"), "{stderr}");
    assert!(stderr.contains("smaller --size"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    // The same style at a size that fits renders under the same limit.
    let (code, stderr) = render_limited("oom-fits", WIDE, "64x64", 12_000_000);
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn a_target_past_the_adapters_texture_limit_is_a_limit_error() {
    let gpu = common::gpu();
    let max = gpu.device.limits().max_texture_dimension_2d;
    let program = compile_text(
        "style \"Twice\"
pass p: image() scale 2 { out c: rgba8unorm = vec4(screen_uv, 0.0, 1.0) }
output p.c
",
    );
    let scene = npr_runner::scene::parse_scene(
        "[camera]\nposition = [0.0, 0.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n",
        npr_diag::FileId(0),
        root(),
    )
    .expect("scene");
    let mut r = Renderer::new(&gpu.device, &gpu.queue, &program, &scene).expect("renderer");
    let spec = |width: u32| FrameSpec {
        width,
        height: 8,
        time_s: 0.0,
        frame: 0,
        eye: 0,
    };
    let err = r
        .render(&scene, &spec(max / 2 + 1))
        .expect_err("past the texture limit");
    let d = err.diagnostics();
    assert_eq!(d[0].code, npr_diag::codes::LIMIT_EXCEEDED, "{d:?}");
    assert!(
        d[0].message.contains(&format!("2D texture limit of {max}")),
        "{}",
        d[0].message
    );
    assert!(err.is_user_error());
    // The renderer still renders at a size that fits.
    r.render(&scene, &spec(max / 2)).expect("at the limit");
    let out = r.read_output().expect("read back");
    assert_eq!((out.width, out.height), (max / 2 * 2, 16));
}

#[test]
fn a_lost_device_is_e0509_and_a_new_device_renders() {
    let program = compile_text(
        "style \"Lost\"
pass p: image() { out c: rgba8unorm = vec4(screen_uv, 0.5, 1.0) }
output p.c
",
    );
    let scene = npr_runner::scene::parse_scene(
        "[camera]\nposition = [0.0, 0.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n",
        npr_diag::FileId(0),
        root(),
    )
    .expect("scene");
    let spec = FrameSpec {
        width: 16,
        height: 16,
        time_s: 0.0,
        frame: 0,
        eye: 0,
    };
    let gpu = Gpu::headless().expect("a device");
    let mut r = Renderer::new(&gpu.device, &gpu.queue, &program, &scene).expect("renderer");
    r.render(&scene, &spec).expect("a frame");
    let before = r.read_output().expect("read back");
    assert!(gpu.watch.lost().is_none());
    gpu.device.destroy();
    let after = gpu.watch.check(r.render(&scene, &spec).and_then(|()| r.read_output()));
    match after {
        Err(RunError::DeviceLost(reason)) => assert!(reason.contains("Destroyed"), "{reason}"),
        other => panic!("expected a lost device, got {:?}", other.map(|_| ())),
    }
    let e = RunError::DeviceLost("Destroyed: device destroyed".into());
    assert_eq!(e.diagnostics()[0].code, npr_diag::codes::DEVICE_LOST);
    assert!(e.is_user_error(), "a lost device is not a bug in npr: exit 1");
    drop(r);
    // What the studio and `npr watch` do next: a new device.
    let fresh = Gpu::headless().expect("a new device");
    let mut r = Renderer::new(&fresh.device, &fresh.queue, &program, &scene).expect("renderer");
    r.render(&scene, &spec).expect("a frame");
    assert_eq!(r.read_output().expect("read back").bytes, before.bytes);
}

#[test]
fn a_read_back_over_the_buffer_limit_is_read_in_bands() {
    let gpu = common::gpu();
    let max_buffer = gpu.device.limits().max_buffer_size;
    let program = compile_text(
        "style \"Rows\"
pass p: image() { out c: rgba8unorm = vec4(screen_uv.x, screen_uv.y, 0.25, 1.0) }
output p.c
",
    );
    let scene = npr_runner::scene::parse_scene(
        "[camera]\nposition = [0.0, 0.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n",
        npr_diag::FileId(0),
        root(),
    )
    .expect("scene");
    let width = 16384u32;
    // One row more than one buffer holds.
    let height = (max_buffer / (width as u64 * 4)) as u32 + 1;
    assert!(
        height <= 16384,
        "max_buffer_size {max_buffer} is too large to test bands here"
    );
    let mut r = Renderer::new(&gpu.device, &gpu.queue, &program, &scene).expect("renderer");
    r.render(
        &scene,
        &FrameSpec {
            width,
            height,
            time_s: 0.0,
            frame: 0,
            eye: 0,
        },
    )
    .expect("a frame");
    let img = r.read_output().expect("read back in bands");
    assert_eq!(img.bytes.len(), width as usize * height as usize * 4);
    // Each texel holds its own coordinates (`screen_uv` at texel centres).
    for (x, y) in [
        (0, 0),
        (width - 1, 0),
        (5, height - 1),
        (width - 1, height - 1),
        (100, height / 2),
    ] {
        let at = (y as usize * width as usize + x as usize) * 4;
        let expect = |v: u32, n: u32| ((v as f64 + 0.5) / n as f64 * 255.0).round();
        assert!(
            (img.bytes[at] as f64 - expect(x, width)).abs() <= 1.0,
            "x at ({x}, {y})"
        );
        assert!(
            (img.bytes[at + 1] as f64 - expect(y, height)).abs() <= 1.0,
            "y at ({x}, {y})"
        );
    }
}

#[test]
fn a_format_the_adapter_cannot_create_is_a_limit_error_with_an_install_hint() {
    let gpu = common::gpu();
    let targets = vec![
        ("ink".to_string(), npr_abi::Format::Rgba8unorm),
        ("shade".to_string(), npr_abi::Format::Rgba8unormSrgb),
    ];
    // Every target format renders here.
    assert!(npr_runner::gpu_error::check_target_formats(
        &gpu.device,
        &targets,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING
    )
    .is_empty());
    // No adapter has storage on sRGB formats.
    let d = npr_runner::gpu_error::check_target_formats(&gpu.device, &targets, wgpu::TextureUsages::STORAGE_BINDING);
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].code, npr_diag::codes::LIMIT_EXCEEDED);
    assert!(
        d[0].message.contains("`rgba8unorm_srgb` targets (target `shade`)"),
        "{}",
        d[0].message
    );
    assert!(d[0].help.as_deref().is_some_and(|h| h.contains("mesa-vulkan-drivers")));
}
