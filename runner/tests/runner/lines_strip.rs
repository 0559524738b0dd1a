//! Strip building: "consistent waviness" (§5) measured from the output
//! geometry across orientations and distances, phase continuity along a
//! chain, taper, near-plane clipping, and the end-on and zero-length cases.

use glam::{DMat4, DVec2, DVec3};
use npr_runner::lines::strip::*;
use std::f64::consts::{PI, TAU};

const SIZE: DVec2 = DVec2::new(512.0, 512.0);

fn view_proj(eye: DVec3, target: DVec3) -> DMat4 {
    DMat4::perspective_rh(40f64.to_radians(), 1.0, 0.1, 100.0) * DMat4::look_at_rh(eye, target, DVec3::Y)
}

fn style() -> LineStyle {
    LineStyle {
        width_px: 2.0,
        amplitude_px: 1.5,
        wavelength_px: 24.0,
        phase: 0.3,
        taper: 0.0,
    }
}

fn all_finite(strips: &Strips) -> bool {
    strips
        .vertices
        .iter()
        .all(|v| v.px.is_finite() && v.depth.is_finite() && v.s.is_finite())
        && strips
            .backbones
            .iter()
            .flatten()
            .all(|b| b.px.is_finite() && b.normal.is_finite())
}

/// Wavelength and amplitude of a displaced straight backbone, measured from
/// its points alone: the signed distance from the chord, its zero crossings
/// (interpolated) and its largest magnitude.
fn measure(backbone: &[BackbonePoint]) -> (f64, f64) {
    let (start, end) = (backbone[0].base, backbone[backbone.len() - 1].base);
    let along = (end - start).normalize();
    let across = DVec2::new(-along.y, along.x);
    let points: Vec<(f64, f64)> = backbone
        .iter()
        .map(|b| ((b.px - start).dot(along), (b.px - start).dot(across)))
        .collect();
    let mut crossings = Vec::new();
    for w in points.windows(2) {
        let ((u0, d0), (u1, d1)) = (w[0], w[1]);
        if (d0 > 0.0) != (d1 > 0.0) {
            crossings.push(u0 + (u1 - u0) * d0 / (d0 - d1));
        }
    }
    let gaps = crossings.len() - 1;
    let half_wavelength = (crossings[gaps] - crossings[0]) / gaps as f64;
    let amplitude = points.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    (2.0 * half_wavelength, amplitude)
}

#[test]
fn waviness_is_the_same_in_px_at_every_orientation_and_distance() {
    let style = style();
    let mut worst: (f64, f64) = (0.0, 0.0);
    for distance in [3.0, 6.0, 12.0, 30.0] {
        let eye = DVec3::new(0.0, 0.0, distance);
        let vp = view_proj(eye, DVec3::ZERO);
        // Long enough for ≥ 6 wavelengths on screen at every distance.
        let half = 0.35 * distance * (20f64.to_radians()).tan();
        for degrees in (0..=180).step_by(15) {
            let theta = f64::from(degrees).to_radians();
            // In the image plane, and tilted 60° into depth (foreshortened
            // unevenly by the perspective: s is screen arc length anyway).
            for direction in [
                DVec3::new(theta.cos(), theta.sin(), 0.0),
                DVec3::new(theta.cos(), 0.5 * theta.sin(), 0.866 * theta.sin()).normalize(),
            ] {
                let points = vec![-direction * half, direction * half];
                let strips = build(&[(points, false)], vp, SIZE, &style);
                assert!(all_finite(&strips));
                if strips.backbones.is_empty() {
                    continue; // θ = 90° tilted lies in depth: a short line
                }
                let backbone = &strips.backbones[0];
                if backbone[backbone.len() - 1].s < 4.0 * style.wavelength_px {
                    continue;
                }
                let (wavelength, amplitude) = measure(backbone);
                let errors = (
                    (wavelength / style.wavelength_px - 1.0).abs(),
                    (amplitude / style.amplitude_px - 1.0).abs(),
                );
                assert!(
                    errors.0 < 0.05 && errors.1 < 0.05,
                    "at {degrees}°, distance {distance}: wavelength {wavelength} px, amplitude {amplitude} px"
                );
                worst = (worst.0.max(errors.0), worst.1.max(errors.1));
            }
        }
    }
    eprintln!(
        "worst relative error: wavelength {:.2e}, amplitude {:.2e}",
        worst.0, worst.1
    );
}

#[test]
fn the_phase_runs_on_along_a_chain() {
    // An L: the second leg continues the first's arc length, so the offset
    // at every sample is amplitude·sin(2π·s/λ + φ) with one s for the chain.
    let style = style();
    let vp = view_proj(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO);
    let points = vec![
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
    ];
    let strips = build(&[(points, false)], vp, SIZE, &style);
    assert_eq!(strips.backbones.len(), 1);
    let backbone = &strips.backbones[0];
    for w in backbone.windows(2) {
        let step = (w[1].base - w[0].base).length();
        assert!((w[1].s - w[0].s - step).abs() < 1e-9, "s is the screen arc length");
        assert!(step <= style.wavelength_px / SAMPLES_PER_WAVELENGTH + 1e-9);
    }
    for b in backbone {
        let offset = (b.px - b.base).dot(b.normal);
        let expected = style.amplitude_px * (TAU * b.s / style.wavelength_px + style.phase).sin();
        assert!((offset - expected).abs() < 1e-9);
        assert!((b.normal.length() - 1.0).abs() < 1e-12);
    }
    // Two strip vertices per sample, two triangles per step.
    assert_eq!(strips.vertices.len(), 2 * backbone.len());
    assert_eq!(strips.indices.len(), 6 * (backbone.len() - 1));
}

