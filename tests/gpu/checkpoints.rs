//! State checkpoints (`npr render --checkpoints`): a path-dependent
//! example's sequence rendered in chunks, each starting from the
//! checkpoint the chunk before it wrote, is bit for bit the sequence
//! rendered in one run: every frame (as EXR, f32 exact) and the state left
//! at its end (the checkpoint files, byte for byte). And on the runner's
//! API: restoring a saved state continues the sequence exactly, where a
//! fresh renderer does not.

use crate::common::cli::{npr, scratch, stderr};
use crate::common::{gpu, root};

/// Every example whose frames depend on earlier ones, with a scene it is
/// shown on (`examples/golden/`).
const PATH_DEPENDENT: &[(&str, &str)] = &[
    ("afterimage", "orbit"),
    ("halftone", "cows"),
    ("hatching", "cows"),
    ("painterly", "cows"),
    ("stipple", "cows"),
];

#[test]
fn every_path_dependent_example_is_tested() {
    let mut found = Vec::new();
    let mut files: Vec<_> = std::fs::read_dir(root().join("examples"))
        .expect("examples")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "npr"))
        .collect();
    files.sort();
    for path in files {
        let mut sources = npr_diag::SourceMap::new();
        let c = npr_compiler::compile_file(&path, &mut sources, &Default::default()).unwrap_or_else(|e| {
            panic!("{}: {e:?}", path.display());
        });
        if c.program().manifest.is_path_dependent() {
            found.push(path.file_stem().expect("stem").to_string_lossy().into_owned());
        }
    }
    let listed: Vec<&str> = PATH_DEPENDENT.iter().map(|(s, _)| *s).collect();
    assert_eq!(found, listed, "add a new path-dependent example to PATH_DEPENDENT");
}

fn strs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

fn run(args: &[&str]) -> String {
    let o = npr(args);
    let err = stderr(&o);
    assert!(o.status.success(), "npr {args:?}:\n{err}");
    err
}

#[test]
fn chunks_from_checkpoints_are_bit_identical_to_one_run() {
    for (style, scene) in PATH_DEPENDENT {
        let dir = scratch("checkpoints", style);
        let s = |p: &str| dir.join(p).to_str().expect("utf-8").to_string();
        let base = |out: &str| {
            vec![
                "render".to_string(),
                format!("examples/{style}.npr"),
                "--scene".into(),
                format!("examples/scenes/{scene}.toml"),
                "--size".into(),
                "48x40".into(),
                "-o".into(),
                s(out),
            ]
        };
        let with = |out: &str, more: &[&str]| {
            let mut a = base(out);
            a.extend(more.iter().map(|m| m.to_string()));
            a
        };
        // One run, writing the state at frames 3 and 6.
        let one = with(
            "one/f_{frame}.exr",
            &[
                "--frames",
                "0..6",
                "--checkpoints",
                &s("one_ck"),
                "--checkpoint-every",
                "3",
            ],
        );
        run(&strs(&one));
        // Two chunks as a farm gives them: 0-2, then chunk 1 of 2 of 0-5.
        let first = with(
            "chunks/f_{frame}.exr",
            &["--frames", "0-2", "--checkpoints", &s("chunk_ck")],
        );
        run(&strs(&first));
        let second = with(
            "chunks/f_{frame}.exr",
            &["--frames", "0-5", "--chunk", "1/2", "--checkpoints", &s("chunk_ck")],
        );
        let log = run(&strs(&second));
        assert!(
            log.contains("starting from checkpoint") && log.contains("(frame 3)"),
            "{style}: {log}"
        );
        assert!(!log.contains("replaying"), "{style}: the second chunk replayed: {log}");
        for f in 0..6 {
            let name = format!("f_{f:04}.exr");
            let (a, b) = (dir.join("one").join(&name), dir.join("chunks").join(&name));
            assert!(
                std::fs::read(&a).expect("one run's frame") == std::fs::read(&b).expect("chunk's frame"),
                "{style}: frame {f} differs between {} and {}",
                a.display(),
                b.display()
            );
        }
        for f in [3, 6] {
            let name = format!("frame_{f:06}.nprstate");
            let (a, b) = (dir.join("one_ck").join(&name), dir.join("chunk_ck").join(&name));
            assert!(
                std::fs::read(&a).expect("one run's state") == std::fs::read(&b).expect("chunks' state"),
                "{style}: the state at frame {f} differs"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn a_restored_state_continues_the_sequence_where_a_fresh_renderer_does_not() {
    let mut sources = npr_diag::SourceMap::new();
    let program = npr_compiler::compile_file(
        &root().join("examples/afterimage.npr"),
        &mut sources,
        &Default::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"))
    .program();
    let scene = npr_runner::scene::load_scene(&root().join("examples/scenes/orbit.toml"), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let spec = |f: u32| npr_runner::FrameSpec::animated(40, 32, f, npr_runner::FrameSpec::DEFAULT_FPS, 0);
    let (device, queue) = (&gpu().device, &gpu().queue);
    let mut one = npr_runner::Renderer::new(device, queue, &program, &scene).expect("renderer");
    for f in 0..4 {
        one.render(&scene, &spec(f)).expect("frame");
    }
    let saved = one.save_state().expect("save");
    let mut restored = npr_runner::Renderer::new(device, queue, &program, &scene).expect("renderer");
    restored.restore_state(&saved).expect("restore");
    assert_eq!(
        restored.save_state().expect("save again"),
        saved,
        "restore puts back what was saved"
    );
    let mut fresh = npr_runner::Renderer::new(device, queue, &program, &scene).expect("renderer");
    for f in 4..7 {
        one.render(&scene, &spec(f)).expect("frame");
        restored.render(&scene, &spec(f)).expect("frame");
        fresh.render(&scene, &spec(f)).expect("frame");
        let expected = one.read_output().expect("read").bytes;
        assert!(
            restored.read_output().expect("read").bytes == expected,
            "frame {f} differs after restoring"
        );
        assert!(
            fresh.read_output().expect("read").bytes != expected,
            "frame {f}: the state should matter"
        );
    }
}

/// A farm's first pass (`--checkpoints` with `--checkpoint-every`, no `-o`)
/// writes the checkpoints and no image: `npr render` without `-o` writes
/// `<style>.png` only when nothing else was asked for.
#[test]
fn a_checkpoint_pass_without_an_output_writes_no_images() {
    let dir = scratch("checkpoints", "pass_without_output");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args([
            "render",
            root().join("examples/afterimage.npr").to_str().expect("utf-8"),
        ])
        .args([
            "--scene",
            root().join("examples/scenes/orbit.toml").to_str().expect("utf-8"),
        ])
        .args([
            "--size",
            "24x16",
            "--frames",
            "0-3",
            "--checkpoints",
            "ck",
            "--checkpoint-every",
            "2",
        ])
        .current_dir(&dir)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr");
    assert!(o.status.success(), "{}", stderr(&o));
    let mut written: Vec<String> = std::fs::read_dir(&dir)
        .expect("scratch")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    assert_eq!(written, ["ck"], "only the checkpoint directory is written");
    let checkpoints = std::fs::read_dir(dir.join("ck")).expect("checkpoints").count();
    assert!(checkpoints >= 2, "checkpoints at frames 2 and 4: {checkpoints}");
}
