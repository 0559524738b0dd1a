//! The painterly ocean's geometry (Age of Sail §6.1): a low-resolution grid
//! tile displaced by a deep-water wave model that repeats exactly in space
//! and in time, tiled around the origin, moved "treadmill-style" past it, and
//! pushed down beyond a false horizon.
//!
//! # The wave model (Tessendorf, "Simulating Ocean Water", 2001)
//!
//! The surface is a finite sum of travelling waves, a DFT without the FFT:
//!
//! ```text
//! θ_k(x, t) = k·x − ω_k t + φ_k
//! h(x, t)   = Σ_k a_k cos θ_k                        height
//! D(x, t)   = −λ Σ_k (k/|k|) a_k sin θ_k             horizontal ("choppy") displacement
//! P(x, t)   = (x + D_x, h, z + D_z)                  the displaced lattice point
//! ```
//!
//! - **Periodic in space:** the wave vectors lie on the tile's reciprocal
//!   lattice, `k = 2π (m, n) / L` with integers `|m|, |n| ≤ modes`, so every
//!   term repeats with period L along x and z.
//! - **Periodic in time:** the deep-water dispersion `ω = √(g |k|)` is
//!   quantized down to a multiple of `ω₀ = 2π / T` (Tessendorf §"Making the
//!   waves loop in time"), so every term repeats with period T, the clip
//!   length (the paper: 20 s, "whose first and last frames match seamlessly").
//! - **Spectrum:** Phillips, `P(k) = exp(−1/(k ℓ)²) / k⁴ · (k̂·ŵ)²` with
//!   `ℓ = V²/g` for wind speed V and direction ŵ; waves travelling against the
//!   wind keep [`AGAINST_WIND`] of their energy. Each mode gets a Rayleigh
//!   amplitude and a uniform phase from a seeded generator (deterministic for
//!   a seed on every machine). The amplitudes are then scaled so the
//!   significant wave height `4 σ_h` equals `wave_height`: an artist sets a
//!   height in metres rather than Phillips' unitless constant A.
//! - **Normals** are analytic: `n ∝ ∂P/∂z × ∂P/∂x`, with the derivatives of
//!   the sums above (and of the false-horizon drop, by the chain rule).
//!
//! # The tiles (§6.1: "80-by-80 square grid about 60 meters wide", "5-by-5")
//!
//! `tiles × tiles` tiles of `cells × cells` quads share one vertex grid (the
//! shared seams cannot crack). The field is evaluated once per frame on one
//! tile's `cells²` lattice points and reused for every tile, since it is
//! periodic. The lattice point `x_l` of a vertex never changes; its UV is
//! `x_l` in metres (u along +x, v along +z), so MetaTexture sees constant
//! world-space UV gradients (§3.2) and the texture travels with the water.
//!
//! # Treadmill and false horizon
//!
//! The water drifts past the origin (where the boat stays) at `drift` tiles
//! per period along x and z: integers, so the motion also loops in T. The
//! grid's offset is the drift distance wrapped into `[−L/2, L/2]`; because
//! the field has period L, the wrap changes no vertex height, only which
//! edge row is outermost. Beyond the false-horizon radius R (the paper:
//! 120 m) a vertex at horizontal distance r from the origin is lowered by
//! `horizon_drop · (r − R)²` (C¹ at R), which hides the tiles' edges: with the
//! defaults the grid reaches at least `2.5 L − L/2 = 120 m` from the origin.
//!
//! Past the false horizon, the paper uses "simpler geometry for the ring of
//! ocean between that and the real horizon (about 1km away)": with `ring`
//! set, [`ocean_mesh`] appends a flat annulus at the mean sea level (y = 0)
//! from R to `ring` metres, [`RING_SEGMENTS`] quads around and one across.
//! The grid's edge rows, lowered by the drop, pass under it a few metres
//! past R, so the treadmilling rows never show against the sky; the ring's
//! UVs move with the treadmill, so the texture on it travels with the water.
//!
//! # Time
//!
//! [`ocean_mesh`] reduces the time modulo T before evaluating anything, so
//! the mesh at `t + T` is bit-identical to the mesh at `t`; the tests check
//! that the *unreduced* model is periodic as well, and that the mesh just
//! before T joins the mesh at 0.

