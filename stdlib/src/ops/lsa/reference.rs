//! CPU f64 references of the LSA contour operators (Zaidi et al., "Local
//! Surface Approximation Contours for Virtual Reality Stylisation"), line by
//! line in meaning with `lsa*.wgsl` beside it. Equation numbers are the
//! paper's; see the WGSL files for the reasoning behind each choice (the
//! e_plane offsets, the background and border rules).

use crate::image_f64::ImageF64;

/// The half neighbourhood: E, SE, S, SW in image coordinates (y down).
pub const DIRS: [(i64, i64); 4] = [(1, 0), (1, 1), (0, 1), (-1, 1)];

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
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
fn len(a: V3) -> f64 {
    dot(a, a).sqrt()
}
/// WGSL `sign`: 0 at 0.
fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// One G-buffer texel, as `npr_lsa_core__fetch` reads it.
#[derive(Debug, Clone, Copy)]
pub struct Texel {
    pub p: V3,
    pub n: V3,
    pub geo: bool,
    pub inside: bool,
}

/// `octahedral`: `normal_encoding: octahedral`, the normal decoded from rg.
pub fn fetch(pos: &ImageF64, normals: &ImageF64, octahedral: bool, x: i64, y: i64) -> Texel {
    let inside = x >= 0 && y >= 0 && x < pos.width as i64 && y < pos.height as i64;
    let pw = pos.load(x, y);
    let n4 = normals.load(x, y);
    let n = if octahedral {
        crate::ops::gbuffer::oct_decode([n4[0], n4[1]])
    } else {
        [n4[0], n4[1], n4[2]]
    };
    let big = 1.0e37;
    let finite = pw.iter().all(|v| v.abs() < big) && n.iter().all(|v| v.abs() < big);
    let geo = inside && finite && pw[3] > 0.5;
    let p = if geo { [pw[0], pw[1], pw[2]] } else { [0.0; 3] };
    let nn = if geo { n } else { [0.0; 3] };
    let n = scale(nn, 1.0 / dot(nn, nn).max(1e-30).sqrt());
    Texel { p, n, geo, inside }
}

/// −2: pair skipped (outside); −1: evaluate; otherwise the fixed error.
pub fn guard(c: &Texel, p: &Texel, q: &Texel) -> f64 {
    if !(c.inside && q.inside) {
        return -2.0;
    }
    if c.geo && p.geo && q.geo {
        return -1.0;
    }
    if c.geo || p.geo || q.geo {
        1.0e6
    } else {
        0.0
    }
}

/// Signed curvature of the sphere fitted to p and control c (eqs. 2–3).
pub fn kappa(c: &Texel, p: &Texel) -> f64 {
    let dn = sub(c.n, p.n);
    let dp = sub(c.p, p.p);
    sign(dot(dn, dp)) * len(dn) / len(dp).max(1e-5)
}

/// e_curv (eq. 5).
pub fn curv(c: &Texel, p: &Texel, q: &Texel) -> f64 {
    let k = kappa(c, p);
    len(sub(scale(sub(q.p, p.p), k), sub(q.n, p.n)))
}

/// The remap of §3.2.
pub fn remap(e: f64, lo: f64, hi: f64) -> f64 {
    if hi <= lo {
        return if e >= lo { 1.0 } else { 0.0 };
    }
    ((e - lo) / (hi - lo)).clamp(0.0, 1.0)
}

/// Minimum of |N·d| over the great-circle arc from `na` to `nb` (closed form).
pub fn arc_min(d: V3, na: V3, nb: V3) -> f64 {
    let (da, db) = (dot(d, na), dot(d, nb));
    if da * db <= 0.0 {
        0.0
    } else {
        da.abs().min(db.abs())
    }
}

/// Maximum of |N·d| over the great-circle arc from `na` to `nb` (closed form).
pub fn arc_max(d: V3, na: V3, nb: V3) -> f64 {
    let ends = dot(d, na).abs().max(dot(d, nb).abs());
    let axis = cross(na, nb);
    let s = len(axis);
    if s < 1e-6 {
        return ends;
    }
    let w = scale(axis, 1.0 / s);
    let dp = sub(d, scale(w, dot(d, w)));
    let x = dot(cross(na, dp), w);
    let y = dot(cross(dp, nb), w);
    if (x >= 0.0 && y >= 0.0) || (x <= 0.0 && y <= 0.0) {
        ends.max(len(dp))
    } else {
        ends
    }
}

