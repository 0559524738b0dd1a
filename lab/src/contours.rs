//! Analytic contour ground truth: scenes of spheres, cubes, tori and planes
//! that are ray-cast on the CPU in f64 to give the exact pixels a contour
//! renderer should mark, and precision/recall of a rendered line mask
//! against them (within one pixel).
//!
//! The same [`AnalyticScene`] is written as scene TOML for the runner (with
//! primitives tessellated finely enough that the mesh deviates from the
//! analytic surface by well under a tenth of a pixel at 512²), and its
//! camera is the runner's camera (`scene::camera`): right-handed
//! `look_at` with `up` re-orthogonalized, a vertical field of view, pixel
//! centres at (x + ½, y + ½) and image row 0 at the top.
//!
//! What counts as a line ("feature pixel"): both pixels of every pair of
//! 4-neighbours whose centre rays see
//! - geometry and background (silhouettes),
//! - different objects, or different faces of a cube (occlusion edges and
//!   creases), or
//! - the same smooth surface with a jump between them (occluding contours
//!   of a surface in front of itself, e.g. a torus): the segment between
//!   the two pixel centres is bisected in screen space towards the larger
//!   3D gap; a continuous surface's gap vanishes, a jump's does not.
//!
//! So a true feature curve lies within half a pixel of every feature pixel.

use glam::{DQuat, DVec3};
use std::fmt::Write as _;

/// An analytic primitive, in object space as `scene::primitives` builds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    Sphere {
        radius: f64,
    },
    /// Axis-aligned, edge length `size`; faces are creases.
    Cube {
        size: f64,
    },
    /// Around the Y axis.
    Torus {
        major: f64,
        minor: f64,
    },
    /// A square in the XZ plane facing +Y, seen from both sides.
    Plane {
        size: f64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalyticObject {
    pub shape: Shape,
    pub translate: [f64; 3],
    /// Degrees about Y, then X, then Z (the scene file's `rotate`).
    pub rotate_deg: [f64; 3],
}

/// A scene with exact geometry and the runner's camera.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalyticScene {
    pub name: &'static str,
    pub eye: [f64; 3],
    pub target: [f64; 3],
    pub fov_deg: f64,
    pub objects: Vec<AnalyticObject>,
}

/// One ray hit: object index, face (cube faces 0..6, else 0), point, normal.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    pub object: usize,
    pub face: u8,
    pub t: f64,
    pub point: DVec3,
    pub normal: DVec3,
}

fn obj(shape: Shape, translate: [f64; 3], rotate_deg: [f64; 3]) -> AnalyticObject {
    AnalyticObject {
        shape,
        translate,
        rotate_deg,
    }
}

/// The built-in accuracy scenes: a sphere, a cube (creases), a tilted torus
/// (self-occlusion), two parallel planes 5 cm apart (the step e_curv cannot
/// see, Fig. 3 of the LSA paper) and a sphere in front of a plane.
pub fn builtin_scenes() -> Vec<AnalyticScene> {
    // Planes turned to face +Z (towards the cameras): +90° about X.
    let facing = [90.0, 0.0, 0.0];
    vec![
        AnalyticScene {
            name: "sphere",
            eye: [0.0, 0.8, 4.0],
            target: [0.0, 0.0, 0.0],
            fov_deg: 40.0,
            objects: vec![obj(Shape::Sphere { radius: 1.0 }, [0.0; 3], [0.0; 3])],
        },
        AnalyticScene {
            name: "cube",
            eye: [0.0, 0.6, 4.0],
            target: [0.0, 0.0, 0.0],
            fov_deg: 40.0,
            objects: vec![obj(Shape::Cube { size: 1.3 }, [0.0; 3], [25.0, 35.0, 0.0])],
        },
        AnalyticScene {
            name: "torus",
            eye: [0.0, 0.0, 4.0],
            target: [0.0, 0.0, 0.0],
            fov_deg: 40.0,
            objects: vec![obj(
                Shape::Torus {
                    major: 0.9,
                    minor: 0.32,
                },
                [0.0; 3],
                [20.0, 0.0, 0.0],
            )],
        },
        AnalyticScene {
            name: "parallel_planes",
            eye: [0.4, 0.3, 4.0],
            target: [0.0, 0.0, 0.0],
            fov_deg: 40.0,
            objects: vec![
                obj(Shape::Plane { size: 40.0 }, [0.0, 0.0, 0.0], facing),
                // Covers x ≥ 0, 5 cm in front: one vertical step line.
                obj(Shape::Plane { size: 40.0 }, [20.0, 0.0, 0.05], facing),
            ],
        },
        AnalyticScene {
            name: "sphere_on_plane",
            eye: [0.0, 0.3, 4.0],
            target: [0.0, 0.0, 0.0],
            fov_deg: 40.0,
            objects: vec![
                obj(Shape::Plane { size: 40.0 }, [0.0, 0.0, 0.0], facing),
                obj(Shape::Sphere { radius: 0.7 }, [0.2, 0.0, 0.9], [0.0; 3]),
            ],
        },
    ]
}

