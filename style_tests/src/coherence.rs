//! Temporal coherence of a test's frames against the scene's exact motion
//! (issue 49, part 4): how much a pixel changes once the previous frame
//! is warped by the true motion (motion-compensated flicker), how far a
//! surface's pattern slides against the surface (px per frame), and the
//! share of marks (strokes, dots, foam shapes) that appear or vanish
//! between frames (popping).
//!
//! npr knows the motion exactly: a render of the scene gives, per pixel,
//! the world position of the surface point seen there and where that
//! point was in the previous frame (`position.previous`); the previous
//! frame's camera projects it to the pixel it was seen at. A pixel is
//! judged only where that point was also visible then (the previous
//! frame's own position there is the same point, within two pixels'
//! footprint), so disocclusions and the background are left out.

use glam::{Mat4, Vec3, Vec4};

/// Per pixel of a frame: where its surface point was seen in the previous
/// frame (pixel coordinates, centres at .5), when it was visible there.
#[derive(Debug, Clone)]
pub struct MotionField {
    pub width: u32,
    pub before: Vec<Option<[f64; 2]>>,
}

/// A frame's world positions per pixel, row-major, `w` ≥ 1 where a surface
/// was drawn and 0 elsewhere (what a render pass writes as
/// `vec4(position, 1.0)` over a transparent clear).
pub type Positions<'a> = &'a [[f32; 4]];

/// The camera of the previous frame, as the measures need it.
pub struct PreviousCamera {
    /// Its projection times its view.
    pub view_projection: Mat4,
    pub eye: Vec3,
    /// The height of a pixel at one metre's distance, in metres
    /// (2·tan(fov_y/2) / image height).
    pub pixel_at_one_metre: f32,
}

impl MotionField {
    /// The field of a frame from its positions (`here`), its surface
    /// points' previous positions (`before`), the previous frame's
    /// positions and its camera.
    pub fn new(
        width: u32,
        height: u32,
        here: Positions,
        before: Positions,
        previous_here: Positions,
        camera: &PreviousCamera,
    ) -> MotionField {
        let n = (width * height) as usize;
        assert!(
            here.len() == n && before.len() == n && previous_here.len() == n,
            "positions of another size"
        );
        let field = (0..n)
            .map(|i| {
                if here[i][3] < 0.5 {
                    return None;
                }
                let p = Vec3::new(before[i][0], before[i][1], before[i][2]);
                let clip = camera.view_projection * Vec4::new(p.x, p.y, p.z, 1.0);
                if clip.w <= 0.0 {
                    return None;
                }
                let ndc = clip.truncate() / clip.w;
                // NDC y up, pixel rows down.
                let x = (f64::from(ndc.x) + 1.0) * 0.5 * f64::from(width);
                let y = (1.0 - f64::from(ndc.y)) * 0.5 * f64::from(height);
                let (px, py) = (x.floor() as i64, y.floor() as i64);
                if px < 0 || py < 0 || px >= i64::from(width) || py >= i64::from(height) {
                    return None;
                }
                let seen = previous_here[py as usize * width as usize + px as usize];
                if seen[3] < 0.5 {
                    return None;
                }
                let seen = Vec3::new(seen[0], seen[1], seen[2]);
                let footprint = 2.0 * camera.pixel_at_one_metre * (p - camera.eye).length();
                ((seen - p).length() <= footprint.max(1e-6)).then_some([x, y])
            })
            .collect();
        MotionField { width, before: field }
    }

    fn at(&self, x: u32, y: u32) -> Option<[f64; 2]> {
        self.before[(y * self.width + x) as usize]
    }
}

/// An RGBA8 frame as linear 0..1 channels, row-major.
pub struct Frame<'a> {
    pub width: u32,
    pub height: u32,
    pub rgba: &'a [u8],
}

impl Frame<'_> {
    fn texel(&self, x: i64, y: i64) -> [f64; 4] {
        let x = x.clamp(0, i64::from(self.width) - 1) as usize;
        let y = y.clamp(0, i64::from(self.height) - 1) as usize;
        let i = (y * self.width as usize + x) * 4;
        std::array::from_fn(|c| f64::from(self.rgba[i + c]) / 255.0)
    }

    /// Bilinear read at pixel coordinates (centres at .5).
    fn sample(&self, at: [f64; 2]) -> [f64; 4] {
        let (x, y) = (at[0] - 0.5, at[1] - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (a, b, c, d) = (
            self.texel(x0, y0),
            self.texel(x0 + 1, y0),
            self.texel(x0, y0 + 1),
            self.texel(x0 + 1, y0 + 1),
        );
        std::array::from_fn(|i| (a[i] * (1.0 - fx) + b[i] * fx) * (1.0 - fy) + (c[i] * (1.0 - fx) + d[i] * fx) * fy)
    }

    fn luminance(&self, x: i64, y: i64) -> f64 {
        let [r, g, b, _] = self.texel(x, y);
        0.2126 * r + 0.7152 * g + 0.0722 * b
    }
}

