//! Screen-space wavy strips along chained edges (Klein et al. 2000, §5:
//! "the lines are drawn as a 2D triangle strip following a sinusoidal
//! backbone along the 2D projection of each visible edge"), in f64 on the
//! CPU.
//!
//! Per polyline (world space) and eye:
//! 1. each segment is clipped to the near plane in clip space (wgpu's depth
//!    runs 0..w, so the plane is z = 0); a chain leaving the view splits
//!    into pieces;
//! 2. points go to pixels (x right, y down) and NDC depth; segments shorter
//!    than [`MIN_SEGMENT_PX`] on screen are merged away, so an edge seen
//!    end-on (a silhouette edge pointing at the eye) or a zero-length edge
//!    gives no direction to normalize and no NaN;
//! 3. segments are resampled every ≤ λ/16 px (screen position and NDC depth
//!    are both affine along a projected 3D segment, so linear interpolation
//!    is exact);
//! 4. s is the screen-space arc length along the piece; the backbone moves
//!    along the 2D normal by amplitude·sin(2π·s/λ + φ). The normals are
//!    taken from the undisplaced backbone and cached before any point moves
//!    (BRIEF §5, Freestyle's sinusoidal displacement), so the offset of one
//!    sample does not bend the normal of the next. "Since the frequency of
//!    the sine function is based on screen space distances, all of the lines
//!    drawn have a consistent waviness" (§5): λ and the amplitude are px on
//!    screen whatever the edge's depth or orientation;
//! 5. the strip is the displaced backbone ± half the width along the
//!    displaced curve's own normal, narrowed by the taper near open ends.
//!
//! Why the CPU: the strips depend on the chains, which come from the CPU
//! (see `edges.rs`), and are rebuilt only when the view or the mesh changes;
//! a frame with an unchanged view reuses the vertex buffer.

use glam::{DMat4, DVec2, DVec3, DVec4};

/// Screen segments shorter than this (px) carry no direction.
pub const MIN_SEGMENT_PX: f64 = 1e-6;
/// Samples per wavelength: at 16 the sampled sine's peak is within
/// 1 − cos(π/16) ≈ 1.9% of the amplitude.
pub const SAMPLES_PER_WAVELENGTH: f64 = 16.0;
/// The most samples one segment gets, so an edge that projects across a
/// huge off-screen span (near the near plane) cannot exhaust memory.
pub const MAX_SAMPLES_PER_SEGMENT: usize = 4096;

/// A line's shape, in pixels (the `lines` pass's parameters).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineStyle {
    pub width_px: f64,
    pub amplitude_px: f64,
    pub wavelength_px: f64,
    /// φ in radians.
    pub phase: f64,
    /// The share of a piece's length over which each open end narrows to
    /// zero width (0 = no taper, at most 0.5).
    pub taper: f64,
}

/// One sample of a displaced backbone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BackbonePoint {
    /// Undisplaced position in px (x right, y down).
    pub base: DVec2,
    /// Unit 2D normal of the undisplaced backbone (cached before moving).
    pub normal: DVec2,
    /// Displaced position in px.
    pub px: DVec2,
    /// NDC depth (0 at the near plane).
    pub depth: f64,
    /// 1 / clip w (affine in screen space along a projected segment, as the
    /// NDC depth): what a view-space bias needs (`draw::vertices`).
    pub inv_w: f64,
    /// Screen-space arc length from the piece's start, px.
    pub s: f64,
}

/// A strip vertex: position in px, NDC depth, and the arc length of its
/// backbone sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripVertex {
    pub px: DVec2,
    /// The undisplaced backbone point (on the edge) it was built around.
    pub base: DVec2,
    pub depth: f64,
    /// 1 / clip w of the backbone sample.
    pub inv_w: f64,
    pub s: f64,
    /// +1 on one side of the strip, −1 on the other.
    pub across: f64,
    /// The index of the line set that drew it (0 without sets; see
    /// `sets::build`).
    pub set: u32,
}

