//! `npr bench pixels`: the cost of a compute pass over the pixels of an ID
//! target (`compute(pixels, ids.id)`) against the image size and the number
//! of objects on screen, next to a plain copy kernel over as many floats as
//! the ID target has pixels, in the same run, and the reduction's error
//! against a CPU f64 reduction of the read-back ID image.
//!
//! The style reduces the pixel count and Σ frag_coord per object (a visible
//! area and centroid). Objects are spheres in a grid that covers most of the
//! screen whatever their number, so more objects means more, smaller
//! objects and more of them per tile: the pass's cost grows with the rounds
//! (one per distinct object per tile), which this measures. Each frame is
//! timed next to a frame of the same ID and render passes without the
//! compute pass (`NULL_STYLE`), and the copy next to an empty submit,
//! interleaved; the differences are the reduction's and the copy's own cost
//! (wall clock: lavapipe's timestamps do not bracket compute work).

use crate::bench_reduce::{against_copy, CopyKernel};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, RunError, StyleProgram};
use std::time::Instant;

/// The benchmarked style.
pub const STYLE: &str = r#"style "Pixel reduction benchmark"
pass ids: render(scene) {
  out id: r32float = object.id
}
pass cover: compute(pixels, ids.id) {
  reduce count: float = sum(1.0)
  reduce centre: vec2 = sum(frag_coord)
}
pass show: render(scene) {
  out c: rg32float = vec2(ids.id) + cover.centre / max(cover.count, 1.0) * 1e-9
}
output show.c
"#;

/// The same ID and render passes without the compute pass.
pub const NULL_STYLE: &str = r#"style "Pixel reduction benchmark, no reduction"
pass ids: render(scene) {
  out id: r32float = object.id
}
pass show: render(scene) {
  out c: rg32float = vec2(ids.id)
}
output show.c
"#;

/// `objects` spheres in a grid over most of the screen (a camera at 6 m
/// with a 40° field of view sees about ±2.2 m).
pub fn scene(objects: usize) -> Result<Scene, RunError> {
    let mut text = String::from(
        "[camera]\nposition = [0.0, 0.0, 6.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n\
         [light]\ndirection = [0.0, 1.0, 1.0]\n\n",
    );
    let n = (objects as f64).sqrt().ceil() as usize;
    let step = 4.0 / n as f64;
    for o in 0..objects {
        let (i, j) = (o % n, o / n);
        text += &format!(
            "[[object]]\nprimitive = {{ kind = \"sphere\", radius = {:.4}, segments = 16, rings = 8 }}\ntranslate = [{:.4}, {:.4}, 0.0]\n\n",
            step * 0.6,
            -2.0 + step * (i as f64 + 0.5),
            -2.0 + step * (j as f64 + 0.5)
        );
    }
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("pixels-bench.toml", text.clone());
    npr_runner::scene::parse_scene(&text, file, std::path::Path::new(".")).map_err(RunError::User)
}

/// One measured configuration.
#[derive(Debug, Clone)]
pub struct Row {
    pub size: u32,
    pub objects: usize,
    /// Pixels that belong to an object.
    pub covered: u64,
    /// The most distinct objects in one 16 × 16 tile.
    pub most_per_tile: usize,
    /// Median wall ms a frame with the reduction takes more than one without.
    pub reduce_ms: f64,
    /// Median wall ms a copy of size² floats takes more than an empty submit.
    pub copy_ms: f64,
    /// Largest |GPU − f64| / (f64) of Σ frag_coord over objects and components.
    pub rel_error: f64,
    /// Whether every pixel count equals the f64 count exactly.
    pub counts_exact: bool,
}

/// Per object (count, Σx, Σy) from the read-back ID image, in f64; and the
/// most distinct objects in a tile.
fn cpu_reduction(ids: &npr_runner::readback::TargetImage, objects: usize) -> (Vec<(f64, f64, f64)>, usize) {
    let mut sums = vec![(0.0, 0.0, 0.0); objects];
    let mut tiles: std::collections::BTreeMap<(u32, u32), std::collections::BTreeSet<usize>> = Default::default();
    for y in 0..ids.height {
        for x in 0..ids.width {
            let id = ids.texel(x, y)[0];
            if id < 0.5 || id > objects as f32 + 0.5 {
                continue;
            }
            let o = id.round() as usize - 1;
            tiles.entry((x / 16, y / 16)).or_default().insert(o);
            sums[o].0 += 1.0;
            sums[o].1 += x as f64 + 0.5;
            sums[o].2 += y as f64 + 0.5;
        }
    }
    (sums, tiles.values().map(|t| t.len()).max().unwrap_or(0))
}

/// Measure every (size, objects) pair; `progress` gets a line per pair.
pub fn run(
    gpu: &Gpu,
    (program, null): (&StyleProgram, &StyleProgram),
    sizes: &[u32],
    objects: &[usize],
    frames: u32,
    progress: impl Fn(&str),
) -> Result<Vec<Row>, RunError> {
    let id_target = program
        .manifest
        .targets
        .iter()
        .position(|t| t.name == "ids.id")
        .ok_or_else(|| RunError::Internal("the benchmark style has no `ids.id`".into()))?;
    let mut rows = Vec::new();
    for &size in sizes {
        for &o in objects {
            let started = Instant::now();
            let scene = scene(o)?;
            let spec = FrameSpec::still(size, size, 0);
            let mut with = npr_runner::Renderer::new(&gpu.device, &gpu.queue, program, &scene)?;
            let mut without = npr_runner::Renderer::new(&gpu.device, &gpu.queue, null, &scene)?;
            let copy = CopyKernel::new(gpu, (size * size) as usize);
            let (reduce_ms, copy_ms) = against_copy(gpu, (&mut with, &mut without), (&scene, &spec), &copy, frames)?;
            let values = with.read_object_values("cover")?;
            let ids = with.render_until_target(&scene, &spec, id_target)?;
            let (cpu, most_per_tile) = cpu_reduction(&ids, scene.objects.len());
            let (mut rel_error, mut counts_exact) = (0.0f64, true);
            for (v, (n, sx, sy)) in values.iter().zip(&cpu) {
                counts_exact &= v[0][0] as f64 == *n;
                for (got, want) in [(v[1][0], sx), (v[1][1], sy)] {
                    if *want > 0.0 {
                        rel_error = rel_error.max((got as f64 - want).abs() / want);
                    }
                }
            }
            let row = Row {
                size,
                objects: o,
                covered: cpu.iter().map(|c| c.0 as u64).sum(),
                most_per_tile,
                reduce_ms,
                copy_ms,
                rel_error,
                counts_exact,
            };
            progress(&format!(
                "{size}², {o} objects: {:.3} ms (copy {:.3} ms) in {:.1} s",
                row.reduce_ms,
                row.copy_ms,
                started.elapsed().as_secs_f64()
            ));
            rows.push(row);
        }
    }
    Ok(rows)
}

/// The rows as a Markdown table.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| size | objects | covered px | most objects in a tile | reduce ms | ns / px | copy ms | reduce ÷ copy | rel. error Σ frag_coord | counts exact |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|:---:|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {0}² | {1} | {2} | {3} | {4:.3} | {5:.2} | {6:.3} | {7:.1}× | {8:.1e} | {9} |\n",
            r.size,
            r.objects,
            r.covered,
            r.most_per_tile,
            r.reduce_ms,
            r.reduce_ms * 1e6 / (r.size as f64 * r.size as f64),
            r.copy_ms,
            r.reduce_ms / r.copy_ms.max(1e-9),
            r.rel_error,
            if r.counts_exact { "yes" } else { "no" }
        ));
    }
    s
}
