//! The halftone's tone correction (Breslav et al. 2007 §3.5) end to end: a
//! style declares `texture dots = halftone_table(edge: 0.1)`, the runner
//! builds the table at load and stores it as half floats, and the style's
//! `halftone(...)` draws one screen cell per (tone, blend) tile. The mean of
//! each tile's pixels is the tone the halftone produced; with the table it
//! is the wanted tone within 2/255 across the whole LOD transition, and
//! without it (`correction: off`) it is not. (`stdlib/tests/gpu_patterns.rs`
//! checks the same on the operator alone, with an f32 table.)

use crate::common;
use common::gpu;

/// Pixels per screen cell along each axis.
const CELL: u32 = 64;
/// Tones 0.05 … 0.95 across, blends 0, 0.1, … 1 down.
const TONES: u32 = 19;
const BLENDS: u32 = 11;

fn style(correction: &str) -> String {
    format!(
        r#"style "Tone over LOD"
texture dots = halftone_table(edge: 0.1, correction: {correction})
pass g: render(scene) {{
  out c: r32float = 1.0
}}
pass ht: image(g) {{
  let px = frag_coord / {CELL}px
  let tile = floor(px)
  let tone = (tile.x + 1.0) * 0.05
  let blend = tile.y / {b}.0
  out paper: rgba32float = vec4(halftone(dots, px - tile, tone, blend), 0.0, 0.0, 1.0)
}}
output ht.paper
"#,
        b = BLENDS - 1
    )
}

/// Per tile: (tone, blend, mean paper share − tone).
fn tone_errors(correction: &str) -> Vec<(f64, f64, f64)> {
    let program = common::compile_text(&style(correction));
    let text = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n[[object]]\nprimitive = { kind = \"sphere\" }\n";
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("tone.toml", text.to_string());
    let scene = npr_runner::scene::parse_scene(text, file, std::path::Path::new(".")).expect("scene");
    let (w, h) = (TONES * CELL, BLENDS * CELL);
    let mut renderer = npr_runner::Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    renderer
        .render(&scene, &npr_runner::FrameSpec::still(w, h, 0))
        .expect("render");
    let image = renderer.read_output().expect("read back").to_rgba_f32();
    let mut errors = Vec::new();
    for j in 0..BLENDS {
        for i in 0..TONES {
            let mut sum = 0.0;
            for y in 0..CELL {
                for x in 0..CELL {
                    sum += image[((j * CELL + y) * w + i * CELL + x) as usize][0] as f64;
                }
            }
            let tone = (i + 1) as f64 * 0.05;
            errors.push((tone, j as f64 / (BLENDS - 1) as f64, sum / (CELL * CELL) as f64 - tone));
        }
    }
    errors
}

fn worst(errors: &[(f64, f64, f64)]) -> (f64, f64, f64) {
    errors
        .iter()
        .copied()
        .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
        .expect("tiles")
}

#[test]
fn the_corrected_halftone_keeps_its_tone_over_an_lod_transition() {
    let (tone, blend, error) = worst(&tone_errors("on"));
    println!("with the table: worst tone error {error:+.5} at tone {tone:.2}, blend {blend:.1}");
    assert!(error.abs() <= 2.0 / 255.0, "tone {tone}, blend {blend}: off by {error}");
    let (tone, blend, error) = worst(&tone_errors("off"));
    println!("without: worst tone error {error:+.5} at tone {tone:.2}, blend {blend:.1}");
    assert!(
        error.abs() > 10.0 / 255.0,
        "the uncorrected halftone is off by only {error}"
    );
}
