//! The camera a host gives with each frame, checked before it is used
//! (E0616): a perspective projection needs a vertical field of view in
//! (0, π), an orthographic one (`ortho_height_m`, decision 0062) a
//! positive finite height and no stereo eyes; both need a near plane past
//! the eye and a far plane past the near one, all finite but `far`, which
//! may be infinite for a perspective camera. Scenes read from files
//! are held to the same rules when parsed (E0405); the compiler's value
//! ranges count on them (`camera.near` and `camera.focal` are positive).

use super::EmbedError;
use crate::scene::Camera;
use npr_diag::{codes, Diagnostic};

/// `Ok` when `camera`'s projection is one npr can draw with.
pub fn check_camera(camera: &Camera) -> Result<(), EmbedError> {
    let problem = if let Some(height) = camera.ortho_height_m {
        orthographic_problem(camera, height)
    } else if !(camera.fov_y_rad > 0.0 && camera.fov_y_rad < std::f32::consts::PI) {
        Some(format!(
            "the camera's vertical field of view is {} rad: it must be between 0 and π (exclusive)",
            camera.fov_y_rad
        ))
    } else if !(camera.near.is_finite() && camera.near > 0.0) {
        Some(format!(
            "the camera's near plane is at {} m: it must be a positive distance",
            camera.near
        ))
    } else if camera.far.is_nan() || camera.far <= camera.near {
        Some(format!(
            "the camera's far plane ({} m) is not beyond its near plane ({} m)",
            camera.far, camera.near
        ))
    } else {
        camera.ipd_m.filter(|ipd| !(ipd.is_finite() && *ipd >= 0.0)).map(|ipd| {
            format!("the stereo camera's interpupillary distance is {ipd} m: it must be a finite distance, 0 or more")
        })
    };
    match problem {
        None => Ok(()),
        Some(message) => Err(EmbedError::Camera(Box::new(
            Diagnostic::error(codes::BAD_HOST_CAMERA, message).with_help(
                "give `Frame::camera` a perspective camera: `fov_y_rad` in (0, π), e.g. 40f32.to_radians(); \
                 0 < `near` < `far` (far may be f32::INFINITY); or an orthographic one: `ortho_height_m = \
                 Some(h)` with h > 0 m, 0 < `near` < `far` < ∞, no `ipd_m`",
            ),
        ))),
    }
}

/// What is wrong with an orthographic camera `height` m high, if anything.
fn orthographic_problem(camera: &Camera, height: f32) -> Option<String> {
    if !(height.is_finite() && height > 0.0) {
        Some(format!(
            "the orthographic camera's view height is {height} m: it must be a positive distance"
        ))
    } else if !(camera.near.is_finite() && camera.near > 0.0) {
        Some(format!(
            "the camera's near plane is at {} m: it must be a positive distance",
            camera.near
        ))
    } else if !(camera.far.is_finite() && camera.far > camera.near) {
        Some(format!(
            "the orthographic camera's far plane ({} m) is not a finite distance beyond its near plane ({} m)",
            camera.far, camera.near
        ))
    } else if camera.ipd_m.is_some() {
        Some("an orthographic camera cannot be stereo (`ipd_m` is set): its eyes would see one image shifted".into())
    } else {
        None
    }
}