impl AnalyticObject {
    fn rotation(&self) -> DQuat {
        let r = self.rotate_deg.map(f64::to_radians);
        // As the scene loader: Rz · Rx · Ry (a vertex turns about Y first).
        DQuat::from_rotation_z(r[2]) * DQuat::from_rotation_x(r[0]) * DQuat::from_rotation_y(r[1])
    }

    /// Nearest hit with t > `t_min` of the world ray `o + t·d`.
    fn intersect(&self, o: DVec3, d: DVec3, t_min: f64) -> Option<(f64, u8, DVec3)> {
        let rot = self.rotation();
        let inv = rot.inverse();
        let lo = inv * (o - DVec3::from(self.translate));
        let ld = inv * d;
        let (t, face, n) = match self.shape {
            Shape::Sphere { radius } => sphere_hit(lo, ld, radius, t_min)?,
            Shape::Cube { size } => cube_hit(lo, ld, size / 2.0, t_min)?,
            Shape::Torus { major, minor } => torus_hit(lo, ld, major, minor, t_min)?,
            Shape::Plane { size } => {
                if ld.y.abs() < 1e-300 {
                    return None;
                }
                let t = -lo.y / ld.y;
                let p = lo + ld * t;
                if t <= t_min || p.x.abs() > size / 2.0 || p.z.abs() > size / 2.0 {
                    return None;
                }
                (t, 0, DVec3::Y)
            }
        };
        Some((t, face, rot * n))
    }
}

fn sphere_hit(o: DVec3, d: DVec3, r: f64, t_min: f64) -> Option<(f64, u8, DVec3)> {
    let a = d.dot(d);
    let b = o.dot(d);
    let c = o.dot(o) - r * r;
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let t = [(-b - s) / a, (-b + s) / a].into_iter().find(|t| *t > t_min)?;
    Some((t, 0, (o + d * t) / r))
}

fn cube_hit(o: DVec3, d: DVec3, h: f64, t_min: f64) -> Option<(f64, u8, DVec3)> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut axis = 0;
    for i in 0..3 {
        if d[i].abs() < 1e-300 {
            if o[i].abs() > h {
                return None;
            }
            continue;
        }
        let (a, b) = ((-h - o[i]) / d[i], (h - o[i]) / d[i]);
        let (a, b) = (a.min(b), a.max(b));
        if a > t0 {
            t0 = a;
            axis = i;
        }
        t1 = t1.min(b);
    }
    if t0 > t1 || t0 <= t_min {
        return None;
    }
    let p = o + d * t0;
    let mut n = DVec3::ZERO;
    n[axis] = p[axis].signum();
    let face = (axis * 2) as u8 + u8::from(n[axis] < 0.0);
    Some((t0, face, n))
}

/// Sphere tracing on the torus's exact distance function. Near-misses within
/// 1e-10 of the surface count as hits, which moves the silhouette by far
/// less than a pixel.
fn torus_hit(o: DVec3, d: DVec3, major: f64, minor: f64, t_min: f64) -> Option<(f64, u8, DVec3)> {
    let len = d.length();
    let u = d / len;
    let sdf = |p: DVec3| (DVec3::new(p.x, 0.0, p.z).length() - major).hypot(p.y) - minor;
    // Skip to the bounding sphere.
    let bound = major + minor;
    let b = o.dot(u);
    let c = o.dot(o) - bound * bound;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let mut t = (-b - disc.sqrt()).max(t_min * len).max(0.0);
    let t_end = -b + disc.sqrt();
    for _ in 0..20000 {
        let p = o + u * t;
        let s = sdf(p);
        if s < 1e-10 {
            let ring = DVec3::new(p.x, 0.0, p.z).normalize_or_zero() * major;
            return Some((t / len, 0, (p - ring).normalize_or_zero()));
        }
        t += s;
        if t > t_end {
            return None;
        }
    }
    None
}