use super::geometry::orthonormal_tangent;
use super::mesh::Mesh;
use glam::{DVec2, DVec3, Vec3};
use std::f64::consts::TAU;

/// Standard gravity, m/s², in the dispersion relation ω = √(g |k|).
pub const GRAVITY: f64 = 9.81;
/// The share of Phillips energy kept by waves travelling against the wind.
pub const AGAINST_WIND: f64 = 0.07;
/// The most quads along one tile's side.
pub const MAX_CELLS: u32 = 256;
/// The most tiles along a side of the tiled grid.
pub const MAX_TILES: u32 = 15;
/// The largest wave-vector index |m|, |n| (at most (2·32+1)² − 1 waves).
pub const MAX_MODES: u32 = 32;
/// The most tiles the water may drift per period along an axis.
pub const MAX_DRIFT: i32 = 100;
/// Quads around the horizon ring: at 1 km a chord of 1/256 turn sags
/// 1000·(1 − cos(π/256)) ≈ 0.08 m below the circle, under a pixel.
pub const RING_SEGMENTS: u32 = 256;

/// The ocean primitive's parameters, as written in a scene (see the scene
/// module docs for the field names and defaults).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ocean {
    /// Tile width L in metres (the spatial period).
    pub size: f32,
    /// Quads along a tile's side.
    pub cells: u32,
    /// Tiles along a side of the grid (odd, so one tile is centred).
    pub tiles: u32,
    /// Loop length T in seconds (the temporal period).
    pub period: f32,
    /// Wave vectors 2π(m, n)/L with |m|, |n| ≤ modes.
    pub modes: u32,
    /// Significant wave height 4σ_h in metres.
    pub wave_height: f32,
    /// Wind speed V in m/s (sets the Phillips length ℓ = V²/g).
    pub wind_speed: f32,
    /// Wind direction in the xz plane (normalized on use).
    pub wind_direction: [f32; 2],
    /// λ of the choppy displacement; 0 is a pure height field.
    pub choppiness: f32,
    pub seed: u32,
    /// Tiles the water travels per period along x and z.
    pub drift: [i32; 2],
    /// False-horizon radius R in metres.
    pub horizon: f32,
    /// Drop beyond R, per square metre past R.
    pub horizon_drop: f32,
    /// Outer radius of the flat ring from R to the real horizon (§6.1:
    /// "simpler geometry for the ring of ocean between that and the real
    /// horizon (about 1km away)"); 0 draws no ring.
    pub ring: f32,
}

impl Default for Ocean {
    /// The paper's numbers where it gives them (60 m tiles of 80 quads, 5×5,
    /// 20 s, 120 m false horizon).
    fn default() -> Self {
        Ocean {
            size: 60.0,
            cells: 80,
            tiles: 5,
            period: 20.0,
            modes: 12,
            wave_height: 1.2,
            wind_speed: 5.0,
            wind_direction: [0.0, 1.0],
            choppiness: 0.7,
            seed: 1,
            drift: [0, 0],
            horizon: 120.0,
            horizon_drop: 0.05,
            ring: 0.0,
        }
    }
}

/// One travelling wave of the sum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wave {
    /// Lattice indices (m, n): k = 2π (m, n) / L.
    pub index: [i32; 2],
    /// Wave vector (x, z), rad/m.
    pub k: DVec2,
    /// Angular frequency, a whole multiple of 2π/T.
    pub omega: f64,
    pub amplitude: f64,
    pub phase: f64,
}

/// The displaced surface at one lattice point: the displacement and the
/// partial derivatives of the displaced point P with respect to the lattice
/// coordinates (so a flat sea has `d_dx = +X`, `d_dz = +Z`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceSample {
    /// (D_x, h, D_z).
    pub displacement: DVec3,
    pub d_dx: DVec3,
    pub d_dz: DVec3,
}

impl SurfaceSample {
    /// The unit normal `∂P/∂z × ∂P/∂x` (+Y for a flat sea; +Y if degenerate).
    pub fn normal(&self) -> DVec3 {
        self.d_dz.cross(self.d_dx).normalize_or(DVec3::Y)
    }
}