/// Motion-compensated flicker: the mean absolute change of a channel
/// (0..1) between `current` and `previous` warped by `motion`, over the
/// pixels whose point was visible in both; `None` when there is none.
pub fn compensated_change(current: &Frame, previous: &Frame, motion: &MotionField) -> Option<f64> {
    let (mut total, mut count) = (0.0, 0usize);
    for y in 0..current.height {
        for x in 0..current.width {
            let Some(at) = motion.at(x, y) else { continue };
            let now = current.texel(i64::from(x), i64::from(y));
            let then = previous.sample(at);
            total += (0..4).map(|c| (now[c] - then[c]).abs()).sum::<f64>() / 4.0;
            count += 1;
        }
    }
    (count > 0).then(|| total / count as f64)
}

/// The side of a block that [`sliding`] matches, in px.
pub const SLIDING_BLOCK: u32 = 8;
/// How far from the true motion [`sliding`] follows a block, in px.
pub const SLIDING_SEARCH: i64 = 6;
/// The least luminance spread (standard deviation) of a block that has a
/// pattern to follow.
const SLIDING_MIN_SPREAD: f64 = 0.04;
/// A block whose structure tensor's eigenvalues are further apart than
/// this ratio is a pattern of parallel lines (one direction only): its
/// slide along the lines cannot be seen, only across them. Antialiased
/// lines measure below 0.04, a crossed or smooth pattern above 0.2.
const SLIDING_LINES_RATIO: f64 = 0.1;

/// Pattern sliding: in each block of `current` that has a pattern (a
/// luminance spread) and whose points were all visible before, how far
/// the block's pattern came from elsewhere than its surface did, in px
/// per frame, the mean over the blocks. 0 for a pattern attached to its
/// surface; the surface's own screen speed for one fixed to the screen.
/// `None` when no block has a pattern.
///
/// The match starts at the true motion and descends to the nearest
/// minimum of the block's squared difference (the previous frame read
/// bilinearly, so a sub-pixel motion is matched exactly), then a
/// parabola refines it. Starting from the true motion, not searching a
/// window for the best match, is what keeps periodic patterns honest:
/// hatching lines 6 px apart match one period away almost as well, and
/// a window search locked onto the neighbouring line (5.4 px/frame
/// measured on `hatching` against < 0.1 px for the same lines moved
/// analytically). The slide found is the smallest that explains the
/// block: a periodic pattern's slide is seen modulo its period. For
/// parallel lines only the slide across them counts (the aperture
/// problem: along them no slide can be seen, by the matcher or a viewer).
pub fn sliding(current: &Frame, previous: &Frame, motion: &MotionField) -> Option<f64> {
    let b = SLIDING_BLOCK;
    let (mut total, mut blocks) = (0.0, 0usize);
    for by in (0..current.height.saturating_sub(b - 1)).step_by(b as usize) {
        for bx in (0..current.width.saturating_sub(b - 1)).step_by(b as usize) {
            if let Some(slide) = block_slide(current, previous, motion, bx, by) {
                total += slide;
                blocks += 1;
            }
        }
    }
    (blocks > 0).then(|| total / blocks as f64)
}

