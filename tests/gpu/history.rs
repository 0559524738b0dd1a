//! History reads (`previous(pass.target)`) on the real runner: the values
//! they see frame after frame against exact counts and a CPU f64 recurrence,
//! resets, partial re-renders, and the time-jump rule (a path-dependent
//! frame rendered alone equals the same frame of a sequence).
//!
//! The afterimage golden (`examples/golden/afterimage_orbit.png`, frame 8)
//! is a sidecar test, `examples/afterimage.tests.toml`.

use npr_runner::{FrameSpec, Renderer, StyleProgram};

use crate::common;
use common::{gpu, root};

fn program(text: &str) -> StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    let c = npr_compiler::compile_source("h.npr", text, root(), &mut sources, &Default::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    c.program()
}

fn scene(path: &str) -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&root().join(path), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn spec(size: u32, frame: u32) -> FrameSpec {
    FrameSpec::animated(size, size, frame, FrameSpec::DEFAULT_FPS, 0)
}

/// Every texel's red channel.
fn reds(img: &npr_runner::TargetImage) -> Vec<f32> {
    img.to_rgba_f32().iter().map(|t| t[0]).collect()
}

const COUNTER: &str =
    "style \"Counter\"\npass acc: image() {\n  out c: r32float = previous(acc.c) + 1.0\n}\noutput acc.c\n";

#[test]
fn a_self_read_counts_frames_exactly_and_restarts_on_resize() {
    let program = program(COUNTER);
    assert!(program.manifest.is_path_dependent());
    let scene = scene("examples/scenes/spheres.toml");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    for n in 1..=5u32 {
        r.render(&scene, &spec(16, n - 1)).expect("frame");
        let v = reds(&r.read_output().expect("read"));
        assert!(v.iter().all(|x| *x == n as f32), "frame {n}: {:?}", &v[..4]);
    }
    // A partial re-render of the same frame neither begins a frame nor
    // changes the history: it reads the same previous value.
    let again = r.render_until_target(&scene, &spec(16, 4), 0).expect("partial");
    assert!(reds(&again).iter().all(|x| *x == 5.0));
    r.render(&scene, &spec(16, 5)).expect("frame");
    assert!(reds(&r.read_output().expect("read")).iter().all(|x| *x == 6.0));
    // New textures (another size) hold no history: frame 0 again.
    r.render(&scene, &spec(24, 0)).expect("resized");
    assert!(reds(&r.read_output().expect("read")).iter().all(|x| *x == 1.0));
    assert_eq!(r.frames_begun(), 1);
}

#[test]
fn a_pass_reads_the_previous_frame_of_a_pass_that_runs_after_it() {
    // `a` runs first and sees last frame's `b`; `b` adds one: b_k = k + 1.
    let text = "style \"Echo\"\npass a: image() {\n  out c: r32float = previous(b.c)\n}\npass b: image(a) {\n  out c: r32float = a.c + 1.0\n}\noutput b.c\n";
    let program = program(text);
    let scene = scene("examples/scenes/spheres.toml");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    for k in 0..4u32 {
        r.render(&scene, &spec(8, k)).expect("frame");
        assert!(reds(&r.read_output().expect("read"))
            .iter()
            .all(|x| *x == (k + 1) as f32));
    }
}

/// The afterimage example against the CPU recurrence it implements,
/// final_k = mix(shade_k, final_{k-1}, p) with final_{-1} = 0, evaluated in
/// f64 from the GPU's own `shade` target and rounded to 8 bits each frame as
/// the rgba8unorm target does.
#[test]
fn afterimage_matches_its_recurrence() {
    let mut sources = npr_diag::SourceMap::new();
    let c = npr_compiler::compile_file(
        &root().join("examples/afterimage.npr"),
        &mut sources,
        &Default::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"));
    let program = c.program();
    let persistence = 0.8;
    let scene = scene("examples/scenes/orbit.toml");
    let shade = program
        .manifest
        .targets
        .iter()
        .position(|t| t.name == "shade.color")
        .expect("shade target");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    let size = 96;
    let mut expected: Vec<[f64; 4]> = vec![[0.0; 4]; (size * size) as usize];
    let mut worst = 0.0f64;
    for k in 0..=8u32 {
        r.render(&scene, &spec(size, k)).expect("frame");
        let s = r.read_target(shade).expect("shade").to_rgba_f32();
        let out = r.read_output().expect("final").to_rgba_f32();
        for ((e, s), o) in expected.iter_mut().zip(&s).zip(&out) {
            for ch in 0..4 {
                let v = s[ch] as f64 * (1.0 - persistence) + e[ch] * persistence;
                e[ch] = (v * 255.0).round() / 255.0;
                worst = worst.max((e[ch] - o[ch] as f64).abs());
            }
        }
        // The CPU side follows the GPU's own quantized value from here, so
        // rounding differences do not compound.
        for (e, o) in expected.iter_mut().zip(&out) {
            *e = o.map(|x| x as f64);
        }
    }
    assert!(worst <= 1.0 / 255.0 + 1e-6, "worst channel difference {worst}");
}

/// `npr render --time t` of a path-dependent style replays frames 0..=t·fps:
/// the image equals frame n of `--frames 0..n+1`, byte for byte.
#[test]
fn a_frame_rendered_alone_equals_the_same_frame_of_a_sequence() {
    let dir = std::env::temp_dir().join(format!("npr-history-{}", std::process::id()));
    let (in_sequence, alone, first) =
        common::sequence_and_alone("examples/afterimage.npr", "examples/scenes/orbit.toml", &dir);
    assert_eq!(alone, in_sequence, "frame 6 alone differs from frame 6 of the sequence");
    // And history matters: frame 6 is not what frame 6 would be without its past.
    assert_ne!(first, in_sequence);
}
