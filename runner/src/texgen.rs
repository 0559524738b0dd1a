//! The texture generator: tileable value and gradient noise with octaves;
//! and the colour maps of the painterly ocean (Age of Sail §6.1), which the
//! ocean example reads as image files (see [`bathic_map`], [`sky_map`]).
//!
//! Tileable because every lattice is periodic: octave `o` has
//! `frequency · 2^o` cells across the texture and its lattice coordinates are
//! taken modulo that count, so the left edge continues the right edge and the
//! top continues the bottom. Each channel uses its own seed, so a 2-channel
//! texture is two independent noises (what a warp field needs).

/// Generated pixels, RGBA, row-major, values in [0, 1].
pub struct NoiseImage {
    pub size: u32,
    pub pixels: Vec<[f32; 4]>,
}

/// The noise parameters are the ABI's (a manifest's `noise` texture source).
pub use npr_abi::NoiseSpec;

pub fn generate(spec: &NoiseSpec) -> NoiseImage {
    let size = spec.size.max(1);
    let mut pixels = vec![[0.0f32, 0.0, 0.0, 1.0]; (size * size) as usize];
    for c in 0..spec.channels.clamp(1, 4) {
        let seed = spec
            .seed
            .wrapping_mul(0x9E37_79B9)
            .wrapping_add(c.wrapping_mul(0x85EB_CA6B));
        for y in 0..size {
            for x in 0..size {
                let u = (x as f64 + 0.5) / size as f64;
                let v = (y as f64 + 0.5) / size as f64;
                let n = fbm(u, v, spec, seed) as f32;
                pixels[(y * size + x) as usize][c as usize] = n;
            }
        }
    }
    if spec.channels == 1 {
        for p in &mut pixels {
            p[1] = p[0];
            p[2] = p[0];
        }
    }
    NoiseImage { size, pixels }
}

/// Sum of octaves, normalized to [0, 1].
pub fn fbm(u: f64, v: f64, spec: &NoiseSpec, seed: u32) -> f64 {
    let mut sum = 0.0;
    let mut amplitude = 1.0;
    let mut total = 0.0;
    for o in 0..spec.octaves.max(1) {
        let period = spec.frequency.max(1).saturating_mul(1 << o.min(20));
        let n = if spec.gradient {
            // Perlin gradient noise lies in about [-0.7, 0.7] in 2D; map to [0, 1].
            (gradient_noise(u * period as f64, v * period as f64, period, seed.wrapping_add(o)) / 1.4 + 0.5)
                .clamp(0.0, 1.0)
        } else {
            value_noise(u * period as f64, v * period as f64, period, seed.wrapping_add(o))
        };
        sum += amplitude * n;
        total += amplitude;
        amplitude *= 0.5;
    }
    sum / total
}

fn hash(x: u32, y: u32, seed: u32) -> u32 {
    // A small integer hash (lowbias32 by Chris Wellons) over the combined key.
    let mut h = x.wrapping_mul(0x27D4_EB2D) ^ y.wrapping_mul(0x1656_67B1) ^ seed.wrapping_mul(0x9E37_79B9);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^= h >> 16;
    h
}

/// Quintic fade 6t⁵ − 15t⁴ + 10t³ (C² continuous, Perlin 2002).
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn lattice(x: f64, period: u32) -> (u32, u32, f64) {
    let xf = x.floor();
    let i = (xf as i64).rem_euclid(period as i64) as u32;
    let j = (i + 1) % period;
    (i, j, x - xf)
}

/// Value noise in [0, 1], periodic with `period` cells.
pub fn value_noise(x: f64, y: f64, period: u32, seed: u32) -> f64 {
    let (x0, x1, tx) = lattice(x, period);
    let (y0, y1, ty) = lattice(y, period);
    let v = |a, b| hash(a, b, seed) as f64 / u32::MAX as f64;
    let (sx, sy) = (fade(tx), fade(ty));
    let top = v(x0, y0) + (v(x1, y0) - v(x0, y0)) * sx;
    let bottom = v(x0, y1) + (v(x1, y1) - v(x0, y1)) * sx;
    top + (bottom - top) * sy
}