/// The slide of the block at (`bx`, `by`) (see [`sliding`]); `None` when
/// it has no pattern or a point not seen before.
fn block_slide(current: &Frame, previous: &Frame, motion: &MotionField, bx: u32, by: u32) -> Option<f64> {
    let b = SLIDING_BLOCK;
    let mut shift = [0.0, 0.0];
    let mut lum = Vec::with_capacity((b * b) as usize);
    // The structure tensor Σ∇L∇Lᵀ of the block (central differences).
    let mut tensor = [0.0; 3];
    for y in by..by + b {
        for x in bx..bx + b {
            let at = motion.at(x, y)?;
            shift[0] += at[0] - (f64::from(x) + 0.5);
            shift[1] += at[1] - (f64::from(y) + 0.5);
            let (x, y) = (i64::from(x), i64::from(y));
            lum.push(current.luminance(x, y));
            let gx = (current.luminance(x + 1, y) - current.luminance(x - 1, y)) / 2.0;
            let gy = (current.luminance(x, y + 1) - current.luminance(x, y - 1)) / 2.0;
            tensor[0] += gx * gx;
            tensor[1] += gx * gy;
            tensor[2] += gy * gy;
        }
    }
    let mean = lum.iter().sum::<f64>() / lum.len() as f64;
    let spread = (lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64).sqrt();
    if spread < SLIDING_MIN_SPREAD {
        return None;
    }
    let n = f64::from(b * b);
    let truth = [shift[0] / n, shift[1] / n];
    // The squared difference of the block against the previous frame
    // read at the true motion plus `d`.
    let cost = |d: [f64; 2]| -> f64 {
        lum.iter()
            .enumerate()
            .map(|(k, l)| {
                let (x, y) = (
                    f64::from(bx) + (k as u32 % b) as f64,
                    f64::from(by) + (k as u32 / b) as f64,
                );
                let then = previous.sample([x + 0.5 + truth[0] + d[0], y + 0.5 + truth[1] + d[1]]);
                (l - (0.2126 * then[0] + 0.7152 * then[1] + 0.0722 * then[2])).powi(2)
            })
            .sum()
    };
    // Descend from the true motion, a pixel at a time, to the nearest minimum.
    let (mut best, mut best_cost) = ([0i64, 0i64], cost([0.0, 0.0]));
    loop {
        let mut step = None;
        for (dx, dy) in [(-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
            let o = [best[0] + dx, best[1] + dy];
            if o[0].abs() > SLIDING_SEARCH || o[1].abs() > SLIDING_SEARCH {
                continue;
            }
            let c = cost([o[0] as f64, o[1] as f64]);
            if c < step.map_or(best_cost * (1.0 - 1e-9) - 1e-12, |(_, sc)| sc) {
                step = Some((o, c));
            }
        }
        match step {
            Some((o, c)) => (best, best_cost) = (o, c),
            None => break,
        }
    }
    let at = [best[0] as f64, best[1] as f64];
    // A parabola through the costs either side refines a step along `dir`.
    let refine = |dir: [f64; 2]| {
        let minus = cost([at[0] - dir[0], at[1] - dir[1]]);
        let plus = cost([at[0] + dir[0], at[1] + dir[1]]);
        let curvature = minus - 2.0 * best_cost + plus;
        if curvature > 1e-12 {
            (0.5 * (minus - plus) / curvature).clamp(-0.5, 0.5)
        } else {
            0.0
        }
    };
    let [a, c_, d] = tensor;
    let half_trace = (a + d) / 2.0;
    let root = (((a - d) / 2.0).powi(2) + c_ * c_).sqrt();
    let (large, small) = (half_trace + root, half_trace - root);
    if small < SLIDING_LINES_RATIO * large {
        // Parallel lines: the slide across them, along the gradient.
        let across = if c_.abs() > 1e-12 {
            [c_, large - a]
        } else if a >= d {
            [1.0, 0.0]
        } else {
            [0.0, 1.0]
        };
        let norm = (across[0] * across[0] + across[1] * across[1]).sqrt();
        let across = [across[0] / norm, across[1] / norm];
        Some((at[0] * across[0] + at[1] * across[1] + refine(across)).abs())
    } else {
        let found = [at[0] + refine([1.0, 0.0]), at[1] + refine([0.0, 1.0])];
        Some((found[0] * found[0] + found[1] * found[1]).sqrt())
    }
}

/// Marks that appeared or vanished between two frames.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Popping {
    /// Marks of the current frame with no mark where their surface was.
    pub appeared: usize,
    /// Marks of the previous frame that no current mark came from.
    pub vanished: usize,
    /// The marks judged in both frames (those with a visible point).
    pub judged: usize,
}

impl Popping {
    /// The share of judged marks that popped (0..1).
    pub fn share(&self) -> f64 {
        if self.judged == 0 {
            0.0
        } else {
            (self.appeared + self.vanished) as f64 / self.judged as f64
        }
    }
}

