//! The tone the halftone (Breslav et al. 2007 §3.5) actually produces on
//! the GPU over an LOD transition, with and without its correction table,
//! and the table's shape. (The patterns' operators against their f64
//! references are data cases in `stdlib/src/ops/patterns/`.)

mod harness;

use harness::*;
use npr_stdlib::halftone_table::{HalftoneTable, ROWS, TONES};
use npr_stdlib::reference::ImageF64;

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
        for j in 0..npr_stdlib::halftone_table::BLENDS {
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
            let mean = |t: f64| npr_stdlib::halftone_table::mean_paper(edge, blend, t);
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
            let got = npr_stdlib::halftone_table::mean_paper(edge, blend, table.at(i, j));
            assert!(
                (got - tone).abs() < 1e-3,
                "edge {edge}: R(R⁻¹({tone})) = {got} at blend {blend}"
            );
        }
        assert_eq!(table.texels()[TONES * (ROWS - 1)], edge as f32);
    }
}
