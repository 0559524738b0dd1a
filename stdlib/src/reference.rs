//! CPU reference implementations in f64, one per operator, for the accuracy
//! tests. They follow the WGSL line by line in meaning, not in precision:
//! the GPU runs in f32 and the tests state the tolerance they allow.

/// An RGBA image of f64 texels with clamp-to-edge reads (like `textureLoad`
/// with clamped coordinates in the WGSL operators).
#[derive(Debug, Clone)]
pub struct ImageF64 {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f64; 4]>,
}

impl ImageF64 {
    pub fn new(width: u32, height: u32, f: impl Fn(u32, u32) -> [f64; 4]) -> ImageF64 {
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

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    // Same guard as the WGSL: a zero vector stays zero.
    let s = 1.0 / l2.max(1e-30).sqrt();
    [v[0] * s, v[1] * s, v[2] * s]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn lambert(n: [f64; 3], l: [f64; 3]) -> f64 {
    dot3(unit(n), unit(l)).max(0.0)
}

pub fn half_lambert(n: [f64; 3], l: [f64; 3]) -> f64 {
    let h = 0.5 * dot3(unit(n), unit(l)) + 0.5;
    h * h
}

pub fn toon(x: f64, steps: i64) -> f64 {
    let n = steps.max(1) as f64;
    let band = (x.clamp(0.0, 1.0) * n).floor().min(n - 1.0);
    if n > 1.0 {
        band / (n - 1.0)
    } else {
        0.0
    }
}

pub fn threshold(x: f64, lo: f64, hi: f64) -> f64 {
    if hi <= lo {
        return if x >= lo { 1.0 } else { 0.0 };
    }
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Largest blur radius in texels (as in gaussian.wgsl).
pub const GAUSSIAN_MAX_RADIUS: i64 = 48;

pub fn gaussian(src: &ImageF64, uv: [f64; 2], sigma: f64, axis: i64) -> [f64; 4] {
    let (px, py) = src.pixel_of(uv);
    let s = sigma.max(1e-3);
    let radius = ((3.0 * s).ceil() as i64).min(GAUSSIAN_MAX_RADIUS);
    let (dx, dy) = if axis == 0 { (1, 0) } else { (0, 1) };
    let mut acc = [0.0; 4];
    let mut total = 0.0;
    for i in -radius..=radius {
        let w = (-((i * i) as f64) / (2.0 * s * s)).exp();
        let t = src.load(px + dx * i, py + dy * i);
        for c in 0..4 {
            acc[c] += w * t[c];
        }
        total += w;
    }
    acc.map(|a| a / total)
}

pub fn downsample(src: &ImageF64, uv: [f64; 2]) -> [f64; 4] {
    let bx = (uv[0] * src.width as f64 - 0.5).floor() as i64;
    let by = (uv[1] * src.height as f64 - 0.5).floor() as i64;
    let mut acc = [0.0; 4];
    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let t = src.load(bx + dx, by + dy);
        for c in 0..4 {
            acc[c] += 0.25 * t[c];
        }
    }
    acc
}

pub fn sobel(src: &ImageF64, uv: [f64; 2]) -> f64 {
    let (px, py) = src.pixel_of(uv);
    let v = |i: i64, j: i64| src.load(px + i, py + j)[0];
    let gx = (v(1, -1) + 2.0 * v(1, 0) + v(1, 1)) - (v(-1, -1) + 2.0 * v(-1, 0) + v(-1, 1));
    let gy = (v(-1, 1) + 2.0 * v(0, 1) + v(1, 1)) - (v(-1, -1) + 2.0 * v(0, -1) + v(1, -1));
    (gx * gx + gy * gy).sqrt() / 8.0
}

pub fn normal_depth_edges(
    normals: &ImageF64,
    depth: &ImageF64,
    uv: [f64; 2],
    depth_threshold: f64,
    normal_threshold: f64,
) -> f64 {
    let (nx, ny) = normals.pixel_of(uv);
    let (dx, dy) = depth.pixel_of(uv);
    let n = |i: i64, j: i64| {
        let t = normals.load(nx + i, ny + j);
        [t[0] * 2.0 - 1.0, t[1] * 2.0 - 1.0, t[2] * 2.0 - 1.0]
    };
    let d = |i: i64, j: i64| depth.load(dx + i, dy + j)[0];
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let (a, b) = (sub(n(1, 1), n(0, 0)), sub(n(0, 1), n(1, 0)));
    let dn = (dot3(a, a) + dot3(b, b)).sqrt();
    let dd = ((d(1, 1) - d(0, 0)).powi(2) + (d(0, 1) - d(1, 0)).powi(2)).sqrt();
    if dn > normal_threshold || dd > depth_threshold {
        1.0
    } else {
        0.0
    }
}

pub fn over(fg: [f64; 4], bg: [f64; 4]) -> [f64; 4] {
    let a = fg[3] + bg[3] * (1.0 - fg[3]);
    if a <= 0.0 {
        return [0.0; 4];
    }
    let c = |i: usize| (fg[i] * fg[3] + bg[i] * bg[3] * (1.0 - fg[3])) / a.max(1e-8);
    [c(0), c(1), c(2), a]
}

pub fn luminance(c: [f64; 4]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

pub fn saturation(c: [f64; 4], amount: f64) -> [f64; 4] {
    let g = luminance(c);
    [
        g + (c[0] - g) * amount,
        g + (c[1] - g) * amount,
        g + (c[2] - g) * amount,
        c[3],
    ]
}

pub fn overlay(base: [f64; 4], blend: [f64; 4], opacity: f64) -> [f64; 4] {
    let ch = |i: usize| {
        let (b, s) = (base[i], blend[i]);
        let o = if b < 0.5 {
            2.0 * b * s
        } else {
            1.0 - 2.0 * (1.0 - b) * (1.0 - s)
        };
        b + (o - b) * opacity
    };
    [ch(0), ch(1), ch(2), base[3]]
}

/// Bilinear filtering with clamp-to-edge addressing at level 0.
pub fn sample(tex: &ImageF64, uv: [f64; 2]) -> [f64; 4] {
    let x = uv[0] * tex.width as f64 - 0.5;
    let y = uv[1] * tex.height as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let (a, b, c, d) = (
        tex.load(x0, y0),
        tex.load(x0 + 1, y0),
        tex.load(x0, y0 + 1),
        tex.load(x0 + 1, y0 + 1),
    );
    std::array::from_fn(|i| {
        let top = a[i] * (1.0 - fx) + b[i] * fx;
        let bottom = c[i] * (1.0 - fx) + d[i] * fx;
        top * (1.0 - fy) + bottom * fy
    })
}

/// Operators that have a reference here (checked by the completeness test).
pub const REFERENCED: &[&str] = &[
    "lambert",
    "half_lambert",
    "toon",
    "threshold",
    "gaussian",
    "downsample",
    "sobel",
    "normal_depth_edges",
    "over",
    "luminance",
    "saturation",
    "overlay",
    "sample",
];

pub fn has_reference(name: &str) -> bool {
    REFERENCED.contains(&name)
}
