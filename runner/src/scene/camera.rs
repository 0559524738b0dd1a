//! The camera: keyframed eye and target, a perspective or orthographic
//! lens (decision 0062), and an optional interpupillary distance that makes
//! it stereo.

use glam::{Mat4, Vec3};

/// Where the camera is at one moment of an animation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraKey {
    pub time_s: f64,
    pub position: Vec3,
    pub target: Vec3,
    /// Roll about the view direction, radians (positive turns the image
    /// counter-clockwise on screen): interpolated like the other fields.
    pub roll_rad: f32,
}

/// A camera whose eye and target may move over time: perspective, or
/// orthographic when `ortho_height_m` is set.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// At least one key, sorted by strictly increasing time. A still camera
    /// has exactly one.
    keys: Vec<CameraKey>,
    pub up: Vec3,
    pub fov_y_rad: f32,
    pub near: f32,
    pub far: f32,
    /// Interpupillary distance in metres; `Some` makes the camera stereo.
    pub ipd_m: Option<f32>,
    /// The view's height in metres; `Some` makes the camera orthographic
    /// (`fov_y_rad` is then unused).
    pub ortho_height_m: Option<f32>,
}

/// The camera at one instant: everything needed for view and projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraPose {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub fov_y_rad: f32,
    pub near: f32,
    pub far: f32,
    pub ipd_m: Option<f32>,
    pub ortho_height_m: Option<f32>,
}

impl Camera {
    /// A still camera with a 40° vertical field of view, near 0.1, far 100.
    pub fn looking_at(position: Vec3, target: Vec3) -> Camera {
        Camera {
            keys: vec![CameraKey {
                time_s: 0.0,
                position,
                target,
                roll_rad: 0.0,
            }],
            up: Vec3::Y,
            fov_y_rad: 40f32.to_radians(),
            near: 0.1,
            far: 100.0,
            ipd_m: None,
            ortho_height_m: None,
        }
    }

    /// A keyframed camera. Keys are sorted by time; of keys with equal times
    /// only the last is kept. Returns `None` for an empty key list.
    pub fn with_keys(mut keys: Vec<CameraKey>, template: &Camera) -> Option<Camera> {
        keys.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
        // Keep the last of equal times: scanning in reverse keeps the first seen.
        keys.reverse();
        keys.dedup_by(|later, earlier| later.time_s == earlier.time_s);
        keys.reverse();
        if keys.is_empty() {
            return None;
        }
        Some(Camera {
            keys,
            ..template.clone()
        })
    }

    pub fn keys(&self) -> &[CameraKey] {
        &self.keys
    }

    pub fn is_stereo(&self) -> bool {
        self.ipd_m.is_some()
    }

    pub fn is_orthographic(&self) -> bool {
        self.ortho_height_m.is_some()
    }

    /// The time of the last key: how long the camera animation lasts.
    pub fn duration_s(&self) -> f64 {
        match (self.keys.first(), self.keys.last()) {
            (Some(first), Some(last)) => last.time_s - first.time_s,
            _ => 0.0,
        }
    }

    /// The pose at `time_s`: position and target interpolated linearly
    /// between the surrounding keys, held at the first/last key outside them.
    pub fn pose(&self, time_s: f64) -> CameraPose {
        let (position, target, roll) = self.interpolate(time_s);
        // Roll turns `up` about the view direction: a positive roll tilts
        // the camera's up to its right, so the image turns counter-clockwise.
        let forward = (target - position).try_normalize().unwrap_or(Vec3::NEG_Z);
        let up = if roll == 0.0 {
            self.up
        } else {
            glam::Quat::from_axis_angle(forward, roll) * self.up
        };
        CameraPose {
            eye: position,
            target,
            up,
            fov_y_rad: self.fov_y_rad,
            near: self.near,
            far: self.far,
            ipd_m: self.ipd_m,
            ortho_height_m: self.ortho_height_m,
        }
    }

    fn interpolate(&self, time_s: f64) -> (Vec3, Vec3, f32) {
        let Some(first) = self.keys.first() else {
            // Unreachable through the constructors; a harmless default.
            return (Vec3::Z, Vec3::ZERO, 0.0);
        };
        // NaN time compares false everywhere and lands on the first key.
        let after = self.keys.partition_point(|key| key.time_s <= time_s);
        if after == 0 {
            return (first.position, first.target, first.roll_rad);
        }
        let before = &self.keys[after - 1];
        let Some(next) = self.keys.get(after) else {
            return (before.position, before.target, before.roll_rad);
        };
        let fraction = ((time_s - before.time_s) / (next.time_s - before.time_s)) as f32;
        (
            before.position.lerp(next.position, fraction),
            before.target.lerp(next.target, fraction),
            before.roll_rad + (next.roll_rad - before.roll_rad) * fraction,
        )
    }
}

impl CameraPose {
    /// Unit vector from the eye towards the target (-Z if they coincide).
    pub fn forward(&self) -> Vec3 {
        (self.target - self.eye).try_normalize().unwrap_or(Vec3::NEG_Z)
    }

