//! `primitive = { kind = "...", ... }` in a scene: kind, sizes and counts,
//! with their defaults, ranges and limits.

use super::mesh::MAX_TRIANGLES;
use super::ocean::{Ocean, MAX_CELLS, MAX_DRIFT, MAX_MODES, MAX_TILES};
use super::primitives::{Primitive, KINDS, MAX_SEGMENTS};
use super::toml_fields::{expect_numbers, list, At, Fields, Report};
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic};

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
        "ocean" => Primitive::Ocean(parse_ocean(&mut fields, report)),
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
            .with_help("lower `segments`, `rings`, `sides` or `subdivisions` (for an ocean, `cells` or `tiles`)"),
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

/// The fields of an `ocean` primitive (see the scene module docs for their
/// meaning). Each bad value is reported at its own span; the defaults stand
/// in for it so the other fields are still checked.
fn parse_ocean(fields: &mut Fields, report: &mut Report) -> Ocean {
    let d = Ocean::default();
    let size = bounded(fields, "size", d.size, (0.0, false), 1e4, "metres", report);
    let cells = whole(fields, "cells", d.cells, 1, MAX_CELLS, report);
    let tiles = whole(fields, "tiles", d.tiles, 1, MAX_TILES, report);
    if tiles.is_multiple_of(2) {
        if let Some(span) = fields.span_of("tiles", report) {
            report.bad_scene(
                span,
                format!("`tiles` must be odd, not {tiles}"),
                "must be odd",
                format!(
                    "an odd count centres one tile on the origin, where the boat stays; write `tiles = {}`",
                    tiles + 1
                ),
            );
        }
    }
    let period = bounded(fields, "period", d.period, (0.0, false), 3600.0, "seconds", report);
    let modes = whole(fields, "modes", d.modes, 1, MAX_MODES, report);
    if modes > cells / 2 {
        if let Some(span) = fields.span_of("modes", report) {
            report.bad_scene(
                span,
                format!("`modes` is {modes}, more than half of `cells` ({cells})"),
                format!("at most {}", cells / 2),
                "a tile of N cells can only show waves up to N/2 cycles across (Nyquist); \
                 lower `modes` or raise `cells`",
            );
        }
    }
    let wave_height = bounded(
        fields,
        "wave_height",
        d.wave_height,
        (0.0, true),
        100.0,
        "metres",
        report,
    );
    let wind_speed = bounded(fields, "wind_speed", d.wind_speed, (0.0, false), 100.0, "m/s", report);
    let wind_direction = match pair(fields, "wind_direction", report) {
        Some(At { value: [x, z], span }) if x == 0.0 && z == 0.0 => {
            report.bad_scene(
                span,
                "`wind_direction` cannot be zero",
                "no direction",
                "write the [x, z] direction the wind blows towards, e.g. `wind_direction = [0.0, 1.0]`",
            );
            d.wind_direction
        }
        Some(At { value: [x, z], .. }) => [x as f32, z as f32],
        None => d.wind_direction,
    };
    let choppiness = bounded(fields, "choppiness", d.choppiness, (0.0, true), 4.0, "", report);
    let seed = whole(fields, "seed", d.seed, 0, u32::MAX, report);
    let drift = match pair(fields, "drift", report) {
        Some(At { value: [x, z], span }) => {
            let whole_tiles = |c: f64| c.fract() == 0.0 && c.abs() <= f64::from(MAX_DRIFT);
            if whole_tiles(x) && whole_tiles(z) {
                [x as i32, z as i32]
            } else {
                report.bad_scene(
                    span,
                    format!("`drift` must be whole numbers of tiles from -{MAX_DRIFT} to {MAX_DRIFT}"),
                    "not whole tiles per period",
                    "the water moves `drift` tiles per period so the loop closes; write e.g. `drift = [0, -1]` \
                     (one tile towards -z every period)",
                );
                d.drift
            }
        }
        None => d.drift,
    };
    let horizon = bounded(fields, "horizon", d.horizon, (0.0, false), 1e5, "metres", report);
    let horizon_drop = bounded(fields, "horizon_drop", d.horizon_drop, (0.0, true), 10.0, "", report);
    let ring = bounded(fields, "ring", d.ring, (0.0, true), 1e5, "metres", report);
    Ocean {
        size,
        cells,
        tiles,
        period,
        modes,
        wave_height,
        wind_speed,
        wind_direction,
        choppiness,
        seed,
        drift,
        horizon,
        horizon_drop,
        ring,
    }
}

/// A number in `(lo, hi]` (or `[lo, hi]` when `lo.1`); the default on error.
fn bounded(
    fields: &mut Fields,
    key: &'static str,
    default: f32,
    lo: (f64, bool),
    hi: f64,
    unit: &str,
    report: &mut Report,
) -> f32 {
    let Some(value) = fields.number(key, report) else {
        return default;
    };
    let (lo, inclusive) = lo;
    let above = if inclusive { value.value >= lo } else { value.value > lo };
    if above && value.value <= hi {
        return value.value as f32;
    }
    let open = if inclusive { "[" } else { "(" };
    let unit = if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    };
    report.bad_scene(
        value.span,
        format!("`{key}` must be in {open}{lo}, {hi}]{unit}, not {}", value.value),
        format!("outside {open}{lo}, {hi}]"),
        format!("write e.g. `{key} = {default:?}`"),
    );
    default
}

/// A whole number in `lo..=hi`; the default on error.
fn whole(fields: &mut Fields, key: &'static str, default: u32, lo: u32, hi: u32, report: &mut Report) -> u32 {
    let Some(value) = fields.integer(key, report) else {
        return default;
    };
    if (i64::from(lo)..=i64::from(hi)).contains(&value.value) {
        return value.value as u32;
    }
    report.bad_scene(
        value.span,
        format!("`{key}` must be from {lo} to {hi}, not {}", value.value),
        format!("outside {lo}..={hi}"),
        format!("write e.g. `{key} = {default}`"),
    );
    default
}

/// Two numbers `[x, z]`.
fn pair(fields: &mut Fields, key: &'static str, report: &mut Report) -> Option<At<[f64; 2]>> {
    let value = fields.raw(key)?;
    let numbers = expect_numbers(value, key, report)?;
    match numbers.value.as_slice() {
        [x, z] => Some(At {
            value: [*x, *z],
            span: numbers.span,
        }),
        other => {
            report.bad_scene(
                numbers.span,
                format!("`{key}` must have 2 numbers ([x, z]), not {}", other.len()),
                "expected `[x, z]`",
                format!("write e.g. `{key} = [0.0, 1.0]`"),
            );
            None
        }
    }
}
