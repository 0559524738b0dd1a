//! `npr view`'s cameras: orbit (turn about a target, zoom, pan) and fly
//! (move through the scene with the keys, look with the mouse), as pure
//! math in f64 on a pose, so the view matrices are tested without a
//! window.
//!
//! Both start from the scene camera's pose at the moment the user first
//! moves (an animated camera is taken where it is) and give a still
//! camera with the scene camera's lens (field of view, near, far, stereo
//! separation). Angles are measured in a frame whose y axis is the scene
//! camera's `up`, so a scene with another up orbits about it. Until the
//! user moves, the view shows the scene camera itself, keys and all.

use glam::{DQuat, DVec3};
use npr_runner::scene::{Camera, CameraKey, CameraPose};

/// Pitch stays this far from straight up or down, where the view's up is
/// undefined (radians: 89°).
pub const MAX_PITCH: f64 = 89.0 * std::f64::consts::PI / 180.0;
/// Radians turned per pixel the mouse moves (a 360-pixel drag turns 180°).
pub const RADIANS_PER_PIXEL: f64 = std::f64::consts::PI / 360.0;
/// Each wheel step (one line) moves the orbit this factor nearer.
pub const ZOOM_PER_STEP: f64 = 0.9;
/// The fly camera crosses its starting distance to the target in this
/// many seconds at normal speed; Shift makes it `FAST` times faster.
pub const FLY_SECONDS_ACROSS: f64 = 2.0;
pub const FAST: f64 = 4.0;

/// A pose in f64: where the eye is, what it looks at, and the up vector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub eye: DVec3,
    pub target: DVec3,
    pub up: DVec3,
}

impl Pose {
    pub fn of(pose: &CameraPose) -> Pose {
        Pose {
            eye: pose.eye.as_dvec3(),
            target: pose.target.as_dvec3(),
            up: pose.up.as_dvec3().normalize_or(DVec3::Y),
        }
    }

    /// A still camera at this pose with `lens`'s field of view, near, far
    /// and stereo separation.
    pub fn camera(&self, lens: &Camera) -> Camera {
        let key = CameraKey {
            time_s: 0.0,
            position: self.eye.as_vec3(),
            target: self.target.as_vec3(),
            roll_rad: 0.0,
        };
        let mut camera = Camera::with_keys(vec![key], lens).unwrap_or_else(|| lens.clone());
        camera.up = self.up.as_vec3();
        camera
    }
}

/// The unit direction at `yaw` (about +y, from +z towards +x) and `pitch`
/// (above the xz plane), in the frame whose y is up.
fn direction(yaw: f64, pitch: f64) -> DVec3 {
    DVec3::new(pitch.cos() * yaw.sin(), pitch.sin(), pitch.cos() * yaw.cos())
}

/// Yaw and pitch of a direction (`direction`'s inverse; `d` need not be unit).
fn angles(d: DVec3) -> (f64, f64) {
    let d = d.normalize_or(DVec3::Z);
    (d.x.atan2(d.z), d.y.clamp(-1.0, 1.0).asin())
}

/// The rotation from the frame whose y is up to the world (y to `up`).
fn frame(up: DVec3) -> DQuat {
    DQuat::from_rotation_arc(DVec3::Y, up.normalize_or(DVec3::Y))
}

/// Turn about a target: the eye is at `distance` from `target` in the
/// direction (`yaw`, `pitch`), measured in the up frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orbit {
    pub target: DVec3,
    pub distance: f64,
    pub yaw: f64,
    pub pitch: f64,
    pub up: DVec3,
}

impl Orbit {
    pub fn from_pose(p: Pose) -> Orbit {
        let local = frame(p.up).inverse() * (p.eye - p.target);
        let (yaw, pitch) = angles(local);
        Orbit {
            target: p.target,
            distance: (p.eye - p.target).length().max(1e-6),
            yaw,
            pitch: pitch.clamp(-MAX_PITCH, MAX_PITCH),
            up: p.up,
        }
    }

    pub fn pose(&self) -> Pose {
        Pose {
            eye: self.target + frame(self.up) * direction(self.yaw, self.pitch) * self.distance,
            target: self.target,
            up: self.up,
        }
    }

