//! Times the CPU pose and deformation of an object playing a clip
//! (`scene::rig`, issue 48): the Blender arm of `examples/models/`
//! (2 joints, 4 weights a vertex) repeated to 10k, 100k and 1M vertices,
//! and the blob's two morph targets likewise. Prints milliseconds per
//! frame for `Rig::pose` + `Rig::deform` (the work a rigid object does not
//! do at all).
//!
//! `cargo run -p npr-runner --example skin_timing`

use npr_runner::scene::load_mesh_and_rig;
use npr_runner::scene::rig::Rig;
use std::path::Path;
use std::time::Instant;

/// `rig` with its (single) piece's vertices repeated until there are at
/// least `vertices`.
fn scaled(rig: &Rig, vertices: usize) -> Rig {
    let mut big = rig.clone();
    let n = rig.bind.vertex_count();
    let copies = vertices.div_ceil(n);
    let repeat = |v: &Vec<[f32; 3]>| v.iter().cycle().take(n * copies).copied().collect::<Vec<_>>();
    big.bind.positions = repeat(&rig.bind.positions);
    big.bind.normals = repeat(&rig.bind.normals);
    big.bind.uvs = rig
        .bind
        .uvs
        .as_ref()
        .map(|u| u.iter().cycle().take(n * copies).copied().collect());
    big.bind.tangents = rig
        .bind
        .tangents
        .as_ref()
        .map(|t| t.iter().cycle().take(n * copies).copied().collect());
    big.bind.indices = (0..copies)
        .flat_map(|c| rig.bind.indices.iter().map(move |i| i + (c * n) as u32))
        .collect();
    big.bind.parts = None;
    big.joints = rig.joints.iter().cycle().take(n * copies).copied().collect();
    big.weights = rig.weights.iter().cycle().take(n * copies).copied().collect();
    big.pieces.truncate(1);
    big.pieces[0].vertex_count = n * copies;
    for target in &mut big.pieces[0].targets {
        target.positions = repeat(&target.positions);
        target.normals = target.normals.as_ref().map(repeat);
        target.tangents = target.tangents.as_ref().map(repeat);
    }
    big
}

fn millis_per_frame(rig: &Rig, frames: u32) -> f64 {
    let duration = rig.clips[0].duration;
    std::hint::black_box(rig.deform(&rig.pose(Some((0, 0.0)))));
    let start = Instant::now();
    for f in 0..frames {
        let t = duration * f as f32 / frames as f32;
        std::hint::black_box(rig.deform(&rig.pose(Some((0, t)))));
    }
    start.elapsed().as_secs_f64() * 1000.0 / f64::from(frames)
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models");
    for file in ["arm.glb", "blob.glb"] {
        let (_, rig) = load_mesh_and_rig(&dir.join(file)).expect("test character");
        let rig = rig.expect("a rig");
        for vertices in [10_000, 100_000, 1_000_000] {
            let big = scaled(&rig, vertices);
            let frames = (2_000_000 / vertices).clamp(3, 100) as u32;
            println!(
                "{file}: {} vertices: {:.2} ms per frame",
                big.bind.vertex_count(),
                millis_per_frame(&big, frames)
            );
        }
    }
}
