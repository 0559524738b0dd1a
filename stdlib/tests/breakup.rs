//! MetaTexture extensions and Edge Breakup (Age of Sail §3.2–3.5, §4, §6.1)
//! against analytic truth in f64: camera-roll compensation on a rolled
//! camera, single-camera gradients in stereo, screen-space size over 1–1000 m
//! and grazing angles, live-texture period and contrast, line-boil stepping,
//! and the hard cases (every parameter at both ends of its range included).

use npr_stdlib::metrics::{self, PlaneSample, Variant};
use npr_stdlib::reference::{self as r, ImageF64, MetaSettings};

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// A pinhole camera over a `size`² image: pixel (x right, y down) ↔ ray.
#[derive(Clone, Copy)]
struct Cam {
    eye: V3,
    fwd: V3,
    right: V3,
    up: V3,
    focal_px: f64,
    size: f64,
}

impl Cam {
    fn looking(eye: V3, target: V3, up_hint: V3, fov_deg: f64, size: u32) -> Cam {
        let fwd = unit(sub(target, eye));
        let right = unit(cross(fwd, up_hint));
        let up = cross(right, fwd);
        Cam {
            eye,
            fwd,
            right,
            up,
            focal_px: size as f64 / 2.0 / (fov_deg.to_radians() / 2.0).tan(),
            size: size as f64,
        }
    }

    /// The same camera rolled 90° about its view axis (up ← right).
    fn rolled(self) -> Cam {
        Cam {
            right: self.up,
            up: [-self.right[0], -self.right[1], -self.right[2]],
            ..self
        }
    }

    fn ray(&self, px: f64, py: f64) -> V3 {
        let (sx, sy) = (px - self.size / 2.0, self.size / 2.0 - py);
        std::array::from_fn(|i| self.fwd[i] * self.focal_px + self.right[i] * sx + self.up[i] * sy)
    }

    /// Pixel position of world point p (x right, y down).
    fn project(&self, p: V3) -> [f64; 2] {
        let d = sub(p, self.eye);
        let z = dot(d, self.fwd);
        [
            self.size / 2.0 + self.focal_px * dot(d, self.right) / z,
            self.size / 2.0 - self.focal_px * dot(d, self.up) / z,
        ]
    }

    /// px per metre along world direction `dir` at `p`: T_s of eqs. 9–10.
    fn project_dir(&self, p: V3, dir: V3) -> [f64; 2] {
        let h = 1e-6;
        let a = self.project(std::array::from_fn(|i| p[i] - h * dir[i]));
        let b = self.project(std::array::from_fn(|i| p[i] + h * dir[i]));
        [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)]
    }
}

/// uv = (x, z) on the plane y = 0: (uv, ∇u, ∇v) at a pixel, or None off the plane.
fn plane_at(cam: &Cam, px: f64, py: f64) -> Option<([f64; 2], [f64; 2], [f64; 2])> {
    let hit = |x: f64, y: f64| -> Option<[f64; 2]> {
        let d = cam.ray(x, y);
        if d[1] >= -1e-9 {
            return None;
        }
        let t = -cam.eye[1] / d[1];
        Some([cam.eye[0] + t * d[0], cam.eye[2] + t * d[2]])
    };
    let h = 1e-4;
    let (c, a, b, e, f) = (
        hit(px, py)?,
        hit(px - h, py)?,
        hit(px + h, py)?,
        hit(px, py - h)?,
        hit(px, py + h)?,
    );
    Some((
        c,
        [(b[0] - a[0]) / (2.0 * h), (f[0] - e[0]) / (2.0 * h)],
        [(b[1] - a[1]) / (2.0 * h), (f[1] - e[1]) / (2.0 * h)],
    ))
}

fn warp_noise() -> ImageF64 {
    metrics::noise_texture(32, 7)
}

