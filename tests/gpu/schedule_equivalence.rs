//! Every schedule gives the naive schedule's image (issue 14): each example
//! style on its scene, the analytic contour scenes, odd image sizes (1×1,
//! 3×7, 17×513) and scale-½ passes, compiled `--schedule naive`, `auto`,
//! `tiled` and `recompute`, rendered through the real runner, and compared.
//!
//! The bound is **bit-identical output texels** (the output target read back
//! as f32, compared by bits). Fusion computes the skipped target's value
//! inline and repeats its format's rounding (`Conversion::Stored`), so no
//! float is computed in another order; a tiled pass runs the same WGSL per
//! pixel, reads the same texels (from workgroup memory) and rounds its
//! storage writes as the device rounds attachment stores; a recomputed
//! target's texels are its producer's WGSL at each texel, rounded as the
//! store would round them. A difference is a bug, not noise.
//! On failure both images and their diff go to
//! `target/npr-test-output/schedule/`.
//!
//! A style's own `schedule:` settings are held to the same bound: LSA
//! contours with passes forced `naive` and `tiled`, under every
//! `--schedule`, against the unannotated style compiled `naive`.
//!
//! Path-dependent styles (history, per-object state) are compared on their
//! fourth frame, so `previous(...)` and state have been read back and
//! written under both schedules.

use npr_compiler::schedule::Schedule;
use npr_lab::harness::{compare_with_golden_file, Tolerance};
use npr_runner::{FrameSpec, Renderer, StyleProgram};
use std::path::{Path, PathBuf};

use crate::common;
use common::{gpu, root};

/// Every example style with the scenes it is shown on (README, goldens).
/// `every_example_is_covered` fails when an example is missing here.
const EXAMPLES: &[(&str, &str)] = &[
    ("afterimage", "orbit"),
    ("age_of_sail", "age_of_sail"),
    ("artmap_gallery", "gallery"),
    ("edge_breakup", "spot"),
    ("halftone", "cows"),
    ("hidden_lines", "hidden_lines"),
    ("hatching", "patched_cow"),
    ("live_contour", "spheres"),
    ("lsa_base", "spheres"),
    ("lsa_base", "spot"),
    ("lsa_contours", "spheres"),
    ("lsa_contours", "spot"),
    ("lsa_stereo", "stereo_sphere_on_plane"),
    ("metatexture", "spot"),
    ("object_centroids", "orbit"),
    ("ocean", "ocean"),
    ("outline", "spot"),
    ("overlay_lines", "spheres"),
    ("painterly", "cows"),
    ("rounded_shadows", "spot"),
    ("sobel_outline", "spheres"),
    ("stipple", "cows"),
    ("technical_lines", "technical"),
    ("toon", "spot"),
    ("toon_ramp", "spot"),
    ("wavy_lines", "fandisk"),
];

/// Frames rendered per comparison: enough for a history read and a state
/// update to have happened under each schedule.
const FRAMES: u32 = 4;

struct Compiled {
    program: StyleProgram,
    /// Passes the runner executes.
    passes: usize,
    /// `fused` lines of the compile report.
    fused: Vec<String>,
    /// Passes run as workgroup tiles (`tiled` lines of the report).
    tiled: Vec<String>,
    /// Passes computed in their reader's tiles (`recomputed` lines).
    recomputed: Vec<String>,
}

fn compile(style: &Path, scene: &npr_runner::scene::Scene, scene_name: &str, schedule: Schedule) -> Compiled {
    compile_narrowed(style, scene, scene_name, schedule, 0)
}

