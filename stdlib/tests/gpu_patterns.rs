//! GPU versus CPU reference for the dynamic 2D patterns' operators (Breslav
//! et al. 2007): the fuzzy visibility, the similarity's complex product, the
//! pattern frame's coordinates, the halftone screen and the tone-corrected
//! halftone (§3.1–3.5); and the tone the halftone actually produces over an
//! LOD transition, with and without its correction table (§3.5).

mod harness;

use harness::*;
use stdlib::halftone_table::{HalftoneTable, ROWS, TONES};
use stdlib::reference::{self as r, ImageF64};

#[test]
fn dynamic_pattern_operators_match_reference() {
    // complex_mul and pattern_uv on random vectors (pattern frames with
    // scales from 1e-3 to 1e3), including a zero u.
    let mut g = Lcg(41);
    let mut cases = Vec::new();
    for k in 0..200 {
        let s = 10f64.powf(g.next() * 6.0 - 3.0);
        let v = |g: &mut Lcg, scale: f64| [(g.next() * 2.0 - 1.0) * scale, (g.next() * 2.0 - 1.0) * scale];
        let (o, q) = (v(&mut g, 500.0), v(&mut g, 500.0));
        let u = if k == 7 { [0.0, 0.0] } else { v(&mut g, s) };
        let w = v(&mut g, s);
        cases.push((o, u, w, q));
    }
    let inputs: Vec<[f32; 4]> = cases
        .iter()
        .flat_map(|(o, u, v, q)| [f32v([o[0], o[1], u[0], u[1]]), f32v([v[0], v[1], q[0], q[1]]), [0.0; 4]])
        .collect();
    let n = cases.len() as u32;
    let out = run(
        &op_wgsl(&["complex_mul", "pattern_uv"]),
        "result = vec4<f32>(npr_complex_mul(a.zw, b.xy), npr_pattern_uv(a.xy, a.zw, b.xy, b.zw));",
        &inputs,
        (n, 1),
        &[],
    );
    // Reference from the f32-rounded inputs the GPU saw.
    let reference: Vec<[f64; 4]> = inputs
        .chunks(3)
        .map(|x| {
            let (a, b) = (x[0].map(|c| c as f64), x[1].map(|c| c as f64));
            let m = r::complex_mul([a[2], a[3]], [b[0], b[1]]);
            let uv = r::pattern_uv([a[0], a[1]], [a[2], a[3]], [b[0], b[1]], [b[2], b[3]]);
            [m[0], m[1], uv[0], uv[1]]
        })
        .collect();
    compare_rel("complex_mul, pattern_uv", &out, &reference, 4, 1e-4);
    assert_eq!(out[7][2], 0.0, "a zero u gives 0, not NaN");

    // id_share on an ID image with three objects, at sizes down to 1×1 and
    // at points off the image, for every radius.
    for (w, h) in [(1, 1), (3, 7), (33, 20)] {
        let ids = ImageF64::new(w, h, |x, y| [((x / 3 + y / 2) % 3) as f64, 0.0, 0.0, 1.0]);
        let tex = [TexIn {
            image: ids.clone(),
            format: wgpu::TextureFormat::Rgba32Float,
        }];
        for radius in [0.0, 1.0, 2.4, 8.0] {
            for id in [0.0, 1.0, 2.0, 5.0] {
                // Points on and off the image (uv from -0.5 to 1.5).
                let out = run(
                    &op_wgsl(&["id_share"]),
                    &format!(
                        "let at = uv * 2.0 - vec2<f32>(0.5);\n    result = vec4<f32>(npr_id_share(t0, at, {id:?}, {radius:?}), 0.0, 0.0, 0.0);"
                    ),
                    &[],
                    (2 * w + 1, 2 * h + 1),
                    &tex,
                );
                let reference = pixels_ref((2 * w + 1, 2 * h + 1), |uv| {
                    let at = [uv[0] * 2.0 - 0.5, uv[1] * 2.0 - 0.5];
                    [r::id_share(&ids, at, id, radius), 0.0, 0.0, 0.0]
                });
                compare(
                    &format!("id_share {w}x{h} r {radius} id {id}"),
                    &out,
                    &reference,
                    1,
                    1e-6,
                );
            }
        }
    }
}

/// A table as a texture input (Rgba32Float: the thresholds exactly as f32).
fn table_texture(table: &HalftoneTable) -> TexIn {
    let texels = table.texels();
    TexIn {
        image: ImageF64::new(TONES as u32, ROWS as u32, |x, y| {
            [texels[y as usize * TONES + x as usize] as f64, 0.0, 0.0, 1.0]
        }),
        format: wgpu::TextureFormat::Rgba32Float,
    }
}

