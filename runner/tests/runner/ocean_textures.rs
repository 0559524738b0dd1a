//! The example colour maps (`examples/textures/ocean_*.png`, and the Age of
//! Sail per-object paint maps `paint_*.png`) are exactly what the generators
//! in `npr_runner::texgen` make, and have the properties the styles rely on.
//!
//! Regenerate after changing a generator with
//! `NPR_UPDATE_TEXTURES=1 cargo test -p npr-runner --test ocean_textures`.

use npr_runner::texgen::{bathic_map, foam_strokes, paint_map, parse_hex, sky_map, Rgba8Image};
use std::path::{Path, PathBuf};

fn texture_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/textures")
        .join(name)
}

fn bathic() -> Rgba8Image {
    bathic_map(64, 16, 4)
}

fn foam() -> Rgba8Image {
    foam_strokes(256, 64, 29)
}

fn sky() -> Rgba8Image {
    sky_map(128, 32, 7)
}

/// The checked-in PNG equals the generator's output byte for byte (or is
/// rewritten when `NPR_UPDATE_TEXTURES` is set).
fn check_file(name: &str, generated: &Rgba8Image) {
    let path = texture_path(name);
    let image = image::RgbaImage::from_fn(generated.width, generated.height, |x, y| {
        image::Rgba(generated.pixels[(y * generated.width + x) as usize])
    });
    if std::env::var_os("NPR_UPDATE_TEXTURES").is_some() {
        npr_runner::output::write_png8(&image, &path).expect("write texture");
    }
    let on_disk = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (regenerate with NPR_UPDATE_TEXTURES=1)", path.display()))
        .to_rgba8();
    assert_eq!(on_disk.dimensions(), image.dimensions(), "{name}");
    assert!(
        on_disk == image,
        "{name} differs from its generator; regenerate with NPR_UPDATE_TEXTURES=1"
    );
}

/// Age of Sail §5.2 lit and shadow maps: (file, base colour, seed). The
/// bases are the flat colours the example used before it had textures.
pub const PAINT_MAPS: [(&str, &str, u32); 8] = [
    ("paint_lit.png", "#e0c090", 1),
    ("paint_shadow.png", "#504070", 2),
    ("paint_spot_lit.png", "#e9c48a", 3),
    ("paint_spot_shadow.png", "#5a4a78", 4),
    ("paint_lamp_lit.png", "#fff2c0", 5),
    ("paint_lamp_shadow.png", "#d8b070", 6),
    ("paint_ground_lit.png", "#b9c98f", 7),
    ("paint_ground_shadow.png", "#4f5f7a", 8),
];

fn paint(base: &str, seed: u32) -> Rgba8Image {
    paint_map(64, parse_hex(base).expect("colour"), seed)
}

#[test]
fn the_checked_in_maps_are_the_generated_ones() {
    check_file("ocean_bathic.png", &bathic());
    check_file("ocean_sky.png", &sky());
    check_file("ocean_foam.png", &foam());
    for (file, base, seed) in PAINT_MAPS {
        check_file(file, &paint(base, seed));
    }
}

#[test]
fn paint_maps_stay_around_their_base_colour_and_vary() {
    for (file, base, seed) in PAINT_MAPS {
        let map = paint(base, seed);
        let want = parse_hex(base).expect("colour").map(|c| c * 255.0);
        let n = map.pixels.len() as f64;
        let mean: Vec<f64> = (0..3)
            .map(|c| map.pixels.iter().map(|p| f64::from(p[c])).sum::<f64>() / n)
            .collect();
        for c in 0..3 {
            // Ramp from 0.8·base to base + 35% of the way to white: the mean stays near base.
            assert!(
                (mean[c] - want[c]).abs() < 0.15 * 255.0,
                "{file}: channel {c} mean {} far from base {}",
                mean[c],
                want[c]
            );
        }
        let lumas: Vec<f64> = map.pixels.iter().map(|p| luma(*p)).collect();
        let (lo, hi) = lumas
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), l| (lo.min(*l), hi.max(*l)));
        assert!(
            hi - lo > 10.0,
            "{file}: luma spans only {lo}..{hi}; the paint should vary"
        );
    }
}

#[test]
fn paint_maps_tile_seamlessly() {
    let map = paint("#808080", 3);
    let (w, h) = (map.width as usize, map.height as usize);
    let at = |x: usize, y: usize| luma(map.pixels[y * w + x]);
    // The step across the wrap is no larger than the largest step inside.
    let inner = (0..h)
        .flat_map(|y| (0..w - 1).map(move |x| (x, y)))
        .map(|(x, y)| (at(x + 1, y) - at(x, y)).abs())
        .fold(0.0, f64::max);
    let wrap = (0..h).map(|y| (at(0, y) - at(w - 1, y)).abs()).fold(0.0, f64::max);
    assert!(wrap <= inner + 1e-9, "wrap step {wrap} > inner step {inner}");
}

fn luma(p: [u8; 4]) -> f64 {
    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
}