/// [`compile`] with every tile `deficit` texels narrower than the
/// footprints ask (`CompileOptions::tile_apron_deficit`).
fn compile_narrowed(
    style: &Path,
    scene: &npr_runner::scene::Scene,
    scene_name: &str,
    schedule: Schedule,
    deficit: u32,
) -> Compiled {
    let mut sources = npr_diag::SourceMap::new();
    let opts = npr_compiler::CompileOptions {
        scene: Some(scene.summary(scene_name)),
        schedule,
        tile_apron_deficit: deficit,
        ..Default::default()
    };
    let c = npr_compiler::compile_file(style, &mut sources, &opts).unwrap_or_else(|e| match e {
        npr_compiler::CompileError::User(d) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        e => panic!("{}: {e:?}", style.display()),
    });
    let entries = |action: &str| -> Vec<String> {
        c.report
            .entries
            .iter()
            .filter(|e| e.action == action)
            .map(|e| format!("{} {}", e.what, e.why))
            .collect()
    };
    let (fused, tiled, recomputed) = (entries("fused"), entries("tiled"), entries("recomputed"));
    let program = c.program();
    let tiled_passes = program
        .manifest
        .passes
        .iter()
        .filter(|p| matches!(p.kind, npr_abi::manifest::PassKindManifest::TiledImage { .. }))
        .count();
    assert_eq!(
        tiled_passes,
        tiled.len(),
        "{}: the report's tiled passes: {tiled:?}",
        style.display()
    );
    Compiled {
        passes: program.manifest.passes.len(),
        program,
        fused,
        tiled,
        recomputed,
    }
}

