//! The scene's directional lights: `[light]`, and `[light2]` … `[light4]`.

use glam::Vec3;

/// A directional light (like the sun): parallel rays, no falloff.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Unit vector pointing TOWARDS the light, in world space.
    pub direction: Vec3,
    /// RGB multiplier, as written: `"#rrggbb"` is its bytes / 255, the same
    /// convention as colour literals in `.npr` styles.
    pub color: [f32; 3],
    pub intensity: f32,
}

impl Light {
    /// The `Frame` block's (direction, intensity) and (colour, 1) of an
    /// optional light: zeros when the scene does not have it.
    pub fn frame_vectors(light: Option<&Light>) -> ([f32; 4], [f32; 4]) {
        match light {
            Some(l) => {
                let d = l.direction.normalize_or_zero();
                ([d.x, d.y, d.z, l.intensity], [l.color[0], l.color[1], l.color[2], 1.0])
            }
            None => ([0.0; 4], [0.0; 4]),
        }
    }

    /// The direction used when a scene has no `[light]` table: from above,
    /// to the right and in front, so that lit and shadowed sides both show.
    pub fn default_direction() -> Vec3 {
        Vec3::new(0.5, 1.0, 0.8).normalize()
    }
}

impl super::Scene {
    /// `Frame::more_light_dir` and `Frame::more_light_color` for this scene.
    pub fn more_light_frame(&self) -> ([[f32; 4]; 3], [[f32; 4]; 3]) {
        let vectors = self.more_lights.each_ref().map(|l| Light::frame_vectors(l.as_ref()));
        (vectors.map(|v| v.0), vectors.map(|v| v.1))
    }
}

impl Default for Light {
    fn default() -> Self {
        Light {
            direction: Light::default_direction(),
            color: [1.0, 1.0, 1.0],
            intensity: 1.0,
        }
    }
}

/// Centre and radius of the bounding sphere of a box (min, max corners);
/// a unit sphere at the origin for an empty or non-finite box.
fn bounding_sphere((lo, hi): (Vec3, Vec3)) -> (Vec3, f32) {
    if lo.is_finite() && hi.is_finite() && lo.cmple(hi).all() {
        ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1e-3))
    } else {
        (Vec3::ZERO, 1.0)
    }
}