/// The sea state: the waves of one [`Ocean`].
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    pub waves: Vec<Wave>,
    /// L, metres.
    pub size: f64,
    /// T, seconds.
    pub period: f64,
    /// λ.
    pub choppiness: f64,
}

impl Ocean {
    /// The parameters forced into their valid ranges (NaN becomes the
    /// default), so that building never panics, allocates without bound or
    /// produces non-finite vertices, whatever a library caller passes. The
    /// scene parser reports out-of-range values as errors before this.
    pub fn sanitized(&self) -> Ocean {
        let d = Ocean::default();
        let clamp = |v: f32, lo: f32, hi: f32, default: f32| if v.is_nan() { default } else { v.clamp(lo, hi) };
        let wind = self.wind_direction;
        let wind_ok = wind.iter().all(|c| c.is_finite()) && (wind[0] != 0.0 || wind[1] != 0.0);
        let mut tiles = self.tiles.clamp(1, MAX_TILES);
        if tiles.is_multiple_of(2) {
            tiles -= 1;
        }
        let cells = self.cells.clamp(1, MAX_CELLS);
        Ocean {
            size: clamp(self.size, 1e-3, 1e4, d.size),
            cells,
            tiles,
            period: clamp(self.period, 1e-3, 3600.0, d.period),
            modes: self.modes.clamp(1, MAX_MODES).min((cells / 2).max(1)),
            wave_height: clamp(self.wave_height, 0.0, 100.0, d.wave_height),
            wind_speed: clamp(self.wind_speed, 1e-3, 100.0, d.wind_speed),
            wind_direction: if wind_ok { wind } else { d.wind_direction },
            choppiness: clamp(self.choppiness, 0.0, 4.0, d.choppiness),
            seed: self.seed,
            drift: self.drift.map(|c| c.clamp(-MAX_DRIFT, MAX_DRIFT)),
            horizon: clamp(self.horizon, 1e-3, 1e5, d.horizon),
            horizon_drop: clamp(self.horizon_drop, 0.0, 10.0, d.horizon_drop),
            ring: clamp(self.ring, 0.0, 1e5, d.ring),
        }
    }

    /// Quads along one side of the whole grid.
    pub fn grid_cells(&self) -> u64 {
        u64::from(self.cells) * u64::from(self.tiles)
    }

    /// The drift velocity (x, z) in m/s: `drift · L / T`.
    pub fn drift_velocity(&self) -> DVec2 {
        let per_tile = f64::from(self.size) / f64::from(self.period);
        DVec2::new(f64::from(self.drift[0]), f64::from(self.drift[1])) * per_tile
    }

    /// The grid's treadmill offset (x, z) at time `t`: the drift distance
    /// wrapped into [−L/2, L/2] per axis.
    pub fn treadmill_offset(&self, t: f64) -> DVec2 {
        let size = f64::from(self.size);
        let travelled = self.drift_velocity() * t;
        travelled - (travelled / size).round() * size
    }

    /// The lattice coordinate of the grid's first vertex along x and z: the
    /// grid is centred on the origin.
    pub fn grid_origin(&self) -> f64 {
        -f64::from(self.size) * f64::from(self.tiles) / 2.0
    }

    /// The final vertex (object space) of lattice point `(x, z)` at time `t`,
    /// given the wave field there: offset by the treadmill, displaced, and
    /// lowered past the false horizon, with the derivatives carried along.
    pub fn place(&self, x: f64, z: f64, t: f64, field: &SurfaceSample) -> SurfaceSample {
        let offset = self.treadmill_offset(t);
        let mut position = DVec3::new(x + offset.x, 0.0, z + offset.y) + field.displacement;
        let (mut d_dx, mut d_dz) = (field.d_dx, field.d_dz);
        let horizontal = DVec2::new(position.x, position.z);
        let r = horizontal.length();
        let radius = f64::from(self.horizon);
        if r > radius {
            // drop(r) = c (r − R)²; ∇drop = 2c (r − R) p/r, chained through
            // the horizontal part of ∂P/∂x and ∂P/∂z.
            let c = f64::from(self.horizon_drop);
            position.y -= c * (r - radius) * (r - radius);
            let gradient = horizontal * (2.0 * c * (r - radius) / r);
            d_dx.y -= gradient.dot(DVec2::new(d_dx.x, d_dx.z));
            d_dz.y -= gradient.dot(DVec2::new(d_dz.x, d_dz.z));
        }
        SurfaceSample {
            displacement: position,
            d_dx,
            d_dz,
        }
    }
}