/// The breakup warp vector in px at one pixel: MetaTexture noise (with
/// radial compensation) remapped to [−1, 1], optionally roll-compensated.
fn warp_px(tex: &ImageF64, cam: &Cam, px: f64, py: f64, compensate: bool, strength: f64) -> Option<[f64; 2]> {
    let (uv, du, dv) = plane_at(cam, px, py)?;
    let focal = cam.focal_px / (cam.size / 2.0);
    let alpha = r::radial_alpha([px / cam.size, py / cam.size], [focal, focal]);
    let s = MetaSettings {
        width: 24.0 * alpha,
        ..MetaSettings::default()
    };
    let m = r::metatexture_grad(tex, uv, du, dv, &s);
    let v = [m[0] * 2.0 - 1.0, m[1] * 2.0 - 1.0];
    let v = if compensate { r::roll_compensate(v, du) } else { v };
    Some([v[0] * strength, v[1] * strength])
}

#[test]
fn roll_compensated_warp_field_rolls_with_the_camera() {
    let tex = warp_noise();
    let n = 48u32;
    let cam = Cam::looking([0.3, 2.0, -4.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 50.0, n);
    let rolled = cam.rolled();
    let strength = 8.0;
    let (mut worst, mut worst_plain, mut count) = (0.0f64, 0.0f64, 0);
    for j in 0..n {
        for i in 0..n {
            let (px, py) = (i as f64 + 0.5, j as f64 + 0.5);
            // The rolled image's pixel that sees the same ray: i' = n−1−j, j' = i.
            let (qx, qy) = ((n - 1 - j) as f64 + 0.5, i as f64 + 0.5);
            let (Some(w), Some(w_rolled)) = (
                warp_px(&tex, &cam, px, py, true, strength),
                warp_px(&tex, &rolled, qx, qy, true, strength),
            ) else {
                continue;
            };
            // Screen vectors rotate as (x, y) → (−y, x) with the image.
            let expected = [-w[1], w[0]];
            worst = worst.max((w_rolled[0] - expected[0]).hypot(w_rolled[1] - expected[1]));
            let p = warp_px(&tex, &cam, px, py, false, strength).expect("same pixel");
            let p_rolled = warp_px(&tex, &rolled, qx, qy, false, strength).expect("same pixel");
            worst_plain = worst_plain.max((p_rolled[0] + p[1]).hypot(p_rolled[1] - p[0]));
            count += 1;
        }
    }
    println!(
        "camera roll 90°: {count} px, max |W_rolled − R·W| = {worst:.2e} px compensated, {worst_plain:.2} px without"
    );
    assert!(count > 500, "{count}");
    assert!(worst < 1e-3, "compensated warp differs by {worst} px");
    assert!(
        worst_plain > 1.0,
        "without compensation the field should not follow the roll ({worst_plain} px)"
    );
}

#[test]
fn single_camera_gradients_select_the_same_level_in_both_eyes() {
    // A large vertical wall (x = 0, uv = (z, y)) seen obliquely from 0.6 m, IPD 64 mm.
    let target = [0.0, 1.5, 1.0];
    let centre = Cam::looking([0.6, 1.5, 0.0], target, [0.0, 1.0, 0.0], 90.0, 256);
    let ipd = 0.064;
    let eye = |side: f64| {
        let e: V3 = std::array::from_fn(|i| centre.eye[i] + side * ipd / 2.0 * centre.right[i]);
        let t: V3 = std::array::from_fn(|i| target[i] + side * ipd / 2.0 * centre.right[i]);
        Cam::looking(e, t, [0.0, 1.0, 0.0], 90.0, 256)
    };
    let (left, right) = (eye(-1.0), eye(1.0));
    let (tangent, bitangent) = ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]);
    let width = 64.0;
    let level = |cam: &Cam, p: V3| -> (i64, i64) {
        let g = r::uv_gradients(
            cam.project_dir(p, tangent),
            cam.project_dir(p, bitangent),
            [1.0, 1.0],
            0,
        );
        let s = MetaSettings {
            width,
            ..MetaSettings::default()
        };
        let (e, _, _) = r::meta_level([g[0], g[1]], [g[2], g[3]], &s);
        (e[0].floor() as i64, e[1].floor() as i64)
    };
    // Projected with one camera (`tangent.screen_center`), T_s and B_s, hence the
    // levels, are the centre camera's in both eyes by construction; the runner
    // test `stereo_center_projection_is_shared_by_both_eyes` checks the GPU side.
    // Here: how often the per-eye projection would disagree.
    let (mut per_eye_differs, mut centre_vs_left, mut total) = (0, 0, 0);
    for zi in 0..60 {
        for yi in 0..20 {
            let p = [0.0, 1.0 + yi as f64 * 0.05, 0.05 + zi as f64 * 0.08];
            let visible = |c: &Cam| {
                let q = c.project(p);
                dot(sub(p, c.eye), c.fwd) > 0.05 && (0.0..256.0).contains(&q[0]) && (0.0..256.0).contains(&q[1])
            };
            if !(visible(&left) && visible(&right)) {
                continue;
            }
            total += 1;
            per_eye_differs += (level(&left, p) != level(&right, p)) as usize;
            centre_vs_left += (level(&centre, p) != level(&left, p)) as usize;
        }
    }
    println!("stereo: {total} wall points; left and right eye pick different levels at {per_eye_differs} with per-eye projection, 0 with the centre camera (which differs from the left eye's at {centre_vs_left})");
    assert!(total > 300);
    assert!(per_eye_differs > 0, "the oblique wall should show the per-eye shimmer");
    assert!(
        centre_vs_left < per_eye_differs * 2,
        "the centre camera sits between the eyes"
    );
}