/// Brute-force arc extrema of |N·d| (slerp sampling), to test the closed forms.
pub fn arc_extrema_sampled(d: V3, na: V3, nb: V3, samples: usize) -> (f64, f64) {
    let theta = dot(na, nb).clamp(-1.0, 1.0).acos();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 0..=samples {
        let t = i as f64 / samples as f64;
        let n = if theta < 1e-9 {
            na
        } else {
            let (a, b) = (((1.0 - t) * theta).sin(), (t * theta).sin());
            scale(
                [na[0] * a + nb[0] * b, na[1] * a + nb[1] * b, na[2] * a + nb[2] * b],
                1.0 / theta.sin(),
            )
        };
        let v = dot(n, d).abs();
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (lo, hi)
}

/// e_plane (eq. 6, offsets as in the WGSL: check over control).
pub fn plane(c: &Texel, p: &Texel, q: &Texel, sc: f64, sq: f64) -> f64 {
    let num = arc_min(scale(sub(q.p, p.p), sq), p.n, q.n);
    let den = arc_max(scale(sub(c.p, p.p), sc), p.n, c.n);
    ((num / (den + 1e-5) - 50.0) / 100.0).clamp(0.0, 1.0)
}

/// Which extensions an `lsa*` operator has on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LsaSettings {
    pub plane: bool,
    pub aa: bool,
    pub eta_min: f64,
    pub eta_max: f64,
    /// `normal_encoding: octahedral` (the packed G-buffer).
    pub octahedral: bool,
}

impl LsaSettings {
    /// The base method (`lsa_curv`) with the paper's η = [1/4, 1/2].
    pub const BASE: LsaSettings = LsaSettings {
        plane: false,
        aa: false,
        eta_min: 0.25,
        eta_max: 0.5,
        octahedral: false,
    };
    /// The full monoscopic method (`lsa` with both extensions on).
    pub const FULL: LsaSettings = LsaSettings {
        plane: true,
        aa: true,
        eta_min: 0.25,
        eta_max: 0.5,
        octahedral: false,
    };
}

/// Remapped error of q against the LSA of p and control c; −1 when unavailable.
fn e(c: &Texel, p: &Texel, q: &Texel, sc: f64, sq: f64, s: &LsaSettings) -> f64 {
    let g = guard(c, p, q);
    if g < -1.5 {
        return -1.0;
    }
    if g >= 0.0 {
        return remap(g, s.eta_min, s.eta_max);
    }
    let mut err = curv(c, p, q);
    if s.plane {
        err += plane(c, p, q, sc, sq);
    }
    remap(err, s.eta_min, s.eta_max)
}

/// e_aa (eq. 8) on remapped terms; negative a or b take no part.
pub fn aa(a: f64, b: f64, c: f64) -> f64 {
    let a = if a < 0.0 { c } else { a };
    let b = if b < 0.0 { c } else { b };
    let m = a.min(b);
    if m < c {
        0.5 * (m + c)
    } else {
        c
    }
}

/// Any `lsa*` operator: per-direction remapped errors (E, SE, S, SW).
/// `lsa_curv` is `LsaSettings::BASE`; `lsa_sum` has `aa: false`;
/// `lsa_curv_aa` has `plane: false`.
pub fn lsa(pos: &ImageF64, normals: &ImageF64, uv: [f64; 2], s: &LsaSettings) -> [f64; 4] {
    let (x, y) = pos.pixel_of(uv);
    let f = |dx: i64, dy: i64| fetch(pos, normals, s.octahedral, x + dx, y + dy);
    let p = f(0, 0);
    let mut out = [0.0; 4];
    for (i, (mx, my)) in DIRS.iter().enumerate() {
        let (b, d) = (f(-mx, -my), f(*mx, *my));
        let mut vd = e(&b, &p, &d, 1.0, 1.0, s).max(0.0);
        let mut vb = e(&d, &p, &b, 1.0, 1.0, s).max(0.0);
        if s.aa {
            let (a, ff) = (f(-2 * mx, -2 * my), f(2 * mx, 2 * my));
            vd = aa(e(&b, &p, &ff, 1.0, 0.5, s), e(&a, &p, &d, 0.5, 1.0, s), vd);
            vb = aa(e(&d, &p, &a, 1.0, 0.5, s), e(&ff, &p, &b, 0.5, 1.0, s), vb);
        }
        out[i] = vd.max(vb);
    }
    out
}

/// `lsa_sum`: [`lsa`] without the anti-aliasing term.
pub fn lsa_sum(
    pos: &ImageF64,
    normals: &ImageF64,
    uv: [f64; 2],
    plane: bool,
    eta: (f64, f64),
    octahedral: bool,
) -> [f64; 4] {
    let (eta_min, eta_max) = eta;
    lsa(
        pos,
        normals,
        uv,
        &LsaSettings {
            plane,
            aa: false,
            eta_min,
            eta_max,
            octahedral,
        },
    )
}

/// `lsa_curv_aa`: [`lsa`] on e_curv alone (no e_plane).
pub fn lsa_curv_aa(
    pos: &ImageF64,
    normals: &ImageF64,
    uv: [f64; 2],
    aa: bool,
    eta: (f64, f64),
    octahedral: bool,
) -> [f64; 4] {
    let (eta_min, eta_max) = eta;
    lsa(
        pos,
        normals,
        uv,
        &LsaSettings {
            plane: false,
            aa,
            eta_min,
            eta_max,
            octahedral,
        },
    )
}

