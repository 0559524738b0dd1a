//! The packed LSA G-buffer (issue 14's "smaller G-buffer"): view positions
//! in rgba16float and octahedral view normals in rg16float (Cigolle et al.
//! 2014 §3.1), 12 bytes a pixel against the 32 of the float32 layout, read
//! by the LSA operators with `normal_encoding: octahedral` (Zaidi et al.,
//! "Local Surface Approximation Contours for Virtual Reality Stylisation",
//! eqs. 1–8; §6 on G-buffer precision).
//!
//! - The GPU operators against their f64 references on the packed
//!   G-buffers the GPU rendered, with constant flags, so the compiler's
//!   specializations (`lsa` → `lsa_curv`, …) carry the encoding along.
//! - Precision and recall against the analytic ground truth
//!   (`npr_lab::contours`) at 128² and 256², against the float32 path's.

use npr_lab::contours::{accuracy, builtin_scenes, ink_mask, Accuracy};
use npr_stdlib::reference_lsa::{self as lsa, LsaSettings};

use crate::common;
use common::lsa::{output, scene_of, style, targets, to_f64, uv, PACKED};

/// `lsa_contours.npr` packed, with its two extensions set to constants.
fn packed(plane: bool, aa: bool) -> npr_runner::StyleProgram {
    let plane_line = format!("param plane: bool = {plane}");
    let aa_line = format!("param aa: bool = {aa}");
    let mut r: Vec<(&str, &str)> = PACKED.to_vec();
    r.push(("param plane: bool = true", &plane_line));
    r.push(("param aa: bool = true", &aa_line));
    style("lsa_contours.npr", &r)
}

#[test]
fn packed_operators_match_f64_reference_on_rendered_gbuffers() {
    let size = (48, 40);
    for s in builtin_scenes()
        .iter()
        .filter(|s| ["cube", "parallel_planes", "sphere_on_plane"].contains(&s.name))
    {
        let scene = scene_of(s);
        for (plane, aa) in [(false, false), (true, false), (false, true), (true, true)] {
            let program = packed(plane, aa);
            // The specialized operator is called with the encoding: no
            // `lsa` call is left where a flag is off.
            let error_wgsl = &program.shaders["error.wgsl"];
            let called = match (plane, aa) {
                (true, true) => "npr_lsa(",
                (true, false) => "npr_lsa_sum(",
                (false, true) => "npr_lsa_curv_aa(",
                (false, false) => "npr_lsa_curv(",
            };
            assert!(error_wgsl.contains(called), "plane={plane} aa={aa}: no call {called}");
            let t = targets(&program, &scene, size, &["gbuffer.pos", "gbuffer.nrm", "error.e"]);
            let (pos, nrm, err) = (to_f64(&t[0]), to_f64(&t[1]), &t[2]);
            let settings = LsaSettings {
                plane,
                aa,
                octahedral: true,
                ..LsaSettings::BASE
            };
            let (mut mismatched, mut lines) = (0, 0);
            for y in 0..size.1 {
                for x in 0..size.0 {
                    let want = lsa::lsa(&pos, &nrm, uv(x, y, size.0, size.1), &settings);
                    let got = err.texel(x, y);
                    assert!(got.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)), "{got:?}");
                    // As for the float32 G-buffer (lsa_contours.rs): rgba16float
                    // output, and a remap decision can flip where f32 and f64
                    // straddle η_min or η_max.
                    if (0..4).any(|c| (got[c] as f64 - want[c]).abs() > 2e-3) {
                        mismatched += 1;
                    }
                    lines += usize::from(lsa::merge(want) > 0.5);
                }
            }
            let n = (size.0 * size.1) as usize;
            if s.name == "parallel_planes" && !plane {
                assert_eq!(lines, 0, "{}: e_curv sees no step (Fig. 3)", s.name);
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

/// Stated bounds, from the measured table (docs/PERFORMANCE.md, "Packed
/// G-buffer"): the octahedral normals alone change nothing (every precision
/// and recall equal to the float32 G-buffer's, checked within 0.01); the
/// packed G-buffer is within 0.01 everywhere but one case, the 5 cm step
/// between the parallel planes at 256², where the rgba16float positions
/// draw 22 false line pixels next to the step (precision 0.9525; 0.9191 with
/// the f16 positions alone, the precision study's known weak spot): there
/// precision ≥ 0.94, recall still within 0.01.
const BOUND: f64 = 0.01;
const PLANES_256_PRECISION: f64 = 0.94;

#[test]
fn packed_accuracy_matches_float32_against_analytic_truth() {
    let full = style("lsa_contours.npr", &[]);
    let packed = style("lsa_contours.npr", PACKED);
    // Each half of the packing alone, to say which one costs what.
    let half_positions = style(
        "lsa_contours.npr",
        &[
            PACKED[0],
            (
                "out nrm: rgba32float = vec4(normal.world, 1.0)",
                "out nrm: rgba32float = vec4(normal.view, 1.0)",
            ),
        ],
    );
    let oct_normals = style(
        "lsa_contours.npr",
        &[
            (
                "out pos: rgba32float = vec4(position.world, 1.0)",
                "out pos: rgba32float = vec4(position.view, 1.0)",
            ),
            PACKED[1],
            PACKED[2],
        ],
    );
    let mut table = String::from(
        "| scene | size | float32 P | packed P | float32 R | packed R | f16 positions only: P / R | octahedral normals only: P / R |\n|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for s in builtin_scenes() {
        let scene = scene_of(&s);
        for size in [128u32, 256] {
            let truth = s.truth(size, size);
            let measure = |p: &npr_runner::StyleProgram| -> Accuracy {
                accuracy(&ink_mask(&output(p, &scene, size), 0.5), &truth, 1)
            };
            let (a, b) = (measure(&full), measure(&packed));
            let (hp, on) = (measure(&half_positions), measure(&oct_normals));
            table.push_str(&format!(
                "| {} | {size} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} / {:.4} | {:.4} / {:.4} |\n",
                s.name, a.precision, b.precision, a.recall, b.recall, hp.precision, hp.recall, on.precision, on.recall
            ));
            assert!(b.truth > 0 && b.predicted > 0, "{} {size}: nothing to compare", s.name);
            let delta = |x: &Accuracy| (a.precision - x.precision).abs().max((a.recall - x.recall).abs());
            if delta(&on) > BOUND {
                failures.push(format!("{} {size}: float32 {a:?}, octahedral normals {on:?}", s.name));
            }
            worst = worst.max(delta(&b));
            let planes_256 = s.name == "parallel_planes" && size == 256;
            let precision_ok = if planes_256 {
                b.precision >= PLANES_256_PRECISION
            } else {
                (a.precision - b.precision).abs() <= BOUND
            };
            if !precision_ok || (a.recall - b.recall).abs() > BOUND {
                failures.push(format!("{} {size}: float32 {a:?}, packed {b:?}", s.name));
            }
        }
    }
    println!("{table}\nlargest |Δ| of precision or recall: {worst:.4}");
    assert!(failures.is_empty(), "{}\n{table}", failures.join("\n"));
}