#[test]
fn screen_space_period_stays_within_an_octave_from_1_m_to_1000_m() {
    let samples = metrics::standard_plane_set(64, 2);
    let w = 32.0;
    let meta = metrics::variant_error(&samples, &Variant::new(w, 0));
    let smooth = metrics::variant_error(
        &samples,
        &Variant {
            smooth: true,
            ..Variant::new(w, 0)
        },
    );
    let plain = metrics::variant_error(
        &samples,
        &Variant {
            plain: true,
            ..Variant::new(w, 0)
        },
    );
    // Distribution of the base tap's period (in units of w) over all samples.
    let mut hist = [0usize; 8];
    for s in &samples {
        let (du, dv) = s.exact;
        for g in [du, dv] {
            let l = g[0].hypot(g[1]);
            let e = -(w * l).log2();
            let p = 1.0 / (e.floor().exp2() * l * w);
            hist[(((p - 1.0) * 8.0).floor() as usize).min(7)] += 1;
        }
    }
    println!(
        "{} plane samples (1–1000 m, elevation 90°–2°, azimuth 0°/35°)",
        samples.len()
    );
    println!(
        "base period / w: MetaTexture [{:.4}, {:.4}], in [1, 2): {:.1}%; plain mapping [{:.3e}, {:.3e}]",
        meta.period_min,
        meta.period_max,
        meta.in_octave * 100.0,
        plain.period_min,
        plain.period_max
    );
    println!("histogram of base period / w in eighths of [1, 2): {hist:?}");
    println!(
        "scale error |log2(period/w)|: MetaTexture {:.3} (smooth eqs. 9–10 gradients {:.3}), plain {:.3}",
        meta.scale, smooth.scale, plain.scale
    );
    assert!(meta.period_min >= 1.0 - 1e-9 && meta.period_max < 2.0, "{meta:?}");
    assert_eq!(meta.in_octave, 1.0);
    assert!(plain.period_max / plain.period_min > 1e4, "{plain:?}");
    // Blend-weighted, a tap is never more than one octave off: the mean error is ≤ 1/2.
    assert!(meta.scale <= 0.5 && plain.scale > 3.0, "{meta:?} {plain:?}");
    // Eqs. 9–10 underestimate |∇u| by sin∠(T_s, B_s) on skewed views: larger, but bounded, error.
    assert!(smooth.scale < 0.75, "{smooth:?}");
}

