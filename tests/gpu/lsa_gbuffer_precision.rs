//! G-buffer precision and space for LSA contours (issue 4; LSA paper §6:
//! "our method requires high-precision G-buffers").
//!
//! `examples/lsa_contours.npr` (the full method) is rendered with its
//! G-buffer in four variants — positions and normals in rgba32float or
//! rgba16float, in world or view space — on the five analytic scenes of
//! `npr_lab::contours`, each moved (objects, eye and target together) 0 m,
//! 10 m, 100 m, 1 km and 10 km from the world origin. The images are the
//! same in exact arithmetic; precision/recall within 1 px against the f64
//! ground truth shows what each variant loses.
//!
//! Why it matters: a float with m mantissa bits stores x with a spacing of
//! 2^(⌊log2 |x|⌋ − m) (m = 10 for f16, 23 for f32). LSA fits a sphere to
//! neighbouring positions (eqs. 2–5) whose spacing is one pixel footprint,
//! d·2·tan(fov/2)/H ≈ 23 mm at 4 m and 128²; f16 world positions are spaced
//! 8 mm at 10 m, 62 mm at 100 m, 0.5 m at 1 km and 8 m at 10 km, so the fit
//! sees noise. View-space positions are relative to the eye (|x| ≲ 5 m
//! here, spacing ≤ 4 mm) wherever the scene is; what remains is the f32
//! world position the vertex stage interpolates (spacing 1 mm at 10 km)
//! before `frame.view` subtracts the eye.
//!
//! Print the table (docs/PERFORMANCE.md, "G-buffer precision and space"):
//! `cargo test --test gpu lsa_gbuffer_precision:: -- --nocapture`

use npr_lab::contours::{accuracy, builtin_scenes, ink_mask, Accuracy};
use npr_runner::{FrameSpec, Gpu, StyleProgram};
use std::path::Path;

const SIZE: u32 = 128;
/// Distances from the origin, along the unit direction (0.6, 0.48, 0.64) so
/// that all three coordinates grow.
const DISTANCES: [f64; 5] = [0.0, 10.0, 100.0, 1000.0, 10000.0];
const DIRECTION: [f64; 3] = [0.6, 0.48, 0.64];

