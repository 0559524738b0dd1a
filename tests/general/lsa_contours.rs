//! LSA contours end to end: the example styles rendered through the runner
//! on analytic scenes and measured against exact ground truth
//! (`npr_lab::contours`, f64 ray casting), the GPU operators against their
//! f64 references on the very G-buffers the GPU rendered, and the hard
//! cases (no NaN or Inf anywhere).
//!
//! Resolutions: 0.25× and 0.5× of 512² here; the 1× figures come from
//! `npr bench contours` (docs/PERFORMANCE.md), which keeps this test fast
//! on lavapipe.

use npr_lab::contours::{accuracy, builtin_scenes, ink_mask, Accuracy, AnalyticScene};
use npr_runner::StyleProgram;
use npr_stdlib::reference_lsa::{self as lsa, LsaSettings};
use std::path::Path;

use crate::common;
use common::lsa::{output, scene_of, style, targets, to_f64, uv};
use common::root;

fn scene_text(text: &str) -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("hard.toml", text.to_string());
    npr_runner::scene::parse_scene(text, file, Path::new("."))
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// The styles compared, with the line threshold on the red channel of their
/// output (ink #141414 over paper: a line where the line value exceeds ~½).
fn methods() -> Vec<(&'static str, StyleProgram)> {
    vec![
        ("LSA full", style("lsa_contours.npr", &[])),
        ("LSA base", style("lsa_base.npr", &[])),
        ("Sobel", style("sobel_outline.npr", &[])),
        ("normal+depth", style("outline.npr", &[])),
    ]
}

fn measure(program: &StyleProgram, s: &AnalyticScene, size: u32) -> Accuracy {
    let img = output(program, &scene_of(s), size);
    accuracy(&ink_mask(&img, 0.5), &s.truth(size, size), 1)
}

#[test]
fn gpu_operators_match_f64_reference_on_rendered_gbuffers() {
    let scenes = builtin_scenes();
    let size = (48, 40);
    for s in scenes
        .iter()
        .filter(|s| ["cube", "parallel_planes", "sphere_on_plane"].contains(&s.name))
    {
        let scene = scene_of(s);
        for (plane, aa) in [(false, false), (true, false), (false, true), (true, true)] {
            let program = style(
                "lsa_contours.npr",
                &[
                    (
                        "param plane: bool = true",
                        if plane {
                            "param plane: bool = true"
                        } else {
                            "param plane: bool = false"
                        },
                    ),
                    (
                        "param aa: bool = true",
                        if aa {
                            "param aa: bool = true"
                        } else {
                            "param aa: bool = false"
                        },
                    ),
                ],
            );
            let t = targets(
                &program,
                &scene,
                size,
                &["gbuffer.pos", "gbuffer.nrm", "error.e", "thin.e"],
            );
            let (pos, nrm, err, thin) = (to_f64(&t[0]), to_f64(&t[1]), &t[2], &t[3]);
            let settings = LsaSettings {
                plane,
                aa,
                ..LsaSettings::BASE
            };
            let err64 = to_f64(err);
            let mut mismatched = 0;
            let mut lines = 0;
            for y in 0..size.1 {
                for x in 0..size.0 {
                    let want = lsa::lsa(&pos, &nrm, uv(x, y, size.0, size.1), &settings);
                    let got = err.texel(x, y);
                    assert!(got.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)), "{got:?}");
                    // rgba16float output: 2^-11 relative; a remap decision can
                    // flip where f32 and f64 straddle η_min or η_max.
                    if (0..4).any(|c| (got[c] as f64 - want[c]).abs() > 2e-3) {
                        mismatched += 1;
                    }
                    lines += usize::from(lsa::merge(want) > 0.5);
                    let dens = lsa::lsa_density(&err64, uv(x, y, size.0, size.1), 1.0);
                    let got = thin.texel(x, y);
                    for c in 0..4 {
                        assert!(
                            (got[c] as f64 - dens[c]).abs() <= 2e-3,
                            "{} density at ({x},{y}) channel {c}: {} vs {}",
                            s.name,
                            got[c],
                            dens[c]
                        );
                    }
                }
            }
            let n = (size.0 * size.1) as usize;
            if s.name == "parallel_planes" && !plane {
                // Fig. 3: e_curv alone is blind to a step between parallel planes.
                assert_eq!(lines, 0, "{}: e_curv sees no step", s.name);
            } else {
                assert!(lines > 20, "{}: the reference draws lines ({lines})", s.name);
            }
            assert!(
                mismatched * 100 <= n,
                "{} plane={plane} aa={aa}: {mismatched} of {n} texels differ from the f64 reference",
                s.name
            );
        }
    }
}