/// Perlin gradient noise in about [-0.7, 0.7], periodic with `period` cells.
pub fn gradient_noise(x: f64, y: f64, period: u32, seed: u32) -> f64 {
    let (x0, x1, tx) = lattice(x, period);
    let (y0, y1, ty) = lattice(y, period);
    let grad = |a: u32, b: u32, dx: f64, dy: f64| {
        let angle = hash(a, b, seed) as f64 / u32::MAX as f64 * std::f64::consts::TAU;
        angle.cos() * dx + angle.sin() * dy
    };
    let (sx, sy) = (fade(tx), fade(ty));
    let n00 = grad(x0, y0, tx, ty);
    let n10 = grad(x1, y0, tx - 1.0, ty);
    let n01 = grad(x0, y1, tx, ty - 1.0);
    let n11 = grad(x1, y1, tx - 1.0, ty - 1.0);
    let top = n00 + (n10 - n00) * sx;
    let bottom = n01 + (n11 - n01) * sx;
    top + (bottom - top) * sy
}

/// An 8-bit RGBA image, row-major, top row first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rgba8Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[u8; 4]>,
}

/// `#rrggbb` as [0, 1] components (display-referred, as `.npr` colours).
const fn hex(rgb: u32) -> [f64; 3] {
    [
        ((rgb >> 16) & 0xff) as f64 / 255.0,
        ((rgb >> 8) & 0xff) as f64 / 255.0,
        (rgb & 0xff) as f64 / 255.0,
    ]
}