/// The strips of one eye: every piece's backbone (for tests and
/// measurement) and one indexed triangle list for all of them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Strips {
    pub backbones: Vec<Vec<BackbonePoint>>,
    pub vertices: Vec<StripVertex>,
    pub indices: Vec<u32>,
}

impl Strips {
    /// Appends `other`, its vertices marked as drawn by line set `set`.
    pub fn append(&mut self, other: Strips, set: u32) {
        let first = self.vertices.len() as u32;
        self.vertices
            .extend(other.vertices.into_iter().map(|v| StripVertex { set, ..v }));
        self.indices.extend(other.indices.into_iter().map(|i| i + first));
        self.backbones.extend(other.backbones);
    }
}

/// Builds the strips of `polylines` (world-space points, closed or not)
/// seen through `view_proj` on a `size` px viewport.
pub fn build(polylines: &[(Vec<DVec3>, bool)], view_proj: DMat4, size: DVec2, style: &LineStyle) -> Strips {
    let mut strips = Strips::default();
    for (points, closed) in polylines {
        for (piece, piece_closed) in clip_pieces(points, *closed, view_proj) {
            let screen: Vec<(DVec2, DVec2)> = piece.iter().map(|c| to_screen(*c, size)).collect();
            let backbone = backbone(&screen, piece_closed, style);
            if backbone.len() >= 2 {
                push_strip(&mut strips, &backbone, piece_closed, style);
                strips.backbones.push(backbone);
            }
        }
    }
    strips
}

/// [`build`] with dashes: `dash[0]` px drawn, then `dash[1]` px left out,
/// along each piece's screen arc length from its start (a closed piece's
/// pattern runs on across its start). Each dash is an open strip whose
/// vertices keep the piece's arc length `s`; dashes take no taper.
pub fn build_dashed(
    polylines: &[(Vec<DVec3>, bool)],
    view_proj: DMat4,
    size: DVec2,
    style: &LineStyle,
    dash: [f64; 2],
) -> Strips {
    let mut strips = Strips::default();
    let untapered = LineStyle { taper: 0.0, ..*style };
    for (points, closed) in polylines {
        for (piece, piece_closed) in clip_pieces(points, *closed, view_proj) {
            let screen: Vec<(DVec2, DVec2)> = piece.iter().map(|c| to_screen(*c, size)).collect();
            let backbone = backbone(&screen, piece_closed, style);
            for run in dash_runs(&backbone, dash) {
                if run.len() >= 2 {
                    push_strip(&mut strips, &run, false, &untapered);
                    strips.backbones.push(run);
                }
            }
        }
    }
    strips
}

/// The parts of `backbone` where `s mod (on + off) < on`, cut exactly at
/// the pattern's boundaries (every field interpolated linearly there).
pub fn dash_runs(backbone: &[BackbonePoint], [on, off]: [f64; 2]) -> Vec<Vec<BackbonePoint>> {
    let period = on + off;
    if !(on > 0.0 && off >= 0.0 && period.is_finite()) {
        return Vec::new();
    }
    let drawn = |s: f64| s.rem_euclid(period) < on;
    let lerp = |a: &BackbonePoint, b: &BackbonePoint, t: f64| BackbonePoint {
        base: a.base.lerp(b.base, t),
        normal: if t < 0.5 { a.normal } else { b.normal },
        px: a.px.lerp(b.px, t),
        depth: a.depth + (b.depth - a.depth) * t,
        inv_w: a.inv_w + (b.inv_w - a.inv_w) * t,
        s: a.s + (b.s - a.s) * t,
    };
    let mut runs: Vec<Vec<BackbonePoint>> = Vec::new();
    let mut current: Vec<BackbonePoint> = Vec::new();
    for (i, point) in backbone.iter().enumerate() {
        if i > 0 {
            let a = &backbone[i - 1];
            let (first, last) = ((a.s / period).floor() as i64, (point.s / period).floor() as i64);
            for k in first..=last {
                let start = k as f64 * period;
                // A dash starts at k·period and ends at k·period + on.
                for (boundary, ends) in [(start, false), (start + on, true)] {
                    if boundary > a.s && boundary < point.s {
                        let cut = lerp(a, point, (boundary - a.s) / (point.s - a.s));
                        if ends {
                            current.push(cut);
                            runs.push(std::mem::take(&mut current));
                        } else {
                            current = vec![cut];
                        }
                    }
                }
            }
        }
        if drawn(point.s) {
            current.push(*point);
        } else if !current.is_empty() {
            // A dash ending exactly on this sample.
            current.push(*point);
            runs.push(std::mem::take(&mut current));
        }
    }
    runs.push(current);
    // A dash that starts on the last sample has no length.
    runs.retain(|run| run.len() >= 2);
    runs
}