#[test]
fn accuracy_against_analytic_ground_truth() {
    let methods = methods();
    let mut table = String::from("| scene | size | method | precision | recall |\n|---|---:|---|---:|---:|\n");
    let mut results = Vec::new();
    for s in builtin_scenes() {
        for size in [128u32, 256] {
            for (name, program) in &methods {
                let a = measure(program, &s, size);
                table.push_str(&format!(
                    "| {} | {size} | {name} | {:.3} | {:.3} |\n",
                    s.name, a.precision, a.recall
                ));
                results.push((s.name, size, *name, a));
            }
        }
    }
    println!("{table}");
    let get = |scene: &str, size: u32, method: &str| {
        results
            .iter()
            .find(|r| r.0 == scene && r.1 == size && r.2 == method)
            .map(|r| r.3)
            .expect("measured")
    };
    for (scene, size, method, a) in &results {
        assert!(a.truth > 0, "{scene} {size} {method}: no ground truth");
        let (p, r) = (a.precision, a.recall);
        let blind = *scene == "parallel_planes" && matches!(*method, "LSA base" | "Sobel");
        match *method {
            // The goal was 0.9/0.9; measured: precision ≥ 0.976 (torus at
            // 128², where inflections near the self-occlusion add lines),
            // recall 1.0 everywhere.
            "LSA full" => assert!(p >= 0.97 && r >= 0.99, "{scene} {size}: LSA full {a:?}\n{table}"),
            // Base and Sobel miss the step between parallel planes entirely
            // (the baseline failure of Fig. 3 / §5.1): nothing predicted.
            _ if blind => assert!(r <= 0.05, "{scene} {size}: {method} should miss the step: {a:?}"),
            "LSA base" => assert!(p >= 0.97 && r >= 0.99, "{scene} {size}: LSA base {a:?}\n{table}"),
            // Depth-only Sobel misses creases where depth is continuous.
            "Sobel" if *scene == "cube" => assert!(r <= 0.75, "{scene} {size}: Sobel {a:?}"),
            "Sobel" => assert!(p >= 0.7 && r >= 0.99, "{scene} {size}: Sobel {a:?}\n{table}"),
            // Roberts cross on normals+depth: every feature found, but thick,
            // noisy lines at low resolution (precision down to 0.34).
            _ => assert!(p >= 0.3 && r >= 0.99, "{scene} {size}: {method} {a:?}\n{table}"),
        }
    }
    // Parallel planes: only LSA with e_plane (eqs. 6–7) finds the step.
    assert_eq!(get("parallel_planes", 256, "LSA full").recall, 1.0);
    assert_eq!(get("parallel_planes", 256, "LSA base").predicted, 0);
    assert_eq!(get("parallel_planes", 256, "Sobel").predicted, 0);
}

/// Renders `program` on `scene` at `size` and checks that the per-direction
/// errors and the thinned errors are finite and in [0, 1]; returns the
/// number of line pixels (merged thinned error > ½).
fn checked_lines(program: &StyleProgram, scene: &npr_runner::scene::Scene, size: (u32, u32), what: &str) -> usize {
    let t = targets(program, scene, size, &["error.e", "thin.e"]);
    let mut lines = 0;
    for img in &t {
        for (i, v) in img.to_rgba_f32().iter().enumerate() {
            assert!(
                v.iter().all(|c| c.is_finite() && (0.0..=1.0).contains(c)),
                "{what}: {} texel {i} is {v:?}",
                img.name
            );
        }
    }
    for v in t[1].to_rgba_f32() {
        lines += usize::from(v.iter().fold(0.0f32, |a, b| a.max(*b)) > 0.5);
    }
    lines
}

