//! `[camera]` (with optional `[[camera.keys]]`) and `[light]` in a scene.

use super::camera::{Camera, CameraKey};
use super::light::Light;
use super::toml_fields::{At, Fields, Report};
use glam::Vec3;
use npr_diag::Span;

const DEFAULT_FOV_DEG: f64 = 40.0;
const DEFAULT_NEAR: f64 = 0.1;
const DEFAULT_FAR: f64 = 100.0;

/// Reads `[camera]`. `None` after reporting what is wrong.
pub fn parse_camera(mut fields: Fields, report: &mut Report) -> Option<Camera> {
    let errors_before = report.diagnostics.len();
    let position = fields.vec3("position", report);
    let target = fields.vec3("target", report);
    let up = fields.vec3("up", report);
    let fov = fields.number("fov", report);
    let near = fields.number("near", report);
    let far = fields.number("far", report);
    let ipd = fields.number("ipd", report);
    let projection = fields.string("projection", report);
    let height = fields.number("height", report);
    let key_tables = fields.tables("keys", |index| format!("camera key #{}", index + 1), report);
    let header = fields.header();

    if let Some(up) = &up {
        if up.value.length_squared() == 0.0 {
            report.bad_scene(
                up.span,
                "`up` is the zero vector",
                "no direction",
                "write e.g. `up = [0.0, 1.0, 0.0]`",
            );
        }
    }
    let fov_deg = fov.as_ref().map_or(DEFAULT_FOV_DEG, |fov| fov.value);
    if let Some(fov) = fov.as_ref().filter(|fov| !(fov.value > 0.0 && fov.value < 180.0)) {
        report.bad_scene(
            fov.span,
            format!("`fov` must be between 0 and 180 degrees (exclusive), not {}", fov.value),
            "out of range",
            "`fov` is the vertical field of view in degrees, e.g. `fov = 40.0`",
        );
    }
    let near_m = near.as_ref().map_or(DEFAULT_NEAR, |near| near.value);
    let far_m = far.as_ref().map_or(DEFAULT_FAR, |far| far.value);
    if let Some(near) = near.as_ref().filter(|near| near.value <= 0.0) {
        report.bad_scene(
            near.span,
            format!("`near` must be positive, not {}", near.value),
            "must be > 0",
            "write e.g. `near = 0.1`",
        );
    } else if far_m <= near_m {
        let span = far.as_ref().or(near.as_ref()).map_or(header, |at| at.span);
        report.bad_scene(
            span,
            format!("`far` ({far_m}) must be greater than `near` ({near_m})"),
            "far ≤ near",
            "write e.g. `near = 0.1` and `far = 100.0`",
        );
    }
    if let Some(ipd) = ipd.as_ref().filter(|ipd| ipd.value <= 0.0) {
        report.bad_scene(
            ipd.span,
            format!("`ipd` must be positive, not {}", ipd.value),
            "must be > 0",
            "`ipd` is the distance between the eyes in metres, e.g. `ipd = 0.064`; leave it out for a mono camera",
        );
    }

    let ortho_height_m = parse_projection(
        &Lens {
            projection: projection.as_ref(),
            height: height.as_ref(),
            fov: fov.as_ref(),
            ipd: ipd.as_ref(),
        },
        fields.header(),
        report,
    );

    let up_axis = up.as_ref().map_or(Vec3::Y, |up| up.value);
    let keys = if key_tables.is_empty() {
        match (&position, &target) {
            (Some(position), Some(target)) => {
                check_view(position.value, target.value, up_axis, position.span, report);
                vec![At {
                    value: CameraKey {
                        time_s: 0.0,
                        position: position.value,
                        target: target.value,
                        roll_rad: 0.0,
                    },
                    span: position.span,
                }]
            }
            _ => {
                for (key, example) in [
                    ("position", "position = [0.0, 0.5, 3.0]"),
                    ("target", "target = [0.0, 0.0, 0.0]"),
                ] {
                    if fields.span_of(key, report).is_none() {
                        fields.missing(key, example, report);
                    }
                }
                Vec::new()
            }
        }
    } else {
        key_tables
            .into_iter()
            .filter_map(|key_fields| parse_key(key_fields, position.as_ref(), target.as_ref(), up_axis, report))
            .collect()
    };
    check_distinct_times(&keys, report);
    fields.finish(report);
    if report.diagnostics.len() > errors_before {
        return None;
    }
    let mut template = Camera::looking_at(Vec3::Z, Vec3::ZERO);
    template.up = up_axis.normalize();
    template.fov_y_rad = (fov_deg as f32).to_radians();
    template.near = near_m as f32;
    template.far = far_m as f32;
    template.ipd_m = ipd.map(|ipd| ipd.value as f32);
    template.ortho_height_m = ortho_height_m;
    Camera::with_keys(keys.into_iter().map(|key| key.value).collect(), &template)
}