/// Clips a polyline to the near plane in clip space: the pieces of
/// consecutive visible points, and whether a piece is still closed.
fn clip_pieces(points: &[DVec3], closed: bool, view_proj: DMat4) -> Vec<(Vec<DVec4>, bool)> {
    let clip: Vec<DVec4> = points.iter().map(|p| view_proj * p.extend(1.0)).collect();
    if clip.is_empty() || clip.iter().any(|c| !c.is_finite()) {
        return Vec::new();
    }
    if clip.iter().all(|c| c.z >= 0.0) {
        return vec![(clip, closed && points.len() >= 3)];
    }
    let mut segments: Vec<(DVec4, DVec4)> = clip.windows(2).map(|w| (w[0], w[1])).collect();
    if closed {
        segments.push((clip[clip.len() - 1], clip[0]));
    }
    let mut pieces: Vec<(Vec<DVec4>, bool)> = Vec::new();
    let mut current: Vec<DVec4> = Vec::new();
    for (a, b) in segments {
        let (inside_a, inside_b) = (a.z >= 0.0, b.z >= 0.0);
        // The point where the segment meets z = 0 (t in [0, 1] because the
        // signs differ, so the denominator is not zero).
        let cross = || a + (b - a) * (a.z / (a.z - b.z));
        match (inside_a, inside_b) {
            (true, true) => {
                if current.is_empty() {
                    current.push(a);
                }
                current.push(b);
            }
            (true, false) => {
                if current.is_empty() {
                    current.push(a);
                }
                current.push(cross());
                pieces.push((std::mem::take(&mut current), false));
            }
            (false, true) => {
                current = vec![cross(), b];
            }
            (false, false) => {}
        }
    }
    if !current.is_empty() {
        // A closed chain that was cut: its last piece continues into its
        // first, so join them and keep the arc length running on.
        if closed && !pieces.is_empty() && clip[0].z >= 0.0 {
            let first = pieces.remove(0).0;
            current.extend(first.into_iter().skip(1));
        }
        pieces.push((current, false));
    }
    pieces
}