/// A small, fixed, portable generator (SplitMix64), so a seed gives the same
/// sea on every machine and in every version of the dependencies.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1]: never 0, so its logarithm is finite.
    fn unit(&mut self) -> f64 {
        ((self.next() >> 11) + 1) as f64 / (1u64 << 53) as f64
    }
}

impl Spectrum {
    /// The waves of `ocean` (after [`Ocean::sanitized`]).
    pub fn new(ocean: &Ocean) -> Spectrum {
        let o = ocean.sanitized();
        let size = f64::from(o.size);
        let period = f64::from(o.period);
        let wind = DVec2::new(f64::from(o.wind_direction[0]), f64::from(o.wind_direction[1])).normalize_or(DVec2::Y);
        let length = f64::from(o.wind_speed).powi(2) / GRAVITY;
        let omega0 = TAU / period;
        let mut rng = SplitMix64(u64::from(o.seed) ^ 0x6F63_6561_6E00_0000);
        let modes = o.modes as i32;
        // Log-energies first (Phillips in log space cannot overflow or give
        // 0/0 for extreme tiles or winds), normalized below.
        let mut draft: Vec<(Wave, f64)> = Vec::new();
        for n in -modes..=modes {
            for m in -modes..=modes {
                if m == 0 && n == 0 {
                    continue;
                }
                // Draw for every mode, used or not, so a mode's randomness
                // does not depend on which others have energy.
                let (u1, u2) = (rng.unit(), rng.unit());
                let k = DVec2::new(f64::from(m), f64::from(n)) * (TAU / size);
                let k_len = k.length();
                let along_wind = (k / k_len).dot(wind);
                let direction = along_wind * along_wind * if along_wind < 0.0 { AGAINST_WIND } else { 1.0 };
                let log_energy = -1.0 / (k_len * length).powi(2) - 4.0 * k_len.ln() + direction.ln();
                // Rayleigh-distributed magnitude of a complex Gaussian, and a
                // uniform phase (Tessendorf's ξ_r + i ξ_i).
                let rayleigh = (-2.0 * u1.ln()).sqrt();
                let omega = ((GRAVITY * k_len).sqrt() / omega0).floor() * omega0;
                let wave = Wave {
                    index: [m, n],
                    k,
                    omega,
                    amplitude: rayleigh,
                    phase: TAU * u2,
                };
                draft.push((wave, log_energy));
            }
        }
        let max_log = draft.iter().map(|(_, e)| *e).fold(f64::NEG_INFINITY, f64::max);
        let mut waves: Vec<Wave> = draft
            .into_iter()
            .map(|(mut wave, log_energy)| {
                let relative = if max_log.is_finite() {
                    ((log_energy - max_log) / 2.0).exp()
                } else {
                    0.0
                };
                wave.amplitude *= if relative.is_finite() { relative } else { 0.0 };
                wave
            })
            .filter(|w| w.amplitude > 0.0)
            .collect();
        // σ_h² = Σ a²/2 for a sum of cosines with independent phases.
        let sigma = (waves.iter().map(|w| w.amplitude * w.amplitude / 2.0).sum::<f64>()).sqrt();
        let scale = f64::from(o.wave_height) / 4.0 / sigma;
        if scale.is_finite() && sigma > 0.0 {
            for wave in &mut waves {
                wave.amplitude *= scale;
            }
        } else {
            waves.clear();
        }
        waves.retain(|w| w.amplitude > 0.0 && w.amplitude.is_finite());
        Spectrum {
            waves,
            size,
            period,
            choppiness: f64::from(o.choppiness),
        }
    }