fn facing_plane(size: f64, translate: [f64; 3]) -> npr_lab::contours::AnalyticObject {
    npr_lab::contours::AnalyticObject {
        shape: npr_lab::contours::Shape::Plane { size },
        translate,
        rotate_deg: [90.0, 0.0, 0.0],
    }
}

#[test]
fn hard_cases_give_no_nan_or_inf() {
    use npr_lab::contours::{AnalyticObject, Shape};
    let full = style("lsa_contours.npr", &[]);
    let base = style("lsa_base.npr", &[]);
    let scenes = builtin_scenes();
    let sphere_on_plane = scene_of(&scenes[4]);

    // Only background: no geometry in view, so no line anywhere.
    let empty = AnalyticScene {
        name: "empty",
        eye: [0.0, 0.0, 4.0],
        target: [0.0, 0.0, 8.0],
        fov_deg: 40.0,
        objects: vec![AnalyticObject {
            shape: Shape::Sphere { radius: 1.0 },
            translate: [0.0; 3],
            rotate_deg: [0.0; 3],
        }],
    };
    for p in [&full, &base] {
        assert_eq!(checked_lines(p, &scene_of(&empty), (32, 24), "only background"), 0);
    }

    // Tiny images: 1×1 (no neighbour inside) and 3×7.
    for size in [(1, 1), (3, 7), (7, 3)] {
        for p in [&full, &base] {
            checked_lines(p, &sphere_on_plane, size, &format!("{size:?}"));
        }
    }

    // Equal normals (κ = 0): a single plane filling the view has no line
    // at all, and its error is exactly 0 (not merely small).
    let flat = AnalyticScene {
        name: "flat",
        eye: [0.3, 0.2, 4.0],
        target: [0.0, 0.0, 0.0],
        fov_deg: 40.0,
        objects: vec![facing_plane(40.0, [0.0; 3])],
    };
    // This also shows that the image border draws no line (no clamping).
    let t = targets(&full, &scene_of(&flat), (40, 30), &["error.e"]);
    assert!(t[0].to_rgba_f32().iter().all(|v| *v == [0.0; 4]), "flat plane: e = 0");

    // Grazing angle: the eye 2 cm above a 40 m ground plane, looking along it.
    let grazing = AnalyticScene {
        name: "grazing",
        eye: [0.0, 0.02, 4.0],
        target: [0.0, 0.02, -4.0],
        fov_deg: 40.0,
        objects: vec![AnalyticObject {
            shape: Shape::Plane { size: 40.0 },
            translate: [0.0; 3],
            rotate_deg: [0.0; 3],
        }],
    };
    for p in [&full, &base] {
        checked_lines(p, &scene_of(&grazing), (64, 48), "grazing");
    }

    // A subpixel gap (0.3 px at 64²) between two cubes in front of a plane.
    let footprint = 2.0 * 4.0 * (20f64.to_radians()).tan() / 64.0;
    let gap = 0.3 * footprint;
    let cube = |x: f64| AnalyticObject {
        shape: Shape::Cube { size: 1.0 },
        translate: [x, 0.0, 0.0],
        rotate_deg: [0.0; 3],
    };
    let gapped = AnalyticScene {
        name: "gap",
        eye: [0.0, 0.0, 4.0],
        target: [0.0, 0.0, 0.0],
        fov_deg: 40.0,
        objects: vec![
            cube(-0.5 - gap / 2.0),
            cube(0.5 + gap / 2.0),
            facing_plane(40.0, [0.0, 0.0, -2.0]),
        ],
    };
    // Every visible face is parallel to the backdrop: only e_plane sees the
    // outlines and the gap; the base method sees nothing at all.
    assert!(checked_lines(&full, &scene_of(&gapped), (64, 64), "subpixel gap") > 100);
    assert_eq!(checked_lines(&base, &scene_of(&gapped), (64, 64), "subpixel gap"), 0);

    // A plane 10 km away with rgba16float positions (spacing 8 m at 1e4)
    // and normals: quantized, but finite; and with float32 positions.
    let far = scene_text(
        "[camera]\nposition = [0.0, 0.0, 0.0]\ntarget = [0.3, 0.2, -1.0]\nfov = 40.0\nnear = 1.0\nfar = 20000.0\n\n[[object]]\nprimitive = { kind = \"plane\", size = 40000.0 }\ntranslate = [0.0, 0.0, -10000.0]\nrotate = [90.0, 0.0, 0.0]\n\n[[object]]\nprimitive = { kind = \"sphere\", radius = 1500.0, segments = 128, rings = 64 }\ntranslate = [2000.0, 1000.0, -8000.0]\n",
    );
    let half = style(
        "lsa_contours.npr",
        &[
            ("out pos: rgba32float", "out pos: rgba16float"),
            ("out nrm: rgba32float", "out nrm: rgba16float"),
        ],
    );
    for (p, what) in [(&half, "1e4 m, rgba16float"), (&full, "1e4 m, rgba32float")] {
        assert!(
            checked_lines(p, &far, (48, 48), what) > 0,
            "{what}: the sphere's outline is drawn"
        );
    }

    // Positions past the f16 range (×1e5: up to ~1.6e5 > 65504) are stored
    // as ±Inf or saturated, depending on the driver; non-finite texels count
    // as background, and nothing turns into NaN.
    let overflow = style(
        "lsa_contours.npr",
        &[(
            "out pos: rgba32float = vec4(position.world, 1.0)",
            "out pos: rgba16float = vec4(position.world * 100000.0, 1.0)",
        )],
    );
    let t = targets(&overflow, &sphere_on_plane, (32, 32), &["gbuffer.pos"]);
    let extreme = t[0].to_rgba_f32().iter().fold(0.0f32, |m, v| m.max(v[0].abs()));
    assert!(extreme >= 65504.0, "the G-buffer overflows f16 (largest |x| {extreme})");
    checked_lines(&overflow, &sphere_on_plane, (32, 32), "f16 overflow to Inf");
}

