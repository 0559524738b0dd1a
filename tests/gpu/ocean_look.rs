//! The Age of Sail ocean as the paper paints it (issue 37; Harvill et al.,
//! journal 2019, §2 and §6.1), measured on `examples/ocean.npr` over
//! `examples/scenes/ocean.toml` at two sizes and three times (0 s, 10 s and
//! 20 s = frame 480 at 24 fps; 10 s is a keyframe of the animated overlay
//! and saturation, so the palette there is known exactly):
//!
//! - **Painted palette** (§2: "there are only four shades of blue in the
//!   ocean"): the share of water pixels within 3/255 of a tone the maps
//!   give at the cells' centres (the bathic map's 4 bands × 2 light levels,
//!   the sky map's 8 × 4 cells, each through the frame's overlay and
//!   saturation, computed here in f64 from the PNGs). The smooth version
//!   (`painted = 0`) is measured too, to show the measure tells them apart.
//! - **Foam as brush strokes** (§6.1, Fig. 19c): the 4-connected components
//!   of the foam's pixels: few single pixels, most foam in shapes of many
//!   pixels, and shapes of about one screen size near and far.
//! - **No shimmer**: at the still camera, of the foam in frame 241, the
//!   share in shapes with no foam of frame 240 within 1 px (shapes that
//!   appear rather than move with the water).
//! - **The loop closes**: frame 0 equals frame 480 byte for byte.
//!
//! The renders are written to `target/tmp/ocean-look/` for a look when a
//! bound fails.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Renderer, StyleProgram};
use npr_stdlib::ops::colour::{overlay, saturation};
use std::path::{Path, PathBuf};

use crate::common::{gpu, root};

const SIZES: [(u32, u32); 2] = [(192, 128), (384, 256)];
const FPS: f64 = 24.0;
/// The clear colour (#e6dcc2): the sky above the horizon.
const CLEAR: [u8; 3] = [0xe6, 0xdc, 0xc2];
/// The style's `foam_color` (#eef1e8).
const FOAM: [u8; 3] = [0xee, 0xf1, 0xe8];
/// A tone's tolerance, per channel: the maps are filtered in f32 and the
/// output rounded to 8 bits (≤ 1/255 apart), overlay and saturation add
/// f32 rounding; 3/255 is still far below the 10–30/255 between tones.
const TOLERANCE: i32 = 3;

fn scratch() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("ocean-look");
    std::fs::create_dir_all(&dir).expect("scratch");
    dir
}

