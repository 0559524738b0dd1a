//! `npr render`'s sequence outputs through the binary: `--layers` (every
//! target as a layer of one EXR, compared bit for bit with the targets the
//! runner reads back in this process) and videos (`.mp4`, `.webm`, `.gif`,
//! decoded back to frames with ffmpeg and compared with the PNG frames of
//! the same render at a stated tolerance). Also: a video leaves nothing
//! behind when it fails, and a missing ffmpeg stops the render before any
//! frame.

use crate::common::cli::{npr, scratch, stderr};
use crate::common::{gpu, root};
use npr_lab::harness::{compare_with_golden_file, Tolerance};
use std::path::Path;

/// Targets of every kind a layer holds: 8-bit, 16- and 32-bit float, one
/// and four channels, half scale, and a target aliased onto a texture a
/// later pass reuses (`a.r` under `c.r`, read by a partial re-render).
const LAYERS_STYLE: &str = r#"style "Layers"
pass shade: render(scene) {
  out light: r8unorm = lambert(normal, light.dir)
  out n: rgba32float = vec4(normal, 1.0)
}
pass a: image(shade) scale 1/2 { out r: r16float = downsample(shade.light).r }
pass b: image(a) scale 1/2 { out r: r16float = gaussian(a.r, sigma: 2px, axis: x).r }
pass c: image(b) scale 1/2 { out r: r16float = gaussian(b.r, sigma: 2px, axis: y).r }
pass d: image(c) { out r: rgba16float = vec4(c.r * 0.5, 0.25, 0.5, 1.0) }
pass final: image(d, shade) { out color: rgba8unorm = vec4(d.r.r, shade.light, shade.n.z * 0.5 + 0.5, 1.0) }
output final.color
"#;

/// One layer of an EXR: name, width, height, and each channel's name and samples as f32.
type Layer = (String, usize, usize, Vec<(String, Vec<f32>)>);

/// Every layer of an EXR.
fn read_layers(path: &Path) -> Vec<Layer> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_file(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    image
        .layer_data
        .iter()
        .map(|l| {
            let name = l
                .attributes
                .layer_name
                .as_ref()
                .map(|n| n.to_string())
                .unwrap_or_default();
            let channels = l
                .channel_data
                .list
                .iter()
                .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
                .collect();
            (name, l.size.0, l.size.1, channels)
        })
        .collect()
}

