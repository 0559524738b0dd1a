//! The ocean primitive (Age of Sail §6.1) against its own f64 model and
//! analytic facts: periodic in space (L) and time (T), continuous across
//! tile seams and across the loop point, pushed down past the false
//! horizon, normals equal to finite differences of the surface, finite for
//! extreme parameters; and its scene fields with their errors.

use glam::{DVec2, DVec3, Vec3};
use npr_diag::{codes, SourceMap};
use npr_runner::scene::ocean::{ocean_mesh, Ocean, Spectrum};
use npr_runner::scene::{parse_scene, Primitive};
use std::path::Path;

/// A smaller grid than the paper's (same tile width and period) so the
/// tests run quickly; `modes` stays well under the Nyquist limit.
fn small() -> Ocean {
    Ocean {
        cells: 24,
        tiles: 3,
        modes: 8,
        wave_height: 2.0,
        drift: [1, -2],
        horizon: 40.0,
        horizon_drop: 0.1,
        ..Ocean::default()
    }
}

fn max_abs(a: DVec3, b: DVec3) -> f64 {
    (a - b).abs().max_element()
}

#[test]
fn the_default_spectrum_has_waves_with_the_requested_height() {
    let spectrum = Spectrum::new(&Ocean::default());
    assert!(spectrum.waves.len() > 100, "{} waves", spectrum.waves.len());
    // 4 σ_h = wave_height, with σ_h² = Σ a²/2.
    let sigma: f64 = spectrum
        .waves
        .iter()
        .map(|w| w.amplitude.powi(2) / 2.0)
        .sum::<f64>()
        .sqrt();
    assert!((4.0 * sigma - 1.2).abs() < 1e-6, "4σ = {}", 4.0 * sigma);
    for w in &spectrum.waves {
        // ω is a whole multiple of 2π/T and at most the deep-water ω = √(g|k|).
        let multiple = w.omega / (std::f64::consts::TAU / 20.0);
        assert!((multiple - multiple.round()).abs() < 1e-9, "ω/ω₀ = {multiple}");
        assert!(w.omega <= (9.81 * w.k.length()).sqrt() + 1e-12);
        // k on the lattice 2π(m, n)/L.
        let expected = DVec2::new(f64::from(w.index[0]), f64::from(w.index[1])) * std::f64::consts::TAU / 60.0;
        assert!((w.k - expected).length() < 1e-12);
    }
    // Deterministic for a seed, different for another.
    assert_eq!(spectrum, Spectrum::new(&Ocean::default()));
    assert_ne!(
        spectrum,
        Spectrum::new(&Ocean {
            seed: 2,
            ..Ocean::default()
        })
    );
    // Waves run mostly along the wind (+z by default): energy-weighted mean direction.
    let along: f64 = spectrum
        .waves
        .iter()
        .map(|w| w.amplitude.powi(2) * w.k.normalize().y)
        .sum();
    let total: f64 = spectrum.waves.iter().map(|w| w.amplitude.powi(2)).sum();
    assert!(along / total > 0.5, "mean k̂·ŵ = {}", along / total);
}

#[test]
fn the_model_is_periodic_in_space_and_time() {
    let ocean = Ocean::default();
    let spectrum = Spectrum::new(&ocean);
    let (size, period) = (60.0, 20.0);
    let mut worst: f64 = 0.0;
    for &(x, z, t) in &[
        (0.3, -7.1, 0.0),
        (12.25, 40.5, 3.3),
        (-29.0, 5.0, 17.9),
        (55.5, -55.5, 9.99),
    ] {
        let here = spectrum.sample(x, z, t);
        for other in [
            spectrum.sample(x + size, z, t),
            spectrum.sample(x, z - size, t),
            spectrum.sample(x + 2.0 * size, z + size, t),
            spectrum.sample(x, z, t + period),
            spectrum.sample(x, z, t - 3.0 * period),
        ] {
            worst = worst.max(max_abs(here.displacement, other.displacement));
            worst = worst.max(max_abs(here.d_dx, other.d_dx));
            worst = worst.max(max_abs(here.d_dz, other.d_dz));
        }
        // ... and it does move: half a period later the sea is different.
        let later = spectrum.sample(x, z, t + period / 2.0);
        assert!(max_abs(here.displacement, later.displacement) > 1e-3);
    }
    assert!(worst < 1e-9, "largest difference over one period: {worst}");
}