#[test]
fn taper_narrows_open_ends_to_nothing() {
    let style = LineStyle {
        taper: 0.25,
        amplitude_px: 0.0,
        ..style()
    };
    let vp = view_proj(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO);
    let strips = build(
        &[(vec![DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0)], false)],
        vp,
        SIZE,
        &style,
    );
    let v = &strips.vertices;
    let width = |i: usize| (v[2 * i].px - v[2 * i + 1].px).length();
    let n = v.len() / 2;
    let length = strips.backbones[0][n - 1].s;
    assert!(width(0) < 1e-12 && width(n - 1) < 1e-12);
    assert!((width(n / 2) - style.width_px).abs() < 1e-9);
    for i in 0..n {
        let s = strips.backbones[0][i].s;
        let expected = style.width_px * (s.min(length - s) / (0.25 * length)).min(1.0);
        assert!((width(i) - expected).abs() < 1e-9);
    }
}

#[test]
fn near_plane_clipping_keeps_the_visible_part() {
    // From behind the eye to in front of it, along the view axis but off
    // to the side so it projects to a line.
    let eye = DVec3::new(0.0, 0.0, 0.0);
    let vp = view_proj(eye, DVec3::new(0.0, 0.0, -1.0));
    let points = vec![DVec3::new(0.3, 0.0, 2.0), DVec3::new(0.3, 0.0, -4.0)];
    let strips = build(&[(points, false)], vp, SIZE, &style());
    assert!(all_finite(&strips));
    assert_eq!(strips.backbones.len(), 1);
    let backbone = &strips.backbones[0];
    assert!(backbone[0].depth.abs() < 1e-9, "starts on the near plane");
    assert!(strips.vertices.iter().all(|v| (0.0..=1.0).contains(&v.depth)));
    // Wholly behind the eye: nothing.
    let behind = vec![DVec3::new(0.3, 0.0, 2.0), DVec3::new(-0.3, 0.0, 3.0)];
    assert!(build(&[(behind, false)], vp, SIZE, &style()).vertices.is_empty());
    // A closed square through the near plane stays one piece, joined
    // where it was cut, with s running on across the join.
    let square = vec![
        DVec3::new(-1.0, -0.5, -3.0),
        DVec3::new(1.0, -0.5, -3.0),
        DVec3::new(1.0, -0.5, 1.0),
        DVec3::new(-1.0, -0.5, 1.0),
    ];
    let strips = build(&[(square, true)], vp, SIZE, &style());
    assert!(all_finite(&strips));
    assert_eq!(strips.backbones.len(), 1);
    assert!(strips.backbones[0].windows(2).all(|w| w[1].s > w[0].s));
}

#[test]
fn end_on_and_zero_length_edges_give_no_nan() {
    let eye = DVec3::new(0.0, 0.0, 5.0);
    let vp = view_proj(eye, DVec3::ZERO);
    // An edge along the line of sight projects to one point: no line.
    let ray = (DVec3::new(0.2, 0.1, 0.0) - eye).normalize();
    let end_on = vec![eye + ray * 3.0, eye + ray * 4.0];
    assert!(build(&[(end_on.clone(), false)], vp, SIZE, &style())
        .vertices
        .is_empty());
    // A zero-length edge: no line.
    let p = DVec3::new(0.2, 0.1, 0.0);
    assert!(build(&[(vec![p, p], false)], vp, SIZE, &style()).vertices.is_empty());
    // Inside a chain, both merge away and the rest is drawn.
    let q = DVec3::new(-0.5, 0.4, 0.0);
    let chain = vec![q, end_on[0], end_on[1], end_on[1], DVec3::new(0.6, -0.3, 0.0)];
    let strips = build(&[(chain, false)], vp, SIZE, &style());
    assert!(all_finite(&strips) && !strips.vertices.is_empty());
    // A hairpin (the chain doubles back on itself) keeps finite normals.
    let hairpin = vec![
        DVec3::new(-0.5, 0.0, 0.0),
        DVec3::new(0.5, 0.0, 0.0),
        DVec3::new(-0.5, 0.0, 0.0),
    ];
    let strips = build(&[(hairpin, false)], vp, SIZE, &style());
    assert!(all_finite(&strips));
    // Non-finite input is refused, not propagated.
    let bad = vec![DVec3::new(f64::NAN, 0.0, 0.0), DVec3::ZERO];
    assert!(build(&[(bad, false)], vp, SIZE, &style()).vertices.is_empty());
    // Degenerate styles: zero wavelength and width stay finite.
    let flat = LineStyle {
        wavelength_px: 0.0,
        width_px: 0.0,
        phase: PI,
        ..style()
    };
    let strips = build(&[(vec![q, p], false)], vp, SIZE, &flat);
    assert!(all_finite(&strips));
}
