//! The dynamic 2D pattern tracker of `examples/lib/dynamic_pattern.npr`
//! (Breslav et al. 2007 §3.1–3.2) in f64 on the CPU, for the tests and
//! `npr bench patterns`: the same stratified samples, projected with the
//! same camera, weighted from read-back ID images with the same window and
//! tangent-disc areas, and solved with `npr_stdlib::reference::similarity`.

use glam::{DMat4, DVec2, DVec3};
use npr_runner::readback::TargetImage;
use npr_runner::scene::samples::Samples;
use npr_runner::scene::Mesh;
use npr_stdlib::reference::{id_share, similarity, ImageF64};

/// The r channel of a read-back ID image, in f64.
pub fn ids_f64(t: &TargetImage) -> ImageF64 {
    ImageF64::new(t.width, t.height, |x, y| [t.texel(x, y)[0] as f64, 0.0, 0.0, 1.0])
}

/// A per-vertex attribute (positions, normals) at sample `s`, in f64: the
/// barycentric mix of its triangle's three values.
pub fn at_sample(attribute: &[[f32; 3]], s: &npr_runner::scene::samples::Sample) -> DVec3 {
    let w = [1.0 - s.b1 as f64 - s.b2 as f64, s.b1 as f64, s.b2 as f64];
    s.triangle
        .iter()
        .zip(w)
        .map(|(i, w)| DVec3::from(attribute[*i as usize].map(|x| x as f64)) * w)
        .sum()
}

/// One frame of one object, as the tracker sees it.
pub struct View<'a> {
    pub model: DMat4,
    pub view_proj: DMat4,
    pub ids: &'a ImageF64,
}

/// `world` in px (y down) at `size`, or `None` behind the eye.
fn project(view_proj: DMat4, size: (u32, u32), world: DVec3) -> DVec2 {
    let c = view_proj * world.extend(1.0);
    if c.w <= 1e-8 {
        return DVec2::splat(-1e9);
    }
    DVec2::new(
        (c.x / c.w * 0.5 + 0.5) * size.0 as f64,
        (0.5 - c.y / c.w * 0.5) * size.1 as f64,
    )
}

/// The tracker's (p̄, c̄, z) for object `id` (its `object.id`) between
/// `before` and `now`, with fuzzy visibility of half-width `radius` px and
/// the symmetric (geometric-mean) weight; `None` when nothing is seen in
/// both frames.
pub fn solve(
    mesh: &Mesh,
    samples: &Samples,
    (before, now): (&View, &View),
    size: (u32, u32),
    (id, radius, symmetric): (f64, f64, bool),
) -> Option<([f64; 2], [f64; 2], [f64; 2])> {
    let spacing = samples.spacing as f64 * now.model.determinant().abs().cbrt();
    let normal_matrix = now.model.inverse().transpose();
    let points: Vec<_> = samples
        .samples
        .iter()
        .map(|s| {
            let (p_obj, n_obj) = (at_sample(&mesh.positions, s), at_sample(&mesh.normals, s));
            let n = normal_matrix.transform_vector3(n_obj).normalize_or_zero();
            let (w_now, w_then) = (now.model.transform_point3(p_obj), before.model.transform_point3(p_obj));
            let (c, p) = (
                project(now.view_proj, size, w_now),
                project(before.view_proj, size, w_then),
            );
            let uv = |x: DVec2| [x.x / size.0 as f64, x.y / size.1 as f64];
            let seen = id_share(now.ids, uv(c), id, radius);
            let seen_before = id_share(before.ids, uv(p), id, radius);
            // The same tangent frame as the style: n × (x or y), then n × t1.
            let a = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
            let t1 = n.cross(a).normalize_or_zero();
            let t2 = n.cross(t1);
            let r = spacing * 0.5;
            let area = |vp: DMat4, at: DVec3, centre: DVec2| {
                let e1 = project(vp, size, at + t1 * r) - centre;
                let e2 = project(vp, size, at + t2 * r) - centre;
                std::f64::consts::PI * (e1.x * e2.y - e1.y * e2.x).abs()
            };
            let now_area = area(now.view_proj, w_now, c) * seen;
            let then_area = area(before.view_proj, w_then, p) * seen_before;
            (p.into(), c.into(), (now_area * then_area).sqrt())
        })
        .collect();
    similarity(&points, symmetric)
}