#[test]
fn the_mesh_matches_the_direct_sum_at_every_vertex_including_seams() {
    // The mesh evaluates one tile with the factored DFT and reuses it for
    // every tile; the reference sums every wave at the vertex's own lattice
    // coordinates, so a wrong index at a seam would show here.
    let ocean = small();
    let spectrum = Spectrum::new(&ocean);
    let t = 7.3;
    let mesh = ocean_mesh(&ocean, t);
    let side = (ocean.cells * ocean.tiles) as usize;
    let spacing = 60.0 / f64::from(ocean.cells);
    assert_eq!(mesh.positions.len(), (side + 1) * (side + 1));
    assert_eq!(mesh.triangle_count(), 2 * side * side);
    let mut worst: f64 = 0.0;
    for row in 0..=side {
        for column in 0..=side {
            let (x, z) = (
                ocean.grid_origin() + column as f64 * spacing,
                ocean.grid_origin() + row as f64 * spacing,
            );
            let reference = ocean.place(x, z, t, &spectrum.sample(x, z, t));
            let vertex = mesh.positions[row * (side + 1) + column];
            let vertex = DVec3::new(f64::from(vertex[0]), f64::from(vertex[1]), f64::from(vertex[2]));
            worst = worst.max(max_abs(vertex, reference.displacement));
            let uv = mesh.uvs.as_ref().expect("uvs")[row * (side + 1) + column];
            assert_eq!(uv, [x as f32, z as f32], "UVs are lattice metres");
        }
    }
    // f32 positions of up to ~100 m: a few ulps.
    assert!(worst < 1e-4, "largest vertex error {worst} m");
}

#[test]
fn tile_seams_are_as_smooth_as_the_interior() {
    // Heights across a seam (lattice column cells−1 → cells) step no more
    // than between any two interior neighbours.
    let ocean = Ocean {
        horizon: 1e5,
        drift: [0, 0],
        ..small()
    };
    let mesh = ocean_mesh(&ocean, 2.5);
    let side = (ocean.cells * ocean.tiles) as usize;
    let y = |row: usize, column: usize| mesh.positions[row * (side + 1) + column][1];
    let (mut seam, mut interior) = (0.0f32, 0.0f32);
    for row in 0..=side {
        for column in 0..side {
            let step = (y(row, column + 1) - y(row, column)).abs();
            if (column + 1) % ocean.cells as usize == 0 {
                seam = seam.max(step);
            } else {
                interior = interior.max(step);
            }
        }
    }
    assert!(
        seam > 0.0 && seam <= interior,
        "seam step {seam} vs interior {interior}"
    );
    // The rows one tile apart carry the same heights (the field repeats).
    let cells = ocean.cells as usize;
    for row in 0..=side - cells {
        for column in 0..=side - cells {
            assert!((y(row, column) - y(row + cells, column + cells)).abs() < 1e-5);
        }
    }
}