/// `lsa_curv`: the base method, e_curv alone without anti-aliasing.
pub fn lsa_curv(pos: &ImageF64, normals: &ImageF64, uv: [f64; 2], eta: (f64, f64), octahedral: bool) -> [f64; 4] {
    let (eta_min, eta_max) = eta;
    lsa(
        pos,
        normals,
        uv,
        &LsaSettings {
            plane: false,
            aa: false,
            eta_min,
            eta_max,
            octahedral,
        },
    )
}

/// The line-density filter (§4.1) on per-direction errors.
pub fn lsa_density(src: &ImageF64, uv: [f64; 2], strength: f64) -> [f64; 4] {
    let (x, y) = src.pixel_of(uv);
    let c = src.load(x, y);
    let mut out = c;
    for (i, (mx, my)) in DIRS.iter().enumerate() {
        let mut lo: f64 = 2.0;
        for k in [-2i64, -1, 1, 2] {
            let (qx, qy) = (x + k * mx, y + k * my);
            if qx >= 0 && qy >= 0 && qx < src.width as i64 && qy < src.height as i64 {
                lo = lo.min(src.load(qx, qy)[i]);
            }
        }
        if lo > 1.5 {
            lo = 0.0;
        }
        out[i] = (c[i] - 2.0 * strength * lo).clamp(0.0, 1.0);
    }
    out
}

/// E(p) of eq. 1 after the remap: the largest of the four direction channels.
pub fn merge(e: [f64; 4]) -> f64 {
    e[0].max(e[1]).max(e[2]).max(e[3])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_extrema_closed_forms_match_sampling() {
        // Deterministic pseudo-random unit normals and offsets.
        let mut s = 12345u64;
        let mut r = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let unit = |v: V3| scale(v, 1.0 / len(v));
        for _ in 0..2000 {
            let na = unit([r(), r(), r()]);
            // Normals within 120° of each other (arcs shorter than π).
            let nb = unit([na[0] + r(), na[1] + r(), na[2] + r()]);
            let d = [r(), r(), r()];
            let (lo, hi) = arc_extrema_sampled(d, na, nb, 20000);
            let (cmin, cmax) = (arc_min(d, na, nb), arc_max(d, na, nb));
            assert!((cmin - lo).abs() < 1e-3, "min {cmin} vs sampled {lo}");
            assert!(
                (cmax - hi).abs() < 1e-6 + 1e-6 * hi.max(1.0),
                "max {cmax} vs sampled {hi}"
            );
        }
    }

    #[test]
    fn sphere_points_have_zero_curvature_error_and_planes_give_kappa_zero() {
        // Three points on a sphere of radius 2 (eqs. 2–5: e_curv = 0 exactly).
        let on = |t: f64| {
            let n = [t.sin(), 0.3, t.cos()];
            let n = scale(n, 1.0 / len(n));
            Texel {
                p: scale(n, 2.0),
                n,
                geo: true,
                inside: true,
            }
        };
        let (c, p, q) = (on(-0.1), on(0.0), on(0.1));
        assert!((kappa(&c, &p) - 0.5).abs() < 1e-12);
        assert!(curv(&c, &p, &q) < 1e-12);
        // Concave: normals pointing inwards give negative curvature.
        let inv = |t: Texel| Texel {
            n: scale(t.n, -1.0),
            ..t
        };
        assert!((kappa(&inv(c), &inv(p)) + 0.5).abs() < 1e-12);
        // A plane: κ = 0, e_curv = 0.
        let flat = |x: f64| Texel {
            p: [x, 0.0, 0.0],
            n: [0.0, 0.0, 1.0],
            geo: true,
            inside: true,
        };
        assert_eq!(kappa(&flat(-1.0), &flat(0.0)), 0.0);
        assert_eq!(curv(&flat(-1.0), &flat(0.0), &flat(1.0)), 0.0);
    }

    #[test]
    fn parallel_planes_miss_e_curv_but_not_e_plane() {
        // Fig. 3: p and control on z = 0, check on the parallel plane z = 0.01.
        let t = |x: f64, z: f64| Texel {
            p: [x, 0.0, z],
            n: [0.0, 0.0, 1.0],
            geo: true,
            inside: true,
        };
        let (c, p, q) = (t(-0.01, 0.0), t(0.0, 0.0), t(0.01, 0.01));
        assert_eq!(curv(&c, &p, &q), 0.0, "e_curv is blind to parallel planes");
        assert_eq!(plane(&c, &p, &q, 1.0, 1.0), 1.0, "e_plane sees them");
        // As printed (both offsets from q) the ratio is 1: no line.
        assert_eq!(plane(&q, &p, &q, 1.0, 1.0), 0.0);
        // The same plane: no line.
        assert_eq!(plane(&c, &p, &t(0.01, 0.0), 1.0, 1.0), 0.0);
    }

    #[test]
    fn eq8_halves_a_lone_outlier_only() {
        assert_eq!(aa(0.0, 1.0, 1.0), 0.5);
        assert_eq!(aa(1.0, 1.0, 1.0), 1.0);
        assert_eq!(aa(-1.0, -1.0, 0.7), 0.7);
        assert_eq!(aa(0.9, 0.2, 0.1), 0.1);
    }
}
