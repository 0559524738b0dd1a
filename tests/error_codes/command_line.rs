//! Error codes of the command line (E05xx) through the `npr` binary, and
//! internal errors (E9001).

use super::*;

#[test]
fn e0501_usage_error_keeps_clap_message() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--size",
            "big",
        ],
        &scratch("e0501"),
    );
    assert!(r.contains("invalid value 'big' for '--size <SIZE>'"), "{r}");
    check("E0501", (d, r));
}

#[test]
fn e0502_bad_argument_value() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--fps",
            "0",
        ],
        &scratch("e0502"),
    );
    check("E0502", (d, r));
}

#[test]
fn e0502_an_eye_the_scene_does_not_have() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--eye",
            "1",
        ],
        &scratch("e0502-eye"),
    );
    check_case("E0502", "E0502_eye", (d, r));
}

#[test]
fn e0503_compile_onto_an_existing_file() {
    let dir = scratch("e0503");
    let file = dir.join("taken");
    std::fs::write(&file, "not a directory").expect("write");
    let (d, r) = cli_errors(
        &["compile", "examples/toon.npr", "-o", file.to_str().expect("utf-8 path")],
        &dir,
    );
    check("E0503", (d, r));
}

#[test]
fn e0503_an_image_extension_npr_does_not_write() {
    let dir = scratch("e0503-ext");
    let file = dir.join("a.jpg");
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "-o",
            file.to_str().expect("utf-8 path"),
        ],
        &dir,
    );
    assert!(r.contains("name the output .png or .exr"), "{r}");
    assert!(!file.exists(), "nothing is written");
    check_case("E0503", "E0503_extension", (d, r));
}

#[test]
fn e0504_bad_compiled_directory() {
    let dir = scratch("e0504");
    let (d, r) = cli_errors(
        &[
            "render",
            "--compiled",
            dir.to_str().expect("utf-8 path"),
            "--scene",
            "examples/scenes/spot.toml",
        ],
        &dir,
    );
    check("E0504", (d, r));
}

#[test]
fn e0505_no_gpu_device() {
    // No machine here lacks an adapter (lavapipe, then GL): render the
    // diagnostic the CLI prints for one.
    let rendered = npr_diag::diagnostic::render(
        &[npr_runner::DeviceError::NoAdapter.to_diagnostic()],
        &SourceMap::new(),
        false,
    );
    check(
        "E0505",
        (vec![npr_runner::DeviceError::NoAdapter.to_diagnostic()], rendered),
    );
}

#[test]
fn e0510_a_device_without_a_limit_the_style_needs() {
    // Refused by a real device made with WebGPU's defaults in
    // tests/gpu/device_needs.rs; here the runner's check of the same style
    // against WebGPU's default limits, and its rendered message.
    let text = style("pass g: render(scene) {\n  out c: rgba16float = vec4(normal, 1.0)\n}\npass b: image(g) {\n  schedule: tiled\n  let v = gaussian(g.c, sigma: 1px, axis: x)\n  out o1: rgba8unorm = v\n  out o2: rgba8unorm = v\n  out o3: rgba16float = v\n  out o4: r32float = v.r\n  out o5: rgba32float = v\n}\npass f: image(b) {\n  out c: rgba8unorm = b.o1 + b.o2 + b.o3 + vec4(b.o4) + b.o5\n}\noutput f.c\n");
    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_source(
        "case.npr",
        &text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"));
    let d = npr_runner::device_needs::unmet(
        &compiled.manifest,
        wgpu::Features::empty(),
        &wgpu::Limits::default(),
        "this device",
    );
    let rendered = npr_diag::diagnostic::render(&d, &SourceMap::new(), false);
    assert!(rendered.contains("pass `b` needs"), "{rendered}");
    check("E0510", (d, rendered));
}

#[test]
fn e0506_a_benchmark_that_cannot_run() {
    let dir = scratch("e0506");
    let missing = dir.join("missing.npr");
    let (d, r) = cli_errors(
        &[
            "bench",
            "compile",
            missing.to_str().expect("utf-8 path"),
            "--iterations",
            "1",
        ],
        &dir,
    );
    check("E0506", (d, r));
}

#[test]
fn e0507_a_studio_port_in_use() {
    // Hold a port, then ask the studio for it: it must refuse at once.
    let taken = std::net::TcpListener::bind("127.0.0.1:0").expect("bind a port");
    let port = taken.local_addr().expect("address").port().to_string();
    let (d, r) = cli_errors(
        &[
            "studio",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--port",
            &port,
        ],
        &scratch("e0507"),
    );
    let r = r.replace(&port, "<port>");
    assert!(r.contains("--port 0"), "{r}");
    check("E0507", (d, r));
}

#[test]
fn e0404_frames_past_the_frame_limit() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--frames",
            "0..1000000",
        ],
        &scratch("e0404-frames"),
    );
    check_case("E0404", "E0404_frames", (d, r));
}

/// `npr render toon on spot` with `extra` arguments, expecting an error.
fn render_errors(extra: &[&str], case: &str) -> (Vec<Diagnostic>, String) {
    let mut args = vec!["render", "examples/toon.npr", "--scene", "examples/scenes/spot.toml"];
    args.extend_from_slice(extra);
    cli_errors(&args, &scratch(case))
}

#[test]
fn e0502_a_frame_range_that_ends_before_it_starts() {
    let (d, r) = render_errors(&["--frames", "10-5"], "e0502-frames");
    assert!(r.contains("--frames:1:1"), "the span points into the argument: {r}");
    check_case("E0502", "E0502_frames_backwards", (d, r));
}

