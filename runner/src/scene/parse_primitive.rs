//! `primitive = { kind = "...", ... }` in a scene: kind, sizes and counts,
//! with their defaults, ranges and limits.

use super::mesh::MAX_TRIANGLES;
use super::primitives::{Primitive, KINDS, MAX_SEGMENTS};
use super::toml_fields::{list, Fields, Report};
use dsl::diagnostic::did_you_mean;
use dsl::{codes, Diagnostic};

/// Reads a primitive table. `None` after reporting what is wrong.
pub fn parse_primitive(mut fields: Fields, report: &mut Report) -> Option<Primitive> {
    let Some(kind) = fields.string("kind", report) else {
        if fields.span_of("kind", report).is_none() {
            fields.missing("kind", "kind = \"sphere\"", report);
        }
        return None;
    };
    let errors_before = report.diagnostics.len();
    let primitive = match kind.value.as_str() {
        "sphere" => Primitive::Sphere {
            radius: size(&mut fields, "radius", 1.0, report),
            segments: count(&mut fields, "segments", 64, 3, report),
            rings: count(&mut fields, "rings", 32, 2, report),
        },
        "cube" => Primitive::Cube {
            size: size(&mut fields, "size", 1.0, report),
        },
        "torus" => Primitive::Torus {
            major: size(&mut fields, "major", 1.0, report),
            minor: size(&mut fields, "minor", 0.25, report),
            segments: count(&mut fields, "segments", 64, 3, report),
            sides: count(&mut fields, "sides", 32, 3, report),
        },
        "plane" => Primitive::Plane {
            size: size(&mut fields, "size", 1.0, report),
            subdivisions: count(&mut fields, "subdivisions", 1, 1, report),
        },
        "cylinder" => Primitive::Cylinder {
            radius: size(&mut fields, "radius", 0.5, report),
            height: size(&mut fields, "height", 1.0, report),
            segments: count(&mut fields, "segments", 64, 3, report),
        },
        unknown => {
            let help = match did_you_mean(unknown, KINDS.iter().copied()) {
                Some(suggestion) => {
                    format!("did you mean `{suggestion}`? The kinds are {}", list(KINDS))
                }
                None => format!("the primitive kinds are {}", list(KINDS)),
            };
            report.bad_scene(
                kind.span,
                format!("unknown primitive kind `{unknown}`"),
                "unknown kind",
                help,
            );
            // The other fields depend on the kind: checking them would only add noise.
            return None;
        }
    };
    let header = fields.header();
    fields.set_context(format!("a `{}` primitive", kind.value));
    fields.finish(report);
    if report.diagnostics.len() > errors_before {
        return None;
    }
    let triangles = primitive.triangle_count();
    if triangles > MAX_TRIANGLES as u64 {
        report.push(
            Diagnostic::error(
                codes::LIMIT_EXCEEDED,
                format!(
                    "{} has {triangles} triangles, more than the limit of {MAX_TRIANGLES}",
                    primitive.description()
                ),
            )
            .with_primary(header, "too many triangles")
            .with_help("lower `segments`, `rings`, `sides` or `subdivisions`"),
        );
        return None;
    }
    Some(primitive)
}

/// A positive length; the default when absent. On error the default is
/// returned too, and the error recorded (the caller checks the report).
fn size(fields: &mut Fields, key: &'static str, default: f32, report: &mut Report) -> f32 {
    let Some(value) = fields.number(key, report) else {
        return default;
    };
    if value.value <= 0.0 || value.value > f64::from(f32::MAX) {
        report.bad_scene(
            value.span,
            format!("`{key}` must be a positive number, not {}", value.value),
            "must be > 0",
            format!("write e.g. `{key} = {default:?}`"),
        );
        return default;
    }
    value.value as f32
}

/// A whole count in `minimum..=MAX_SEGMENTS`; past the maximum is E0404.
fn count(fields: &mut Fields, key: &'static str, default: u32, minimum: u32, report: &mut Report) -> u32 {
    let Some(value) = fields.integer(key, report) else {
        return default;
    };
    if value.value > i64::from(MAX_SEGMENTS) {
        report.push(
            Diagnostic::error(
                codes::LIMIT_EXCEEDED,
                format!("`{key}` is {}, more than the limit of {MAX_SEGMENTS}", value.value),
            )
            .with_primary(value.span, format!("at most {MAX_SEGMENTS}"))
            .with_help(format!(
                "use at most `{key} = {MAX_SEGMENTS}`; finer tessellation is invisible at npr's resolutions"
            )),
        );
        return default;
    }
    if value.value < i64::from(minimum) {
        report.bad_scene(
            value.span,
            format!("`{key}` must be at least {minimum}, not {}", value.value),
            format!("at least {minimum}"),
            format!("write e.g. `{key} = {default}`"),
        );
        return default;
    }
    value.value as u32
}
