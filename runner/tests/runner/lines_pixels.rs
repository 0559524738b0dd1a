//! The lines' pixels against analytic truth, with the strips rasterized on
//! the CPU (coverage at pixel centres, as a GPU rasterizer decides it):
//! precision and recall within 1.5 px of the sphere's analytic silhouette
//! circle and the cube's silhouette hexagon, and the wavelength and
//! amplitude measured from the drawn pixels across orientations 0–180° and
//! distances (Klein et al. 2000, §5: "all of the lines drawn have a
//! consistent waviness, regardless of their orientation relative to the
//! viewer"). Hidden-edge removal is the GPU depth test's, not tested here.

use glam::{DMat4, DVec2, DVec3};
use npr_runner::lines::cache::{EdgeSelection, LineObject, LinesCache};
use npr_runner::lines::strip::{self, LineStyle, Strips};
use npr_runner::scene::primitives::{cube, sphere};
use std::f64::consts::TAU;

const SIZE: usize = 256;

fn view_proj(eye: DVec3) -> DMat4 {
    DMat4::perspective_rh(40f64.to_radians(), 1.0, 0.1, 100.0) * DMat4::look_at_rh(eye, DVec3::ZERO, DVec3::Y)
}

fn project(vp: DMat4, p: DVec3) -> DVec2 {
    let c = vp * p.extend(1.0);
    let n = c.truncate() / c.w;
    DVec2::new((n.x + 1.0) * 0.5 * SIZE as f64, (1.0 - n.y) * 0.5 * SIZE as f64)
}

/// The pixels whose centres the strips' triangles cover.
fn rasterize(strips: &Strips) -> Vec<bool> {
    rasterize_triangles(&strips.vertices, &strips.indices)
}

/// One mask per piece (backbone) of `strips`: a piece's vertices are
/// contiguous, two per backbone sample, in the backbones' order.
fn rasterize_pieces(strips: &Strips) -> Vec<Vec<bool>> {
    let mut first = 0u32;
    strips
        .backbones
        .iter()
        .map(|backbone| {
            let end = first + 2 * backbone.len() as u32;
            let indices: Vec<u32> = strips
                .indices
                .chunks_exact(3)
                .filter(|t| t.iter().all(|&i| (first..end).contains(&i)))
                .flatten()
                .copied()
                .collect();
            first = end;
            rasterize_triangles(&strips.vertices, &indices)
        })
        .collect()
}

fn rasterize_triangles(vertices: &[strip::StripVertex], indices: &[u32]) -> Vec<bool> {
    let mut mask = vec![false; SIZE * SIZE];
    let cross = |a: DVec2, b: DVec2, p: DVec2| (b - a).perp_dot(p - a);
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| vertices[t[k] as usize].px);
        let area = cross(a, b, c);
        if area.abs() < 1e-12 {
            continue;
        }
        let (lo, hi) = (a.min(b).min(c).floor().max(DVec2::ZERO), a.max(b).max(c).ceil());
        for y in lo.y as usize..(hi.y as usize).min(SIZE) {
            for x in lo.x as usize..(hi.x as usize).min(SIZE) {
                let p = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                let w = [cross(a, b, p), cross(b, c, p), cross(c, a, p)].map(|e| e * area.signum());
                if w.iter().all(|&e| e >= 0.0) {
                    mask[y * SIZE + x] = true;
                }
            }
        }
    }
    mask
}