#[test]
fn the_loop_closes_through_the_treadmill() {
    // No horizon drop here: past it a vertex sinks as the treadmill carries
    // it outwards, which is motion too, but not what this test bounds.
    let ocean = Ocean {
        horizon: 1e5,
        ..small()
    };
    let start = ocean_mesh(&ocean, 0.0);
    // Bit-identical at t = T (time is reduced modulo T) ...
    assert_eq!(start, ocean_mesh(&ocean, 20.0));
    assert_eq!(start, ocean_mesh(&ocean, 40.0));
    // ... and the unreduced motion joins up: just before T the mesh is
    // within the motion of one millisecond of the mesh at 0. The drift
    // ([1, -2] tiles per period: 3 and 6 m/s) plus wave motion bounds it.
    let before = ocean_mesh(&ocean, 20.0 - 1e-3);
    let worst = start
        .positions
        .iter()
        .zip(&before.positions)
        .map(|(a, b)| (Vec3::from_array(*a) - Vec3::from_array(*b)).abs().max_element())
        .fold(0.0f32, f32::max);
    assert!(
        worst > 0.0 && worst < 0.02,
        "largest step across the loop point: {worst} m"
    );
    // The treadmill offset wraps within ±L/2 and has moved 1·L and −2·L in one period.
    for i in 0..200 {
        let offset = ocean.treadmill_offset(f64::from(i) * 0.1);
        assert!(
            offset.x.abs() <= 30.0 + 1e-9 && offset.y.abs() <= 30.0 + 1e-9,
            "{offset}"
        );
    }
    assert_eq!(ocean.drift_velocity(), DVec2::new(3.0, -6.0));
}

#[test]
fn vertices_beyond_the_false_horizon_are_pushed_down() {
    let ocean = small();
    let spectrum = Spectrum::new(&ocean);
    let t = 4.0;
    let mesh = ocean_mesh(&ocean, t);
    let side = (ocean.cells * ocean.tiles) as usize;
    let spacing = 60.0 / f64::from(ocean.cells);
    let (mut inside, mut outside) = (0, 0);
    for row in 0..=side {
        for column in 0..=side {
            let (x, z) = (
                ocean.grid_origin() + column as f64 * spacing,
                ocean.grid_origin() + row as f64 * spacing,
            );
            let sample = spectrum.sample(x, z, t);
            let offset = ocean.treadmill_offset(t);
            let unpushed = DVec3::new(x + offset.x, 0.0, z + offset.y) + sample.displacement;
            let r = DVec2::new(unpushed.x, unpushed.z).length();
            let y = f64::from(mesh.positions[row * (side + 1) + column][1]);
            if r <= 40.0 {
                inside += 1;
                assert!(
                    (y - unpushed.y).abs() < 1e-5,
                    "inside the horizon the height is the wave's"
                );
            } else {
                outside += 1;
                let drop = 0.1 * (r - 40.0).powi(2);
                assert!((y - (unpushed.y - drop)).abs() < 1e-4 * drop.max(1.0), "r = {r}");
                if r > 60.0 {
                    // 0.1 · 20² = 40 m down: far below any wave (|h| ≤ Σa).
                    assert!(y < -30.0, "y = {y} at r = {r}");
                }
            }
        }
    }
    assert!(inside > 100 && outside > 100, "{inside} inside, {outside} outside");
}

#[test]
fn normals_match_finite_differences_of_the_surface() {
    // The reference surface P'(x, z) (waves, choppy displacement, treadmill
    // and horizon drop) differenced in f64; compared with the mesh's f32
    // normals, including vertices past the horizon.
    let ocean = Ocean {
        choppiness: 1.2,
        ..small()
    };
    let spectrum = Spectrum::new(&ocean);
    let t = 11.0;
    let mesh = ocean_mesh(&ocean, t);
    let side = (ocean.cells * ocean.tiles) as usize;
    let spacing = 60.0 / f64::from(ocean.cells);
    let surface = |x: f64, z: f64| ocean.place(x, z, t, &spectrum.sample(x, z, t)).displacement;
    let h = 1e-4;
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for row in (0..=side).step_by(3) {
        for column in (0..=side).step_by(2) {
            let (x, z) = (
                ocean.grid_origin() + column as f64 * spacing,
                ocean.grid_origin() + row as f64 * spacing,
            );
            let d_dx = (surface(x + h, z) - surface(x - h, z)) / (2.0 * h);
            let d_dz = (surface(x, z + h) - surface(x, z - h)) / (2.0 * h);
            let expected = d_dz.cross(d_dx).normalize();
            let n = mesh.normals[row * (side + 1) + column];
            let n = DVec3::new(f64::from(n[0]), f64::from(n[1]), f64::from(n[2]));
            worst = worst.max(n.angle_between(expected));
            // The tangent follows +u (∂P/∂x), orthogonal to the normal.
            let tangent = mesh.tangents.as_ref().expect("tangents")[row * (side + 1) + column];
            let tangent = DVec3::new(f64::from(tangent[0]), f64::from(tangent[1]), f64::from(tangent[2]));
            assert!(tangent.dot(n).abs() < 1e-5 && tangent.dot(d_dx) > 0.0);
            checked += 1;
        }
    }
    assert!(checked > 100);
    assert!(worst < 1e-4, "largest normal error {worst} rad");
    // Not trivially flat: the normals vary by tens of degrees.
    let tilt = mesh.normals.iter().map(|n| n[1].acos()).fold(0.0f32, f32::max);
    assert!(tilt > 0.2, "largest tilt {tilt} rad");
}