#[test]
fn contour_orientation_blends_without_a_seam() {
    let tex = metrics::noise_texture(32, 9);
    let s = MetaSettings {
        width: 32.0,
        ..MetaSettings::default()
    };
    // Sweep |∇u|/|∇v| through 1 (the switch): M changes continuously.
    let uv = [0.37, 0.61];
    let mut prev = None;
    let mut worst = 0.0f64;
    for i in 0..=2000 {
        let r = -1.0 + i as f64 * 1e-3;
        let du = [r.exp2() / 64.0, 0.0];
        let dv = [0.0, 1.0 / 64.0];
        let m = r::metatexture_contour_grad(&tex, uv, du, dv, &s, 1, 1.0);
        assert!(m.iter().all(|x| x.is_finite()));
        if let Some(p) = prev {
            let p: [f64; 4] = p;
            worst = worst.max((m[0] - p[0]).abs());
        }
        prev = Some(m);
    }
    // A step of 1e-3 octave moves M by O(1e-3); a seam would jump by O(0.1).
    println!("contour orientation: max change per 1e-3 octave {worst:.2e}");
    assert!(worst < 0.02, "{worst}");
    // Far from the band the result is exactly one orientation.
    let m_default = r::metatexture_grad(&tex, uv, [0.1 / 64.0, 0.0], [0.0, 1.0 / 64.0], &s);
    let m_oriented = r::metatexture_contour_grad(&tex, uv, [0.1 / 64.0, 0.0], [0.0, 1.0 / 64.0], &s, 1, 1.0);
    assert_eq!(m_default, m_oriented);
    let m_rot = r::metatexture_grad(&tex, [uv[1], -uv[0]], [0.0, 1.0 / 64.0], [-10.0 / 64.0, 0.0], &s);
    assert_eq!(
        m_rot,
        r::metatexture_contour_grad(&tex, uv, [10.0 / 64.0, 0.0], [0.0, 1.0 / 64.0], &s, 1, 1.0)
    );
}

#[test]
fn live_texture_cycles_at_f_hertz_with_constant_contrast() {
    let mut state = 3u64;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let texels: Vec<[f64; 4]> = (0..20000).map(|_| [next(), next(), next(), 1.0]).collect();
    let f = 0.75;
    // Period 1/f: ft is 2π·f·t.
    for t in [0.0, 0.3, 1.7] {
        for c in texels.iter().take(50) {
            assert!((r::live_texture(*c, f, t) - r::live_texture(*c, f, t + 1.0 / f)).abs() < 1e-9);
        }
    }
    // Half a period later the chroma term flips sign around ½.
    let c = [0.9, 0.2, 0.4, 1.0];
    assert!((r::live_texture(c, f, 0.0) - 0.5 + (r::live_texture(c, f, 0.5 / f) - 0.5)).abs() < 1e-9);
    let stats = |t: f64| {
        let v: Vec<f64> = texels.iter().map(|c| r::live_texture(*c, f, t)).collect();
        let m = v.iter().sum::<f64>() / v.len() as f64;
        (
            m,
            (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / v.len() as f64).sqrt(),
        )
    };
    let (m0, s0) = stats(0.0);
    println!("live texture, uniform independent rgb: t = 0: mean {m0:.4} std {s0:.4}");
    for t in [0.1, 0.25, 0.4, 0.9] {
        let (m, s) = stats(t);
        println!("  t = {t}: mean {m:.4} std {s:.4}");
        assert!(
            (m - 0.5).abs() < 0.01 && (s / s0 - 1.0).abs() < 0.02,
            "t = {t}: {m} {s}"
        );
    }
}