fn load_scene(scene: &Path) -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(scene, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// The output of frame `FRAMES - 1` (frames at 24 fps), per eye.
fn render(
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    width: u32,
    height: u32,
) -> Vec<npr_runner::TargetImage> {
    let g = gpu();
    let eyes = if scene.camera.is_stereo() { 2 } else { 1 };
    (0..eyes)
        .map(|eye| {
            let mut r = Renderer::new(&g.device, &g.queue, program, scene)
                .unwrap_or_else(|e| panic!("renderer: {e}: {:?}", e.diagnostics()));
            for frame in 0..FRAMES {
                let spec = FrameSpec::animated(width, height, frame, FrameSpec::DEFAULT_FPS, eye);
                r.render(scene, &spec)
                    .unwrap_or_else(|e| panic!("render: {e}: {:?}", e.diagnostics()));
            }
            r.read_output().expect("read back the output")
        })
        .collect()
}

/// Texels equal bit for bit; otherwise the two images and their diff are
/// written and the test fails with the first differing texel.
fn assert_bit_identical(case: &str, naive: &npr_runner::TargetImage, scheduled: &npr_runner::TargetImage) {
    let (a, b) = (naive.to_rgba_f32(), scheduled.to_rgba_f32());
    assert_eq!(a.len(), b.len(), "{case}: sizes differ");
    let first = a
        .iter()
        .zip(&b)
        .position(|(x, y)| x.iter().zip(y).any(|(p, q)| p.to_bits() != q.to_bits()));
    let Some(i) = first else { return };
    let differing = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    let dir = root().join("target/npr-test-output/schedule");
    std::fs::create_dir_all(&dir).expect("output dir");
    let naive_png = dir.join(format!("{case}_naive.png"));
    npr_runner::output::write_png8(&naive.to_rgba8(), &naive_png).expect("write naive");
    let c = compare_with_golden_file(
        &scheduled.to_rgba8(),
        &naive_png,
        Tolerance::PerPixel {
            max_abs: 0,
            outlier_fraction: 0.0,
        },
        false,
    );
    panic!(
        "{case}: differs from naive at texel {i} ({:?} against {:?}); {differing} texel(s) differ; \
         8-bit: {}; images: {naive_png:?}, {:?}",
        b[i], a[i], c.summary, c.written
    );
}

/// What the schedules did to one style: passes fused (`auto`), passes
/// tiled (`tiled`), passes computed in their reader's tiles (`recompute`).
#[derive(Debug, Clone, Copy)]
struct Changes {
    fused: usize,
    tiled: usize,
    recomputed: usize,
}

/// Compiles `style` both ways, renders both at `width`×`height`, asserts the
/// same texels; returns what the `auto` schedule changed.
fn same_image(case: &str, style: &Path, scene_path: &Path, width: u32, height: u32) -> Changes {
    let scene = load_scene(scene_path);
    let name = scene_path.display().to_string();
    let naive = compile(style, &scene, &name, Schedule::Naive);
    let auto = compile(style, &scene, &name, Schedule::Auto);
    assert!(auto.tiled.is_empty(), "{case}: auto tiled {:?}", auto.tiled);
    let tiled = compile(style, &scene, &name, Schedule::Tiled);
    assert_eq!(tiled.fused, auto.fused, "{case}: `tiled` fuses as `auto` does");
    assert!(naive.fused.is_empty(), "{case}: naive fused {:?}", naive.fused);
    assert!(naive.tiled.is_empty(), "{case}: naive tiled {:?}", naive.tiled);
    assert_eq!(
        naive.passes - auto.passes,
        auto.fused.len(),
        "{case}: each fused pass removes one pass ({:?})",
        auto.fused
    );
    let recompute = compile(style, &scene, &name, Schedule::Recompute);
    assert_eq!(recompute.fused, auto.fused, "{case}: `recompute` fuses as `auto` does");
    assert_eq!(
        tiled.passes - recompute.passes,
        recompute.recomputed.len(),
        "{case}: each recomputed pass removes one pass ({:?})",
        recompute.recomputed
    );
    let expected = render(&naive.program, &scene, width, height);
    let mut schedules = vec![("auto", &auto.program), ("tiled", &tiled.program)];
    // Without a recomputed pass, `recompute` compiles to `tiled`'s program.
    if !recompute.recomputed.is_empty() {
        schedules.push(("recompute", &recompute.program));
    }
    for (schedule, program) in schedules {
        let got = render(program, &scene, width, height);
        for (eye, (a, b)) in expected.iter().zip(&got).enumerate() {
            assert_bit_identical(&format!("{case}_{schedule}_eye{eye}"), a, b);
        }
    }
    Changes {
        fused: auto.fused.len(),
        tiled: tiled.tiled.len(),
        recomputed: recompute.recomputed.len(),
    }
}

fn example(style: &str) -> PathBuf {
    root().join(format!("examples/{style}.npr"))
}

fn scene(name: &str) -> PathBuf {
    root().join(format!("examples/scenes/{name}.toml"))
}

#[test]
fn every_example_gives_the_same_image_under_every_schedule() {
    let mut changed = Vec::new();
    for (style, scene_name) in EXAMPLES {
        let n = same_image(
            &format!("{style}_on_{scene_name}"),
            &example(style),
            &scene(scene_name),
            64,
            48,
        );
        changed.push((*style, *scene_name, n));
    }
    eprintln!("passes fused and tiled per example: {changed:?}");
    // The test must exercise fusion and tiling, not only styles where
    // nothing changes.
    let lsa = changed.iter().filter(|(s, _, _)| s.starts_with("lsa_")).map(|f| f.2);
    assert!(
        lsa.clone().all(|c| c.fused >= 1 && c.tiled >= 1),
        "the LSA styles fuse their merge and tile their error pass: {changed:?}"
    );
    let recomputed: Vec<&str> = changed.iter().filter(|c| c.2.recomputed >= 1).map(|c| c.0).collect();
    assert!(
        recomputed.contains(&"lsa_contours") && recomputed.contains(&"lsa_base"),
        "the monoscopic LSA styles compute their error pass in the merge's tiles: {changed:?}"
    );
    let tiled_elsewhere = changed
        .iter()
        .filter(|(s, _, c)| !s.starts_with("lsa_") && c.tiled >= 1)
        .count();
    assert!(tiled_elsewhere >= 2, "Sobel and the outline tile too: {changed:?}");
}

#[test]
fn every_example_is_covered() {
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(root().join("examples")).expect("examples/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "npr") {
            let stem = path
                .file_stem()
                .and_then(|s| s.to_str())
                .expect("utf-8 name")
                .to_owned();
            if !EXAMPLES.iter().any(|(s, _)| *s == stem) {
                missing.push(stem);
            }
        }
    }
    assert!(
        missing.is_empty(),
        "examples without a schedule-equivalence case: {missing:?}"
    );
}

/// Fused and tiled passes at image edges: sizes whose width and height are
/// not multiples of anything (1×1, 3×7, 17×513: partial tiles, tiles whose
/// apron leaves the image on every side), on the LSA styles (where the
/// merge fuses and the errors tile), Sobel, and Age of Sail (scale-½ and ¼
/// blur chains).
#[test]
fn odd_sizes_and_scaled_passes_give_the_same_image() {
    let cases = [
        ("lsa_contours", "spheres"),
        ("lsa_base", "spheres"),
        ("sobel_outline", "spheres"),
        ("age_of_sail", "age_of_sail"),
    ];
    for (style, scene_name) in cases {
        for (w, h) in [(1, 1), (3, 7), (17, 513)] {
            same_image(&format!("{style}_{w}x{h}"), &example(style), &scene(scene_name), w, h);
        }
    }
}