/// The lens keys of `[camera]` that choose the projection.
struct Lens<'a> {
    projection: Option<&'a At<String>>,
    height: Option<&'a At<f64>>,
    fov: Option<&'a At<f64>>,
    ipd: Option<&'a At<f64>>,
}

/// `projection = "perspective"` (the default, with `fov`) or
/// `projection = "orthographic"` with `height`, the view's height in metres
/// (decision 0062). Returns the orthographic height, `None` for a
/// perspective camera (or after reporting what is wrong).
fn parse_projection(lens: &Lens<'_>, header: Span, report: &mut Report) -> Option<f32> {
    let orthographic = match lens.projection {
        None => false,
        Some(p) if p.value == "perspective" => false,
        Some(p) if p.value == "orthographic" => true,
        Some(p) => {
            report.bad_scene(
                p.span,
                format!("unknown camera projection \"{}\"", p.value),
                "not a projection",
                "write `projection = \"perspective\"` (the default) or `projection = \"orthographic\"` with a `height` in metres",
            );
            return None;
        }
    };
    if !orthographic {
        if let Some(height) = lens.height {
            report.bad_scene(
                height.span,
                "`height` is the view height of an orthographic camera, and this camera is perspective",
                "needs `projection = \"orthographic\"`",
                "add `projection = \"orthographic\"` to make the camera orthographic, or remove `height` and give `fov`",
            );
        }
        return None;
    }
    let span = lens.projection.map_or(header, |p| p.span);
    if let Some(fov) = lens.fov {
        report.bad_scene(
            fov.span,
            "an orthographic camera has no field of view",
            "perspective only",
            "remove `fov`; the view's size is its `height` in metres",
        );
    }
    if let Some(ipd) = lens.ipd {
        report.bad_scene(
            ipd.span,
            "an orthographic camera cannot be stereo: its parallel eyes would see the same image shifted",
            "stereo needs a perspective camera",
            "remove `ipd`, or remove `projection = \"orthographic\"`",
        );
    }
    match lens.height {
        None => {
            report.bad_scene(
                span,
                "an orthographic camera needs a `height`",
                "no view height",
                "add the view's height in metres, e.g. `height = 4.0` (its width follows the image's aspect)",
            );
            None
        }
        Some(h) if !(h.value > 0.0 && h.value.is_finite() && (h.value as f32).is_finite()) => {
            report.bad_scene(
                h.span,
                format!("`height` must be a positive number of metres, not {}", h.value),
                "must be > 0",
                "write the view's height in metres, e.g. `height = 4.0`",
            );
            None
        }
        Some(h) => Some(h.value as f32),
    }
}