impl AnalyticScene {
    fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let eye = DVec3::from(self.eye);
        let forward = (DVec3::from(self.target) - eye).normalize();
        let right = forward.cross(DVec3::Y).normalize();
        let up = right.cross(forward);
        (forward, right, up)
    }

    /// The ray through the continuous pixel position (sx, sy) (pixel centres
    /// at half-integers) of a `width`×`height` image.
    pub fn ray(&self, width: u32, height: u32, sx: f64, sy: f64) -> (DVec3, DVec3) {
        let (forward, right, up) = self.basis();
        let tan_half = (self.fov_deg.to_radians() / 2.0).tan();
        let aspect = f64::from(width) / f64::from(height);
        let nx = 2.0 * sx / f64::from(width) - 1.0;
        let ny = 1.0 - 2.0 * sy / f64::from(height);
        let dir = forward + right * (nx * tan_half * aspect) + up * (ny * tan_half);
        (DVec3::from(self.eye), dir)
    }

    /// The same scene with every object, the eye and the target moved by
    /// `offset` metres: identical images in exact arithmetic, so any change
    /// in a render measures precision lost far from the world origin.
    pub fn translated(&self, offset: [f64; 3]) -> AnalyticScene {
        let add = |a: [f64; 3]| [a[0] + offset[0], a[1] + offset[1], a[2] + offset[2]];
        AnalyticScene {
            eye: add(self.eye),
            target: add(self.target),
            objects: self
                .objects
                .iter()
                .map(|o| AnalyticObject {
                    translate: add(o.translate),
                    ..*o
                })
                .collect(),
            ..self.clone()
        }
    }

    /// The nearest surface along the ray through (sx, sy), if any.
    pub fn cast(&self, width: u32, height: u32, sx: f64, sy: f64) -> Option<Hit> {
        let (o, d) = self.ray(width, height, sx, sy);
        let mut best: Option<Hit> = None;
        for (i, object) in self.objects.iter().enumerate() {
            if let Some((t, face, normal)) = object.intersect(o, d, 1e-9) {
                if best.is_none_or(|b| t < b.t) {
                    best = Some(Hit {
                        object: i,
                        face,
                        t,
                        point: o + d * t,
                        normal,
                    });
                }
            }
        }
        best
    }

    /// The scene as runner TOML, tessellated finely.
    pub fn to_toml(&self) -> String {
        let v = |a: [f64; 3]| format!("[{:?}, {:?}, {:?}]", a[0], a[1], a[2]);
        let mut s = format!(
            "# Analytic contour scene `{}`, written by npr_lab::contours::AnalyticScene::to_toml\n# (ground truth: the same scene ray-cast in f64). Do not edit by hand.\n[camera]\nposition = {}\ntarget = {}\nfov = {:?}\nnear = 0.1\nfar = 100.0\n\n[light]\ndirection = [0.5, 1.0, 0.7]\n",
            self.name,
            v(self.eye),
            v(self.target),
            self.fov_deg
        );
        for (i, o) in self.objects.iter().enumerate() {
            let prim = match o.shape {
                Shape::Sphere { radius } => {
                    format!("{{ kind = \"sphere\", radius = {radius:?}, segments = 512, rings = 256 }}")
                }
                Shape::Cube { size } => format!("{{ kind = \"cube\", size = {size:?} }}"),
                Shape::Torus { major, minor } => {
                    format!("{{ kind = \"torus\", major = {major:?}, minor = {minor:?}, segments = 512, sides = 256 }}")
                }
                Shape::Plane { size } => format!("{{ kind = \"plane\", size = {size:?}, subdivisions = 1 }}"),
            };
            let _ = write!(
                s,
                "\n[[object]]\nname = \"o{i}\"\nprimitive = {prim}\ntranslate = {}\nrotate = {}\n",
                v(o.translate),
                v(o.rotate_deg)
            );
        }
        s
    }

    /// The scene for the runner (parsed from [`AnalyticScene::to_toml`]).
    pub fn scene(
        &self,
        sources: &mut npr_diag::SourceMap,
    ) -> Result<npr_runner::scene::Scene, Vec<npr_diag::Diagnostic>> {
        let text = self.to_toml();
        let file = sources.add(format!("{}.toml", self.name), text.clone());
        npr_runner::scene::parse_scene(&text, file, std::path::Path::new("."))
    }

    /// The exact feature pixels of a `width`×`height` render.
    pub fn truth(&self, width: u32, height: u32) -> Mask {
        let (w, h) = (width as usize, height as usize);
        let hits: Vec<Option<Hit>> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| self.cast(width, height, x as f64 + 0.5, y as f64 + 0.5))
            .collect();
        let mut mask = Mask::new(width, height);
        let pixel_angle = 2.0 * (self.fov_deg.to_radians() / 2.0).tan() / f64::from(height);
        for y in 0..h {
            for x in 0..w {
                for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                    if nx >= w || ny >= h {
                        continue;
                    }
                    let a = (x as f64 + 0.5, y as f64 + 0.5);
                    let b = (nx as f64 + 0.5, ny as f64 + 0.5);
                    if self.feature_between(width, height, a, b, hits[y * w + x], hits[ny * w + nx], pixel_angle) {
                        mask.set(x as u32, y as u32);
                        mask.set(nx as u32, ny as u32);
                    }
                }
            }
        }
        mask
    }

    #[allow(clippy::too_many_arguments)]
    fn feature_between(
        &self,
        width: u32,
        height: u32,
        mut a: (f64, f64),
        mut b: (f64, f64),
        ha: Option<Hit>,
        hb: Option<Hit>,
        pixel_angle: f64,
    ) -> bool {
        let (Some(mut ha), Some(mut hb)) = (ha, hb) else {
            return ha.is_some() != hb.is_some();
        };
        let same = |p: &Hit, q: &Hit| p.object == q.object && p.face == q.face;
        if !same(&ha, &hb) {
            return true;
        }
        // A continuous surface seen at an angle keeps neighbouring hits
        // within a few footprints; only larger gaps need bisecting.
        let eye = DVec3::from(self.eye);
        let footprint = (ha.point - eye).length().max((hb.point - eye).length()) * pixel_angle;
        if (ha.point - hb.point).length() < 4.0 * footprint {
            return false;
        }
        for _ in 0..40 {
            let m = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
            let Some(hm) = self.cast(width, height, m.0, m.1) else {
                return true;
            };
            if !same(&hm, &ha) {
                return true;
            }
            if (hm.point - ha.point).length() >= (hb.point - hm.point).length() {
                b = m;
                hb = hm;
            } else {
                a = m;
                ha = hm;
            }
        }
        // After 40 halvings a continuous surface leaves a gap of ~1e-12 of
        // the original; a jump keeps (at least) its depth difference.
        (ha.point - hb.point).length() > 1e-6
    }
}