fn lerp3(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

/// Piecewise-linear ramp through `keys` (evenly spaced) at `t` in [0, 1].
fn ramp(keys: &[[f64; 3]], t: f64) -> [f64; 3] {
    let scaled = t.clamp(0.0, 1.0) * (keys.len() - 1) as f64;
    let i = (scaled.floor() as usize).min(keys.len() - 2);
    lerp3(keys[i], keys[i + 1], scaled - i as f64)
}

fn to_byte(c: f64) -> u8 {
    (c.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The water, deepest/darkest to lightest, in full light.
const BATHIC_LIT: [[f64; 3]; 6] = [
    hex(0x0e2a40),
    hex(0x174560),
    hex(0x216073),
    hex(0x357f83),
    hex(0x5a9f92),
    hex(0x9fcab4),
];
/// The same tones in shadow: darker and bluer.
const BATHIC_SHADOW: [[f64; 3]; 6] = [
    hex(0x07121f),
    hex(0x0b2136),
    hex(0x123248),
    hex(0x1c4658),
    hex(0x2d5d66),
    hex(0x4f7f80),
];

/// The bathic map of Age of Sail §6.1 ("the full palette of colors of the
/// water at different depths and levels of illumination", Fig. 19b): u is
/// the tone index (the MetaTexture dither, dark/deep at 0 to light/foamy at
/// 1), v the illumination (lit at the top row, shadow at the bottom).
/// Tones are quantized into `bands` flat colours, a limited palette like the
/// brushstrokes of the film's reference paintings, so the dither reads as
/// painted strokes rather than a smooth gradient. Values are display-referred
/// (load it `linear` in a style so the bytes reach the output unchanged).
pub fn bathic_map(width: u32, height: u32, bands: u32) -> Rgba8Image {
    let (width, height, bands) = (width.clamp(1, 4096), height.clamp(1, 4096), bands.clamp(1, 256));
    let mut pixels = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        let light = 1.0 - (f64::from(y) + 0.5) / f64::from(height);
        for x in 0..width {
            let tone = (f64::from(x) + 0.5) / f64::from(width);
            // The centre of the tone's band, so every band is one flat colour.
            let band = ((tone * f64::from(bands)).floor() + 0.5) / f64::from(bands);
            let c = lerp3(ramp(&BATHIC_SHADOW, band), ramp(&BATHIC_LIT, band), light);
            pixels.push([to_byte(c[0]), to_byte(c[1]), to_byte(c[2]), 255]);
        }
    }
    Rgba8Image { width, height, pixels }
}

/// Zenith to horizon.
const SKY: [[f64; 3]; 4] = [hex(0x3f6690), hex(0x6f93b3), hex(0xaabfcc), hex(0xe6dcc2)];
const CLOUD: [f64; 3] = hex(0xf5efe2);

/// The sky reflection map of Age of Sail §6.1 (Fig. 19d): u is the azimuth
/// of the reflected ray (one turn across, seamless from the right edge to
/// the left), v its elevation from the zenith (v = 0) to the horizon
/// (v = 1). A zenith-to-horizon ramp with soft clouds from tileable value
/// noise (`seed`), thicker towards the horizon. Display-referred, like
/// [`bathic_map`].
pub fn sky_map(width: u32, height: u32, seed: u32) -> Rgba8Image {
    let (width, height) = (width.clamp(1, 4096), height.clamp(1, 4096));
    let clouds = NoiseSpec {
        size: width,
        octaves: 4,
        seed,
        gradient: false,
        channels: 1,
        frequency: 4,
    };
    let mut pixels = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        let elevation = (f64::from(y) + 0.5) / f64::from(height);
        for x in 0..width {
            let u = (f64::from(x) + 0.5) / f64::from(width);
            // Periodic in u with period 1 (the noise lattice wraps).
            let n = fbm(u, elevation * 0.5, &clouds, seed);
            let cover = ((n - 0.45) / 0.25).clamp(0.0, 1.0) * (0.35 + 0.65 * elevation);
            let c = lerp3(ramp(&SKY, elevation), CLOUD, cover * 0.8);
            pixels.push([to_byte(c[0]), to_byte(c[1]), to_byte(c[2]), 255]);
        }
    }
    Rgba8Image { width, height, pixels }
}

/// The foam "erosion" map of Age of Sail §6.1 (Fig. 19c): `strokes` brush
/// strokes on a tileable `size`² tile, in every colour channel. A stroke is
/// a capsule around a short spine, laid roughly along u (±20°: foam lies
/// along the crests, across the wind that runs along v), whose half-width
/// narrows from the pressed start to the lifted end (a brush leaving the
/// canvas). Each stroke has a strength in (0.1, 1]: its value is that
/// strength over the inner half of its half-width, falling to 0 over the
/// outer half. Where strokes overlap the map keeps the larger value.
/// Thresholding the map at e erodes it stroke by stroke: the strokes
/// stronger than e stay, at least half their width, the others vanish, so
/// foam grows and shrinks as connected shapes, never as slivers or specks;
/// the ramp lets a stroke swell over a few frames rather than pop in.
/// Seamless: offsets wrap by one tile.
pub fn foam_strokes(size: u32, strokes: u32, seed: u32) -> Rgba8Image {
    // (centre, unit direction, half-length, half-width at the start, strength).
    type Stroke = ([f64; 2], [f64; 2], f64, f64, f64);
    let size = size.clamp(1, 4096);
    let unit = |k: u32, i: u32| f64::from(hash(k, i, seed)) / f64::from(u32::MAX);
    let shapes: Vec<Stroke> = (0..strokes.min(4096))
        .map(|k| {
            let angle = (unit(k, 2) - 0.5) * 40f64.to_radians();
            (
                [unit(k, 0), unit(k, 1)],
                [angle.cos(), angle.sin()],
                0.04 + 0.05 * unit(k, 3),
                0.022 + 0.018 * unit(k, 4),
                0.1 + 0.9 * unit(k, 5),
            )
        })
        .collect();
    let mut pixels = Vec::with_capacity((size * size) as usize);
    for y in 0..size {
        for x in 0..size {
            let p = [
                (f64::from(x) + 0.5) / f64::from(size),
                (f64::from(y) + 0.5) / f64::from(size),
            ];
            let mut value: f64 = 0.0;
            for (centre, dir, half_length, half_width, strength) in &shapes {
                // The nearest copy of the stroke on the torus.
                let d = [0, 1].map(|i| {
                    let o = p[i] - centre[i];
                    o - o.round()
                });
                let along = (d[0] * dir[0] + d[1] * dir[1]).clamp(-half_length, *half_length);
                let off = [d[0] - along * dir[0], d[1] - along * dir[1]];
                let distance = off[0].hypot(off[1]);
                // 1 at the start of the spine, 0.4 at its end.
                let press = 1.0 - 0.3 * (along / half_length + 1.0);
                let width = half_width * press;
                let body = (2.0 * (1.0 - distance / width)).clamp(0.0, 1.0);
                value = value.max(strength * body);
            }
            let byte = to_byte(value);
            pixels.push([byte, byte, byte, 255]);
        }
    }
    Rgba8Image {
        width: size,
        height: size,
        pixels,
    }
}

/// A painterly colour map for Age of Sail §5.2's per-object lit and shadow
/// textures ("two full sets of texture maps, one for shadowed areas, one
/// for illuminated areas"): tileable value-noise fBm (`seed`, 5 octaves,
/// 4 cells at the first) mapped through a ramp around `base` — a darker
/// tone (`base`·0.8) below, `base` in the middle, a lighter one (a 35% mix
/// towards white) above — so flat object colours read as uneven paint.
/// The ramp input is quantized into 6 levels, a limited palette as in the
/// film's painted textures, softened by ½ step of the noise so the band
/// edges wander. Tiles seamlessly (the fBm lattice wraps). Display-referred, like [`bathic_map`]: load it `linear`.
pub fn paint_map(size: u32, base: [f64; 3], seed: u32) -> Rgba8Image {
    let size = size.clamp(1, 4096);
    let spec = NoiseSpec {
        size,
        octaves: 5,
        seed,
        gradient: false,
        channels: 1,
        frequency: 4,
    };
    let keys = [base.map(|c| c * 0.8), base, base.map(|c| c + (1.0 - c) * 0.35)];
    let mut pixels = Vec::with_capacity((size * size) as usize);
    for y in 0..size {
        let v = (f64::from(y) + 0.5) / f64::from(size);
        for x in 0..size {
            let u = (f64::from(x) + 0.5) / f64::from(size);
            let n = fbm(u, v, &spec, seed);
            // Widen the fBm's concentrated middle (≈0.3..0.7) to the ramp's 0..1.
            let t = ((n - 0.5) * 2.2 + 0.5).clamp(0.0, 1.0);
            let t = ((t * 6.0).floor() + 0.5) / 6.0 * 0.7 + t * 0.3;
            let c = ramp(&keys, t);
            pixels.push([to_byte(c[0]), to_byte(c[1]), to_byte(c[2]), 255]);
        }
    }
    Rgba8Image {
        width: size,
        height: size,
        pixels,
    }
}

/// `#rrggbb` (or `rrggbb`) as [0, 1] components; `None` if malformed.
pub fn parse_hex(text: &str) -> Option<[f64; 3]> {
    let digits = text.strip_prefix('#').unwrap_or(text);
    if digits.len() != 6 || !digits.chars().all(|c| c.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(digits, 16).ok().map(hex)
}

/// Write a generated texture as a 16-bit RGBA PNG (atomically): 16 bits keep
/// warp vectors smooth where 8 bits would quantize them visibly.
pub fn write_png16(img: &NoiseImage, path: &std::path::Path) -> std::io::Result<()> {
    let data: Vec<u16> = img
        .pixels
        .iter()
        .flat_map(|p| p.map(|c| (c.clamp(0.0, 1.0) * 65535.0).round() as u16))
        .collect();
    let buffer = image::ImageBuffer::<image::Rgba<u16>, Vec<u16>>::from_raw(img.size, img.size, data)
        .ok_or_else(|| std::io::Error::other("texture size does not match its pixels"))?;
    let mut bytes = Vec::new();
    buffer
        .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .map_err(std::io::Error::other)?;
    crate::output::write_atomic(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(gradient: bool) -> NoiseSpec {
        NoiseSpec {
            size: 64,
            octaves: 4,
            seed: 7,
            gradient,
            channels: 2,
            frequency: 4,
        }
    }

    #[test]
    fn noise_is_in_unit_range_and_deterministic() {
        for g in [false, true] {
            let a = generate(&spec(g));
            let b = generate(&spec(g));
            assert_eq!(a.pixels, b.pixels);
            for p in &a.pixels {
                for c in &p[..2] {
                    assert!((0.0..=1.0).contains(c) && c.is_finite(), "{c}");
                }
            }
        }
    }

    #[test]
    fn noise_tiles_seamlessly() {
        // The step across the wrap-around seam must look like any other step
        // between neighbours: compare with the largest interior step.
        for g in [false, true] {
            let img = generate(&spec(g));
            let n = img.size as usize;
            let at = |x: usize, y: usize| img.pixels[y * n + x][0] as f64;
            let mut interior: f64 = 0.0;
            let mut seam: f64 = 0.0;
            for y in 0..n {
                for x in 0..n - 1 {
                    interior = interior.max((at(x + 1, y) - at(x, y)).abs());
                }
                seam = seam.max((at(0, y) - at(n - 1, y)).abs());
            }
            for x in 0..n {
                seam = seam.max((at(x, 0) - at(x, n - 1)).abs());
            }
            assert!(seam <= interior * 1.05, "seam step {seam} vs interior {interior}");
        }
    }

    #[test]
    fn channels_are_independent() {
        let img = generate(&spec(false));
        let same = img.pixels.iter().filter(|p| (p[0] - p[1]).abs() < 1e-6).count();
        assert!(same < img.pixels.len() / 10);
    }
}
