//! `npr watch` through the binary on a temp copy of a style: every save
//! (by rename, as editors do) re-renders `-o`; a broken save prints the
//! diagnostic and keeps the last good image byte for byte; fixing it renders
//! again. Images are checked against `npr render` of the same input.

use crate::common;

use common::live::{save_by_rename, Live};
use std::path::Path;

fn render(style: &Path, sets: &[&str], out: &Path) -> Vec<u8> {
    let mut args = vec![
        "render",
        style.to_str().expect("utf-8"),
        "--scene",
        "examples/scenes/spot.toml",
        "--size",
        "64x64",
        "-o",
        out.to_str().expect("utf-8"),
    ];
    args.extend_from_slice(sets);
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(&args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("npr render");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read(out).expect("render output")
}

#[test]
fn saves_re_render_a_broken_save_keeps_the_last_image_and_a_fix_recovers() {
    let dir = common::live::scratch("watch", "cycle");
    let style = dir.join("toon.npr");
    let original = std::fs::read_to_string("examples/toon.npr").expect("toon.npr");
    std::fs::write(&style, &original).expect("copy style");
    let out = dir.join("out.png");
    let mut w = Live::start(&[
        "watch",
        style.to_str().expect("utf-8"),
        "--scene",
        "examples/scenes/spot.toml",
        "--size",
        "64x64",
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    w.wait_for("watch: build 1 done");
    let first = std::fs::read(&out).expect("first image");
    assert_eq!(
        first,
        render(&style, &[], &dir.join("ref0.png")),
        "watch renders as npr render does"
    );

    let edited = original.replace("param bands: int = 3", "param bands: int = 5");
    assert_ne!(edited, original);
    save_by_rename(&style, &edited);
    w.wait_for("watch: build 2 done");
    let second = std::fs::read(&out).expect("second image");
    assert_ne!(second, first, "the edit must change the image");
    assert_eq!(second, render(&style, &[], &dir.join("ref1.png")));

    save_by_rename(&style, &edited.replace("output", "outptu"));
    let printed = w.wait_for("watch: build 3 done").join("\n");
    assert!(printed.contains("error[E0"), "the diagnostic is printed:\n{printed}");
    assert!(printed.contains("toon.npr:"), "it points into the file:\n{printed}");
    assert_eq!(
        std::fs::read(&out).expect("kept image"),
        second,
        "a broken save keeps the last good image"
    );

    save_by_rename(&style, &original);
    w.wait_for("watch: build 4 done");
    assert_eq!(
        std::fs::read(&out).expect("recovered image"),
        first,
        "fixing the file renders again"
    );
    assert!(
        w.child.try_wait().expect("status").is_none(),
        "watch never exits on a bad save"
    );
}