fn distance_to_polyline(p: DVec2, truth: &[DVec2]) -> f64 {
    truth
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let t = ((p - a).dot(b - a) / (b - a).length_squared().max(1e-300)).clamp(0.0, 1.0);
            (a + (b - a) * t - p).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// (precision, recall): drawn pixels within half the width + 1.5 px of the
/// truth, and truth samples with a drawn pixel within 1.5 px.
fn precision_recall(mask: &[bool], truth: &[DVec2], width: f64) -> (f64, f64) {
    let drawn: Vec<DVec2> = (0..SIZE * SIZE)
        .filter(|&i| mask[i])
        .map(|i| DVec2::new((i % SIZE) as f64 + 0.5, (i / SIZE) as f64 + 0.5))
        .collect();
    assert!(!drawn.is_empty(), "nothing drawn");
    let near = drawn
        .iter()
        .filter(|p| distance_to_polyline(**p, truth) <= 0.5 * width + 1.5)
        .count();
    let found = truth
        .iter()
        .filter(|t| drawn.iter().any(|p| (*p - **t).length() <= 1.5))
        .count();
    (near as f64 / drawn.len() as f64, found as f64 / truth.len() as f64)
}

fn straight(width: f64) -> LineStyle {
    LineStyle {
        width_px: width,
        amplitude_px: 0.0,
        wavelength_px: 24.0,
        phase: 0.0,
        taper: 0.0,
    }
}

#[test]
fn sphere_silhouette_pixels_match_the_analytic_circle() {
    let mesh = sphere(1.0, 64, 32);
    let mut cache = LinesCache::default();
    for eye in [DVec3::new(0.0, 0.0, 4.0), DVec3::new(1.5, 2.0, 3.0)] {
        let vp = view_proj(eye);
        let objects = [LineObject {
            mesh: &mesh,
            model: DMat4::IDENTITY,
        }];
        let selection = EdgeSelection {
            silhouettes: true,
            crease_deg: Some(30.0),
        };
        let size = DVec2::splat(SIZE as f64);
        let strips = cache
            .strips(0, &objects, eye, vp, size, &straight(2.0), selection)
            .clone();
        // Truth: the cone from the eye touches the unit sphere on the circle
        // p·ê = 1/d of radius √(1 − 1/d²).
        let (d, axis) = (eye.length(), eye.normalize());
        let (u, v) = axis.any_orthonormal_pair();
        let radius = (1.0 - 1.0 / (d * d)).sqrt();
        let truth: Vec<DVec2> = (0..=2048)
            .map(|k| {
                let a = TAU * k as f64 / 2048.0;
                project(vp, axis / d + (u * a.cos() + v * a.sin()) * radius)
            })
            .collect();
        let (precision, recall) = precision_recall(&rasterize(&strips), &truth, 2.0);
        eprintln!("sphere from {eye}: precision {precision:.4}, recall {recall:.4}");
        assert!(
            precision >= 0.99 && recall >= 0.99,
            "precision {precision}, recall {recall}"
        );
    }
    assert_eq!(cache.mesh_builds, 1, "one edge mesh for both views");
    assert_eq!(cache.rebuilds, 2);
}

#[test]
fn cube_silhouette_pixels_match_the_hexagon() {
    let mesh = cube(2.0);
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let vp = view_proj(eye);
    let mut cache = LinesCache::default();
    let objects = [LineObject {
        mesh: &mesh,
        model: DMat4::IDENTITY,
    }];
    let selection = EdgeSelection {
        silhouettes: true,
        crease_deg: None,
    };
    let strips = cache
        .strips(
            0,
            &objects,
            eye,
            vp,
            DVec2::splat(SIZE as f64),
            &straight(2.0),
            selection,
        )
        .clone();
    let corners = [
        DVec3::new(1.0, -1.0, -1.0),
        DVec3::new(1.0, 1.0, -1.0),
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(-1.0, 1.0, 1.0),
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(1.0, -1.0, 1.0),
        DVec3::new(1.0, -1.0, -1.0),
    ];
    let truth: Vec<DVec2> = corners
        .windows(2)
        .flat_map(|w| (0..256).map(move |k| w[0].lerp(w[1], k as f64 / 256.0)))
        .map(|p| project(vp, p))
        .collect();
    let (precision, recall) = precision_recall(&rasterize(&strips), &truth, 2.0);
    eprintln!("cube hexagon: precision {precision:.4}, recall {recall:.4}");
    assert!(
        precision >= 0.99 && recall >= 0.99,
        "precision {precision}, recall {recall}"
    );
}

#[test]
fn strips_are_rebuilt_only_when_the_view_or_the_mesh_changes() {
    let mut mesh = cube(2.0);
    let mut cache = LinesCache::default();
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let size = DVec2::splat(SIZE as f64);
    let selection = EdgeSelection {
        silhouettes: true,
        crease_deg: Some(40.0),
    };
    let draw = |cache: &mut LinesCache, mesh: &npr_runner::scene::Mesh, eye: DVec3, eye_index: u32| {
        let objects = [LineObject {
            mesh,
            model: DMat4::IDENTITY,
        }];
        cache
            .strips(
                eye_index,
                &objects,
                eye,
                view_proj(eye),
                size,
                &straight(2.0),
                selection,
            )
            .indices
            .len()
    };
    let first = draw(&mut cache, &mesh, eye, 0);
    assert!(first > 0);
    assert_eq!(draw(&mut cache, &mesh, eye, 0), first);
    assert_eq!((cache.rebuilds, cache.mesh_builds), (1, 1), "same view: reused");
    draw(&mut cache, &mesh, eye + DVec3::X * 0.1, 0);
    assert_eq!(
        (cache.rebuilds, cache.mesh_builds),
        (2, 1),
        "new view: strips again, edges kept"
    );
    draw(&mut cache, &mesh, eye, 1);
    assert_eq!(cache.rebuilds, 3, "the other eye has strips of its own");
    mesh.positions[0][0] += 0.25;
    draw(&mut cache, &mesh, eye, 1);
    assert_eq!(
        (cache.rebuilds, cache.mesh_builds),
        (4, 2),
        "a changed mesh is extracted again"
    );
}

/// The wavelength and amplitude of a rasterized wavy straight line: drawn
/// pixels binned by position along the chord, the mean offset per bin, its
/// best-fitting sine's wavelength and amplitude (least squares).
fn measure_pixels(mask: &[bool], a: DVec2, b: DVec2) -> (f64, f64) {
    measure_between(mask, a, b, 0.0, (b - a).length(), f64::INFINITY)
}

/// [`measure_pixels`] over the part of the chord from `from` to `to` px
/// along it, counting only pixels within `reach` px across it.
fn measure_between(mask: &[bool], a: DVec2, b: DVec2, from: f64, to: f64, reach: f64) -> (f64, f64) {
    let along = (b - a).normalize();
    let across = along.perp();
    let bins = (to - from).floor() as usize;
    let mut sum = vec![(0.0, 0usize); bins];
    for i in (0..SIZE * SIZE).filter(|&i| mask[i]) {
        let p = DVec2::new((i % SIZE) as f64 + 0.5, (i / SIZE) as f64 + 0.5) - a;
        let u = p.dot(along) - from;
        if u >= 0.0 && (u as usize) < bins && p.dot(across).abs() <= reach {
            sum[u as usize].0 += p.dot(across);
            sum[u as usize].1 += 1;
        }
    }
    let length = to - from;
    let signal: Vec<(f64, f64)> = sum
        .iter()
        .enumerate()
        .filter(|(_, s)| s.1 > 0)
        .map(|(k, s)| (k as f64 + 0.5, s.0 / s.1 as f64))
        .collect();
    // The least-squares sine fit at wavelength λ: (amplitude, residual).
    let fit = |wavelength: f64| {
        let (mut sc, mut ss, mut cc, mut ys, mut yc) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for &(u, y) in &signal {
            let (s, c) = (TAU * u / wavelength).sin_cos();
            (ss, cc, sc, ys, yc) = (ss + s * s, cc + c * c, sc + s * c, ys + y * s, yc + y * c);
        }
        let det = ss * cc - sc * sc;
        let (p, q) = ((ys * cc - yc * sc) / det, (yc * ss - ys * sc) / det);
        let residual: f64 = signal
            .iter()
            .map(|&(u, y)| {
                let (s, c) = (TAU * u / wavelength).sin_cos();
                (y - p * s - q * c).powi(2)
            })
            .sum();
        (p.hypot(q), residual)
    };
    // The wavelength whose sine fits best, searched from 4 px to a quarter
    // of the line's length in steps of 0.01 px (pixel quantization makes
    // zero crossings jitter; the fit uses every bin).
    let best = (400..=(length * 25.0) as usize)
        .map(|k| k as f64 / 100.0)
        .min_by(|a, b| fit(*a).1.total_cmp(&fit(*b).1))
        .expect("a line long enough to measure");
    (best, fit(best).0)
}

#[test]
fn drawn_waviness_is_consistent_across_orientations_and_distances() {
    let style = LineStyle {
        width_px: 2.0,
        amplitude_px: 3.0,
        wavelength_px: 20.0,
        phase: 0.4,
        taper: 0.0,
    };
    let mut worst: (f64, f64) = (0.0, 0.0);
    for distance in [3.0, 8.0, 20.0] {
        let eye = DVec3::new(0.0, 0.0, distance);
        let vp = view_proj(eye);
        // 70% of the view's height, whatever the distance.
        let half = 0.35 * distance * 2.0 * 20f64.to_radians().tan();
        for degrees in (0..=180).step_by(15) {
            let theta = f64::from(degrees).to_radians();
            let direction = DVec3::new(theta.cos(), theta.sin(), 0.0);
            let (p, q) = (-direction * half, direction * half);
            let strips = strip::build(&[(vec![p, q], false)], vp, DVec2::splat(SIZE as f64), &style);
            let (wavelength, amplitude) = measure_pixels(&rasterize(&strips), project(vp, p), project(vp, q));
            let errors = (
                (wavelength / style.wavelength_px - 1.0).abs(),
                (amplitude / style.amplitude_px - 1.0).abs(),
            );
            assert!(
                errors.0 < 0.05 && errors.1 < 0.05,
                "{degrees}° at distance {distance}: wavelength {wavelength:.3} px, amplitude {amplitude:.3} px"
            );
            worst = (worst.0.max(errors.0), worst.1.max(errors.1));
        }
    }
    eprintln!(
        "drawn pixels, worst relative error: wavelength {:.4}, amplitude {:.4}",
        worst.0, worst.1
    );
}

/// The corners of the cube of side 2 and its 12 edges (corner pairs one
/// coordinate apart).
fn cube_edges() -> Vec<(DVec3, DVec3)> {
    let corner = |k: u32| {
        DVec3::new(
            [-1.0, 1.0][k as usize & 1],
            [-1.0, 1.0][(k >> 1) as usize & 1],
            [-1.0, 1.0][(k >> 2) as usize & 1],
        )
    };
    let mut edges = Vec::new();
    for k in 0..8u32 {
        for axis in [1, 2, 4] {
            if k & axis == 0 {
                edges.push((corner(k), corner(k | axis)));
            }
        }
    }
    edges
}

/// Ink per px of chord of a strip of `width` around `amplitude`·sin(2πu/λ)
/// over whole periods: width × the sine's mean arc length per px (the
/// strip's area; its ends are cut square by the measuring window).
fn ink_per_px(style: &LineStyle) -> f64 {
    let k = TAU / style.wavelength_px;
    let n = 100_000;
    let arc: f64 = (0..n)
        .map(|i| {
            let u = (i as f64 + 0.5) / n as f64 * style.wavelength_px;
            (1.0 + (style.amplitude_px * k * (k * u).cos()).powi(2)).sqrt()
        })
        .sum::<f64>()
        / n as f64;
    style.width_px * arc
}

/// Issue 35 item 8: with silhouettes and creases both on, each of a cube's
/// outer edges (a silhouette and a crease at once) is one strip, with one
/// phase along the silhouette loop. Exact truth: the backbones' total
/// screen length is the 12 projected edges' once each; along every outline
/// edge one piece is drawn; its ink per px of edge is a lone strip's
/// (width × the sine's arc length per px), as is a lone edge's drawn with
/// the same style; and the drawn wave has the wavelength and amplitude set.
/// Drawn from both lists (the bug), the outline edges are two pieces each,
/// the total length counts them twice, and their ink is up to twice as wide.
#[test]
fn an_edge_both_silhouette_and_crease_is_one_strip() {
    let mesh = cube(2.0);
    let eye = DVec3::new(2.6, 2.1, 3.4);
    let vp = view_proj(eye);
    let style = LineStyle {
        width_px: 2.0,
        amplitude_px: 3.0,
        wavelength_px: 16.0,
        phase: 0.7,
        taper: 0.0,
    };
    let selection = EdgeSelection {
        silhouettes: true,
        crease_deg: Some(40.0),
    };
    let objects = [LineObject {
        mesh: &mesh,
        model: DMat4::IDENTITY,
    }];
    let size = DVec2::splat(SIZE as f64);
    let strips = LinesCache::default()
        .strips(0, &objects, eye, vp, size, &style, selection)
        .clone();

    let edges = cube_edges();
    assert_eq!(edges.len(), 12);
    let truth: f64 = edges
        .iter()
        .map(|(a, b)| (project(vp, *a) - project(vp, *b)).length())
        .sum();
    let drawn: f64 = strips.backbones.iter().map(|b| b.last().map_or(0.0, |p| p.s)).sum();
    eprintln!(
        "backbones: {} pieces, {drawn:.6} px; the 12 edges: {truth:.6} px",
        strips.backbones.len()
    );
    assert!(
        (drawn / truth - 1.0).abs() < 1e-9,
        "drawn {drawn} px of backbone, edges {truth} px"
    );

    // The outline: edges whose two faces differ in facing from the eye.
    let facing = |n: DVec3| n.dot(eye - n) > 0.0; // a face of the cube is at n, normal n
    let normals = [DVec3::X, DVec3::Y, DVec3::Z];
    let outline: Vec<(DVec3, DVec3)> = edges
        .iter()
        .copied()
        .filter(|(a, b)| {
            // The edge's two faces: the axes along which a and b agree.
            let faces: Vec<DVec3> = normals
                .iter()
                .filter(|n| (a.dot(**n) - b.dot(**n)).abs() < 1e-12)
                .map(|n| *n * a.dot(*n))
                .collect();
            facing(faces[0]) != facing(faces[1])
        })
        .collect();
    assert_eq!(
        outline.len(),
        6,
        "a cube seen from a general eye has a hexagonal outline"
    );

    let pieces = rasterize_pieces(&strips);
    let union = rasterize(&strips);
    let expected_ink = ink_per_px(&style);
    let reach = style.amplitude_px + 0.5 * style.width_px + 1.5;
    for (a3, b3) in outline {
        let (a, b) = (project(vp, a3), project(vp, b3));
        let length = (b - a).length();
        let (from, to) = (0.15 * length, 0.85 * length);
        let (along, across) = ((b - a).normalize(), (b - a).normalize().perp());
        let in_window = |i: usize| {
            let p = DVec2::new((i % SIZE) as f64 + 0.5, (i / SIZE) as f64 + 0.5) - a;
            (from..to).contains(&p.dot(along)) && p.dot(across).abs() <= reach
        };
        let ink = |mask: &[bool]| (0..SIZE * SIZE).filter(|&i| mask[i] && in_window(i)).count() as f64 / (to - from);
        let drawing: Vec<usize> = (0..pieces.len()).filter(|&k| ink(&pieces[k]) > 0.0).collect();
        let lone = rasterize(&strip::build(&[(vec![a3, b3], false)], vp, size, &style));
        let (wavelength, amplitude) = measure_between(&union, a, b, from, to, reach);
        eprintln!(
            "edge {a3} → {b3} ({length:.1} px): pieces {drawing:?}, ink {:.3} px/px (lone edge {:.3}, truth {expected_ink:.3}), wavelength {wavelength:.3}, amplitude {amplitude:.3}",
            ink(&union),
            ink(&lone)
        );
        assert_eq!(drawing.len(), 1, "one strip along the edge, not {}", drawing.len());
        assert!(strips.backbones[drawing[0]].len() > 2, "the outline is chained");
        // Pixel centres sample the strip's area: ±6% over a window of
        // ≥ 35 px of chord (a strip 2 px wide quantizes to 2 ± 1 px per
        // column, and the window's ends cut the sine mid-period).
        for (what, measured) in [("drawn", ink(&union)), ("lone edge", ink(&lone))] {
            assert!(
                (measured / expected_ink - 1.0).abs() < 0.06,
                "{what}: {measured:.3} px of ink per px, a lone strip has {expected_ink:.3}"
            );
        }
        // ±5%, as for the lone lines above: a bin's mean pixel centre
        // rounds the sine's peaks in (2.87–2.95 px measured for 3 px).
        assert!(
            (wavelength / style.wavelength_px - 1.0).abs() < 0.05
                && (amplitude / style.amplitude_px - 1.0).abs() < 0.05,
            "wavelength {wavelength:.3} px, amplitude {amplitude:.3} px"
        );
    }
}