/// A pointwise chain at scale ½ fuses into its scale-½ reader (same scale),
/// but not into the full-size pass after it; a scale-½ neighbourhood pass
/// tiles the scale-½ target it reads and not the full-size one (a tile is
/// in the pass's own pixel grid), and computes it in its tiles under
/// `recompute`; every image equals naive's at odd sizes, where the ½ size
/// rounds.
#[test]
fn a_scale_half_chain_fuses_at_its_own_scale() {
    let dir = root().join("target/npr-test-output/schedule-styles");
    std::fs::create_dir_all(&dir).expect("dir");
    let style = dir.join("half_chain.npr");
    std::fs::write(
        &style,
        r#"style "half chain"
pass g: render(scene) {
  out c: rgba16float = vec4(normal.world * 0.5 + 0.5, 1.0)
}
pass half: image(g) scale 1/2 {
  out c: rgba16float = g.c * vec4(0.9, 0.8, 0.7, 1.0)
}
pass tone: image(half) scale 1/2 {
  out c: rgba8unorm = vec4(sqrt(half.c.rgb), 1.0)
}
pass edges: image(g, tone) scale 1/2 {
  let e = sobel(tone.c, screen_uv) + sobel(g.c, screen_uv)
  out c: rgba8unorm = vec4(e, e, e, 1.0)
}
pass up: image(edges) {
  out c: rgba8unorm = edges.c
}
output up.c
"#,
    )
    .expect("write style");
    let scene_path = scene("spheres");
    let loaded = load_scene(&scene_path);
    let auto = compile(&style, &loaded, "spheres", Schedule::Auto);
    assert_eq!(auto.fused.len(), 1, "`half` fuses into `tone` only: {:?}", auto.fused);
    let tiled = compile(&style, &loaded, "spheres", Schedule::Tiled);
    assert_eq!(
        tiled.tiled.len(),
        1,
        "`edges` tiles `tone.c` at scale ½, not `g.c` at full size: {:?}",
        tiled.tiled
    );
    assert!(
        tiled.tiled[0].contains("`tone.c`") && !tiled.tiled[0].contains("`g.c`"),
        "{:?}",
        tiled.tiled
    );
    let recompute = compile(&style, &loaded, "spheres", Schedule::Recompute);
    assert_eq!(
        recompute.recomputed.len(),
        1,
        "`tone` (with `half` fused in) is computed in `edges`'s scale-½ tiles: {:?}",
        recompute.recomputed
    );
    assert!(
        recompute.recomputed[0].starts_with("pass `tone` in `edges`'s tiles"),
        "{:?}",
        recompute.recomputed
    );
    for (w, h) in [(1, 1), (3, 7), (17, 513), (64, 48)] {
        let changes = same_image(&format!("half_chain_{w}x{h}"), &style, &scene_path, w, h);
        assert_eq!(changes.recomputed, 1, "{w}x{h}");
    }
}

/// A tile narrower than the footprints ask (what a wrong footprint would
/// do; `CompileOptions::tile_apron_deficit`): reads fall outside the tiles,
/// each workgroup where one did runs again reading the targets themselves
/// (computing a recomputed one where it is read), and the image is still
/// the naive one, bit for bit, with the apron 1 or 2 texels short (no
/// apron at all for Sobel). The check can fail: the same program with the
/// second run taken out gives another image.
#[test]
fn reads_outside_a_too_narrow_tile_give_the_same_image() {
    let scene_path = scene("spheres");
    let loaded = load_scene(&scene_path);
    let (w, h) = (40, 33);
    for style in ["lsa_contours", "sobel_outline"] {
        let path = example(style);
        let naive = compile(&path, &loaded, "spheres", Schedule::Naive);
        let expected = render(&naive.program, &loaded, w, h);
        for schedule in [Schedule::Tiled, Schedule::Recompute] {
            for deficit in [1, 2] {
                let c = compile_narrowed(&path, &loaded, "spheres", schedule, deficit);
                assert!(!c.tiled.is_empty(), "{style}: nothing tiled");
                let case = format!("{style}_{}_deficit{deficit}", schedule.name());
                let got = render(&c.program, &loaded, w, h);
                for (eye, (a, b)) in expected.iter().zip(&got).enumerate() {
                    assert_bit_identical(&format!("{case}_eye{eye}"), a, b);
                }
                if deficit == 1 && schedule == Schedule::Tiled {
                    let mut without = c.program.clone();
                    let mut removed = 0;
                    for wgsl in without.shaders.values_mut() {
                        let second_run = "if (workgroupUniformLoad(&npr_tile_any_missed) != 0u) {";
                        removed += wgsl.matches(second_run).count();
                        *wgsl = wgsl.replace(second_run, "if (false) {");
                    }
                    assert!(removed >= 1, "{case}: no second run in the tiled modules");
                    let wrong = render(&without, &loaded, w, h);
                    assert!(
                        wrong[0].to_rgba_f32() != expected[0].to_rgba_f32(),
                        "{case}: without its second run the narrow tile still gave naive's image"
                    );
                }
            }
        }
    }
}

