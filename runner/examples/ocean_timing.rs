//! Times the ocean primitive's per-frame rebuild (Age of Sail §6.1) at the
//! scene defaults: the wave field by the factored DFT (`Spectrum::tile`)
//! against summing sines directly (`Spectrum::sample`, the f64 reference),
//! and the whole mesh (`ocean_mesh`). Prints milliseconds per call.
//!
//! `cargo build --workspace --example ocean_timing && target/debug/examples/ocean_timing`

use npr_runner::scene::ocean::{ocean_mesh, Ocean, Spectrum};
use std::time::Instant;

fn millis_per_call(calls: u32, mut f: impl FnMut(u32)) -> f64 {
    f(0); // warm-up
    let start = Instant::now();
    for i in 0..calls {
        f(i);
    }
    start.elapsed().as_secs_f64() * 1000.0 / f64::from(calls)
}

fn main() {
    let ocean = Ocean::default();
    let spectrum = Spectrum::new(&ocean);
    let cells = ocean.cells;
    let spacing = f64::from(ocean.size) / f64::from(cells);
    let factored = millis_per_call(10, |i| {
        std::hint::black_box(spectrum.tile(ocean.grid_origin(), cells, f64::from(i) * 0.7));
    });
    let lattice = |j: u32, k: u32| {
        (
            ocean.grid_origin() + f64::from(k) * spacing,
            ocean.grid_origin() + f64::from(j) * spacing,
        )
    };
    let direct = millis_per_call(2, |i| {
        for j in 0..cells {
            for k in 0..cells {
                let (x, z) = lattice(j, k);
                std::hint::black_box(spectrum.sample(x, z, f64::from(i) * 0.7));
            }
        }
    });
    // The two agree (the tests check the same through the mesh).
    let tile = spectrum.tile(ocean.grid_origin(), cells, 3.1);
    let mut largest_difference: f64 = 0.0;
    for j in 0..cells {
        for k in 0..cells {
            let (x, z) = lattice(j, k);
            let (reference, fast) = (spectrum.sample(x, z, 3.1), tile[(j * cells + k) as usize]);
            largest_difference = largest_difference
                .max((reference.displacement - fast.displacement).abs().max_element())
                .max((reference.d_dx - fast.d_dx).abs().max_element());
        }
    }
    let mesh = millis_per_call(10, |i| {
        std::hint::black_box(ocean_mesh(&ocean, f64::from(i) * 0.7));
    });
    let side = ocean.cells * ocean.tiles + 1;
    println!(
        "ocean defaults: {} waves, {cells}² field points, {side}² vertices",
        spectrum.waves.len()
    );
    println!("wave field, factored DFT : {factored:8.2} ms");
    println!("wave field, direct sum   : {direct:8.2} ms");
    println!("largest difference       : {largest_difference:.2e} (m, and slope)");
    println!("whole mesh (field + vertices): {mesh:8.2} ms");
}