#[test]
fn triangles_wind_counter_clockwise_seen_from_above() {
    let mesh = ocean_mesh(&small(), 3.0);
    for triangle in mesh.indices.chunks_exact(3).step_by(7) {
        let [a, b, c] = [0, 1, 2].map(|k| Vec3::from_array(mesh.positions[triangle[k] as usize]));
        let face = (b - a).cross(c - a);
        let normal: Vec3 = triangle
            .iter()
            .map(|&i| Vec3::from_array(mesh.normals[i as usize]))
            .sum();
        assert!(face.dot(normal) > 0.0, "{triangle:?}");
    }
}

#[test]
fn extreme_parameters_give_finite_geometry() {
    let extremes = [
        Ocean {
            wave_height: 100.0,
            choppiness: 4.0,
            ..small()
        },
        Ocean {
            wind_speed: 1e-3,
            ..small()
        },
        Ocean {
            wind_speed: 100.0,
            size: 1e4,
            ..small()
        },
        Ocean {
            size: 1e-3,
            period: 1e-3,
            ..small()
        },
        Ocean {
            horizon: 1e-3,
            horizon_drop: 10.0,
            size: 1e4,
            ..small()
        },
        Ocean {
            size: f32::NAN,
            period: f32::INFINITY,
            wave_height: f32::NAN,
            wind_direction: [0.0, 0.0],
            cells: 0,
            tiles: 1000,
            modes: 1000,
            ..small()
        },
        Ocean {
            wave_height: 0.0,
            cells: 1,
            tiles: 1,
            ..small()
        },
    ];
    for ocean in extremes {
        for t in [0.0, 1e-7, 3.7, 1e9, -5.0, f64::NAN, f64::INFINITY] {
            let mesh = Primitive::Ocean(ocean).build_at(t);
            assert!(mesh.validate().is_ok(), "{ocean:?}");
            let finite = |v: &[f32]| v.iter().all(|c| c.is_finite());
            assert!(mesh.positions.iter().all(|p| finite(p)), "{ocean:?} at {t}");
            assert!(mesh.normals.iter().all(|p| finite(p)), "{ocean:?} at {t}");
            assert!(
                mesh.tangents.as_ref().expect("t").iter().all(|p| finite(p)),
                "{ocean:?}"
            );
            assert!(mesh.uvs.as_ref().expect("uv").iter().all(|p| finite(p)), "{ocean:?}");
            assert_eq!(
                mesh.triangle_count() as u64,
                Primitive::Ocean(ocean).triangle_count(),
                "{ocean:?}"
            );
        }
    }
    // A calm sea is flat and faces up.
    let calm = ocean_mesh(
        &Ocean {
            wave_height: 0.0,
            horizon: 1e5,
            ..small()
        },
        1.0,
    );
    assert!(calm.positions.iter().all(|p| p[1] == 0.0));
    assert!(calm.normals.iter().all(|n| *n == [0.0, 1.0, 0.0]));
}

// ---- the scene fields ----

