//! What the `lines` pass tests share (`tests/gpu/lines_pass.rs`,
//! `tests/general/lines_fandisk.rs`; Klein et al. 2000 §5): the test style (a fill
//! that keeps its depth, black lines over white), projection to pixels, the
//! ink read back from the real renderer, and recall and precision of ink
//! pixels against truth samples (issue 10: "precision and recall of the
//! drawn line pixels within 1.5 px").
//!
//! Ink is read where the output is darker than half grey. Recall: the share
//! of truth samples with ink within 1.5 px; precision: the share of ink
//! pixels within 1.5 px + the half width of the truth. Both look points up
//! in a [`PointGrid`], so a fandisk's thousands of samples stay cheap.

use std::collections::HashMap;

use glam::{DMat4, DVec2, DVec3};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer};

use super::{compile_text, gpu};

/// A fill that keeps its depth, and black lines over white with `settings`
/// (`w` is an animated width for the tests that need one).
pub fn style(settings: &str) -> String {
    format!(
        "style \"L\"
param w: px = 2px animate {{ 0s: 2px, 1s: 8px }}
pass shade: render(scene) {{
  out color: rgba8unorm = #808080
  depth: keep
}}
pass ink: lines(scene) {{
  {settings}
  out ink: rgba8unorm = vec4(0.0, 0.0, 0.0, 1.0) {{ blend: over }}
  clear: #ffffff
}}
output ink.ink
"
    )
}

/// `p` (world) in pixels of a `size`² image (x right, y down) through `vp`.
pub fn project(vp: DMat4, p: DVec3, size: u32) -> DVec2 {
    let c = vp * p.extend(1.0);
    let n = c.truncate() / c.w;
    DVec2::new((n.x + 1.0) * 0.5 * f64::from(size), (1.0 - n.y) * 0.5 * f64::from(size))
}

/// Pixel centres with ink in the renderer's output.
pub fn ink(renderer: &Renderer) -> Vec<DVec2> {
    let image = renderer.read_output().expect("read back");
    let (w, h) = (image.width, image.height);
    (0..w * h)
        .filter(|i| image.texel(i % w, i / w)[0] < 0.5)
        .map(|i| DVec2::new(f64::from(i % w) + 0.5, f64::from(i / w) + 0.5))
        .collect()
}

/// The ink of `text` on `scene`, rendered at `size`² and `time_s`.
pub fn render_ink(text: &str, scene: &Scene, size: u32, time_s: f64) -> Vec<DVec2> {
    let program = compile_text(text);
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, scene).expect("renderer");
    let mut spec = FrameSpec::still(size, size, 0);
    spec.time_s = time_s;
    r.render(scene, &spec).expect("render");
    ink(&r)
}

/// Samples every 0.25 px along the projected segments.
pub fn samples(vp: DMat4, segments: &[(DVec3, DVec3)], size: u32) -> Vec<DVec2> {
    let mut out = Vec::new();
    for (a, b) in segments {
        let (pa, pb) = (project(vp, *a, size), project(vp, *b, size));
        let n = ((pb - pa).length() * 4.0).ceil().max(1.0) as usize;
        out.extend((0..=n).map(|k| pa.lerp(pb, k as f64 / n as f64)));
    }
    out
}

/// Points bucketed in square cells, for "is any point within r of p".
pub struct PointGrid {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<DVec2>>,
}

impl PointGrid {
    pub fn new(points: &[DVec2], cell: f64) -> PointGrid {
        let mut cells: HashMap<(i64, i64), Vec<DVec2>> = HashMap::new();
        for p in points {
            cells.entry(Self::key(*p, cell)).or_default().push(*p);
        }
        PointGrid { cell, cells }
    }

    fn key(p: DVec2, cell: f64) -> (i64, i64) {
        ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64)
    }

    /// The distance from `p` to the nearest point, if one is within `r`
    /// (inclusive); `None` otherwise.
    pub fn nearest_within(&self, p: DVec2, r: f64) -> Option<f64> {
        let (lo, hi) = (Self::key(p - r, self.cell), Self::key(p + r, self.cell));
        let mut best: Option<f64> = None;
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for q in self.cells.get(&(x, y)).into_iter().flatten() {
                    let d = (*q - p).length();
                    if d <= r && best.is_none_or(|b| d < b) {
                        best = Some(d);
                    }
                }
            }
        }
        best
    }

    pub fn any_within(&self, p: DVec2, r: f64) -> bool {
        self.nearest_within(p, r).is_some()
    }
}

/// The distance from `p` to the nearest of `truth`.
pub fn distance(p: DVec2, truth: &[DVec2]) -> f64 {
    truth.iter().map(|t| (p - *t).length()).fold(f64::INFINITY, f64::min)
}

/// (recall, precision) of `drawn` ink pixels against `truth` samples of
/// lines `2 · half_width` px wide (see the module header).
pub fn recall_precision(drawn: &[DVec2], truth: &[DVec2], half_width: f64) -> (f64, f64) {
    let ink = PointGrid::new(drawn, 4.0);
    let lines = PointGrid::new(truth, 4.0);
    let found = truth.iter().filter(|t| ink.any_within(**t, 1.5)).count();
    let near = drawn.iter().filter(|p| lines.any_within(**p, half_width + 1.5)).count();
    (
        found as f64 / truth.len() as f64,
        near as f64 / drawn.len().max(1) as f64,
    )
}