/// Popping of the marks (`is_mark` on a pixel's RGBA, 0..1): 4-connected
/// components of mark pixels in each frame; a current mark persists when
/// one of its visible pixels came from a mark pixel (within one pixel) of
/// the previous frame, and a previous mark persists when some current mark
/// pixel came from it.
pub fn popping(current: &Frame, previous: &Frame, motion: &MotionField, is_mark: impl Fn([f64; 4]) -> bool) -> Popping {
    let marks_now = components(current, &is_mark);
    let marks_then = components(previous, &is_mark);
    let (w, h) = (i64::from(current.width), i64::from(current.height));
    let mut reached_then = vec![false; marks_then.count];
    // A previous mark is judged when its pixels are seen now: some current
    // pixel's point came from one of them.
    let mut judged_then = vec![false; marks_then.count];
    let mut judged_now = vec![false; marks_now.count];
    let mut persists_now = vec![false; marks_now.count];
    let then_at = |qx: i64, qy: i64| {
        (qx >= 0 && qy >= 0 && qx < w && qy < h)
            .then(|| marks_then.label[(qy * w + qx) as usize])
            .flatten()
    };
    for y in 0..current.height {
        for x in 0..current.width {
            let Some(at) = motion.at(x, y) else { continue };
            let (px, py) = (at[0].floor() as i64, at[1].floor() as i64);
            if let Some(then) = then_at(px, py) {
                judged_then[then] = true;
            }
            let Some(label) = marks_now.label[(y * current.width + x) as usize] else {
                continue;
            };
            judged_now[label] = true;
            for (dx, dy) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)] {
                if let Some(then) = then_at(px + dx, py + dy) {
                    persists_now[label] = true;
                    reached_then[then] = true;
                }
            }
        }
    }
    let appeared = (0..marks_now.count)
        .filter(|&m| judged_now[m] && !persists_now[m])
        .count();
    let vanished = (0..marks_then.count)
        .filter(|&m| judged_then[m] && !reached_then[m])
        .count();
    Popping {
        appeared,
        vanished,
        judged: judged_now.iter().filter(|j| **j).count() + judged_then.iter().filter(|j| **j).count(),
    }
}

/// The 4-connected components of a frame's mark pixels.
struct Components {
    label: Vec<Option<usize>>,
    count: usize,
}