/// The measured 16-bit float rounding (`npr_runner::half_rounding`) is how this
/// device's stores round every value, not only the probes: 8192 values over
/// 24 octaves stored into an `rgba16float` target, next to the same values
/// in `rgba32float`, each rounded by the measured mode equals what was
/// stored, bit for bit.
#[test]
fn the_measured_half_rounding_is_how_every_store_rounds() {
    let g = gpu();
    let mode = npr_runner::half_rounding::measure(&g.device, &g.queue).expect("a rounding this device has");
    let style = common::compile_text(
        r#"style "stores"
pass a: image() {
  let x = exp2(mix(-12.0, 12.0, screen_uv.y)) * (1.0 + screen_uv.x * 0.37)
  out h: rgba16float = vec4(x, -x, x * 0.3, 1.0)
  out f: rgba32float = vec4(x, -x, x * 0.3, 1.0)
}
pass b: image(a) {
  out c: rgba32float = vec4(a.h.x, a.f.x, a.h.z, a.f.z)
}
output b.c
"#,
    );
    let scene = load_scene(&scene("spheres"));
    let img = npr_runner::render_frame(g, &style, &scene, &FrameSpec::still(64, 64, 0)).expect("render");
    let (mut checked, mut modes_differ) = (0, 0);
    for texel in img.to_rgba_f32() {
        for (stored, exact) in [(texel[0], texel[1]), (texel[2], texel[3])] {
            let other = match mode {
                npr_abi::formats::HalfRounding::NearestEven => npr_abi::formats::HalfRounding::TowardZero,
                npr_abi::formats::HalfRounding::TowardZero => npr_abi::formats::HalfRounding::NearestEven,
            };
            assert_eq!(
                mode.round(exact).to_bits(),
                stored.to_bits(),
                "{exact:e} stored as {stored:e}, but {mode:?} gives {:e}",
                mode.round(exact)
            );
            modes_differ += usize::from(other.round(exact) != stored);
            checked += 1;
        }
    }
    // The check can fail: the other mode disagrees with many stores.
    assert!(modes_differ > checked / 4, "{modes_differ} of {checked}");
    eprintln!("{mode:?}: {checked} stores, the other mode differs on {modes_differ}");
}

/// A constant written to a target and read through `sqrt`: fused,
/// `sqrt(vec4(-0.827))` would be a WGSL const-expression that naga rejects
/// (E9001; the generated-style soak's case 48924), and even wrapped so that
/// naga accepts it, lavapipe folds it to NaN where its run-time `sqrt` of
/// the stored -0.827 gives 0.909 (WGSL leaves it indeterminate). So a
/// constant target is not fused: the style compiles under `auto` and gives
/// naive's image.
#[test]
fn a_constant_target_fuses_without_becoming_a_constant_expression() {
    let dir = root().join("target/npr-test-output/schedule-styles");
    std::fs::create_dir_all(&dir).expect("dir");
    let style = dir.join("constant_target.npr");
    std::fs::write(
        &style,
        r#"style "constant target"
pass k: image() {
  out o: rgba32float = vec4(-0.827)
}
pass r: image(k) {
  out c: rgba32float = vec4(fract(length(sqrt(k.o))), screen_uv, 1.0)
}
output r.c
"#,
    )
    .expect("write style");
    let scene_path = scene("spheres");
    let loaded = load_scene(&scene_path);
    let auto = compile(&style, &loaded, "spheres", Schedule::Auto);
    assert!(auto.fused.is_empty(), "{:?}", auto.fused);
    same_image("constant_target", &style, &scene_path, 8, 8);
}