fn scene_with(primitive: &str) -> Result<npr_runner::scene::Scene, (Vec<npr_diag::Diagnostic>, SourceMap)> {
    let text = format!(
        "[camera]\nposition = [0.0, 5.0, 20.0]\ntarget = [0.0, 0.0, 0.0]\n[[object]]\nprimitive = {primitive}\n"
    );
    let mut sources = SourceMap::new();
    let file = sources.add("scene.toml", text.clone());
    parse_scene(&text, file, Path::new(".")).map_err(|d| (d, sources))
}

#[test]
fn an_ocean_scene_object_is_time_varying_with_its_fields() {
    let scene = scene_with(
        "{ kind = \"ocean\", size = 30.0, cells = 16, tiles = 3, period = 10.0, modes = 4, wave_height = 0.5, \
         wind_speed = 7.0, wind_direction = [1.0, 1.0], choppiness = 0.0, seed = 9, drift = [0, -1], \
         horizon = 40.0, horizon_drop = 0.2, ring = 100.0 }",
    )
    .unwrap_or_else(|(d, s)| panic!("{}", npr_diag::diagnostic::render(&d, &s, false)));
    let object = &scene.objects[0];
    assert_eq!(object.name, "ocean");
    let Some(Primitive::Ocean(ocean)) = object.time_varying else {
        panic!("the ocean is time-varying: {:?}", object.time_varying);
    };
    assert_eq!(
        ocean,
        Ocean {
            size: 30.0,
            cells: 16,
            tiles: 3,
            period: 10.0,
            modes: 4,
            wave_height: 0.5,
            wind_speed: 7.0,
            wind_direction: [1.0, 1.0],
            choppiness: 0.0,
            seed: 9,
            drift: [0, -1],
            horizon: 40.0,
            horizon_drop: 0.2,
            ring: 100.0,
        }
    );
    assert_eq!(*object.mesh, ocean_mesh(&ocean, 0.0));
    // The grid, and the ring's quads around.
    assert_eq!(
        object.mesh.triangle_count(),
        2 * 48 * 48 + 2 * npr_runner::scene::ocean::RING_SEGMENTS as usize
    );
    // Defaults are the paper's grid.
    let scene = scene_with("{ kind = \"ocean\" }")
        .unwrap_or_else(|(d, s)| panic!("{}", npr_diag::diagnostic::render(&d, &s, false)));
    assert_eq!(scene.objects[0].time_varying, Some(Primitive::Ocean(Ocean::default())));
    assert_eq!(scene.objects[0].mesh.positions.len(), 401 * 401);
    // Static primitives are not.
    let sphere = scene_with("{ kind = \"sphere\" }")
        .unwrap_or_else(|(d, s)| panic!("{}", npr_diag::diagnostic::render(&d, &s, false)));
    assert_eq!(sphere.objects[0].time_varying, None);
}

/// The single diagnostic for an ocean written as `primitive`: its code and
/// the text its primary span covers.
fn ocean_error(primitive: &str, code: &str, spanned: &str) -> String {
    let (diagnostics, sources) = match scene_with(primitive) {
        Ok(_) => panic!("expected an error for {primitive}"),
        Err(e) => e,
    };
    assert_eq!(
        diagnostics.len(),
        1,
        "{}",
        npr_diag::diagnostic::render(&diagnostics, &sources, false)
    );
    let d = &diagnostics[0];
    assert_eq!(d.code, code, "{d:#?}");
    assert_eq!(sources.snippet(d.primary_span().expect("span")), spanned, "{d:#?}");
    assert!(d.help.as_deref().is_some_and(|h| !h.is_empty()));
    format!("{} / {}", d.message, d.help.clone().unwrap_or_default())
}