/// A binary image: which pixels hold a line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mask {
    pub width: u32,
    pub height: u32,
    pub bits: Vec<bool>,
}

impl Mask {
    pub fn new(width: u32, height: u32) -> Mask {
        Mask {
            width,
            height,
            bits: vec![false; (width * height) as usize],
        }
    }

    /// Pixels where `f(x, y)` holds.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> bool) -> Mask {
        let mut m = Mask::new(width, height);
        for y in 0..height {
            for x in 0..width {
                if f(x, y) {
                    m.set(x, y);
                }
            }
        }
        m
    }

    pub fn get(&self, x: u32, y: u32) -> bool {
        self.bits[(y * self.width + x) as usize]
    }

    pub fn set(&mut self, x: u32, y: u32) {
        self.bits[(y * self.width + x) as usize] = true;
    }

    pub fn count(&self) -> usize {
        self.bits.iter().filter(|b| **b).count()
    }

    /// Grown by `r` pixels (Chebyshev distance: a (2r+1)² square).
    pub fn dilate(&self, r: u32) -> Mask {
        let r = r as i64;
        let (w, h) = (self.width as i64, self.height as i64);
        Mask::from_fn(self.width, self.height, |x, y| {
            (-r..=r).any(|dy| {
                (-r..=r).any(|dx| {
                    let (qx, qy) = (x as i64 + dx, y as i64 + dy);
                    qx >= 0 && qy >= 0 && qx < w && qy < h && self.get(qx as u32, qy as u32)
                })
            })
        })
    }
}

/// Precision and recall of a predicted line mask against the truth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accuracy {
    /// Predicted line pixels within `tolerance` px of a true feature pixel,
    /// as a fraction of all predicted line pixels (1 when none is predicted).
    pub precision: f64,
    /// True feature pixels within `tolerance` px of a predicted line pixel,
    /// as a fraction of all true feature pixels (1 when there are none).
    pub recall: f64,
    pub predicted: usize,
    pub truth: usize,
}

