//! Images on the CPU as the texture builders hold them: a [`Level`] of
//! linear RGBA texels and the box filters that make mip and rip-map
//! levels from it. A leaf: textures, art-maps, their cache and the host
//! inputs all share these without importing each other.

/// One level: linear RGBA texels, row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 4]>,
}

/// The mip chain of `base` (2×2 box filter, odd edges clamped), `count` levels.
pub fn mip_chain(base: Level, count: u32) -> Vec<Level> {
    let mut levels = vec![base];
    while (levels.len() as u32) < count {
        let last = &levels[levels.len() - 1];
        if last.width == 1 && last.height == 1 {
            break;
        }
        let (pixels, width, height) = downsample_box(&last.pixels, last.width, last.height);
        levels.push(Level { width, height, pixels });
    }
    levels
}

/// Halve `level` along x (`axis` 0) or y (1) with a 2-tap box filter (an
/// odd last texel is kept alone): a rip-map's anisotropic reduction.
pub fn halve_axis(level: &Level, axis: usize) -> Level {
    let (w, h) = (level.width, level.height);
    let (nw, nh) = if axis == 0 {
        ((w / 2).max(1), h)
    } else {
        (w, (h / 2).max(1))
    };
    let at = |x: u32, y: u32| level.pixels[(y.min(h - 1) * w + x.min(w - 1)) as usize];
    let mut pixels = Vec::with_capacity((nw * nh) as usize);
    for y in 0..nh {
        for x in 0..nw {
            let (a, b) = if axis == 0 {
                (at(2 * x, y), at(2 * x + 1, y))
            } else {
                (at(x, 2 * y), at(x, 2 * y + 1))
            };
            pixels.push(std::array::from_fn(|c| 0.5 * (a[c] + b[c])));
        }
    }
    Level {
        width: nw,
        height: nh,
        pixels,
    }
}

/// Halve an RGBA float image with a 2×2 box filter (odd edges clamp).
pub fn downsample_box(pixels: &[[f32; 4]], w: u32, h: u32) -> (Vec<[f32; 4]>, u32, u32) {
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    let mut out = vec![[0.0f32; 4]; (nw * nh) as usize];
    for y in 0..nh {
        for x in 0..nw {
            let mut acc = [0.0f32; 4];
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let sx = (2 * x + dx).min(w - 1);
                let sy = (2 * y + dy).min(h - 1);
                let p = pixels[(sy * w + sx) as usize];
                for c in 0..4 {
                    acc[c] += p[c] * 0.25;
                }
            }
            out[(y * nw + x) as usize] = acc;
        }
    }
    (out, nw, nh)
}