    /// A drag of (`dx`, `dy`) pixels: right turns the scene to the right
    /// (the eye goes left round the target), down raises the eye.
    pub fn drag(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * RADIANS_PER_PIXEL;
        self.pitch = (self.pitch + dy * RADIANS_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// `steps` wheel steps: positive comes nearer (`ZOOM_PER_STEP` each).
    pub fn zoom(&mut self, steps: f64) {
        self.distance = (self.distance * ZOOM_PER_STEP.powf(steps)).max(1e-6);
    }

    /// Move the target (and the eye with it) so that the point under the
    /// cursor follows a drag of (`dx`, `dy`) pixels in a view `height`
    /// pixels high with vertical field of view `fov_y` (radians), at the
    /// target's depth.
    pub fn pan(&mut self, dx: f64, dy: f64, height: f64, fov_y: f64) {
        let p = self.pose();
        let forward = (p.target - p.eye).normalize();
        let right = forward.cross(self.up).normalize();
        let true_up = right.cross(forward);
        let metres_per_pixel = 2.0 * self.distance * (fov_y / 2.0).tan() / height.max(1.0);
        self.target += (-right * dx + true_up * dy) * metres_per_pixel;
    }
}

/// Which movement keys are held (the fly camera moves while they are).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Held {
    pub forward: bool,
    pub back: bool,
    pub left: bool,
    pub right: bool,
    pub up: bool,
    pub down: bool,
    pub fast: bool,
}

/// Move through the scene: the eye at `eye` looks in the direction (`yaw`,
/// `pitch`) of the up frame; `speed` is metres a second.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fly {
    pub eye: DVec3,
    pub yaw: f64,
    pub pitch: f64,
    pub up: DVec3,
    pub speed: f64,
    /// How far ahead the target is kept (the pose's distance when the fly
    /// began), so that orbiting again turns about a point in view.
    pub focus: f64,
}

impl Fly {
    pub fn from_pose(p: Pose) -> Fly {
        let (yaw, pitch) = angles(frame(p.up).inverse() * (p.target - p.eye));
        let focus = (p.target - p.eye).length().max(1e-6);
        Fly {
            eye: p.eye,
            yaw,
            pitch: pitch.clamp(-MAX_PITCH, MAX_PITCH),
            up: p.up,
            speed: focus / FLY_SECONDS_ACROSS,
            focus,
        }
    }

    fn forward(&self) -> DVec3 {
        frame(self.up) * direction(self.yaw, self.pitch)
    }

    pub fn pose(&self) -> Pose {
        Pose {
            eye: self.eye,
            target: self.eye + self.forward() * self.focus,
            up: self.up,
        }
    }

    /// The mouse moved (`dx`, `dy`) pixels while looking: right turns
    /// right, down looks down.
    pub fn look(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * RADIANS_PER_PIXEL;
        self.pitch = (self.pitch - dy * RADIANS_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Move for `dt` seconds with `held` keys: forward along the view
    /// direction, sideways along the view's right, up and down along up.
    pub fn advance(&mut self, held: Held, dt: f64) {
        let forward = self.forward();
        let right = forward.cross(self.up).normalize_or(DVec3::X);
        let axis = |plus: bool, minus: bool| f64::from(u8::from(plus)) - f64::from(u8::from(minus));
        let v = forward * axis(held.forward, held.back)
            + right * axis(held.right, held.left)
            + self.up * axis(held.up, held.down);
        let speed = if held.fast { self.speed * FAST } else { self.speed };
        self.eye += v.normalize_or_zero() * speed * dt;
    }
}

/// The view's camera: the scene's own until the user moves it, then an
/// orbit or a fly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    Scene,
    Orbit(Orbit),
    Fly(Fly),
}

impl Control {
    /// The pose shown at `time_s` for `scene`'s camera.
    pub fn pose(&self, scene: &Camera, time_s: f64) -> Pose {
        match self {
            Control::Scene => Pose::of(&scene.pose(time_s)),
            Control::Orbit(o) => o.pose(),
            Control::Fly(f) => f.pose(),
        }
    }

    /// The camera to render at `time_s`.
    pub fn camera(&self, scene: &Camera, time_s: f64) -> Camera {
        match self {
            Control::Scene => scene.clone(),
            _ => self.pose(scene, time_s).camera(scene),
        }
    }

    /// As an orbit, taking over from the current pose.
    pub fn orbit(&mut self, scene: &Camera, time_s: f64) -> &mut Orbit {
        if !matches!(self, Control::Orbit(_)) {
            *self = Control::Orbit(Orbit::from_pose(self.pose(scene, time_s)));
        }
        match self {
            Control::Orbit(o) => o,
            _ => unreachable!("just made an orbit"),
        }
    }

