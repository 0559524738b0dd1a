//! Host input sequences through the `npr` binary (issue 47): `--inputs
//! 'shots/{frame:04}.exr'` and `--input NAME='b_{frame}.png'` with
//! `--frames`, each frame rendered from its own files, frame numbers in
//! the pattern as `-o` writes them. The files are small images the tests
//! write with the crates the runner reads them with; each frame's values
//! are known, so every output frame is checked against what its inputs
//! give. Also: a path-dependent style's history goes on across a
//! sequence's frames and across chunks from checkpoints, and a frame whose
//! inputs do not load is not written.

use crate::common::cli::{npr, scratch, stderr};
use std::path::Path;

/// A style over a colour and a depth input: red is the colour's, green
/// the depth over 10 m.
const COLOUR_AND_DEPTH: &str = "style \"Seq\"\ntexture c = input(color, linear)\ntexture z = input(depth)\n\
    pass p: image() {\n  out o: rgba8unorm = vec4(c.r, z.r / 10.0, 0.0, 1.0)\n}\noutput p.o\n";

/// Blender's layout: one part whose channels are `ViewLayer.Combined.R`,
/// `.G`, `.B`, `.A` and `ViewLayer.Depth.Z`, here of one value each.
fn blender_exr(path: &Path, (w, h): (usize, usize), red: f32, depth: f32) {
    use exr::prelude::*;
    let flat = |v: f32| FlatSamples::F32(vec![v; w * h]);
    let list: Vec<AnyChannel<FlatSamples>> = vec![
        AnyChannel::new("ViewLayer.Combined.R", flat(red)),
        AnyChannel::new("ViewLayer.Combined.G", flat(0.0)),
        AnyChannel::new("ViewLayer.Combined.B", flat(0.0)),
        AnyChannel::new("ViewLayer.Combined.A", flat(1.0)),
        AnyChannel::new("ViewLayer.Depth.Z", flat(depth)),
    ];
    let layer = Layer::new(
        (w, h),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(list.into()),
    );
    Image::from_layer(layer).write().to_file(path).expect("write exr");
}

fn style_file(dir: &Path, text: &str) -> String {
    let path = dir.join("style.npr");
    std::fs::write(&path, text).expect("write style");
    path.display().to_string()
}

fn run(args: &[&str]) -> String {
    let o = npr(args);
    let err = stderr(&o);
    assert!(o.status.success(), "npr {args:?}:\n{err}");
    err
}