#[test]
fn e0502_a_frame_range_that_is_not_a_number() {
    let (d, r) = render_errors(&["--frames", "0-x"], "e0502-frames-nan");
    assert!(r.contains("--frames:1:3"), "{r}");
    check_case("E0502", "E0502_frames_not_a_number", (d, r));
}

#[test]
fn e0502_a_chunk_past_the_last() {
    let (d, r) = render_errors(&["--frames", "0-47", "--chunk", "3/2"], "e0502-chunk");
    assert!(r.contains("--chunk:1:1"), "{r}");
    check_case("E0502", "E0502_chunk_past_the_last", (d, r));
}

#[test]
fn e0502_more_chunks_than_frames() {
    let (d, r) = render_errors(&["--frames", "0..3", "--chunk", "0/4"], "e0502-chunk-count");
    assert!(r.contains("--chunk:1:3"), "{r}");
    check_case("E0502", "E0502_more_chunks_than_frames", (d, r));
}

#[test]
fn e0501_a_chunk_without_its_range() {
    let (d, r) = render_errors(&["--chunk", "0/2"], "e0501-chunk");
    assert!(r.contains("--frames"), "{r}");
    check_case("E0501", "E0501_chunk_without_frames", (d, r));
}

#[test]
fn e0511_a_video_without_ffmpeg() {
    let dir = scratch("e0511");
    let clip = dir.join("clip.mp4");
    let (d, r) = cli_errors_with_env(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--frames",
            "0-3",
            "-o",
            clip.to_str().expect("utf-8"),
        ],
        &dir,
        &[("NPR_FFMPEG", &dir.join("no-ffmpeg"))],
    );
    assert!(!clip.exists());
    check("E0511", (d, r));
}

/// `npr render afterimage on spot` at `size` for `frames`, with checkpoints
/// in `ck` and the frames beside it (not in the repository, where a render
/// without `-o` would write them).
fn afterimage_chunk(size: &str, frames: &str, ck: &Path) -> Vec<String> {
    let out = ck.with_file_name("f_{frame}.png");
    [
        "render",
        "examples/afterimage.npr",
        "--scene",
        "examples/scenes/spot.toml",
        "--size",
        size,
        "--frames",
        frames,
        "--checkpoints",
        ck.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
    ]
    .map(String::from)
    .to_vec()
}

/// The checkpoints of a first chunk (frames 0-2 at 16x16) in `dir/ck`,
/// which the next chunk starts from.
fn first_chunk_checkpoints(dir: &Path) -> std::path::PathBuf {
    let ck = dir.join("ck");
    let _ = std::fs::remove_dir_all(&ck);
    let made = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(afterimage_chunk("16x16", "0-2", &ck))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run npr");
    assert!(made.status.success(), "{}", String::from_utf8_lossy(&made.stderr));
    ck
}

#[test]
fn e0512_a_checkpoint_of_another_size() {
    let dir = scratch("e0512");
    let ck = first_chunk_checkpoints(&dir);
    let args = afterimage_chunk("24x16", "3-5", &ck);
    let (d, r) = cli_errors(&args.iter().map(String::as_str).collect::<Vec<_>>(), &dir);
    assert!(r.contains("16x16") && r.contains("24x16"), "{r}");
    check("E0512", (d, r));
}

#[test]
fn e0513_a_truncated_checkpoint() {
    let dir = scratch("e0513");
    let ck = first_chunk_checkpoints(&dir);
    let file = ck.join("frame_000003.nprstate");
    let bytes = std::fs::read(&file).expect("checkpoint written");
    std::fs::write(&file, &bytes[..bytes.len() / 2]).expect("truncate");
    let args = afterimage_chunk("16x16", "3-5", &ck);
    let (d, r) = cli_errors(&args.iter().map(String::as_str).collect::<Vec<_>>(), &dir);
    check("E0513", (d, r));
}

#[test]
fn e9001_internal_error_names_the_npr_span() {
    // Internal errors come from compiler bugs, so none can be triggered from
    // valid input; render one the way the pipeline builds it.
    let mut sources = SourceMap::new();
    let file = sources.add("case.npr", SIMPLE_PASS);
    let err = npr_compiler::InternalError {
        message: "emitted WGSL for pass `p` failed naga validation".into(),
        detail: "error: example naga message".into(),
        span: Some(npr_diag::Span::new(file, 0, 6)),
        wgsl: Some("// the rejected module".into()),
    };
    let rendered = npr_diag::diagnostic::render(&[err.to_diagnostic()], &sources, false);
    assert!(rendered.contains("case.npr:1:1"), "{rendered}");
    insta::assert_snapshot!("E9001", rendered);
}

#[test]
fn e9001_without_wgsl_names_an_impossible_state() {
    // Internal errors outside validation (allocate, manifest, resolve's
    // stdlib defaults) carry no module: the label says what happened.
    let mut sources = SourceMap::new();
    let file = sources.add("case.npr", SIMPLE_PASS);
    let err = npr_compiler::InternalError {
        message: "the output target has no allocated target".into(),
        detail: "`p.color` is not among the allocated targets".into(),
        span: Some(npr_diag::Span::new(file, 0, 6)),
        wgsl: None,
    };
    let rendered = npr_diag::diagnostic::render(&[err.to_diagnostic()], &sources, false);
    assert!(rendered.contains("E9001"), "{rendered}");
    assert!(
        rendered.contains("the compiler reached an impossible state here"),
        "{rendered}"
    );
}