/// One `[[camera.keys]]`: `time` is required; `position` and `target`
/// default to the camera's own.
fn parse_key(
    mut fields: Fields,
    default_position: Option<&At<Vec3>>,
    default_target: Option<&At<Vec3>>,
    up: Vec3,
    report: &mut Report,
) -> Option<At<CameraKey>> {
    let time = fields.number("time", report);
    // Degrees, like `fov`.
    let roll = fields.number("roll", report);
    let position = fields.vec3("position", report).or_else(|| default_position.cloned());
    let target = fields.vec3("target", report).or_else(|| default_target.cloned());
    if time.is_none() && fields.span_of("time", report).is_none() {
        fields.missing("time", "time = 0.0", report);
    }
    for (key, value, example) in [
        ("position", &position, "position = [0.0, 0.5, 3.0]"),
        ("target", &target, "target = [0.0, 0.0, 0.0]"),
    ] {
        if value.is_none() && fields.span_of(key, report).is_none() {
            report.bad_scene(
                fields.header(),
                format!("{} has no `{key}`, and [camera] has none to inherit", fields.context()),
                format!("`{key}` is required here"),
                format!("add `{example}` to this key or to [camera]"),
            );
        }
    }
    // Point view errors at this key's own `position` when it has one.
    let view_span = fields.span_of("position", report).unwrap_or(fields.header());
    fields.finish(report);
    let (time, position, target) = (time?, position?, target?);
    check_view(position.value, target.value, up, view_span, report);
    Some(At {
        value: CameraKey {
            time_s: time.value,
            position: position.value,
            target: target.value,
            roll_rad: roll.map_or(0.0, |r| (r.value as f32).to_radians()),
        },
        span: time.span,
    })
}

/// The camera must look somewhere, and not along its `up` axis.
fn check_view(position: Vec3, target: Vec3, up: Vec3, span: Span, report: &mut Report) {
    let forward = target - position;
    if forward.length_squared() == 0.0 {
        report.bad_scene(
            span,
            "the camera's position and target are the same point",
            "looks nowhere",
            "move `position` away from `target`",
        );
    } else if up.length_squared() > 0.0 && forward.normalize().cross(up.normalize()).length() < 1e-6 {
        report.bad_scene(
            span,
            "the camera looks straight along its `up` axis",
            "view direction parallel to `up`",
            "set `up` to a direction across the view, e.g. `up = [0.0, 0.0, -1.0]` when looking straight down",
        );
    }
}

fn check_distinct_times(keys: &[At<CameraKey>], report: &mut Report) {
    for (index, key) in keys.iter().enumerate() {
        if let Some(earlier) = keys[..index]
            .iter()
            .find(|earlier| earlier.value.time_s == key.value.time_s)
        {
            report.push(
                npr_diag::Diagnostic::error(
                    npr_diag::codes::BAD_SCENE,
                    format!("two camera keys at time {}", key.value.time_s),
                )
                .with_primary(key.span, "second key at this time")
                .with_secondary(earlier.span, "first key at this time")
                .with_help("give each key its own `time`"),
            );
        }
    }
}

/// Reads `[light]`; absent fields take [`Light::default`]'s values.
pub fn parse_light(mut fields: Fields, report: &mut Report) -> Light {
    let defaults = Light::default();
    let direction = match fields.vec3("direction", report) {
        Some(direction) => direction.value.try_normalize().unwrap_or_else(|| {
            report.bad_scene(
                direction.span,
                "the light `direction` is the zero vector",
                "no direction",
                "`direction` points towards the light, e.g. `direction = [0.5, 1.0, 0.8]`",
            );
            defaults.direction
        }),
        None => defaults.direction,
    };
    let color = fields
        .color("color", report)
        .map_or(defaults.color, |c| [c.value[0], c.value[1], c.value[2]]);
    let intensity = match fields.number("intensity", report) {
        Some(intensity) if intensity.value < 0.0 => {
            report.bad_scene(
                intensity.span,
                format!("`intensity` must not be negative, not {}", intensity.value),
                "negative",
                "write e.g. `intensity = 1.0`",
            );
            defaults.intensity
        }
        Some(intensity) => intensity.value as f32,
        None => defaults.intensity,
    };
    fields.finish(report);
    Light {
        direction,
        color,
        intensity,
    }
}