fn compile(text: &str) -> StyleProgram {
    let mut sources = SourceMap::new();
    let dir = root().join("examples");
    match npr_compiler::compile_source("ocean.npr", text, &dir, &mut sources, &CompileOptions::default()) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

fn style_text() -> String {
    std::fs::read_to_string(root().join("examples/ocean.npr")).expect("examples/ocean.npr")
}

/// One frame's RGB pixels, row by row.
struct Frame {
    rgb: Vec<[u8; 3]>,
}

fn render(program: &StyleProgram, size: (u32, u32), times: &[f64], name: &str) -> Vec<Frame> {
    let mut sources = SourceMap::new();
    let scene = npr_runner::scene::load_scene(&root().join("examples/scenes/ocean.toml"), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let mut renderer = Renderer::new(&gpu().device, &gpu().queue, program, &scene).expect("renderer");
    times
        .iter()
        .map(|&t| {
            let frame = (t * FPS).round() as u32;
            let spec = FrameSpec::animated(size.0, size.1, frame, FPS, 0);
            renderer.render(&scene, &spec).expect("render");
            let image = renderer.read_output().expect("read back");
            let path = scratch().join(format!("{name}_{}x{}_{frame:03}.png", size.0, size.1));
            let rgba = image::RgbaImage::from_raw(size.0, size.1, image.bytes.clone()).expect("rgba8 output");
            rgba.save(&path).expect("write render");
            Frame {
                rgb: image.bytes.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect(),
            }
        })
        .collect()
}

fn near(a: [u8; 3], b: [u8; 3], tolerance: i32) -> bool {
    (0..3).all(|i| (i32::from(a[i]) - i32::from(b[i])).abs() <= tolerance)
}

/// Bilinear sample of an RGBA8 map at `uv` (texel centres at (i + ½)/w),
/// clamped or wrapped, as the GPU's linear filter does: bytes / 255.
fn bilinear(map: &image::RgbaImage, uv: [f64; 2], wrap: bool) -> [f64; 4] {
    let (w, h) = (map.width() as i64, map.height() as i64);
    let (x, y) = (uv[0] * w as f64 - 0.5, uv[1] * h as f64 - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |i: i64, j: i64| {
        let (i, j) = if wrap {
            (i.rem_euclid(w), j.rem_euclid(h))
        } else {
            (i.clamp(0, w - 1), j.clamp(0, h - 1))
        };
        map.get_pixel(i as u32, j as u32).0.map(|c| f64::from(c) / 255.0)
    };
    let (x0, y0) = (x0 as i64, y0 as i64);
    let mut out = [0.0; 4];
    for (i, j, weight) in [
        (x0, y0, (1.0 - fx) * (1.0 - fy)),
        (x0 + 1, y0, fx * (1.0 - fy)),
        (x0, y0 + 1, (1.0 - fx) * fy),
        (x0 + 1, y0 + 1, fx * fy),
    ] {
        let t = texel(i, j);
        for c in 0..4 {
            out[c] += weight * t[c];
        }
    }
    out
}

fn hex(c: u32) -> [f64; 4] {
    [(c >> 16) & 255, (c >> 8) & 255, c & 255]
        .map(|b| f64::from(b) / 255.0)
        .into_iter()
        .chain([1.0])
        .collect::<Vec<_>>()
        .try_into()
        .unwrap()
}

fn to_bytes(c: [f64; 4]) -> [u8; 3] {
    [0, 1, 2].map(|i| (c[i].clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// The painted tones at a time: the bathic map at its 4 × 2 cell centres
/// through the water overlay (#7a6a88) and saturation, and the sky map at
/// its 8 × 4 cell centres through the sky overlay (#c08a5a, 0.25) at
/// saturation 1, the style's defaults. `overlay_amount` and `saturation`
/// are the animated water values at that time.
fn palette(water_overlay: f64, water_saturation: f64) -> Vec<[u8; 3]> {
    let open = |name: &str| {
        image::open(root().join("examples/textures").join(name))
            .expect(name)
            .to_rgba8()
    };
    let (bathic, sky) = (open("ocean_bathic.png"), open("ocean_sky.png"));
    let mut tones = Vec::new();
    for i in 0..4 {
        for j in 0..2 {
            let c = bilinear(&bathic, [(f64::from(i) + 0.5) / 4.0, (f64::from(j) + 0.5) / 2.0], false);
            tones.push(to_bytes(saturation(
                overlay(c, hex(0x7a6a88), water_overlay),
                water_saturation,
            )));
        }
    }
    for i in 0..8 {
        for j in 0..4 {
            let c = bilinear(&sky, [(f64::from(i) + 0.5) / 8.0, (f64::from(j) + 0.5) / 4.0], true);
            tones.push(to_bytes(saturation(overlay(c, hex(0xc08a5a), 0.25), 1.0)));
        }
    }
    tones
}

/// The water's pixels (the ocean, not the clear sky, not foam) and the
/// share of them within [`TOLERANCE`] of a tone.
fn palette_share(frame: &Frame, tones: &[[u8; 3]]) -> (usize, f64) {
    let water: Vec<[u8; 3]> = frame
        .rgb
        .iter()
        .copied()
        .filter(|&p| !near(p, CLEAR, 1) && !near(p, FOAM, TOLERANCE))
        .collect();
    let painted = water
        .iter()
        .filter(|&&p| tones.iter().any(|&t| near(p, t, TOLERANCE)))
        .count();
    (water.len(), painted as f64 / water.len().max(1) as f64)
}

fn foam_mask(frame: &Frame) -> Vec<bool> {
    frame.rgb.iter().map(|&p| near(p, FOAM, TOLERANCE)).collect()
}

/// The sizes (px) of the 4-connected components of `mask`, with the row
/// of each component's first pixel.
fn components(mask: &[bool], width: usize, height: usize) -> Vec<(usize, usize)> {
    let mut seen = vec![false; mask.len()];
    let mut out = Vec::new();
    for start in 0..mask.len() {
        if !mask[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        let (mut stack, mut size) = (vec![start], 0);
        while let Some(i) = stack.pop() {
            size += 1;
            let (x, y) = (i % width, i / width);
            let mut visit = |j: usize| {
                if mask[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            };
            if x > 0 {
                visit(i - 1);
            }
            if x + 1 < width {
                visit(i + 1);
            }
            if y > 0 {
                visit(i - width);
            }
            if y + 1 < height {
                visit(i + width);
            }
        }
        out.push((size, start / width));
    }
    out
}

/// The component size that half the foam's pixels lie in components at
/// least as large as (a pixel-weighted median).
fn weighted_median(sizes: &[usize]) -> usize {
    let mut sorted = sizes.to_vec();
    sorted.sort_unstable();
    let total: usize = sorted.iter().sum();
    let mut running = 0;
    for s in &sorted {
        running += s;
        if 2 * running >= total {
            return *s;
        }
    }
    0
}

/// Of the foam in `b`, the share in components with no pixel within 1 px
/// (8-neighbourhood) of foam in `a`: shapes that appeared rather than
/// moved with the water (a moving stroke overlaps where it was; a stroke
/// that pops in, or a speck that shimmers, does not).
fn appeared(a: &[bool], b: &[bool], width: usize, height: usize) -> (usize, f64) {
    let close = |i: usize| {
        let (x, y) = (i % width, i / width);
        (y.saturating_sub(1)..=(y + 1).min(height - 1))
            .any(|v| (x.saturating_sub(1)..=(x + 1).min(width - 1)).any(|u| a[v * width + u]))
    };
    let mut seen = vec![false; b.len()];
    let (mut total, mut new) = (0, 0);
    for start in 0..b.len() {
        if !b[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        let (mut stack, mut pixels, mut overlaps) = (vec![start], 0, false);
        while let Some(i) = stack.pop() {
            pixels += 1;
            overlaps |= close(i);
            let (x, y) = (i % width, i / width);
            for (ok, j) in [
                (x > 0, i.wrapping_sub(1)),
                (x + 1 < width, i + 1),
                (y > 0, i.wrapping_sub(width)),
                (y + 1 < height, i + width),
            ] {
                if ok && b[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        total += pixels;
        if !overlaps {
            new += pixels;
        }
    }
    (total, new as f64 / total.max(1) as f64)
}

#[test]
fn the_ocean_is_painted_in_few_tones_with_brush_foam_and_loops() {
    let text = style_text();
    assert!(
        text.contains("param painted: float = 1.0"),
        "examples/ocean.npr lost its `painted` parameter"
    );
    let program = compile(&text);
    // Frames 0, 240, 241 and 480: t = 0, 10 s, 10 s + 1/24, 20 s.
    let times = [0.0, 10.0, 10.0 + 1.0 / FPS, 20.0];
    let palettes = [palette(0.0, 1.0), palette(0.45, 0.7)];
    for size in SIZES {
        let frames = render(&program, size, &times, "painted");
        let (w, h) = (size.0 as usize, size.1 as usize);
        // The loop closes: the geometry and every animated value repeat.
        assert!(
            frames[0].rgb == frames[3].rgb,
            "{w}x{h}: frame 480 differs from frame 0"
        );

        for (frame, tones, label) in [(&frames[0], &palettes[0], "0 s"), (&frames[1], &palettes[1], "10 s")] {
            let (water, share) = palette_share(frame, tones);
            eprintln!(
                "{w}x{h} at {label}: {water} water px, {:.2}% on a painted tone",
                100.0 * share
            );
            // Painted: every water pixel is a tone, but the ring at the
            // horizon and the grid meet there in sub-pixel slivers whose
            // rasterization picks either; 97% leaves them room.
            assert!(
                share >= 0.97,
                "{w}x{h} at {label}: only {:.2}% of the water on a painted tone",
                100.0 * share
            );
        }

        let mut pooled: (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
        for (k, frame) in frames[..3].iter().enumerate() {
            let sizes: Vec<(usize, usize)> = components(&foam_mask(frame), w, h);
            let pixels: usize = sizes.iter().map(|s| s.0).sum();
            let singles = sizes.iter().filter(|s| s.0 == 1).count();
            let small_px: usize = sizes.iter().filter(|s| s.0 < 4).map(|s| s.0).sum();
            // Near and far: components starting in the lower and the upper
            // half of the water (the horizon is near a third down).
            let horizon = frame.rgb.iter().position(|&p| !near(p, CLEAR, 1)).map_or(0, |i| i / w);
            let middle = (horizon + h) / 2;
            let far: Vec<usize> = sizes.iter().filter(|s| s.1 < middle).map(|s| s.0).collect();
            let close: Vec<usize> = sizes.iter().filter(|s| s.1 >= middle).map(|s| s.0).collect();
            eprintln!(
                "{w}x{h} frame {k}: foam {pixels} px in {} components, {singles} single, {:.1}% in components under 4 px",
                sizes.len(),
                100.0 * small_px as f64 / pixels.max(1) as f64
            );
            assert!(pixels > w * h / 200, "{w}x{h}: almost no foam ({pixels} px)");
            // Specks: under 5% of the foam in components under 4 px
            // (measured 1–3%; the style before issue 37 had 19–22% at
            // 384×256, its foam a threshold of gradient noise).
            assert!(
                (small_px as f64) < 0.05 * pixels as f64,
                "{w}x{h}: {small_px} of {pixels} foam px in specks under 4 px"
            );
            pooled.0.extend(far);
            pooled.1.extend(close);
        }
        // One screen size near and far, over the three frames: MetaTexture
        // keeps a stroke's size in px, so far foam is not much smaller than
        // near foam. A texture fixed to the water would shrink with the
        // distance ratio of the halves (about 12 m against 40 m, an area
        // ratio near 0.1); a quarter tells the two apart, and leaves room
        // for strokes the up-wind mask and the distance fade cut short.
        let (m_far, m_near) = (weighted_median(&pooled.0), weighted_median(&pooled.1));
        eprintln!("{w}x{h}: median foam shape far {m_far} px, near {m_near} px");
        assert!(
            4 * m_far >= m_near,
            "{w}x{h}: far foam shapes ({m_far} px) much smaller than near ones ({m_near} px)"
        );

        let masks: Vec<Vec<bool>> = frames[1..3].iter().map(foam_mask).collect();
        let (foam, share) = appeared(&masks[0], &masks[1], w, h);
        eprintln!(
            "{w}x{h}: frame 240 → 241, {:.2}% of {foam} foam px appeared",
            100.0 * share
        );
        // Foam moves with the water (several px a frame near the boat):
        // what counts is shapes with nothing of the last frame's foam
        // within 1 px. At most 2.5% (measured 0.6–1.0%; the style before
        // issue 37, its foam specks of thresholded noise, had 4.9% at
        // 384×256).
        assert!(
            share <= 0.025,
            "{w}x{h}: {:.2}% of the foam appeared from frame 240 to 241",
            100.0 * share
        );
    }
    // The smooth version, for contrast: the same measure finds few pixels on a tone.
    let smooth = compile(&text.replace("param painted: float = 1.0", "param painted: float = 0.0"));
    let frame = &render(&smooth, SIZES[0], &[10.0], "smooth")[0];
    let (_, share) = palette_share(frame, &palettes[1]);
    eprintln!("smooth at 10 s: {:.2}% on a painted tone", 100.0 * share);
    assert!(
        share < 0.5,
        "the smooth version has {:.2}% on a tone: the measure does not tell them apart",
        100.0 * share
    );
}
