//! Times quantitative invisibility (issue 51, decision 0063): the runs of
//! one QI along a torus's silhouettes and its creases over 30°, seen from
//! an eye where the torus hides part of itself, at four tessellations. Per
//! row: triangles, the hierarchy's build (`Occluders::new`), the lines'
//! segments and the time to cut them into runs (`Occluders::runs`, a ray
//! per sample plus bisections), and that time per segment. The
//! fastest of 5 repeats. A measurement, never a test.
//!
//! `cargo build --workspace --example qi_timing && target/debug/examples/qi_timing`

use glam::{DMat4, DVec3};
use npr_runner::lines::edges::EdgeMesh;
use npr_runner::lines::visibility::Occluders;
use npr_runner::scene::primitives::torus;
use std::time::Instant;

fn fastest<T>(repeats: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..repeats {
        let start = Instant::now();
        let out = f();
        best = best.min(start.elapsed().as_secs_f64());
        last = Some(out);
    }
    (best, last.expect("repeats > 0"))
}

fn main() {
    println!("| triangles | build (ms) | segments | runs (ms) | µs / segment | pieces |");
    println!("|---:|---:|---:|---:|---:|---:|");
    for (segments, sides) in [(32, 16), (96, 48), (256, 128), (512, 256)] {
        let mesh = EdgeMesh::new(&torus(1.0, 0.35, segments, sides));
        let model = DMat4::from_rotation_x(0.5);
        let eye = DVec3::new(0.3, 0.8, 4.0);
        let (build_s, occluders) = fastest(5, || Occluders::new([(&mesh, model)]));
        let local_eye = model.inverse().transform_point3(eye);
        let mut edges = mesh.silhouettes(local_eye);
        edges.extend(mesh.creases_over(30.0));
        let lines: Vec<(Vec<DVec3>, bool)> = mesh
            .chain(&edges)
            .iter()
            .map(|c| {
                let points = c
                    .vertices
                    .iter()
                    .map(|&v| model.transform_point3(mesh.positions[v as usize]));
                (points.collect(), c.closed)
            })
            .collect();
        let segment_count: usize = lines.iter().map(|(p, closed)| p.len() - 1 + usize::from(*closed)).sum();
        let (runs_s, pieces) = fastest(5, || {
            lines
                .iter()
                .map(|(points, closed)| occluders.runs(points, *closed, eye).len())
                .sum::<usize>()
        });
        println!(
            "| {} | {:.2} | {} | {:.2} | {:.1} | {} |",
            mesh.faces.len(),
            build_s * 1e3,
            segment_count,
            runs_s * 1e3,
            runs_s * 1e6 / segment_count as f64,
            pieces
        );
    }
}