fn components(frame: &Frame, is_mark: &impl Fn([f64; 4]) -> bool) -> Components {
    let (w, h) = (frame.width as usize, frame.height as usize);
    let mark: Vec<bool> = (0..w * h)
        .map(|i| is_mark(frame.texel((i % w) as i64, (i / w) as i64)))
        .collect();
    let mut label = vec![None; w * h];
    let mut count = 0;
    let mut stack = Vec::new();
    for start in 0..w * h {
        if !mark[start] || label[start].is_some() {
            continue;
        }
        label[start] = Some(count);
        stack.push(start);
        while let Some(i) = stack.pop() {
            let (x, y) = (i % w, i / w);
            let neighbours = [
                (x > 0).then(|| i - 1),
                (x + 1 < w).then(|| i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then(|| i + w),
            ];
            for j in neighbours.into_iter().flatten() {
                if mark[j] && label[j].is_none() {
                    label[j] = Some(count);
                    stack.push(j);
                }
            }
        }
        count += 1;
    }
    Components { label, count }
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: u32 = 64;
    const H: u32 = 48;

    /// A field where every pixel's point was `shift` px away before.
    fn shifted(shift: [f64; 2]) -> MotionField {
        MotionField {
            width: W,
            before: (0..W * H)
                .map(|i| {
                    let (x, y) = (f64::from(i % W) + 0.5, f64::from(i / W) + 0.5);
                    let at = [x + shift[0], y + shift[1]];
                    (at[0] >= 0.0 && at[1] >= 0.0 && at[0] < f64::from(W) && at[1] < f64::from(H)).then_some(at)
                })
                .collect(),
        }
    }

    /// An RGBA8 image of `f(x, y)` in 0..1 grey.
    fn image(f: impl Fn(f64, f64) -> f64) -> Vec<u8> {
        (0..W * H)
            .flat_map(|i| {
                let v = (f(f64::from(i % W), f64::from(i / W)).clamp(0.0, 1.0) * 255.0).round() as u8;
                [v, v, v, 255]
            })
            .collect()
    }

    fn frame(rgba: &[u8]) -> Frame<'_> {
        Frame {
            width: W,
            height: H,
            rgba,
        }
    }

    /// A smooth pattern with texture at every scale the search can see.
    fn pattern(x: f64, y: f64) -> f64 {
        0.5 + 0.25 * (x * 0.7).sin() * (y * 0.45).cos() + 0.2 * ((x + 2.0 * y) * 0.31).sin()
    }

    #[test]
    fn a_pattern_moving_with_its_surface_neither_flickers_nor_slides() {
        // The surface moved by (-3, 2) px: each point was at +3, -2 before.
        let motion = shifted([3.0, -2.0]);
        let before = image(pattern);
        let now = image(|x, y| pattern(x + 3.0, y - 2.0));
        let change = compensated_change(&frame(&now), &frame(&before), &motion).expect("visible pixels");
        assert!(change < 1e-9, "compensated change {change}");
        let slide = sliding(&frame(&now), &frame(&before), &motion).expect("patterned blocks");
        assert!(slide < 0.05, "sliding {slide} px");
        // Without compensation the same frames change a lot.
        assert!(
            super::super::checks::frame_change(
                &image::RgbaImage::from_raw(W, H, now.clone()).unwrap(),
                &image::RgbaImage::from_raw(W, H, before.clone()).unwrap()
            ) > 0.02
        );
    }

    #[test]
    fn a_pattern_fixed_to_the_screen_slides_by_the_surfaces_speed() {
        let motion = shifted([3.0, -2.0]);
        let still = image(pattern);
        let slide = sliding(&frame(&still), &frame(&still), &motion).expect("patterned blocks");
        let speed = (3.0f64 * 3.0 + 2.0 * 2.0).sqrt();
        assert!(
            (slide - speed).abs() < 0.05,
            "sliding {slide} px, surface speed {speed} px"
        );
        // A fraction of a pixel is found too: half a pixel along x.
        let motion = shifted([0.5, 0.0]);
        let slide = sliding(&frame(&still), &frame(&still), &motion).expect("patterned blocks");
        assert!((slide - 0.5).abs() < 0.15, "sliding {slide} px for 0.5 px");
    }

    /// Antialiased ink lines across `normal` (a unit vector) every
    /// `period` px, 0.3 of it wide: the cover of each pixel from 4x4
    /// subsamples, ink 0.15 on paper 0.9 (hatching's pattern).
    fn stripes(x: f64, y: f64, normal: [f64; 2], period: f64) -> f64 {
        let mut cover = 0.0;
        for k in 0..16 {
            let (sx, sy) = ((f64::from(k % 4) + 0.5) / 4.0, (f64::from(k / 4) + 0.5) / 4.0);
            let u = ((x + sx) * normal[0] + (y + sy) * normal[1]) / period;
            if (u - u.round()).abs() < 0.15 {
                cover += 1.0 / 16.0;
            }
        }
        0.9 - 0.75 * cover
    }

    fn unit(deg: f64) -> [f64; 2] {
        [deg.to_radians().cos(), deg.to_radians().sin()]
    }

    #[test]
    fn periodic_stripes_moving_with_their_surface_do_not_slide() {
        // Hatching's case: lines 6 px apart at several angles, the surface
        // moving by a fraction of a pixel and by more than half a period.
        for deg in [0.0, 30.0, 45.0, 63.0, 90.0, 120.0] {
            for shift in [[2.3, -1.6], [0.4, 0.7], [-4.2, 3.5]] {
                let n = unit(deg);
                let motion = shifted(shift);
                let before = image(|x, y| stripes(x, y, n, 6.0));
                let now = image(|x, y| stripes(x + shift[0], y + shift[1], n, 6.0));
                let slide = sliding(&frame(&now), &frame(&before), &motion).expect("patterned blocks");
                assert!(slide < 0.15, "lines at {deg}°, moved by {shift:?}: sliding {slide} px");
            }
        }
    }

    #[test]
    fn periodic_stripes_fixed_to_the_screen_slide_by_the_motion_across_them() {
        // Along the lines, a slide cannot be seen; across them it can,
        // modulo the period (4.2 px across 6 px lines is seen as 1.8 px).
        for deg in [0.0, 30.0, 45.0, 63.0, 90.0, 120.0] {
            for shift in [[2.3, -1.6], [0.4, 0.7], [-1.2, 2.0], [-4.2, 3.5]] {
                let n = unit(deg);
                let across = (shift[0] * n[0] + shift[1] * n[1]).abs();
                let across = (across + 3.0).rem_euclid(6.0) - 3.0;
                let across = across.abs();
                let still = image(|x, y| stripes(x, y, n, 6.0));
                let slide = sliding(&frame(&still), &frame(&still), &shifted(shift)).expect("patterned blocks");
                assert!(
                    (slide - across).abs() < 0.25,
                    "lines at {deg}°, surface moved by {shift:?}: sliding {slide} px, {across} px across the lines"
                );
            }
        }
    }

    #[test]
    fn popping_counts_marks_that_appear_and_vanish() {
        // Dots (3x3 black squares) on white; the surface moved by -4 px in x.
        let dot = |cx: f64, cy: f64| move |x: f64, y: f64| (x - cx).abs() <= 1.0 && (y - cy).abs() <= 1.0;
        let before_dots = [(10.0, 10.0), (30.0, 20.0), (50.0, 30.0)];
        let now_dots = [(6.0, 10.0), (26.0, 20.0), (20.0, 40.0)];
        let draw = |dots: &[(f64, f64)]| {
            image(|x, y| {
                if dots.iter().any(|&(cx, cy)| dot(cx, cy)(x, y)) {
                    0.0
                } else {
                    1.0
                }
            })
        };
        let (before, now) = (draw(&before_dots), draw(&now_dots));
        let motion = shifted([4.0, 0.0]);
        let p = popping(&frame(&now), &frame(&before), &motion, |c| c[0] < 0.5);
        // (20, 40) appeared; (50, 30) vanished; two persisted.
        assert_eq!(
            p,
            Popping {
                appeared: 1,
                vanished: 1,
                judged: 6
            }
        );
        assert!((p.share() - 2.0 / 6.0).abs() < 1e-12);
        let same = popping(&frame(&before), &frame(&before), &shifted([0.0, 0.0]), |c| c[0] < 0.5);
        assert_eq!(same.share(), 0.0);
    }

    #[test]
    fn the_field_of_a_moved_camera_is_its_parallax() {
        // A plane at z = -5 seen by a camera at the origin looking down -z;
        // the previous camera was 0.1 m to the right: a point now at pixel
        // x was then f·0.1/5 px to the left.
        let (fov, aspect) = (0.8f32, W as f32 / H as f32);
        let projection = Mat4::perspective_rh(fov, aspect, 0.1, 100.0);
        let view_now = Mat4::look_at_rh(Vec3::ZERO, -Vec3::Z, Vec3::Y);
        let eye_then = Vec3::new(0.1, 0.0, 0.0);
        let view_then = Mat4::look_at_rh(eye_then, eye_then - Vec3::Z, Vec3::Y);
        // The plane's point seen at each pixel by a camera.
        let plane_seen = |view: Mat4| -> Vec<[f32; 4]> {
            let inverse = (projection * view).inverse();
            let eye = view.inverse().transform_point3(Vec3::ZERO);
            (0..W * H)
                .map(|i| {
                    let ndc = Vec3::new(
                        ((i % W) as f32 + 0.5) / W as f32 * 2.0 - 1.0,
                        1.0 - ((i / W) as f32 + 0.5) / H as f32 * 2.0,
                        0.5,
                    );
                    let ray = inverse.project_point3(ndc) - eye;
                    let p = eye + ray * ((-5.0 - eye.z) / ray.z);
                    [p.x, p.y, p.z, 1.0]
                })
                .collect()
        };
        let here = plane_seen(view_now);
        let previous_here = plane_seen(view_then);
        // A still plane: the previous positions are the same points.
        let camera = PreviousCamera {
            view_projection: projection * view_then,
            eye: eye_then,
            pixel_at_one_metre: 2.0 * (fov / 2.0).tan() / H as f32,
        };
        let field = MotionField::new(W, H, &here, &here, &previous_here, &camera);
        let focal_px = f64::from(H) / 2.0 / f64::from((fov / 2.0).tan());
        let expected = -focal_px * 0.1 / 5.0;
        let mut seen = 0;
        for y in 0..H {
            for x in 0..W {
                if let Some(at) = field.at(x, y) {
                    assert!(
                        (at[0] - (f64::from(x) + 0.5) - expected).abs() < 1e-3,
                        "({x}, {y}): {at:?}"
                    );
                    assert!((at[1] - (f64::from(y) + 0.5)).abs() < 1e-3);
                    seen += 1;
                }
            }
        }
        // Only the columns the previous camera did not see are left out.
        let hidden = (-expected).ceil() as u32 * H;
        assert!(seen >= W * H - hidden - H, "{seen} of {} pixels judged", W * H);
        // A point that is not the one the previous frame saw there
        // (disoccluded) is not judged.
        let elsewhere: Vec<[f32; 4]> = previous_here.iter().map(|p| [p[0], p[1], p[2] - 1.0, 1.0]).collect();
        let field = MotionField::new(W, H, &here, &here, &elsewhere, &camera);
        assert!(field.before.iter().all(Option::is_none));
    }
}