/// The analytic scenes are also files, for `npr render`; they must match the
/// definitions the ground truth is computed from. Regenerate with
/// `NPR_UPDATE_SCENES=1 cargo test --test general lsa_contours::`.
#[test]
fn scene_files_match_the_analytic_definitions() {
    let dir = root().join("tests/data/contours");
    for s in builtin_scenes() {
        let path = dir.join(format!("{}.toml", s.name));
        if std::env::var_os("NPR_UPDATE_SCENES").is_some() {
            std::fs::create_dir_all(&dir).expect("dir");
            std::fs::write(&path, s.to_toml()).expect("write");
        }
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(text, s.to_toml(), "{} is stale", path.display());
        // And it loads as a scene with one object per analytic object.
        let mut sources = npr_diag::SourceMap::new();
        let scene = npr_runner::scene::load_scene(&path, &mut sources).expect("loads");
        assert_eq!(scene.objects.len(), s.objects.len());
    }
}

/// The G-buffer the LSA styles render is the analytic scene: world positions
/// and normals match the f64 ray cast (same camera, pixel centres, y-flip),
/// and alpha is 1 exactly where the ray hits (0 on the cleared background).
#[test]
fn gbuffer_matches_the_analytic_ray_cast() {
    let program = style("lsa_contours.npr", &[]);
    for s in builtin_scenes() {
        let (w, h) = (64u32, 48u32);
        let t = targets(&program, &scene_of(&s), (w, h), &["gbuffer.pos", "gbuffer.nrm"]);
        let (mut compared, mut worst_p, mut worst_n) = (0, 0.0f64, 0.0f64);
        for y in 0..h {
            for x in 0..w {
                let hit = s.cast(w, h, x as f64 + 0.5, y as f64 + 0.5);
                // Skip pixels next to a silhouette: the mesh's edge is within
                // a tessellation error of the analytic one.
                let stable = (-1i64..=1).all(|dy| {
                    (-1i64..=1).all(|dx| {
                        s.cast(w, h, x as f64 + 0.5 + dx as f64, y as f64 + 0.5 + dy as f64)
                            .map(|hh| hh.object)
                            == hit.map(|hh| hh.object)
                    })
                });
                if !stable {
                    continue;
                }
                let p = t[0].texel(x, y);
                let n = t[1].texel(x, y);
                match hit {
                    None => assert_eq!(p[3], 0.0, "{} ({x},{y}): background alpha", s.name),
                    Some(hit) => {
                        assert_eq!(p[3], 1.0, "{} ({x},{y}): geometry alpha", s.name);
                        let dist = |a: [f64; 3], b: [f32; 4]| {
                            (0..3).map(|i| (a[i] - f64::from(b[i])).powi(2)).sum::<f64>().sqrt()
                        };
                        let dp = dist(hit.point.to_array(), p);
                        let dn = dist(hit.normal.to_array(), n);
                        worst_p = worst_p.max(dp);
                        worst_n = worst_n.max(dn);
                        compared += 1;
                    }
                }
            }
        }
        // Positions: the mesh lies within 2e-5 m of the surface (512
        // segments) and f32 interpolation adds ~1e-6; normals are
        // interpolated vertex normals (within the facet angle, 2π/512).
        assert!(compared > 100, "{}: {compared} pixels compared", s.name);
        assert!(worst_p < 2e-3, "{}: position error {worst_p} m", s.name);
        assert!(worst_n < 2e-2, "{}: normal error {worst_n}", s.name);
    }
}

