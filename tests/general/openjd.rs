//! The Open Job Description template `farm/openjd/npr-render.yaml`, run by
//! the reference implementation (`openjd run`, PyPI `openjd-cli`): its
//! Checkpoints step, then its Render step in chunks (TASK_CHUNKING), each
//! chunk starting from a checkpoint. The frames must be byte for byte those
//! of one `npr render` of the whole range.

use crate::common::cli::{npr, scratch, stderr};
use crate::common::root;

/// The `openjd` program; fails naming the package when it is missing.
fn openjd() -> &'static str {
    let ok = std::process::Command::new("openjd")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "this test runs the job template with openjd: install it with `pip install openjd-cli`"
    );
    "openjd"
}

#[test]
fn the_job_template_renders_the_frames_of_one_run() {
    let dir = scratch("openjd", "afterimage");
    let path = |p: &str| dir.join(p).to_str().expect("utf-8").to_string();
    let style = root().join("examples/afterimage.npr");
    let scene = root().join("examples/scenes/orbit.toml");
    let params = [
        format!("Npr={}", env!("CARGO_BIN_EXE_npr")),
        format!("Style={}", style.display()),
        format!("Scene={}", scene.display()),
        "Frames=0-9".into(),
        "ChunkSize=4".into(),
        "Size=48x40".into(),
        format!("Output={}", path("farm/f_{frame}.png")),
        format!("CheckpointDir={}", path("ck")),
    ];
    let mut job = std::process::Command::new(openjd());
    job.args([
        "run",
        "farm/openjd/npr-render.yaml",
        "--step",
        "Render",
        "--run-dependencies",
    ])
    .current_dir(root());
    for p in &params {
        job.args(["-p", p]);
    }
    let o = job.output().expect("openjd runs");
    let log = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "openjd run failed:\n{log}\n{}", stderr(&o));
    // openjd chooses the chunks (ChunkSize is their default size; it
    // balances them); every chunk after the first started from a
    // checkpoint, of the first pass or of the chunk before it.
    let chunks = log.matches("Frame(CHUNK[INT]) = ").count();
    assert!(chunks >= 3, "expected the range in chunks:\n{log}");
    assert_eq!(
        log.matches("note: starting from checkpoint").count(),
        chunks - 1,
        "{log}"
    );
    assert!(!log.contains("replaying"), "a chunk replayed:\n{log}");

    let one = npr(&[
        "render",
        style.to_str().expect("utf-8"),
        "--scene",
        scene.to_str().expect("utf-8"),
        "--size",
        "48x40",
        "--frames",
        "0-9",
        "-o",
        &path("one/f_{frame}.png"),
    ]);
    assert!(one.status.success(), "{}", stderr(&one));
    for f in 0..10 {
        let name = format!("f_{f:04}.png");
        let farm = std::fs::read(dir.join("farm").join(&name)).unwrap_or_else(|e| panic!("{name} from the job: {e}"));
        let single = std::fs::read(dir.join("one").join(&name)).expect("single run's frame");
        assert!(farm == single, "frame {f} differs between the job and one run");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