#[test]
fn line_boil_steps_on_twos_and_repeats() {
    let uv = [0.2, 0.7];
    // 24 fps with f32 frame times, 12 drawings per second, 4 drawings per cycle.
    let at = |frame: u32| r::line_boil(uv, 1.0, 12.0, 4, (frame as f32 / 24.0) as f64);
    let mut changes = 0;
    for frame in 1..48 {
        let (a, b) = (at(frame - 1), at(frame));
        if a != b {
            changes += 1;
            assert_eq!(frame % 2, 0, "changed on an odd frame {frame}");
        }
    }
    assert_eq!(changes, 23, "one change every two frames");
    for frame in 0..40 {
        assert_eq!(at(frame), at(frame + 8), "4 drawings × 2 frames repeat every 8 frames");
    }
    let distinct: std::collections::BTreeSet<String> = (0..8).map(|f| format!("{:?}", at(f))).collect();
    assert_eq!(distinct.len(), 4);
    // Rate 0 is a still image; negative times stay in the cycle.
    assert_eq!(r::line_boil(uv, 1.0, 0.0, 4, 123.4), uv);
    assert!((0.0..4.0).contains(&r::line_boil_step(12.0, 4, -3.21)));
}

#[test]
fn distance_attenuation_is_eq_26() {
    assert_eq!(r::distance_attenuate(2.0, 0.0, 1.0), 2.0);
    assert!((r::distance_attenuate(2.0, 1.0, 1.0) - 1.0).abs() < 1e-15);
    assert!((r::distance_attenuate(1.0, 3.0, 1.0) - 0.1).abs() < 1e-15);
    assert!((r::distance_attenuate(1.0, 1e5, 1.0) / 1e-10 - 1.0).abs() < 1e-9);
    assert_eq!(r::distance_attenuate(1.0, f64::INFINITY, 1.0), 0.0);
    assert!((r::distance_attenuate(1.0, 12.0, 6.0) - 0.2).abs() < 1e-15);
}

#[test]
fn hard_cases_stay_finite_and_bounded() {
    let tex = metrics::noise_texture(16, 3);
    let s = MetaSettings::default();
    // |∇u| → 0 at an extreme close-up with uv far from the origin (2^E·u beyond f32).
    for (uv, du, dv) in [
        ([12345.678, -9876.5], [1e-30, 0.0], [0.0, 1e-30]),
        ([0.5, 0.5], [1e30, 0.0], [0.0, 1e30]),
        ([0.5, 0.5], [0.1, 0.1], [0.2, 0.2]),
        ([0.5, 0.5], [0.0, 0.0], [0.0, 0.0]),
        ([0.5, 0.5], [f64::MIN_POSITIVE, 0.0], [1.0, 0.0]),
    ] {
        for skew in [0, 1, 8] {
            for contrast in [0, 1, 2] {
                for orient in [0, 1] {
                    let st = MetaSettings { skew, contrast, ..s };
                    let m = r::metatexture_contour_grad(&tex, uv, du, dv, &st, orient, 1.0);
                    assert!(
                        m.iter().all(|x| x.is_finite() && (-1.5..=2.5).contains(x)),
                        "{uv:?} {du:?} {dv:?}: {m:?}"
                    );
                }
            }
        }
    }
    // Every operator parameter at both ends of its declared range (others at their defaults).
    for op in [
        "radial_alpha",
        "uv_gradients",
        "live_texture",
        "line_boil",
        "distance_attenuate",
        "warp",
        "metatexture_contour_grad",
    ] {
        let o = npr_stdlib::find(op).expect("operator");
        for p in o.params.iter().filter(|p| p.range.is_some()) {
            let (lo, hi) = p.range.expect("range");
            for x in [lo, hi] {
                let arg = |name: &str, default: f64| if name == p.name { x } else { default };
                let v: Vec<f64> = match op {
                    "uv_gradients" => [0, 1]
                        .iter()
                        .flat_map(|m| r::uv_gradients([3.0, 0.0], [0.0, 0.0], [arg("density", 1.0); 2], *m))
                        .collect(),
                    "live_texture" => vec![r::live_texture([1.0, 0.0, 1.0, 1.0], arg("freq", 0.75), 1e6)],
                    "line_boil" => r::line_boil(
                        [0.3, 0.3],
                        arg("amount", 1.0),
                        arg("rate", 12.0),
                        arg("cycle", 4.0) as i64,
                        1e7,
                    )
                    .to_vec(),
                    "distance_attenuate" => vec![r::distance_attenuate(1.0, 1e5, arg("falloff", 1.0))],
                    "warp" => r::warp(&tex, [1e30, -1e30], arg("strength", 4.0), [0.5, 0.5]).to_vec(),
                    "metatexture_contour_grad" => {
                        let st = MetaSettings {
                            width: arg("width", 256.0),
                            base: arg("base", 2.0),
                            skew: arg("skew", 0.0) as i64,
                            ..s
                        };
                        r::metatexture_contour_grad(
                            &tex,
                            [0.3, 0.9],
                            [1e-3, 2e-4],
                            [3e-4, 2e-3],
                            &st,
                            1,
                            arg("band", 1.0),
                        )
                        .to_vec()
                    }
                    _ => vec![r::radial_alpha([0.0, 1.0], [1.0, 1.0])],
                };
                assert!(v.iter().all(|x| x.is_finite()), "{op}.{} = {x}: {v:?}", p.name);
            }
        }
    }
    // Degenerate triangles give zero tangents: zero T_s, B_s → zero gradients, still finite.
    assert_eq!(r::uv_gradients([0.0, 0.0], [0.0, 0.0], [1.0, 1.0], 1), [0.0; 4]);
    assert!(r::uv_gradients([0.0, 0.0], [0.0, 0.0], [1.0, 1.0], 0)
        .iter()
        .all(|x| x.is_finite()));
    // T_s ∥ B_s (edge-on): finite.
    assert!(r::uv_gradients([3.0, 1.0], [6.0, 2.0], [1.0, 1.0], 0)
        .iter()
        .all(|x| x.is_finite()));
    assert!(r::roll_compensate([0.5, -0.5], [f64::NAN, 0.0])
        .iter()
        .all(|x| x.is_finite()));
    assert_eq!(r::roll_compensate([0.5, -0.5], [0.0, 0.0]), [0.5, -0.5]);
    assert!(r::radial_alpha([1.0, 1.0], [0.0, 0.0]).is_finite());
    assert_eq!(r::radial_alpha([f64::NAN, 0.5], [1.0, 1.0]), 1.0);
}