    /// As a fly, taking over from the current pose.
    pub fn fly(&mut self, scene: &Camera, time_s: f64) -> &mut Fly {
        if !matches!(self, Control::Fly(_)) {
            *self = Control::Fly(Fly::from_pose(self.pose(scene, time_s)));
        }
        match self {
            Control::Fly(f) => f,
            _ => unreachable!("just made a fly"),
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            Control::Scene => "scene camera",
            Control::Orbit(_) => "orbit",
            Control::Fly(_) => "fly",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DMat4, Vec3};

    impl Pose {
        /// World to view, right-handed (the camera looks down its −z), as
        /// the runner's `CameraPose::view` computes it in f32.
        fn view_matrix(&self) -> DMat4 {
            DMat4::look_at_rh(self.eye, self.target, self.up)
        }
    }
    use std::f64::consts::FRAC_PI_2;

    /// The f32 view matrix the runner computes for `camera` at `time_s`.
    fn runner_view(camera: &Camera, time_s: f64) -> glam::Mat4 {
        camera.pose(time_s).center_view()
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-9
    }

    /// Every entry within `tol`.
    fn close_mat(a: DMat4, b: DMat4, tol: f64) -> bool {
        a.to_cols_array()
            .iter()
            .zip(b.to_cols_array())
            .all(|(x, y)| (x - y).abs() <= tol)
    }

    fn pose(eye: [f64; 3], target: [f64; 3]) -> Pose {
        Pose {
            eye: DVec3::from(eye),
            target: DVec3::from(target),
            up: DVec3::Y,
        }
    }

    /// The view matrix written out from its definition: rows are the
    /// camera's right, up and back axes, translated by −eye.
    fn analytic_view(eye: DVec3, right: DVec3, up: DVec3, back: DVec3) -> DMat4 {
        DMat4::from_cols(
            DVec3::new(right.x, up.x, back.x).extend(0.0),
            DVec3::new(right.y, up.y, back.y).extend(0.0),
            DVec3::new(right.z, up.z, back.z).extend(0.0),
            DVec3::new(-right.dot(eye), -up.dot(eye), -back.dot(eye)).extend(1.0),
        )
    }

    #[test]
    fn an_orbit_of_a_pose_gives_the_pose_back() {
        let p = pose([1.0, 2.0, 5.0], [0.5, 0.25, -1.0]);
        let o = Orbit::from_pose(p);
        assert!(close(o.pose().eye, p.eye), "{:?}", o.pose().eye);
        assert!(close_mat(o.pose().view_matrix(), p.view_matrix(), 1e-12));
    }

    #[test]
    fn a_quarter_turn_orbit_looks_along_minus_x_from_plus_x() {
        // From +z, 4 m out; a drag left by 180 px (a quarter turn of yaw)
        // moves the eye to +x, where it looks down −x.
        let mut o = Orbit::from_pose(pose([0.0, 0.0, 4.0], [0.0; 3]));
        o.drag(-180.0, 0.0);
        let p = o.pose();
        assert!(close(p.eye, DVec3::new(4.0, 0.0, 0.0)), "{:?}", p.eye);
        // Camera axes: right = −z, up = +y, back = +x.
        let expected = analytic_view(p.eye, DVec3::NEG_Z, DVec3::Y, DVec3::X);
        assert!(close_mat(p.view_matrix(), expected, 1e-12), "{:?}", p.view_matrix());
        // The origin is 4 m in front of the camera.
        let origin = p.view_matrix().transform_point3(DVec3::ZERO);
        assert!(close(origin, DVec3::new(0.0, 0.0, -4.0)), "{origin:?}");
    }

    #[test]
    fn orbit_pitch_raises_the_eye_and_stops_short_of_the_pole() {
        let mut o = Orbit::from_pose(pose([0.0, 0.0, 4.0], [0.0; 3]));
        o.drag(0.0, 90.0); // 45°
        let e = o.pose().eye;
        let s = 4.0 * std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(e, DVec3::new(0.0, s, s)), "{e:?}");
        o.drag(0.0, 10_000.0);
        assert!((o.pitch - MAX_PITCH).abs() < 1e-12);
        assert!(((o.pose().eye.y / 4.0).asin() - MAX_PITCH).abs() < 1e-9);
    }