fn rgba(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// Every pixel of `img` within 1 of `want` in each of r, g, b.
fn assert_all(img: &image::RgbaImage, want: [f64; 3], what: &str) {
    for p in img.pixels() {
        for (c, (got, want)) in p.0.iter().zip(want).enumerate() {
            assert!(
                (f64::from(*got) - want).abs() <= 1.0,
                "{what}: channel {c} is {got}, expected {want:.1}"
            );
        }
    }
}

#[test]
fn a_multi_layer_exr_sequence_renders_each_frame_from_its_own_file() {
    let dir = scratch("input_sequences", "exr");
    let style = style_file(&dir, COLOUR_AND_DEPTH);
    // Frames 1-3, as Blender numbers them: red 0.2·k, depth 1.5·k m.
    for k in 1..=3u32 {
        blender_exr(
            &dir.join(format!("shot_{k:04}.exr")),
            (6, 4),
            0.2 * k as f32,
            1.5 * k as f32,
        );
    }
    let shots = dir.join("shot_{frame:04}.exr").display().to_string();
    let out = dir.join("out/{frame:02}.png").display().to_string();
    std::fs::create_dir_all(dir.join("out")).expect("out dir");
    run(&["render", &style, "--inputs", &shots, "--frames", "1-3", "-o", &out]);
    for k in 1..=3u32 {
        let img = rgba(&dir.join(format!("out/{k:02}.png")));
        assert_eq!(img.dimensions(), (6, 4), "the inputs' size");
        let want = [0.2 * k as f64 * 255.0, 0.15 * k as f64 * 255.0, 0.0];
        assert_all(&img, want, &format!("frame {k}"));
    }
    assert!(!dir.join("out/00.png").exists() && !dir.join("out/04.png").exists());
}

/// A style that keeps half of its previous frame: path-dependent, so its
/// history must go on from one input frame to the next.
const TRAIL: &str = "style \"Trail\"\ntexture c = input(color, display)\n\
    pass final: image() {\n  out color: rgba8unorm = mix(c, previous(final.color), 0.5)\n}\noutput final.color\n";

/// Frame k's colour: red 40 + 50·k (8-bit, display-referred).
fn red(k: u32) -> u8 {
    (40 + 50 * k) as u8
}

#[test]
fn a_png_sequence_keeps_the_history_and_chunks_from_checkpoints_match_one_run() {
    let dir = scratch("input_sequences", "trail");
    let style = style_file(&dir, TRAIL);
    for k in 0..4u32 {
        image::RgbaImage::from_pixel(4, 4, image::Rgba([red(k), 0, 0, 255]))
            .save(dir.join(format!("b_{k:04}.png")))
            .expect("write png");
    }
    let beauty = format!("c={}", dir.join("b_{frame}.png").display());
    let s = |p: &str| dir.join(p).display().to_string();
    run(&[
        "render",
        &style,
        "--input",
        &beauty,
        "--frames",
        "0-3",
        "-o",
        &s("one_{frame}.png"),
    ]);
    // The recurrence the style writes, in 8 bits: v_k = (c_k + v_{k-1}) / 2,
    // v_{-1} = 0 (`previous` reads zero on the first frame).
    let mut v = 0.0f64;
    for k in 0..4u32 {
        v = ((red(k) as f64 + v) / 2.0).round();
        assert_all(
            &rgba(&dir.join(format!("one_{k:04}.png"))),
            [v, 0.0, 0.0],
            &format!("frame {k}"),
        );
    }
    // Two chunks, the second from the checkpoint the first wrote.
    let ck = s("ck");
    run(&[
        "render",
        &style,
        "--input",
        &beauty,
        "--frames",
        "0-1",
        "--checkpoints",
        &ck,
        "-o",
        &s("two_{frame}.png"),
    ]);
    let err = run(&[
        "render",
        &style,
        "--input",
        &beauty,
        "--frames",
        "2-3",
        "--checkpoints",
        &ck,
        "-o",
        &s("two_{frame}.png"),
    ]);
    assert!(err.contains("starting from checkpoint"), "{err}");
    for k in 0..4u32 {
        let (one, two) = (format!("one_{k:04}.png"), format!("two_{k:04}.png"));
        assert_eq!(
            rgba(&dir.join(&one)).into_raw(),
            rgba(&dir.join(&two)).into_raw(),
            "frame {k}: chunked differs from one run"
        );
    }
}

#[test]
fn a_frame_whose_inputs_do_not_load_is_not_written() {
    let dir = scratch("input_sequences", "half");
    let style = style_file(&dir, COLOUR_AND_DEPTH);
    for k in 0..3u32 {
        let depth = if k == 2 { f32::NAN } else { 2.0 };
        blender_exr(&dir.join(format!("shot_{k:04}.exr")), (4, 4), 0.5, depth);
    }
    let shots = dir.join("shot_{frame}.exr").display().to_string();
    let out = dir.join("out_{frame}.png").display().to_string();
    let o = npr(&["render", &style, "--inputs", &shots, "--frames", "0..3", "-o", &out]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("error[E0420]") && err.contains("shot_0002.exr") && err.contains("`z`"),
        "{err}"
    );
    assert!(dir.join("out_0000.png").is_file() && dir.join("out_0001.png").is_file());
    assert!(
        !dir.join("out_0002.png").exists(),
        "frame 2 was written from inputs that did not load"
    );
}

#[test]
fn without_frames_a_pattern_reads_the_frame_at_the_time() {
    let dir = scratch("input_sequences", "time");
    let style = style_file(&dir, COLOUR_AND_DEPTH);
    for k in 0..3u32 {
        blender_exr(&dir.join(format!("shot_{k}.exr")), (4, 4), 0.25 * k as f32, 5.0);
    }
    let shots = dir.join("shot_{frame:01}.exr").display().to_string();
    let out = dir.join("at.png").display().to_string();
    // --time 0.5 at 4 fps is frame 2.
    run(&[
        "render", &style, "--inputs", &shots, "--time", "0.5", "--fps", "4", "-o", &out,
    ]);
    assert_all(&rgba(Path::new(&out)), [0.5 * 255.0, 0.5 * 255.0, 0.0], "frame 2");
}