/// Precision/recall with a tolerance of `tolerance` pixels (Chebyshev).
pub fn accuracy(predicted: &Mask, truth: &Mask, tolerance: u32) -> Accuracy {
    let near_truth = truth.dilate(tolerance);
    let near_pred = predicted.dilate(tolerance);
    let p = predicted.count();
    let t = truth.count();
    let tp_p = predicted
        .bits
        .iter()
        .zip(&near_truth.bits)
        .filter(|(a, b)| **a && **b)
        .count();
    let tp_t = truth
        .bits
        .iter()
        .zip(&near_pred.bits)
        .filter(|(a, b)| **a && **b)
        .count();
    Accuracy {
        precision: if p == 0 { 1.0 } else { tp_p as f64 / p as f64 },
        recall: if t == 0 { 1.0 } else { tp_t as f64 / t as f64 },
        predicted: p,
        truth: t,
    }
}

/// The line pixels of a rendered ink-on-paper image: red below `level`
/// (the example styles mix a light paper with a dark ink by the line value).
pub fn ink_mask(image: &npr_runner::TargetImage, level: f32) -> Mask {
    Mask::from_fn(image.width, image.height, |x, y| image.texel(x, y)[0] < level)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_silhouette_is_where_the_geometry_says() {
        let s = &builtin_scenes()[0];
        // Centre ray hits the unit sphere at distance |eye| − 1.
        let h = s.cast(64, 64, 32.0, 32.0).expect("hit");
        let eye = DVec3::from(s.eye);
        assert!(((h.point - eye).length() - (eye.length() - 1.0)).abs() < 1e-9);
        assert!((h.normal.length() - 1.0).abs() < 1e-12);
        // A corner ray misses.
        assert!(s.cast(64, 64, 0.5, 0.5).is_none());
        let truth = s.truth(64, 64);
        assert!(truth.count() > 0 && !truth.get(32, 32) && !truth.get(0, 0));
    }

    #[test]
    fn torus_self_occlusion_is_a_feature_but_its_smooth_surface_is_not() {
        let s = builtin_scenes().into_iter().find(|s| s.name == "torus").expect("torus");
        let truth = s.truth(96, 96);
        // More feature pixels than the outer silhouette and the hole alone:
        // tilted by 20°, the near tube hides part of the far one.
        let outline = Mask::from_fn(96, 96, |x, y| {
            let here = s.cast(96, 96, x as f64 + 0.5, y as f64 + 0.5).is_some();
            [(1i64, 0i64), (0, 1), (-1, 0), (0, -1)].iter().any(|(dx, dy)| {
                let (qx, qy) = (x as i64 + dx, y as i64 + dy);
                (0..96).contains(&qx)
                    && (0..96).contains(&qy)
                    && s.cast(96, 96, qx as f64 + 0.5, qy as f64 + 0.5).is_some() != here
            })
        });
        assert!(
            truth.count() > outline.count() + 20,
            "{} vs {}",
            truth.count(),
            outline.count()
        );
    }

    #[test]
    fn translated_scenes_have_the_same_ground_truth() {
        // f64 keeps ~1e-12 relative precision: 10 km away the feature pixels
        // are those at the origin.
        for s in builtin_scenes() {
            let far = s.translated([6000.0, 4800.0, 6400.0]);
            assert_ne!(far.eye, s.eye);
            assert_eq!(far.truth(48, 40), s.truth(48, 40), "{}", s.name);
        }
    }

    #[test]
    fn accuracy_counts_within_one_pixel() {
        let truth = Mask::from_fn(10, 10, |x, _| x == 4);
        let shifted = Mask::from_fn(10, 10, |x, _| x == 5);
        let far = Mask::from_fn(10, 10, |x, _| x == 7);
        assert_eq!(accuracy(&shifted, &truth, 1).precision, 1.0);
        assert_eq!(accuracy(&shifted, &truth, 1).recall, 1.0);
        assert_eq!(accuracy(&far, &truth, 1).precision, 0.0);
        assert_eq!(accuracy(&far, &truth, 1).recall, 0.0);
        let half = Mask::from_fn(10, 10, |x, y| x == 4 && y < 5);
        assert_eq!(accuracy(&half, &truth, 0).recall, 0.5);
    }
}