#[test]
fn smooth_gradient_variant_errors_are_reported() {
    // On a skewed view eqs. 9–10 as printed differ from exact gradients (and
    // flip the sign of ∇u·∇v): report the anisotropy each leaves with skew on.
    let samples: Vec<PlaneSample> = metrics::plane_samples(5.0, 10.0, 35.0, 90.0, 64, 2);
    let exact = metrics::variant_error(&samples, &Variant::new(32.0, 4));
    let smooth = metrics::variant_error(
        &samples,
        &Variant {
            smooth: true,
            ..Variant::new(32.0, 4)
        },
    );
    println!(
        "skew n = 4: anisotropy with exact gradients {:.1}°, with eqs. 9–10 as printed {:.1}°",
        exact.anisotropy_deg, smooth.anisotropy_deg
    );
    assert!(exact.anisotropy_deg.is_finite() && smooth.anisotropy_deg.is_finite());
    assert!(exact.anisotropy_deg < metrics::variant_error(&samples, &Variant::new(32.0, 0)).anisotropy_deg);
}

#[test]
fn variance_compensation_restores_contrast_over_the_plane_set() {
    // White noise (uncorrelated taps), every blend weight the plane set produces.
    let samples = metrics::standard_plane_set(64, 4);
    let tex = metrics::noise_texture(64, 5);
    for skew in [0, 4] {
        let ratio = |contrast| {
            metrics::contrast_ratio(
                &tex,
                &samples,
                &Variant {
                    contrast,
                    ..Variant::new(32.0, skew)
                },
            )
        };
        let (none, printed, variance) = (ratio(0), ratio(1), ratio(2));
        println!("skew {skew}: σ_M/σ_T none {none:.3}, printed × c {printed:.3}, ÷ √c {variance:.3}");
        assert!((variance - 1.0).abs() < 0.03, "skew {skew}: {variance}");
        assert!(printed < none && none < 0.9, "skew {skew}: {printed} {none}");
    }
}