    /// The surface at lattice point (x, z) and time t, summed directly (the
    /// f64 reference; [`Spectrum::tile`] is the fast path the mesh uses).
    /// Time is used as given, not reduced modulo T.
    pub fn sample(&self, x: f64, z: f64, t: f64) -> SurfaceSample {
        let mut sums = Sums::default();
        for wave in &self.waves {
            let theta = wave.k.x * x + wave.k.y * z - wave.omega * t + wave.phase;
            let (sin, cos) = theta.sin_cos();
            sums.add(wave, wave.amplitude * cos, wave.amplitude * sin);
        }
        sums.finish(self.choppiness)
    }

    /// The surface at the `cells × cells` lattice points
    /// `(origin + i L/cells, origin + j L/cells)`, row by row (j outer), at
    /// time t. Because k lies on the lattice, `e^{iθ}` factors into a per-wave
    /// constant times table entries `e^{2πi·(m i mod N)/N}` and
    /// `e^{2πi·(n j mod N)/N}`: two complex products per point and wave
    /// instead of a sine and a cosine.
    pub fn tile(&self, origin: f64, cells: u32, t: f64) -> Vec<SurfaceSample> {
        let cells = cells.clamp(1, MAX_CELLS) as usize;
        let roots: Vec<(f64, f64)> = (0..cells)
            .map(|q| {
                let (sin, cos) = (TAU * q as f64 / cells as f64).sin_cos();
                (cos, sin)
            })
            .collect();
        let mut sums = vec![Sums::default(); cells * cells];
        for wave in &self.waves {
            let theta0 = (wave.k.x + wave.k.y) * origin - wave.omega * t + wave.phase;
            let (sin0, cos0) = theta0.sin_cos();
            let c0 = (wave.amplitude * cos0, wave.amplitude * sin0);
            let [m, n] = wave.index.map(i64::from);
            for j in 0..cells {
                let row = roots[(n * j as i64).rem_euclid(cells as i64) as usize];
                let cj = complex_mul(c0, row);
                for i in 0..cells {
                    let column = roots[(m * i as i64).rem_euclid(cells as i64) as usize];
                    let (cos, sin) = complex_mul(cj, column);
                    sums[j * cells + i].add(wave, cos, sin);
                }
            }
        }
        sums.into_iter().map(|s| s.finish(self.choppiness)).collect()
    }
}

fn complex_mul(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

/// Running sums of the model's terms at one point.
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    h: f64,
    dh_dx: f64,
    dh_dz: f64,
    dx: f64,
    dz: f64,
    ddx_dx: f64,
    ddx_dz: f64,
    ddz_dz: f64,
}

impl Sums {
    /// Adds one wave with `a cos θ` and `a sin θ` at this point.
    fn add(&mut self, wave: &Wave, a_cos: f64, a_sin: f64) {
        let k = wave.k;
        let unit = k / k.length();
        self.h += a_cos;
        self.dh_dx -= k.x * a_sin;
        self.dh_dz -= k.y * a_sin;
        self.dx -= unit.x * a_sin;
        self.dz -= unit.y * a_sin;
        self.ddx_dx -= unit.x * k.x * a_cos;
        // ∂D_x/∂z = ∂D_z/∂x: k̂_x k_z = k_x k_z/|k| = k̂_z k_x.
        self.ddx_dz -= unit.x * k.y * a_cos;
        self.ddz_dz -= unit.y * k.y * a_cos;
    }

    fn finish(self, lambda: f64) -> SurfaceSample {
        SurfaceSample {
            displacement: DVec3::new(lambda * self.dx, self.h, lambda * self.dz),
            d_dx: DVec3::new(1.0 + lambda * self.ddx_dx, self.dh_dx, lambda * self.ddx_dz),
            d_dz: DVec3::new(lambda * self.ddx_dz, self.dh_dz, 1.0 + lambda * self.ddz_dz),
        }
    }
}

