//! The studio's orbit/zoom camera: a drag on the page turns the camera
//! about the scene camera's target, the wheel moves it nearer or farther,
//! and "reset to the scene's camera" drops the override.
//!
//! The orbit is relative to the scene camera's pose at the view's time
//! (yaw about the camera's up, pitch about its right, distance scaled by
//! `zoom`), so an animated camera is orbited where it is, and everything
//! else of the scene camera (field of view, near, far, stereo separation)
//! is kept. The result is a still camera at that pose.

use glam::{Quat, Vec3};
use npr_runner::scene::{Camera, CameraKey, Scene};

/// Pitch stays this far from straight up or down, where the view's up is
/// undefined.
const MAX_PITCH_DEG: f64 = 89.0;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orbit {
    /// Degrees about the camera's up (positive turns the camera to its right).
    pub yaw_deg: f64,
    /// Degrees about the camera's right (positive raises the camera).
    pub pitch_deg: f64,
    /// Distance to the target, as a factor of the scene camera's (> 0).
    pub zoom: f64,
}

impl Orbit {
    /// From the page's JSON `{"yaw": deg, "pitch": deg, "zoom": factor}`;
    /// `None` when a field is missing or not finite, or the zoom is not
    /// positive.
    pub fn from_json(v: &serde_json::Value) -> Option<Orbit> {
        let get = |k: &str| v[k].as_f64().filter(|x| x.is_finite());
        let o = Orbit {
            yaw_deg: get("yaw")?,
            pitch_deg: get("pitch")?.clamp(-MAX_PITCH_DEG, MAX_PITCH_DEG),
            zoom: get("zoom").filter(|z| *z > 0.0)?,
        };
        Some(o)
    }

    pub fn to_json(self) -> serde_json::Value {
        serde_json::json!({ "yaw": self.yaw_deg, "pitch": self.pitch_deg, "zoom": self.zoom })
    }

    /// `camera` orbited at `time_s`: a still camera with the same lens.
    pub fn camera(&self, camera: &Camera, time_s: f64) -> Camera {
        let pose = camera.pose(time_s);
        let offset = pose.eye - pose.target;
        let up = pose.up.normalize_or(Vec3::Y);
        let forward = (-offset).normalize_or(Vec3::NEG_Z);
        let right = forward.cross(up).normalize_or(Vec3::X);
        // Pitch first (about the right axis), limited so the view never
        // passes over the pole, then yaw about the up axis.
        let elevation = (offset.normalize_or(Vec3::Z).dot(up) as f64).asin().to_degrees();
        let pitch = (elevation + self.pitch_deg).clamp(-MAX_PITCH_DEG, MAX_PITCH_DEG) - elevation;
        // Both rotations by the right-hand rule: a positive yaw about up
        // moves the eye to the camera's right, a negative turn about right
        // raises it.
        let turned = Quat::from_axis_angle(up, (self.yaw_deg as f32).to_radians())
            * Quat::from_axis_angle(right, (-pitch as f32).to_radians())
            * offset;
        let position = pose.target + turned * self.zoom as f32;
        let key = CameraKey {
            time_s: 0.0,
            position,
            target: pose.target,
            roll_rad: 0.0,
        };
        Camera::with_keys(vec![key], camera).unwrap_or_else(|| camera.clone())
    }

    /// `scene` with its camera orbited at `time_s`.
    pub fn scene(&self, scene: &Scene, time_s: f64) -> Scene {
        let mut s = scene.clone();
        s.camera = self.camera(&scene.camera, time_s);
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn no_turn_and_unit_zoom_is_the_scene_camera() {
        let cam = Camera::looking_at(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO);
        let o = Orbit {
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            zoom: 1.0,
        };
        let p = o.camera(&cam, 0.0).pose(0.0);
        assert!(close(p.eye, Vec3::new(0.0, 1.0, 4.0)), "{:?}", p.eye);
        assert!(close(p.target, Vec3::ZERO));
        assert_eq!(p.fov_y_rad, cam.pose(0.0).fov_y_rad);
    }

    #[test]
    fn yaw_turns_about_the_up_axis_and_zoom_scales_the_distance() {
        let cam = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
        let o = Orbit {
            yaw_deg: 90.0,
            pitch_deg: 0.0,
            zoom: 0.5,
        };
        let p = o.camera(&cam, 0.0).pose(0.0);
        // Turning to the camera's right: from +z round to +x, at half the distance.
        assert!(close(p.eye, Vec3::new(2.0, 0.0, 0.0)), "{:?}", p.eye);
    }

    #[test]
    fn pitch_stops_short_of_the_pole() {
        let cam = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
        let o = Orbit {
            yaw_deg: 0.0,
            pitch_deg: 170.0,
            zoom: 1.0,
        };
        let p = o.camera(&cam, 0.0).pose(0.0);
        let elevation = (p.eye.normalize().dot(Vec3::Y) as f64).asin().to_degrees();
        assert!((elevation - MAX_PITCH_DEG).abs() < 1e-3, "{elevation}");
        assert!((p.eye.length() - 4.0).abs() < 1e-4);
    }
}