#[test]
fn halftone_operators_match_reference() {
    // The screen at random points near and far from the origin (where f32
    // pattern coordinates are coarse), at blends inside and outside [0, 1].
    let mut g = Lcg(7);
    let mut cases: Vec<[[f64; 4]; 3]> = (0..400)
        .map(|i| {
            let scale = [1.0, 10.0, 1000.0][i % 3];
            let uv = [g.range(-scale, scale), g.range(-scale, scale)];
            let blend = [0.0, 1.0, g.next(), -0.5, 2.0][i % 5];
            let tone = g.range(-0.1, 1.1);
            [q([uv[0], uv[1], blend, tone]), [0.0; 4], [0.0; 4]]
        })
        .collect();
    // Cell corners and centres, where the screen has its extremes.
    for uv in [[0.0, 0.0], [0.5, 0.5], [0.25, 0.75], [-3.0, 7.5]] {
        cases.push([[uv[0], uv[1], 0.5, 0.5], [0.0; 4], [0.0; 4]]);
    }
    let out = one(
        "halftone_screen",
        "result = vec4<f32>(npr_halftone_screen(a.xy, a.z), 0.0, 0.0, 0.0);",
        &cases,
        &[],
    );
    let reference: Vec<[f64; 4]> = cases
        .iter()
        .map(|c| [r::halftone_screen([c[0][0], c[0][1]], c[0][2]), 0.0, 0.0, 0.0])
        .collect();
    compare("halftone_screen", &out, &reference, 1, 2e-6);

    // The corrected and the uncorrected halftone, with soft and sharp edges.
    for (edge, corrected) in [(0.1, true), (0.2, true), (0.02, true), (0.1, false)] {
        let table = HalftoneTable::build(edge as f32 as f64, corrected);
        let inputs: Vec<[f32; 4]> = cases.iter().flat_map(|c| c.map(f32v)).collect();
        let out = run(
            &op_wgsl(&["halftone_screen", "halftone"]),
            "result = vec4<f32>(npr_halftone(t0, a.xy, a.w, a.z), 0.0, 0.0, 0.0);",
            &inputs,
            (cases.len() as u32, 1),
            &[table_texture(&table)],
        );
        let reference: Vec<[f64; 4]> = cases
            .iter()
            .map(|c| [r::halftone(&table, [c[0][0], c[0][1]], c[0][3], c[0][2]), 0.0, 0.0, 0.0])
            .collect();
        // smoothstep's slope is 1.5/(2·edge): the screen's f32 error (2e-6)
        // and the thresholds' f32 rounding, times that.
        let tol = 1e-5 * 1.5 / (2.0 * edge);
        compare(
            &format!("halftone edge {edge} corrected {corrected}"),
            &out,
            &reference,
            1,
            tol,
        );
    }
}

/// The tones of the tone-over-LOD test: 0.05, 0.10, …, 0.95.
const TEST_TONES: usize = 19;
/// Its blends: 0, 0.1, …, 1 (most between the table's 16 rows).
const TEST_BLENDS: usize = 11;
/// Pixels per screen cell along each axis of a test tile.
const CELL_PX: u32 = 64;

/// Draws one screen cell per (tone, blend) tile with `npr_halftone` on the
/// GPU and returns, per tile, the mean paper share the pixels show minus
/// the wanted tone.
fn tone_errors(table: &TexIn) -> Vec<(f64, f64, f64)> {
    let size = (TEST_TONES as u32 * CELL_PX, TEST_BLENDS as u32 * CELL_PX);
    let body = format!(
        "let px = uv * vec2<f32>({w}.0, {h}.0) / {c}.0;\n    let tile = floor(px);\n    let tone = (tile.x + 1.0) * 0.05;\n    let blend = tile.y / {b}.0;\n    result = vec4<f32>(npr_halftone(t0, px - tile, tone, blend), 0.0, 0.0, 0.0);",
        w = size.0,
        h = size.1,
        c = CELL_PX,
        b = TEST_BLENDS - 1
    );
    let out = run(
        &op_wgsl(&["halftone_screen", "halftone"]),
        &body,
        &[],
        size,
        std::slice::from_ref(table),
    );
    let mut errors = Vec::new();
    for j in 0..TEST_BLENDS {
        for i in 0..TEST_TONES {
            let mut sum = 0.0;
            for y in 0..CELL_PX {
                for x in 0..CELL_PX {
                    let at = (j as u32 * CELL_PX + y) * size.0 + i as u32 * CELL_PX + x;
                    sum += out[at as usize][0] as f64;
                }
            }
            let tone = (i + 1) as f64 * 0.05;
            let mean = sum / (CELL_PX * CELL_PX) as f64;
            errors.push((tone, j as f64 / (TEST_BLENDS - 1) as f64, mean - tone));
        }
    }
    errors
}

