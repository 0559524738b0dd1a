//! Command-line mistakes through the `npr` binary: clap's errors exit 1
//! with E0501 (not clap's 2, which is npr's internal-error code), values
//! outside their domain exit 1 with E0502 or a limit's code, and `--help`
//! and `--version` exit 0. Each runs before any GPU work.

use crate::common;

use common::cli::npr;

/// Exit 1, `error[code]` on stderr, and nothing that looks like a crash.
fn assert_user_error(args: &[&str], code: &str) -> String {
    let o = npr(args);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(1), "npr {args:?}: {stderr}");
    assert!(stderr.contains(&format!("error[{code}]")), "npr {args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

const RENDER: [&str; 5] = [
    "render",
    "examples/toon.npr",
    "--scene",
    "examples/scenes/spot.toml",
    "-o/dev/null",
];

fn render_with(extra: &[&str]) -> Vec<String> {
    RENDER.iter().chain(extra).map(|s| s.to_string()).collect()
}

fn strs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

#[test]
fn help_and_version_exit_0() {
    for args in [
        &["--help"][..],
        &["--version"],
        &["render", "--help"],
        &["help", "compile"],
    ] {
        let o = npr(args);
        assert_eq!(o.status.code(), Some(0), "npr {args:?}");
        assert!(!o.stdout.is_empty(), "npr {args:?} printed nothing");
    }
}

#[test]
fn clap_errors_are_usage_errors_with_clap_message() {
    for (extra, says) in [
        (&["--size", "512"][..], "expected WIDTHxHEIGHT"),
        (&["--size", "0x4"], "at least 1"),
        (&["--message-format", "xml"], "possible values: human, json"),
        (&["--no-such-flag"], "unexpected argument"),
    ] {
        let args = render_with(extra);
        let stderr = assert_user_error(&strs(&args), npr_diag::codes::USAGE);
        assert!(stderr.contains(says), "{extra:?}: {stderr}");
    }
    // With no command, the help is printed, then the error.
    let stderr = assert_user_error(&[], npr_diag::codes::USAGE);
    assert!(stderr.contains("Usage: npr"), "{stderr}");
}

#[test]
fn usage_errors_are_json_when_asked() {
    let o = npr(&["check", "--message-format", "json", "--bogus"]);
    assert_eq!(o.status.code(), Some(1));
    let line = String::from_utf8_lossy(&o.stdout)
        .lines()
        .next()
        .unwrap_or("")
        .to_string();
    let json: serde_json::Value = serde_json::from_str(&line).expect("a JSON diagnostic");
    assert_eq!(json["code"], npr_diag::codes::USAGE);
    assert!(json["message"].as_str().unwrap_or("").contains("--bogus"), "{json}");
}

#[test]
fn render_values_outside_their_domain() {
    for extra in [
        &["--fps", "0"][..],
        &["--fps=-24"],
        &["--fps", "inf"],
        &["--time", "nan"],
        &["--time", "inf"],
        &["--eye", "1"],
        &["--eye", "2"],
    ] {
        let args = render_with(extra);
        assert_user_error(&strs(&args), npr_diag::codes::BAD_ARGUMENT_VALUE);
    }
    // Frame ranges are read after clap, pointing into the argument.
    for (extra, says) in [
        (&["--frames", "9..3"][..], "the frame range 9..3 is empty"),
        (&["--frames", "a..b"], "`a` is not a frame number"),
        (&["--frames", "10-5"], "ends before it starts"),
        (&["--frames", "0-9", "--chunk", "3/2"], "chunk 3 of 2 does not exist"),
    ] {
        let args = render_with(extra);
        let stderr = assert_user_error(&strs(&args), npr_diag::codes::BAD_ARGUMENT_VALUE);
        assert!(stderr.contains(says), "{extra:?}: {stderr}");
    }
}

#[test]
fn sizes_and_frame_counts_past_their_limits() {
    for extra in [&["--size", "16385x16"][..], &["--frames", "0..4000000000"]] {
        let args = render_with(extra);
        assert_user_error(&strs(&args), npr_diag::codes::LIMIT_EXCEEDED);
    }
    // A path-dependent style replays every frame up to `--time`.
    assert_user_error(
        &[
            "render",
            "examples/afterimage.npr",
            "--scene",
            "examples/scenes/orbit.toml",
            "-o/dev/null",
            "--time",
            "1e7",
        ],
        npr_diag::codes::LIMIT_EXCEEDED,
    );
}

#[test]
fn a_stereo_scene_has_eye_1() {
    let o = npr(&[
        "render",
        "examples/lsa_stereo.npr",
        "--scene",
        "examples/scenes/stereo_sphere_on_plane.toml",
        "-o/dev/null",
        "--size",
        "8x8",
        "--eye",
        "1",
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{stderr}");
}

#[test]
fn texgen_argument_errors_have_a_code() {
    for args in [
        &["texgen", "-o", "/dev/null", "--kind", "plasma"][..],
        &["texgen", "-o", "/dev/null", "--kind", "paint"],
        &["texgen", "-o", "/dev/null", "--kind", "paint", "--color", "orange"],
        &["texgen", "-o", "/dev/null", "--size", "0"],
        &["texgen", "-o", "/dev/null", "--channels", "5"],
        &["texgen", "-o", "/dev/null", "--octaves", "13"],
        &["texgen", "-o", "/dev/null", "--frequency", "0"],
    ] {
        assert_user_error(args, npr_diag::codes::BAD_ARGUMENT_VALUE);
    }
    assert_user_error(
        &["texgen", "-o", "README.md/x.png", "--size", "4"],
        npr_diag::codes::CANNOT_WRITE,
    );
}

#[test]
fn compile_onto_an_existing_file_is_refused_before_compiling() {
    assert_user_error(
        &["compile", "examples/toon.npr", "-o", "README.md"],
        npr_diag::codes::CANNOT_WRITE,
    );
}