/// Clip space → (px with y down, (NDC depth, 1/w)). Only called for w ≥
/// near > 0.
fn to_screen(c: DVec4, size: DVec2) -> (DVec2, DVec2) {
    let ndc = c.truncate() / c.w;
    (
        DVec2::new((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y),
        DVec2::new(ndc.z.max(0.0), 1.0 / c.w),
    )
}

/// Resampled, displaced backbone of one piece.
fn backbone(screen: &[(DVec2, DVec2)], closed: bool, style: &LineStyle) -> Vec<BackbonePoint> {
    // Merge points that coincide on screen (end-on and zero-length edges).
    let mut points: Vec<(DVec2, DVec2)> = Vec::with_capacity(screen.len());
    for &(p, z) in screen {
        if points.last().is_none_or(|(q, _)| (p - *q).length() >= MIN_SEGMENT_PX) {
            points.push((p, z));
        }
    }
    if closed && points.len() >= 2 && (points[0].0 - points[points.len() - 1].0).length() >= MIN_SEGMENT_PX {
        points.push(points[0]);
    } else if closed && points.len() >= 2 {
        let first = points[0];
        *points.last_mut().unwrap() = first;
    }
    if points.len() < 2 {
        return Vec::new();
    }
    let wavelength = style.wavelength_px.max(MIN_SEGMENT_PX);
    let step = wavelength / SAMPLES_PER_WAVELENGTH;
    // (px, (NDC depth, 1/w), s): both depth terms are affine in screen space.
    let mut samples: Vec<(DVec2, DVec2, f64)> = vec![(points[0].0, points[0].1, 0.0)];
    let mut s = 0.0;
    for w in points.windows(2) {
        let ((a, za), (b, zb)) = (w[0], w[1]);
        let length = (b - a).length();
        let count = ((length / step).ceil() as usize).clamp(1, MAX_SAMPLES_PER_SEGMENT);
        for k in 1..=count {
            let t = k as f64 / count as f64;
            samples.push((a.lerp(b, t), za + (zb - za) * t, s + length * t));
        }
        s += length;
    }
    // Normals of the undisplaced backbone, cached before any point moves.
    let n = samples.len();
    let tangent = |i: usize| -> DVec2 {
        let (prev, next) = if closed {
            // The last sample repeats the first.
            (if i == 0 { n - 2 } else { i - 1 }, if i == n - 1 { 1 } else { i + 1 })
        } else {
            (i.saturating_sub(1), (i + 1).min(n - 1))
        };
        let central = samples[next].0 - samples[prev].0;
        let incoming = samples[i].0 - samples[prev].0;
        let outgoing = samples[next].0 - samples[i].0;
        // A hairpin (the chain doubles back) cancels the central
        // difference: fall back to either side's own direction.
        [central, incoming, outgoing]
            .into_iter()
            .find(|d| d.length() >= MIN_SEGMENT_PX)
            .map_or(DVec2::X, |d| d.normalize())
    };
    let phase_per_px = std::f64::consts::TAU / wavelength;
    (0..n)
        .map(|i| {
            let t = tangent(i);
            let normal = DVec2::new(-t.y, t.x);
            let (base, depth, s) = samples[i];
            let offset = style.amplitude_px * (phase_per_px * s + style.phase).sin();
            BackbonePoint {
                base,
                normal,
                px: base + normal * offset,
                depth: depth.x,
                inv_w: depth.y,
                s,
            }
        })
        .collect()
}

/// Appends the strip around `backbone` as triangles.
fn push_strip(strips: &mut Strips, backbone: &[BackbonePoint], closed: bool, style: &LineStyle) {
    let n = backbone.len();
    let length = backbone[n - 1].s;
    let taper = style.taper.clamp(0.0, npr_abi::lines::MAX_TAPER) * length;
    let first = strips.vertices.len() as u32;
    for i in 0..n {
        let prev = if i == 0 {
            if closed {
                n - 2
            } else {
                0
            }
        } else {
            i - 1
        };
        let next = if i == n - 1 {
            if closed {
                1
            } else {
                n - 1
            }
        } else {
            i + 1
        };
        let d = backbone[next].px - backbone[prev].px;
        // The displaced curve's normal; where it has none (amplitude making
        // a cusp), the cached backbone normal.
        let normal = if d.length() >= MIN_SEGMENT_PX {
            DVec2::new(-d.y, d.x).normalize()
        } else {
            backbone[i].normal
        };
        let s = backbone[i].s;
        let narrow = if closed || taper <= 0.0 {
            1.0
        } else {
            (s.min(length - s) / taper).clamp(0.0, 1.0)
        };
        let half = 0.5 * style.width_px.max(0.0) * narrow;
        for side in [1.0, -1.0] {
            strips.vertices.push(StripVertex {
                px: backbone[i].px + normal * (half * side),
                base: backbone[i].base,
                depth: backbone[i].depth,
                inv_w: backbone[i].inv_w,
                s,
                across: side,
                set: 0,
            });
        }
    }
    for i in 0..(n as u32 - 1) {
        let (a, b, c, d) = (first + 2 * i, first + 2 * i + 1, first + 2 * i + 2, first + 2 * i + 3);
        strips.indices.extend_from_slice(&[a, b, c, c, b, d]);
    }
}