    #[test]
    fn zoom_scales_the_distance_and_pan_moves_eye_and_target_together() {
        let mut o = Orbit::from_pose(pose([0.0, 0.0, 4.0], [0.0; 3]));
        o.zoom(2.0);
        assert!((o.distance - 4.0 * 0.81).abs() < 1e-12);
        let mut o = Orbit::from_pose(pose([0.0, 0.0, 4.0], [0.0; 3]));
        // A 90° field of view, 100 px high: at 4 m the view is 8 m high,
        // 0.08 m a pixel. Dragging 50 px right moves the scene right, so
        // the camera goes 4 m left; 25 px down moves it 2 m up.
        o.pan(50.0, 25.0, 100.0, FRAC_PI_2);
        assert!(close(o.target, DVec3::new(-4.0, 2.0, 0.0)), "{:?}", o.target);
        assert!(close(o.pose().eye, DVec3::new(-4.0, 2.0, 4.0)), "{:?}", o.pose().eye);
    }

    #[test]
    fn orbit_about_another_up_turns_about_that_axis() {
        // Up is +z: the eye at +x orbits in the xy plane, staying at z = 0.
        let p = Pose {
            eye: DVec3::new(3.0, 0.0, 0.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
        };
        let mut o = Orbit::from_pose(p);
        assert!(close(o.pose().eye, p.eye), "{:?}", o.pose().eye);
        o.drag(-180.0, 0.0);
        let e = o.pose().eye;
        assert!(e.z.abs() < 1e-9 && (e.length() - 3.0).abs() < 1e-9, "{e:?}");
    }

    #[test]
    fn fly_moves_along_the_view_and_looks_with_the_mouse() {
        // Looking down −z from z = 4, 4 m from the target: 2 m/s.
        let mut f = Fly::from_pose(pose([0.0, 0.0, 4.0], [0.0; 3]));
        assert!((f.speed - 2.0).abs() < 1e-12);
        let forward = Held {
            forward: true,
            ..Held::default()
        };
        f.advance(forward, 0.5);
        assert!(close(f.eye, DVec3::new(0.0, 0.0, 3.0)), "{:?}", f.eye);
        // Right and up together move diagonally at the same speed (not √2 faster).
        let diagonal = Held {
            right: true,
            up: true,
            fast: true,
            ..Held::default()
        };
        f.advance(diagonal, 0.25);
        let s = 2.0 * FAST * 0.25 * std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(f.eye, DVec3::new(s, s, 3.0)), "{:?}", f.eye);
        // A 180 px move right turns a quarter to the right: now looking down +x.
        f.look(180.0, 0.0);
        let p = f.pose();
        assert!(
            close((p.target - p.eye).normalize(), DVec3::X),
            "{:?}",
            p.target - p.eye
        );
        let expected = analytic_view(p.eye, DVec3::Z, DVec3::Y, DVec3::NEG_X);
        assert!(close_mat(p.view_matrix(), expected, 1e-12));
        // Moving down the mouse looks down.
        f.look(0.0, 90.0);
        assert!((f.pitch + std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    }

    #[test]
    fn the_runner_sees_the_view_matrix_of_the_pose() {
        // The f32 camera handed to the runner has the f64 view, to f32's precision.
        let scene = Camera::looking_at(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 0.5, 0.0));
        let mut control = Control::Scene;
        control.orbit(&scene, 0.0).drag(-123.0, 47.0);
        control.orbit(&scene, 0.0).zoom(1.5);
        let pose = control.pose(&scene, 0.0);
        let camera = control.camera(&scene, 0.0);
        let runner = runner_view(&camera, 0.0).as_dmat4();
        assert!(close_mat(runner, pose.view_matrix(), 1e-5), "{runner:?}");
        assert_eq!(camera.fov_y_rad, scene.fov_y_rad);
        // Switching to fly keeps the pose.
        let before = control.pose(&scene, 0.0);
        control.fly(&scene, 0.0);
        let after = control.pose(&scene, 0.0);
        assert!(close_mat(before.view_matrix(), after.view_matrix(), 1e-9));
    }

    #[test]
    fn an_untouched_control_is_the_animated_scene_camera() {
        let still = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
        let keys = vec![
            CameraKey {
                time_s: 0.0,
                position: Vec3::new(-2.0, 0.0, 4.0),
                target: Vec3::ZERO,
                roll_rad: 0.0,
            },
            CameraKey {
                time_s: 2.0,
                position: Vec3::new(2.0, 0.0, 4.0),
                target: Vec3::ZERO,
                roll_rad: 0.0,
            },
        ];
        let scene = Camera::with_keys(keys, &still).expect("keys");
        let p = Control::Scene.pose(&scene, 1.0);
        assert!(close(p.eye, DVec3::new(0.0, 0.0, 4.0)), "{:?}", p.eye);
        assert_eq!(Control::Scene.camera(&scene, 1.0), scene);
    }
}
