//! The image type the f64 references work on, and the small vector
//! helpers they share. A leaf: the operators' references (`ops::*`) and the
//! `reference` facade both build on it.

/// An RGBA image of f64 texels with clamp-to-edge reads (like `textureLoad`
/// with clamped coordinates in the WGSL operators).
#[derive(Debug, Clone)]
pub struct ImageF64 {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f64; 4]>,
}

impl ImageF64 {
    pub fn new(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> [f64; 4]) -> ImageF64 {
        let mut pixels = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                pixels.push(f(x, y));
            }
        }
        ImageF64 { width, height, pixels }
    }

    pub fn load(&self, x: i64, y: i64) -> [f64; 4] {
        let x = x.clamp(0, self.width as i64 - 1) as usize;
        let y = y.clamp(0, self.height as i64 - 1) as usize;
        self.pixels[y * self.width as usize + x]
    }

    /// The texel under `uv` (floor(uv · dims), clamped), as the operators pick it.
    pub fn pixel_of(&self, uv: [f64; 2]) -> (i64, i64) {
        (
            ((uv[0] * self.width as f64).floor() as i64).clamp(0, self.width as i64 - 1),
            ((uv[1] * self.height as f64).floor() as i64).clamp(0, self.height as i64 - 1),
        )
    }
}

pub(crate) fn unit(v: [f64; 3]) -> [f64; 3] {
    let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    // Same guard as the WGSL: a zero vector stays zero.
    let s = 1.0 / l2.max(1e-30).sqrt();
    [v[0] * s, v[1] * s, v[2] * s]
}

pub(crate) fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Bilinear filtering with repeat addressing at level 0 (a tileable texture).
pub fn sample_repeat(tex: &ImageF64, uv: [f64; 2]) -> [f64; 4] {
    let (w, h) = (tex.width as i64, tex.height as i64);
    let x = uv[0] * w as f64 - 0.5;
    let y = uv[1] * h as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let at = |i: i64, j: i64| tex.load(i.rem_euclid(w), j.rem_euclid(h));
    let (a, b, c, d) = (at(x0, y0), at(x0 + 1, y0), at(x0, y0 + 1), at(x0 + 1, y0 + 1));
    std::array::from_fn(|i| {
        let top = a[i] * (1.0 - fx) + b[i] * fx;
        let bottom = c[i] * (1.0 - fx) + d[i] * fx;
        top * (1.0 - fy) + bottom * fy
    })
}