    /// Unit vector to the camera's right. When `up` is parallel to the view
    /// direction (looking straight down, say) another up is substituted, so a
    /// keyframed path through such a pose never yields NaN.
    pub fn right(&self) -> Vec3 {
        let forward = self.forward();
        [self.up, Vec3::Y, Vec3::Z, Vec3::X]
            .into_iter()
            .find_map(|up| forward.cross(up).try_normalize())
            .unwrap_or(Vec3::X)
    }

    /// The camera's up, orthogonal to forward and right.
    pub fn true_up(&self) -> Vec3 {
        self.right().cross(self.forward())
    }

    /// Eye position: eye 0 is the left eye (or the only one), eye 1 the
    /// right. Stereo eyes sit ±ipd/2 along the camera's right axis.
    pub fn position(&self, eye_index: u32) -> Vec3 {
        self.eye + self.eye_offset(eye_index)
    }

    /// World-to-view matrix (right-handed, looking down -Z). Stereo eyes are
    /// parallel (no toe-in): the target moves with the eye.
    pub fn view(&self, eye_index: u32) -> Mat4 {
        let offset = self.eye_offset(eye_index);
        Mat4::look_at_rh(self.eye + offset, self.target + offset, self.true_up())
    }

    /// World-to-view matrix of the centre camera, between the stereo eyes
    /// (the mono view): what both eyes share for view-independent choices.
    pub fn center_view(&self) -> Mat4 {
        Mat4::look_at_rh(self.eye, self.target, self.true_up())
    }

    /// Right-handed perspective, or orthographic `ortho_height_m` high and
    /// `aspect` times as wide, with wgpu's 0..1 depth range.
    pub fn projection(&self, aspect: f32) -> Mat4 {
        match self.ortho_height_m {
            None => Mat4::perspective_rh(self.fov_y_rad, aspect, self.near, self.far),
            Some(height) => {
                let (half_w, half_h) = (0.5 * height * aspect, 0.5 * height);
                Mat4::orthographic_rh(-half_w, half_w, -half_h, half_h, self.near, self.far)
            }
        }
    }

    /// Eye `eye_index` in homogeneous world coordinates: (position, 1) for
    /// a perspective camera, the point at infinity (−forward, 0) behind an
    /// orthographic one. A face faces this eye where n · (e.xyz − p·e.w) > 0,
    /// and it transforms with any matrix as a point does.
    pub fn homogeneous_eye(&self, eye_index: u32) -> glam::Vec4 {
        match self.ortho_height_m {
            None => self.position(eye_index).extend(1.0),
            Some(_) => (-self.forward()).extend(0.0),
        }
    }

    fn eye_offset(&self, eye_index: u32) -> Vec3 {
        match self.ipd_m {
            None => Vec3::ZERO,
            Some(ipd) => {
                let side = if eye_index == 0 { -0.5 } else { 0.5 };
                self.right() * (side * ipd)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_positive_roll_tilts_up_to_the_right_and_interpolates() {
        let mut camera = Camera::looking_at(Vec3::ZERO, Vec3::NEG_Z);
        camera.keys[0].roll_rad = 0.0;
        camera.keys.push(CameraKey {
            time_s: 1.0,
            position: Vec3::ZERO,
            target: Vec3::NEG_Z,
            roll_rad: std::f32::consts::FRAC_PI_2,
        });
        let up = camera.pose(1.0).true_up();
        assert!((up - Vec3::X).length() < 1e-5, "rolled 90°: up {up}");
        let half = camera.pose(0.5).true_up();
        let want = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert!((half - want).length() < 1e-5, "rolled 45° halfway: up {half}");
    }

    fn key(time_s: f64, x: f32) -> CameraKey {
        CameraKey {
            time_s,
            position: Vec3::new(x, 0.0, 5.0),
            target: Vec3::new(x, 0.0, 0.0),
            roll_rad: 0.0,
        }
    }

    #[test]
    fn keys_are_sorted_and_equal_times_keep_the_last() {
        let template = Camera::looking_at(Vec3::Z, Vec3::ZERO);
        let camera =
            Camera::with_keys(vec![key(2.0, 2.0), key(0.0, 0.0), key(2.0, 3.0)], &template).expect("non-empty");
        assert_eq!(camera.keys().len(), 2);
        assert_eq!(camera.keys()[1].position.x, 3.0);
        assert!(Camera::with_keys(vec![], &template).is_none());
    }

    #[test]
    fn looking_straight_down_the_up_axis_gives_a_finite_view() {
        let pose = Camera::looking_at(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO).pose(0.0);
        assert!(pose.view(0).is_finite());
        assert!((pose.right().length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn nan_time_is_the_first_key() {
        let template = Camera::looking_at(Vec3::Z, Vec3::ZERO);
        let camera = Camera::with_keys(vec![key(0.0, 0.0), key(1.0, 1.0)], &template).expect("keys");
        assert_eq!(camera.pose(f64::NAN).eye.x, 0.0);
    }
}