#[test]
fn layers_hold_every_target_bit_for_bit() {
    let dir = scratch("sequence-outputs", "layers");
    let style = dir.join("layers.npr");
    std::fs::write(&style, LAYERS_STYLE).expect("style");
    let out = dir.join("shot.exr");
    let o = npr(&[
        "render",
        style.to_str().expect("utf-8"),
        "--scene",
        "examples/scenes/spheres.toml",
        "--size",
        "40x30",
        "--layers",
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let layers = read_layers(&out);

    // The same frame in this process, naive as `--layers` is.
    let mut sources = npr_diag::SourceMap::new();
    let opts = npr_compiler::CompileOptions {
        schedule: npr_compiler::schedule::Schedule::Naive,
        ..Default::default()
    };
    let program = npr_compiler::compile_source("layers.npr", LAYERS_STYLE, root(), &mut sources, &opts)
        .unwrap_or_else(|e| panic!("{e:?}"))
        .program();
    let scene = npr_runner::scene::load_scene(&root().join("examples/scenes/spheres.toml"), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let mut r = npr_runner::Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let spec = npr_runner::FrameSpec::animated(40, 30, 0, npr_runner::FrameSpec::DEFAULT_FPS, 0);
    r.render(&scene, &spec).expect("frame");
    let count = r.manifest().targets.len();
    let survivors: Vec<bool> = (0..count).map(|t| r.target_survives_frame(t)).collect();
    assert!(
        survivors.contains(&false),
        "the style should alias a target, to test partial re-renders"
    );
    let mut targets = Vec::new();
    for (t, survives) in survivors.iter().enumerate() {
        if *survives {
            targets.push(r.read_target(t).expect("read"));
        }
    }
    for (t, survives) in survivors.iter().enumerate() {
        if !*survives {
            targets.push(r.render_until_target(&scene, &spec, t).expect("partial"));
        }
    }
    assert_eq!(layers.len(), count, "one layer per target");
    for target in &targets {
        let (_, w, h, channels) = layers.iter().find(|l| l.0 == target.name).unwrap_or_else(|| {
            panic!(
                "no layer `{}` in {:?}",
                target.name,
                layers.iter().map(|l| &l.0).collect::<Vec<_>>()
            )
        });
        assert_eq!(
            (*w, *h),
            (target.width as usize, target.height as usize),
            "{}",
            target.name
        );
        let names: Vec<&str> = channels.iter().map(|c| c.0.as_str()).collect();
        let expected_names: &[&str] = match target.format.channels() {
            1 => &["R"],
            2 => &["G", "R"],
            _ => &["A", "B", "G", "R"],
        };
        assert_eq!(names, expected_names, "{}", target.name);
        let texels = target.to_rgba_f32();
        for (name, samples) in channels {
            let c = ["R", "G", "B", "A"].iter().position(|n| n == name).expect("channel");
            for (i, (got, texel)) in samples.iter().zip(&texels).enumerate() {
                // Float targets: the texture's bits; 8-bit: v / 255 in f32, as read.
                assert_eq!(
                    got.to_bits(),
                    texel[c].to_bits(),
                    "{}.{name} at texel {i}: {got} in the EXR, {} on the GPU",
                    target.name,
                    texel[c]
                );
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The ffmpeg program the video tests decode with; fails naming the package.
fn ffmpeg() -> &'static str {
    let ok = std::process::Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "these tests decode videos with ffmpeg: install it (Debian: apt-get install ffmpeg)"
    );
    "ffmpeg"
}

/// Every frame of `video` as RGBA8, decoded by ffmpeg.
fn decode(video: &Path, (w, h): (u32, u32)) -> Vec<image::RgbaImage> {
    let o = std::process::Command::new(ffmpeg())
        .args(["-hide_banner", "-loglevel", "error", "-i"])
        .arg(video)
        .args(["-f", "rawvideo", "-pix_fmt", "rgba", "-"])
        .output()
        .expect("ffmpeg runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o.stdout
        .chunks_exact((w * h * 4) as usize)
        .map(|f| image::RgbaImage::from_raw(w, h, f.to_vec()).expect("a frame"))
        .collect()
}

const SIZE: (u32, u32) = (192, 128);
const FRAMES: u32 = 16;

/// `npr render afterimage on orbit` at [`SIZE`], frames 0..[`FRAMES`], into `out`.
fn render_to(out: &Path) -> std::process::Output {
    npr(&[
        "render",
        "examples/afterimage.npr",
        "--scene",
        "examples/scenes/orbit.toml",
        "--size",
        &format!("{}x{}", SIZE.0, SIZE.1),
        "--frames",
        &format!("0..{FRAMES}"),
        "-o",
        out.to_str().expect("utf-8"),
    ])
}

/// Each decoded frame of `ext` against the PNG frame, opaque (videos drop
/// alpha), within `tol`; on failure the actual and diff images are written
/// beside the reference.
fn check_video(ext: &str, tol: Tolerance) {
    let dir = scratch("sequence-outputs", ext);
    let pngs = dir.join("f_{frame}.png");
    let o = render_to(&pngs);
    assert!(o.status.success(), "{}", stderr(&o));
    let video = dir.join(format!("clip.{ext}"));
    let o = render_to(&video);
    assert!(o.status.success(), "{}", stderr(&o));
    let decoded = decode(&video, SIZE);
    assert_eq!(decoded.len(), FRAMES as usize, "frames in {}", video.display());
    let mut failures = Vec::new();
    for (n, frame) in decoded.iter().enumerate() {
        let mut expected = image::open(dir.join(format!("f_{n:04}.png")))
            .expect("png frame")
            .to_rgba8();
        expected.pixels_mut().for_each(|p| p.0[3] = 255);
        let reference = dir.join(format!("expected_{n:04}.png"));
        expected.save(&reference).expect("reference");
        let c = compare_with_golden_file(frame, &reference, tol, false);
        if !c.passed {
            failures.push(format!("frame {n}: {}", c.summary));
        }
    }
    assert!(
        failures.is_empty(),
        "{ext} against the PNG frames:\n{}",
        failures.join("\n")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

// Tolerances: mean FLIP per frame. Measured on this clip (lavapipe,
// Debian's ffmpeg 5.1): mp4 up to 0.067, webm up to 0.060, gif under 0.05;
// bounded at 0.1 (mp4, webm) and 0.05 (gif). A lossy codec's error is no
// per-pixel bound: 4:2:0 chroma moves the pixels of a saturated orange edge
// by up to 89 levels on a 192×128 frame, while FLIP, a perceptual measure,
// stays low.

#[test]
fn an_mp4_decodes_to_the_png_frames() {
    check_video("mp4", Tolerance::Flip { max_mean: 0.1 });
}

#[test]
fn a_webm_decodes_to_the_png_frames() {
    check_video("webm", Tolerance::Flip { max_mean: 0.1 });
}

#[test]
fn a_gif_decodes_to_the_png_frames() {
    check_video("gif", Tolerance::Flip { max_mean: 0.05 });
}

#[test]
fn a_missing_ffmpeg_stops_the_render_before_any_frame_and_leaves_nothing() {
    let dir = scratch("sequence-outputs", "no-ffmpeg");
    let video = dir.join("clip.mp4");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args([
            "render",
            "examples/afterimage.npr",
            "--scene",
            "examples/scenes/orbit.toml",
        ])
        .args(["--size", "16x16", "--frames", "0-3", "-o"])
        .arg(&video)
        .current_dir(root())
        .env("NPR_FFMPEG", dir.join("no-such-ffmpeg"))
        .output()
        .expect("npr runs");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("error[E0511]") && err.contains("apt install ffmpeg"),
        "{err}"
    );
    assert!(!err.contains("replaying"), "no frame rendered before the error: {err}");
    assert_eq!(std::fs::read_dir(&dir).expect("dir").count(), 0, "nothing written");
}

#[test]
fn a_failing_encoder_leaves_no_video_behind() {
    // An "ffmpeg" that lists the encoder but fails to encode.
    let dir = scratch("sequence-outputs", "failing-ffmpeg");
    let fake = dir.join("ffmpeg");
    std::fs::write(
        &fake,
        "#!/bin/sh\nif [ \"$2\" = -encoders ]; then echo ' V..... libx264 H.264'; exit 0; fi\ncat >/dev/null; echo 'no space left' >&2; exit 1\n",
    )
    .expect("fake ffmpeg");
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).expect("chmod");
    let out = dir.join("out");
    let video = out.join("clip.mp4");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args([
            "render",
            "examples/afterimage.npr",
            "--scene",
            "examples/scenes/orbit.toml",
        ])
        .args(["--size", "16x16", "--frames", "0-3", "-o"])
        .arg(&video)
        .current_dir(root())
        .env("NPR_FFMPEG", &fake)
        .output()
        .expect("npr runs");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("error[E0503]") && err.contains("no space left"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&out)
        .expect("dir")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