/// 60 frames of a camera orbiting the tilted torus by 0.25° per frame (under
/// a pixel of motion per frame at 96²): accuracy holds in every frame, and
/// lines do not flicker. Flicker: a pixel that is a line, not a line, and a
/// line again in three consecutive frames (or the reverse) — slow motion
/// moves an edge monotonically and cannot do that.
#[test]
fn temporal_stability_over_60_frames() {
    let base = builtin_scenes().into_iter().find(|s| s.name == "torus").expect("torus");
    let size = 96u32;
    let frames: Vec<AnalyticScene> = (0..60)
        .map(|f| {
            let a = (f as f64 * 0.25).to_radians();
            AnalyticScene {
                eye: [4.0 * a.sin(), 0.3, 4.0 * a.cos()],
                ..base.clone()
            }
        })
        .collect();
    let mut report = String::new();
    // Measured: min precision 0.967, min recall 1.000, no flicker at all in
    // ~40k line pixels (the base method behaves the same on this scene).
    for (name, program, min_p, min_r, max_flicker) in [("LSA full", style("lsa_contours.npr", &[]), 0.95, 0.99, 0.001)]
    {
        let mut masks = Vec::new();
        let (mut lo_p, mut lo_r) = (1.0f64, 1.0f64);
        for s in &frames {
            let mask = ink_mask(&output(&program, &scene_of(s), size), 0.5);
            let a = accuracy(&mask, &s.truth(size, size), 1);
            lo_p = lo_p.min(a.precision);
            lo_r = lo_r.min(a.recall);
            masks.push(mask);
        }
        let mut flicker = 0usize;
        let mut line_pixels = 0usize;
        for w in masks.windows(3) {
            for i in 0..w[1].bits.len() {
                line_pixels += usize::from(w[1].bits[i]);
                flicker += usize::from(w[0].bits[i] == w[2].bits[i] && w[0].bits[i] != w[1].bits[i]);
            }
        }
        let rate = flicker as f64 / line_pixels.max(1) as f64;
        report.push_str(&format!(
            "{name}: min precision {lo_p:.3}, min recall {lo_r:.3}, flicker {flicker} per {line_pixels} line pixels ({rate:.4})\n"
        ));
        assert!(
            lo_p >= min_p && lo_r >= min_r && rate <= max_flicker,
            "{name}: {report}"
        );
    }
    println!("{report}");
}