#[test]
fn the_bathic_map_brightens_with_tone_and_light_in_flat_bands() {
    let map = bathic();
    let at = |x: u32, y: u32| map.pixels[(y * map.width + x) as usize];
    for y in 0..map.height {
        let row: Vec<f64> = (0..map.width).map(|x| luma(at(x, y))).collect();
        assert!(row.windows(2).all(|w| w[1] >= w[0]), "row {y} not monotonic: {row:?}");
        // 4 bands ("only four shades of blue in the ocean", Age of Sail
        // §2): exactly 4 distinct colours per row.
        let mut distinct: Vec<[u8; 4]> = (0..map.width).map(|x| at(x, y)).collect();
        distinct.dedup();
        assert_eq!(distinct.len(), 4, "row {y}");
    }
    for x in 0..map.width {
        assert!(
            luma(at(x, 0)) > luma(at(x, map.height - 1)) + 10.0,
            "lit above shadow at column {x}"
        );
    }
}

#[test]
fn the_sky_map_wraps_around_the_azimuth_and_brightens_to_the_horizon() {
    let map = sky();
    let at = |x: u32, y: u32| map.pixels[(y * map.width + x) as usize];
    let (mut seam, mut interior) = (0.0f64, 0.0f64);
    for y in 0..map.height {
        for x in 0..map.width - 1 {
            interior = interior.max((luma(at(x + 1, y)) - luma(at(x, y))).abs());
        }
        seam = seam.max((luma(at(0, y)) - luma(at(map.width - 1, y))).abs());
    }
    assert!(seam <= interior, "seam step {seam} vs interior {interior}");
    let mean_row = |y: u32| (0..map.width).map(|x| luma(at(x, y))).sum::<f64>() / f64::from(map.width);
    assert!(mean_row(map.height - 1) > mean_row(0) + 60.0);
    // Not a bare ramp: clouds vary along the azimuth.
    let spread = (0..map.width)
        .map(|x| luma(at(x, map.height - 4)))
        .fold((f64::MAX, f64::MIN), |(lo, hi), l| (lo.min(l), hi.max(l)));
    assert!(spread.1 - spread.0 > 10.0, "{spread:?}");
}

#[test]
fn generators_are_total() {
    for (w, h) in [(0, 0), (1, 1), (5000, 1)] {
        let b = bathic_map(w, h, 0);
        assert_eq!(b.pixels.len(), (b.width * b.height) as usize);
        let s = sky_map(w, h, u32::MAX);
        assert_eq!(s.pixels.len(), (s.width * s.height) as usize);
    }
}

/// The art-map gallery's sources (`examples/textures/SOURCES.md`): 256² paint
/// maps, (file, base colour, seed).
const GALLERY_MAPS: [(&str, &str, u32); 3] = [
    ("gallery_wall.png", "#e6cfb4", 7),
    ("gallery_floor.png", "#d9c8a4", 8),
    ("gallery_stone.png", "#c8c0b0", 9),
];

#[test]
fn shipped_gallery_maps_are_what_texgen_writes() {
    for (file, base, seed) in GALLERY_MAPS {
        check_file(file, &paint_map(256, parse_hex(base).expect("colour"), seed));
    }
}

/// The foam map is brush strokes: both 0 (open water) and near 1 (the
/// strongest strokes) occur, the strokes cover a minority of the tile at a low threshold, and
/// it wraps (the left column continues the right, as the top the bottom:
/// no edge steps larger than inside the tile).
#[test]
fn the_foam_map_is_seamless_strokes() {
    let map = foam();
    let v = |x: u32, y: u32| f64::from(map.pixels[((y % map.height) * map.width + x % map.width) as usize][0]);
    let n = f64::from(map.width * map.height);
    let covered = (0..map.height)
        .flat_map(|y| (0..map.width).map(move |x| (x, y)))
        .filter(|&(x, y)| v(x, y) > 25.0)
        .count() as f64
        / n;
    let spines = (0..map.height)
        .flat_map(|y| (0..map.width).map(move |x| (x, y)))
        .filter(|&(x, y)| v(x, y) > 240.0)
        .count();
    assert!((0.1..0.6).contains(&covered), "strokes cover {covered:.3} of the tile");
    assert!(spines > 0, "no stroke is near full strength");
    let step = |a: f64, b: f64| (a - b).abs();
    let seam = (0..map.height)
        .map(|y| step(v(map.width - 1, y), v(0, y)))
        .fold(0.0, f64::max)
        .max(
            (0..map.width)
                .map(|x| step(v(x, map.height - 1), v(x, 0)))
                .fold(0.0, f64::max),
        );
    let inside = (0..map.height)
        .flat_map(|y| (1..map.width).map(move |x| (x, y)))
        .map(|(x, y)| step(v(x - 1, y), v(x, y)))
        .fold(0.0, f64::max)
        .max(
            (0..map.width)
                .flat_map(|x| (1..map.height).map(move |y| (x, y)))
                .map(|(x, y)| step(v(x, y - 1), v(x, y)))
                .fold(0.0, f64::max),
        );
    assert!(seam <= inside, "seam step {seam} over the largest inner step {inside}");
}