fn worst(errors: &[(f64, f64, f64)]) -> (f64, f64, f64) {
    errors
        .iter()
        .copied()
        .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
        .expect("errors")
}

#[test]
fn halftone_tone_holds_over_an_lod_transition_only_with_correction() {
    // §3.5: with the table, the mean tone over a cell is the wanted tone
    // within 2/255 at every blend of the LOD transition.
    let corrected = tone_errors(&table_texture(&HalftoneTable::build(0.1, true)));
    let (tone, blend, error) = worst(&corrected);
    println!("corrected (edge 0.1): worst tone error {error:+.5} at tone {tone:.2}, blend {blend:.1}");
    assert!(
        error.abs() <= 2.0 / 255.0,
        "corrected tone error {error} at tone {tone}, blend {blend}"
    );

    // Without it the threshold is the tone, and the screen's tone response
    // (and its change with the blend) shows.
    let plain = tone_errors(&table_texture(&HalftoneTable::build(0.1, false)));
    let (tone, blend, error) = worst(&plain);
    println!("uncorrected (edge 0.1): worst tone error {error:+.5} at tone {tone:.2}, blend {blend:.1}");
    assert!(
        error.abs() > 10.0 / 255.0,
        "the uncorrected halftone is off by {error} at most"
    );
    let mean_abs = |e: &[(f64, f64, f64)]| e.iter().map(|x| x.2.abs()).sum::<f64>() / e.len() as f64;
    println!(
        "mean |tone error|: corrected {:.5}, uncorrected {:.5}",
        mean_abs(&corrected),
        mean_abs(&plain)
    );

    // jot-lib's mismatch: a table built for a ±0.1 edge drawn with ±0.2.
    // Writing 0.2 into the table's edge texel makes the shader draw that.
    let mut mismatched = table_texture(&HalftoneTable::build(0.1, true));
    let edge_texel = mismatched.image.clone();
    mismatched.image = ImageF64::new(TONES as u32, ROWS as u32, |x, y| {
        if (x, y) == (0, ROWS as u32 - 1) {
            [0.2, 0.0, 0.0, 1.0]
        } else {
            edge_texel.load(x as i64, y as i64)
        }
    });
    let (tone, blend, error) = worst(&tone_errors(&mismatched));
    println!(
        "table for ±0.1 drawn with ±0.2 (jot-lib): worst tone error {error:+.5} at tone {tone:.2}, blend {blend:.1}"
    );
    assert!(error.abs() > 2.0 / 255.0, "a mismatched edge should show: {error}");
}

#[test]
fn halftone_table_is_monotone_and_spans_the_screen() {
    for edge in [0.005, 0.05, 0.1, 0.2, 0.5] {
        let table = HalftoneTable::build(edge, true);
        for j in 0..stdlib::halftone_table::BLENDS {
            for i in 1..TONES {
                assert!(
                    table.at(i, j) >= table.at(i - 1, j),
                    "edge {edge}: row {j} decreases at {i}"
                );
            }
            // Tone 0 (all ink) needs a threshold where no paper shows, and
            // tone 1 one where no ink does.
            let blend = j as f64 / 15.0;
            let (first, last) = (table.at(0, j), table.at(TONES - 1, j));
            let mean = |t: f64| stdlib::halftone_table::mean_paper(edge, blend, t);
            assert!(
                mean(first) < 1e-3,
                "edge {edge}: row {j} starts at {first}, R = {}",
                mean(first)
            );
            assert!(
                mean(last) > 1.0 - 1e-3,
                "edge {edge}: row {j} ends at {last}, R = {}",
                mean(last)
            );
        }
        // The f64 mean paper share at the stored thresholds is the tone.
        for (i, j) in [(10, 0), (128, 7), (200, 15), (64, 3)] {
            let tone = i as f64 / 255.0;
            let blend = j as f64 / 15.0;
            let got = stdlib::halftone_table::mean_paper(edge, blend, table.at(i, j));
            assert!(
                (got - tone).abs() < 1e-3,
                "edge {edge}: R(R⁻¹({tone})) = {got} at blend {blend}"
            );
        }
        assert_eq!(table.texels()[TONES * (ROWS - 1)], edge as f32);
    }
}