/// `schedule:` settings in the style (issue 14's per-pass annotation) give
/// the naive image too: LSA contours with its error pass forced `tiled`
/// and its density pass forced `naive` (so it is not fused into the ink
/// pass), the other way round (the density pass tiled as its own pass
/// instead of fused), and its error pass forced `recompute`, each compiled under every `--schedule` and compared
/// bit for bit with the unannotated style compiled `naive`. A forced
/// `tiled` pass runs tiled even under `--schedule naive`; so does the
/// reader of a pass forced `recompute` (the error pass, the third variant).
#[test]
fn schedule_settings_give_the_naive_image_under_every_run_schedule() {
    let dir = root().join("target/npr-test-output/schedule-styles");
    std::fs::create_dir_all(&dir).expect("dir");
    let original = example("lsa_contours");
    let text = std::fs::read_to_string(&original).expect("lsa_contours.npr");
    let scene_path = scene("spheres");
    let loaded = load_scene(&scene_path);
    let reference = compile(&original, &loaded, "spheres", Schedule::Naive);
    let sizes = [(64, 48), (17, 33)];
    let expected: Vec<_> = sizes
        .iter()
        .map(|(w, h)| render(&reference.program, &loaded, *w, *h))
        .collect();
    // Neither forced pass fuses, and `ink_lines` is the output: nothing
    // fuses, except where `thin` is left to the run's schedule.
    type FusedUnder = fn(Schedule) -> usize;
    let none: FusedUnder = |_| 0;
    let unless_naive: FusedUnder = |s| usize::from(s != Schedule::Naive);
    let variants: [(&str, &str, &str, &str, FusedUnder); 3] = [
        (
            "error_tiled_thin_naive",
            "schedule: tiled",
            "schedule: naive",
            "forced by `schedule: tiled`",
            none,
        ),
        (
            "error_naive_thin_tiled",
            "schedule: naive",
            "schedule: tiled",
            "forced by `schedule: tiled`",
            none,
        ),
        // `error` is computed in its reader's tiles: `thin`'s under
        // `--schedule naive`, else `ink_lines`'s, into which `thin` fuses.
        (
            "error_recompute",
            "schedule: recompute",
            "schedule: auto",
            "it computes a target in its tiles",
            unless_naive,
        ),
    ];
    for (name, error, thin, tiled_why, fused_passes) in variants {
        let tiled_passes = 1;
        let annotated = text
            .replacen(
                "pass error: image(gbuffer) {\n",
                &format!("pass error: image(gbuffer) {{\n  {error}\n"),
                1,
            )
            .replacen(
                "pass thin: image(error) {\n",
                &format!("pass thin: image(error) {{\n  {thin}\n"),
                1,
            );
        assert_eq!(
            annotated.matches("schedule: ").count(),
            2,
            "the passes moved in lsa_contours.npr"
        );
        let style = dir.join(format!("{name}.npr"));
        std::fs::write(&style, &annotated).expect("write style");
        for schedule in Schedule::ALL {
            let c = compile(&style, &loaded, "spheres", schedule);
            assert_eq!(
                c.tiled.len(),
                tiled_passes,
                "{name} --schedule {}: {:?}",
                schedule.name(),
                c.tiled
            );
            assert!(c.tiled[0].contains(tiled_why), "{:?}", c.tiled);
            assert_eq!(
                c.fused.len(),
                fused_passes(schedule),
                "{name} --schedule {}: {:?}",
                schedule.name(),
                c.fused
            );
            for ((w, h), want) in sizes.iter().zip(&expected) {
                let got = render(&c.program, &loaded, *w, *h);
                for (eye, (a, b)) in want.iter().zip(&got).enumerate() {
                    assert_bit_identical(&format!("{name}_{}_{w}x{h}_eye{eye}", schedule.name()), a, b);
                }
            }
        }
    }
}