#[test]
fn bad_ocean_fields_point_at_the_value() {
    let bad = codes::BAD_SCENE;
    let m = ocean_error("{ kind = \"ocean\", size = -60.0 }", bad, "-60.0");
    assert!(m.contains("`size` must be in (0, 10000] metres"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", tiles = 4 }", bad, "4");
    assert!(m.contains("must be odd") && m.contains("tiles = 5"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", cells = 16, modes = 9 }", bad, "9");
    assert!(m.contains("Nyquist"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", cells = 300 }", bad, "300");
    assert!(m.contains("from 1 to 256"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", wind_direction = [0, 0] }", bad, "[0, 0]");
    assert!(m.contains("cannot be zero"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", wind_direction = [1, 0, 0] }", bad, "[1, 0, 0]");
    assert!(m.contains("2 numbers"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", drift = [0.5, 0] }", bad, "[0.5, 0]");
    assert!(m.contains("whole numbers of tiles"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", period = 0 }", bad, "0");
    assert!(m.contains("(0, 3600] seconds"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", choppiness = 9.0 }", bad, "9.0");
    assert!(m.contains("[0, 4]"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", wave_hieght = 2.0 }", bad, "wave_hieght");
    assert!(m.contains("did you mean `wave_height`"), "{m}");
    let m = ocean_error("{ kind = \"ocean\", seed = \"one\" }", bad, "\"one\"");
    assert!(m.contains("whole number"), "{m}");
    // Too many triangles for the renderer is E0404 at the primitive.
    let m = ocean_error(
        "{ kind = \"ocean\", cells = 256, tiles = 15 }",
        codes::LIMIT_EXCEEDED,
        "{ kind = \"ocean\", cells = 256, tiles = 15 }",
    );
    assert!(m.contains("`cells` or `tiles`"), "{m}");
    // Several bad fields are all reported.
    let (diagnostics, _) =
        scene_with("{ kind = \"ocean\", size = 0, tiles = 2, horizon = -1 }").expect_err("three errors");
    assert_eq!(diagnostics.len(), 3, "{diagnostics:#?}");
}

/// §6.1's "simpler geometry for the ring of ocean between [the false
/// horizon] and the real horizon": a flat annulus at y = 0 from R to
/// `ring`, every triangle facing up, its UVs the lattice coordinates under
/// it (world position less the treadmill offset, as the grid's), and the
/// grid's outermost rows sunk under it once they are a few metres past R.
#[test]
fn the_ring_is_flat_faces_up_and_covers_the_sunk_grid() {
    let ocean = Ocean {
        ring: 1000.0,
        ..small()
    };
    let plain = Ocean { ring: 0.0, ..ocean };
    let t = 3.7;
    let (mesh, grid) = (ocean_mesh(&ocean, t), ocean_mesh(&plain, t));
    let first = grid.positions.len();
    assert_eq!(mesh.positions[..first], grid.positions[..]);
    let offset = ocean.treadmill_offset(t);
    for (i, p) in mesh.positions[first..].iter().enumerate() {
        let r = f64::from(p[0]).hypot(f64::from(p[2]));
        let expected = if i % 2 == 0 { 40.0 } else { 1000.0 };
        assert!((r - expected).abs() < 1e-3 * expected, "ring vertex {i} at r = {r}");
        assert_eq!(p[1], 0.0);
        let uv = mesh.uvs.as_ref().unwrap()[first + i];
        assert!((f64::from(uv[0]) - (f64::from(p[0]) - offset.x)).abs() < 1e-3);
        assert!((f64::from(uv[1]) - (f64::from(p[2]) - offset.y)).abs() < 1e-3);
    }
    for tri in mesh.indices[grid.indices.len()..].chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| DVec3::from(mesh.positions[tri[k] as usize].map(f64::from)));
        assert!((b - a).cross(c - a).y > 0.0, "a ring triangle faces down");
    }
    // Past R + 10 m the drop (0.1 m per m² here) is 10 m: under the ring
    // whatever the waves (2 m significant height).
    for p in &grid.positions {
        let r = f64::from(p[0]).hypot(f64::from(p[2]));
        if r > 50.0 {
            assert!(p[1] < 0.0, "a grid vertex at r = {r} is above the ring ({})", p[1]);
        }
    }
}