/// The light's camera for `view(light)` passes (shadow-caster depth maps):
/// an orthographic projection along the light's rays whose x, y extent
/// encloses the bounding sphere of `casters` (what the depth pass draws) and
/// whose depth range encloses the bounding sphere of the whole `scene`, so
/// every receiver has a depth in [0, 1]. Points outside the casters' extent
/// cannot be shadowed, so `shadow()` reads them as lit: the map's texels all
/// go to the casters. Boxes are world-space (min, max) corners.
///
/// Clip space follows wgpu: x, y in [−1, 1] (y up), z in [0, 1] increasing
/// away from the light, w = 1. Fitting spheres rather than boxes makes the
/// map independent of the light's azimuth, so a rotating light gives a
/// stable texel size.
pub fn light_view_proj(direction: Vec3, casters: (Vec3, Vec3), scene: (Vec3, Vec3)) -> glam::Mat4 {
    let (centre, radius) = bounding_sphere(casters);
    let (scene_centre, scene_radius) = bounding_sphere(scene);
    let dir = direction.try_normalize().unwrap_or(Light::default_direction());
    // Any up vector not parallel to the rays.
    let up = if dir.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
    // Along the rays, the scene spans [s − R, s + R] around its centre's
    // coordinate s; put the eye one R before the nearest point.
    let s = (scene_centre - centre).dot(-dir);
    let back = scene_radius.max(radius);
    let eye = centre + dir * (back - s + back);
    let view = glam::Mat4::look_at_rh(eye, centre, up);
    let (near, far) = (back * 0.999, 3.0 * back * 1.0005);
    let proj = glam::Mat4::orthographic_rh(-radius, radius, -radius, radius, near, far);
    proj * view
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    #[test]
    fn light_camera_encloses_the_bounds_and_orders_depth_along_the_rays() {
        let bounds = (Vec3::new(-2.0, 0.0, -1.0), Vec3::new(3.0, 2.0, 4.0));
        for dir in [Vec3::new(0.6, 0.9, -0.7), Vec3::Y, -Vec3::Y, Vec3::X] {
            let m = light_view_proj(dir, bounds, bounds);
            for i in 0..8 {
                let c = Vec3::new(
                    if i & 1 == 0 { bounds.0.x } else { bounds.1.x },
                    if i & 2 == 0 { bounds.0.y } else { bounds.1.y },
                    if i & 4 == 0 { bounds.0.z } else { bounds.1.z },
                );
                let p = m * Vec4::new(c.x, c.y, c.z, 1.0);
                assert!((p.w - 1.0).abs() < 1e-6, "orthographic: w = 1");
                assert!(
                    p.x.abs() <= 1.0 + 1e-5 && p.y.abs() <= 1.0 + 1e-5,
                    "{dir} corner {c} -> {p}"
                );
                assert!((0.0..=1.0).contains(&p.z), "{dir} corner {c} -> z {}", p.z);
            }
            // A point nearer the light has a smaller depth.
            let centre = (bounds.0 + bounds.1) * 0.5;
            let near = m * (centre + dir.normalize() * 0.5).extend(1.0);
            let far = m * (centre - dir.normalize() * 0.5).extend(1.0);
            assert!(near.z < far.z, "{dir}: {} !< {}", near.z, far.z);
        }
    }

    #[test]
    fn casters_fill_the_map_while_every_receiver_keeps_a_depth_in_range() {
        // A small caster over a wide ground.
        let caster = (Vec3::new(-0.5, 1.0, -0.5), Vec3::new(0.5, 2.0, 0.5));
        let scene = (Vec3::new(-10.0, 0.0, -10.0), Vec3::new(10.0, 2.0, 10.0));
        for dir in [Vec3::new(0.6, 0.9, -0.7), Vec3::Y, Vec3::new(-1.0, 0.3, 0.2)] {
            let m = light_view_proj(dir, caster, scene);
            // The caster's bounding sphere spans the map: its centre is at the
            // middle and a point one radius off-centre (across the rays) at the edge.
            let centre = m * Vec3::new(0.0, 1.5, 0.0).extend(1.0);
            assert!(centre.x.abs() < 1e-5 && centre.y.abs() < 1e-5, "{dir}: {centre}");
            let r = (Vec3::new(1.0, 1.0, 1.0)).length() * 0.5;
            let side = dir.normalize().any_orthonormal_vector();
            let edge = m * (Vec3::new(0.0, 1.5, 0.0) + side * r).extend(1.0);
            assert!(
                (edge.truncate().truncate().length() - 1.0).abs() < 1e-4,
                "{dir}: {edge}"
            );
            // Every corner of the scene, caster or receiver, has depth in [0, 1].
            for i in 0..8 {
                let c = Vec3::new(
                    if i & 1 == 0 { scene.0.x } else { scene.1.x },
                    if i & 2 == 0 { scene.0.y } else { scene.1.y },
                    if i & 4 == 0 { scene.0.z } else { scene.1.z },
                );
                let z = (m * c.extend(1.0)).z;
                assert!((0.0..=1.0).contains(&z), "{dir}: corner {c} has depth {z}");
            }
        }
    }

    #[test]
    fn degenerate_bounds_and_direction_give_a_finite_camera() {
        let empty = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        assert!(light_view_proj(Vec3::ZERO, empty, empty).is_finite());
        assert!(light_view_proj(Vec3::Y, (Vec3::ONE, Vec3::ONE), (Vec3::ONE, Vec3::ONE)).is_finite());
    }
}