/// The tiled, displaced, treadmilled ocean grid at time `time_s` (reduced
/// modulo the period first). `(cells · tiles + 1)²` vertices laid out row by
/// row along +z, columns along +x; UVs are the lattice coordinates in metres;
/// triangles wind counter-clockwise seen from above.
pub fn ocean_mesh(ocean: &Ocean, time_s: f64) -> Mesh {
    let o = ocean.sanitized();
    let spectrum = Spectrum::new(&o);
    let t = if time_s.is_finite() {
        time_s.rem_euclid(f64::from(o.period))
    } else {
        0.0
    };
    let cells = o.cells as usize;
    let side = cells * o.tiles as usize;
    let stride = side + 1;
    let origin = o.grid_origin();
    let spacing = f64::from(o.size) / cells as f64;
    let field = spectrum.tile(origin, o.cells, t);
    let vertex_count = stride * stride;
    let mut positions = Vec::with_capacity(vertex_count);
    let mut normals = Vec::with_capacity(vertex_count);
    let mut uvs = Vec::with_capacity(vertex_count);
    let mut tangents = Vec::with_capacity(vertex_count);
    for row in 0..stride {
        let z = origin + row as f64 * spacing;
        for column in 0..stride {
            let x = origin + column as f64 * spacing;
            let sample = &field[(row % cells) * cells + column % cells];
            let placed = o.place(x, z, t, sample);
            let normal = placed.normal();
            positions.push(placed.displacement.as_vec3().to_array());
            normals.push(normal.as_vec3().to_array());
            uvs.push([x as f32, z as f32]);
            let to_f32 = |v: DVec3| -> Vec3 { v.as_vec3() };
            tangents.push(orthonormal_tangent(
                to_f32(normal),
                to_f32(placed.d_dx),
                to_f32(-placed.d_dz),
            ));
        }
    }
    let mut indices = Vec::with_capacity(side * side * 6);
    for row in 0..side {
        for column in 0..side {
            let top_left = (row * stride + column) as u32;
            let (bottom_left, top_right) = (top_left + stride as u32, top_left + 1);
            let bottom_right = bottom_left + 1;
            indices.extend([top_left, bottom_left, bottom_right, top_left, bottom_right, top_right]);
        }
    }
    if o.ring > o.horizon {
        let offset = o.treadmill_offset(t);
        let first = positions.len() as u32;
        for k in 0..RING_SEGMENTS {
            let angle = TAU * f64::from(k) / f64::from(RING_SEGMENTS);
            for radius in [f64::from(o.horizon), f64::from(o.ring)] {
                let (x, z) = (radius * angle.cos(), radius * angle.sin());
                positions.push([x as f32, 0.0, z as f32]);
                normals.push([0.0, 1.0, 0.0]);
                // The lattice point under (x, z): the grid's UV convention.
                uvs.push([(x - offset.x) as f32, (z - offset.y) as f32]);
                tangents.push(orthonormal_tangent(Vec3::Y, Vec3::X, Vec3::NEG_Z));
            }
        }
        for k in 0..RING_SEGMENTS {
            let (inner, outer) = (first + 2 * k, first + 2 * k + 1);
            let next = first + 2 * ((k + 1) % RING_SEGMENTS);
            // Facing +y, as the grid's quads: (next − inner) × (outer −
            // inner) points up for a ring running counter-clockwise in xz.
            indices.extend([inner, next + 1, outer, inner, next, next + 1]);
        }
    }
    Mesh {
        positions,
        normals,
        uvs: Some(uvs),
        tangents: Some(tangents),
        indices,
        source: description(ocean),
        parts: None,
        edge_marks: None,
    }
}

/// `ocean(size=60, cells=80, ...)`: every parameter, so equal descriptions
/// mean equal geometry (the scene's mesh cache relies on it).
pub fn description(o: &Ocean) -> String {
    format!(
        "ocean(size={}, cells={}, tiles={}, period={}, modes={}, wave_height={}, wind_speed={}, \
         wind_direction=[{}, {}], choppiness={}, seed={}, drift=[{}, {}], horizon={}, horizon_drop={}, ring={})",
        o.size,
        o.cells,
        o.tiles,
        o.period,
        o.modes,
        o.wave_height,
        o.wind_speed,
        o.wind_direction[0],
        o.wind_direction[1],
        o.choppiness,
        o.seed,
        o.drift[0],
        o.drift[1],
        o.horizon,
        o.horizon_drop,
        o.ring
    )
}