/// `lsa_contours.npr` with its G-buffer stored as `format` in `space`.
fn variant(format: &str, space: &str) -> StyleProgram {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut text = std::fs::read_to_string(root.join("examples/lsa_contours.npr")).expect("read style");
    for (from, to) in [
        (
            "out pos: rgba32float = vec4(position.world, 1.0)",
            format!("out pos: {format} = vec4(position.{space}, 1.0)"),
        ),
        (
            "out nrm: rgba32float = vec4(normal.world, 1.0)",
            format!("out nrm: {format} = vec4(normal.{space}, 1.0)"),
        ),
    ] {
        assert!(text.contains(from), "`{from}` not in lsa_contours.npr");
        text = text.replace(from, &to);
    }
    let mut sources = npr_diag::SourceMap::new();
    match npr_compiler::compile_source(
        "lsa_contours.npr",
        &text,
        &root.join("examples"),
        &mut sources,
        &Default::default(),
    ) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

#[test]
fn gbuffer_precision_and_space_against_distance_from_the_origin() {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("LSA tests need a GPU adapter: {e}"));
    let variants: Vec<(&str, StyleProgram)> = [
        ("rgba32float world", "rgba32float", "world"),
        ("rgba32float view", "rgba32float", "view"),
        ("rgba16float world", "rgba16float", "world"),
        ("rgba16float view", "rgba16float", "view"),
    ]
    .into_iter()
    .map(|(name, format, space)| (name, variant(format, space)))
    .collect();
    let spec = FrameSpec::still(SIZE, SIZE, 0);
    // (variant, distance) → the worst precision and recall over the scenes,
    // and which scene was worst.
    let mut worst: Vec<Vec<(Accuracy, &str, &str)>> = vec![Vec::new(); variants.len()];
    let mut detail = String::new();
    let mut results: Vec<(f64, &str, &str, Accuracy)> = Vec::new();
    for &d in &DISTANCES {
        let mut lo: Vec<(Accuracy, &str, &str)> = variants
            .iter()
            .map(|_| {
                (
                    Accuracy {
                        precision: 1.0,
                        recall: 1.0,
                        predicted: 0,
                        truth: 0,
                    },
                    "",
                    "",
                )
            })
            .collect();
        for s in builtin_scenes() {
            let moved = s.translated(DIRECTION.map(|c| c * d));
            let truth = moved.truth(SIZE, SIZE);
            let mut sources = npr_diag::SourceMap::new();
            let scene = moved
                .scene(&mut sources)
                .unwrap_or_else(|e| panic!("{}", npr_diag::diagnostic::render(&e, &sources, false)));
            for (i, (name, program)) in variants.iter().enumerate() {
                let img = npr_runner::render_frame(&gpu, program, &scene, &spec).unwrap_or_else(|e| panic!("{e}"));
                let a = accuracy(&ink_mask(&img, 0.5), &truth, 1);
                results.push((d, s.name, *name, a));
                detail.push_str(&format!(
                    "| {d} | {} | {name} | {:.3} | {:.3} | {} |\n",
                    s.name, a.precision, a.recall, a.predicted
                ));
                if a.precision < lo[i].0.precision {
                    lo[i].0.precision = a.precision;
                    lo[i].1 = s.name;
                }
                if a.recall < lo[i].0.recall {
                    lo[i].0.recall = a.recall;
                    lo[i].2 = s.name;
                }
            }
        }
        for (i, l) in lo.into_iter().enumerate() {
            worst[i].push(l);
        }
    }
    let mut table = format!(
        "LSA full at {SIZE}², min precision / min recall over the five analytic scenes (the worst scene for P, R)\n| distance from origin | {} |\n|---:|{}\n",
        variants.iter().map(|v| v.0).collect::<Vec<_>>().join(" | "),
        "---|".repeat(variants.len())
    );
    for (k, d) in DISTANCES.iter().enumerate() {
        table.push_str(&format!("| {d} m |"));
        for w in &worst {
            let (a, wp, wr) = w[k];
            let mut worst_of = vec![];
            if a.precision < 1.0 {
                worst_of.push(format!("P: {wp}"));
            }
            if a.recall < 1.0 {
                worst_of.push(format!("R: {wr}"));
            }
            table.push_str(&format!(
                " {:.3} / {:.3} ({}) |",
                a.precision,
                a.recall,
                worst_of.join(", ")
            ));
        }
        table.push('\n');
    }
    println!("{table}\n| distance | scene | variant | precision | recall | predicted |\n|---:|---|---|---:|---:|---:|\n{detail}");

    // Per scene, for the assertions.
    let get = |variant: &str, distance: f64, scene: &str| {
        results
            .iter()
            .find(|r| r.0 == distance && r.1 == scene && r.2 == variant)
            .map(|r| r.3)
            .expect("measured")
    };
    let scenes: Vec<&str> = builtin_scenes().iter().map(|s| s.name).collect();
    let min_over = |variant: &str, distance: f64| {
        scenes.iter().fold((1.0f64, 1.0f64), |(p, r), s| {
            let a = get(variant, distance, s);
            (p.min(a.precision), r.min(a.recall))
        })
    };
    let check = |variant: &str, distance: f64, min_p: f64, min_r: f64| {
        let (p, r) = min_over(variant, distance);
        assert!(
            p >= min_p && r >= min_r,
            "{variant} at {distance} m: {p:.3} / {r:.3}, expected ≥ {min_p} / {min_r}\n{table}"
        );
    };
    for d in [0.0, 10.0, 100.0, 1000.0] {
        // float32, either space: unchanged up to 1 km (0.976 / 1.000: the
        // torus's inflections at 128², as at the origin).
        check("rgba32float world", d, 0.97, 0.99);
        check("rgba32float view", d, 0.97, 0.99);
        // float16 view-space positions stay relative to the eye.
        check("rgba16float view", d, 0.97, 0.99);
    }
    // 10 km: the f32 world position the vertex stage interpolates (spacing
    // 1 mm) costs the parallel planes' 5 cm step a little, in both spaces
    // (measured 0.924 / 0.984 world, 0.976 / 0.984 view); f16 view loses
    // some precision around the sphere before the plane (0.932).
    check("rgba32float world", 10000.0, 0.9, 0.97);
    check("rgba32float view", 10000.0, 0.95, 0.97);
    check("rgba16float view", 10000.0, 0.9, 0.99);
    // float16 world is as good as float32 near the origin (spacing ≤ 8 mm
    // at 10 m, under a third of the 23 mm pixel footprint)...
    check("rgba16float world", 0.0, 0.97, 0.99);
    check("rgba16float world", 10.0, 0.97, 0.99);
    // ...and collapses by 100 m (spacing 62 mm, ~3 footprints): false lines
    // at the quantization steps (precision 0.027 / 0.418 on the planes and
    // sphere-on-plane), and the 5 cm step is lost (recall 0.504).
    let planes = get("rgba16float world", 100.0, "parallel_planes");
    assert!(planes.precision < 0.1 && planes.recall < 0.6, "{planes:?}\n{table}");
    assert!(get("rgba16float world", 100.0, "sphere_on_plane").precision < 0.5);
    // At 1 km (spacing 0.5 m) every scene has more false lines than true
    // ones (precision 0.04–0.47).
    for s in &scenes {
        let a = get("rgba16float world", 1000.0, s);
        assert!(a.precision < 0.5, "rgba16float world at 1 km, {s}: {a:?}\n{table}");
    }
    // At 10 km (spacing 8 m, larger than the objects) most neighbours store
    // the same position and the fit degenerates (κ of eq. 3 divides by the
    // clamped |Δp|): fewer false lines on the small objects than at 1 km, but
    // the planes' step is still drowned (precision 0.076).
    assert!(get("rgba16float world", 10000.0, "parallel_planes").precision < 0.1);
    assert!(min_over("rgba16float world", 10000.0).0 < 0.5);
}
