//! The values inside a test's fields: `set` tables and `variants` as the
//! text `--set` takes, and the `flip` and `per_pixel` bounds, each checked
//! with an E0407 at the value.

use super::{CoherenceBound, FlipBound, Marks, PerPixelBound, Variant, PERCENTILES};
use npr_diag::Span;
use npr_runner::scene::toml_fields::{describe, At, Fields, Report};
use toml::de::DeValue;

/// A set table's entries as `--set` texts (`set = { .. }`, a variant's table).
pub(super) fn set_entries(mut set: Fields, report: &mut Report) -> Vec<(At<String>, At<String>)> {
    let mut sets = Vec::new();
    for (name, value) in set.entries(report) {
        if let Some(text) = set_text(value.get_ref()) {
            sets.push((
                name,
                At {
                    value: text,
                    span: report.span(value.span()),
                },
            ));
        } else {
            report.bad_scene(
                report.span(value.span()),
                format!("`{}` cannot be {}", name.value, describe(value.get_ref())),
                "not a parameter value",
                "write the value as `--set` takes it: a number, `true`, a string (`\"2px\"`, `\"#3080ff\"`, `\"cubic\"`) or an array of numbers",
            );
        }
    }
    set.finish(report);
    sets
}

/// `variants` and `reference`, in a `[[test]]`.
pub(super) fn variants(fields: &mut Fields, report: &mut Report) -> (Vec<Variant>, usize) {
    let reference = fields.string("reference", report);
    let Some(mut table) = fields.table("variants", "`variants`", report) else {
        if let Some(r) = reference {
            report.bad_scene(
                r.span,
                "`reference` names a variant, but the test has no `variants`",
                "no variants",
                "add `variants = { fast = { .. }, exact = { .. } }`",
            );
        }
        return (Vec::new(), 0);
    };
    let header = table.header();
    let mut found = Vec::new();
    for (name, value) in table.entries(report) {
        match value.get_ref() {
            DeValue::Table(t) => {
                let span = report.span(value.span());
                let sets = set_entries(Fields::new(t, span, format!("variant `{}`", name.value)), report);
                found.push(Variant { name, sets });
            }
            other => report.bad_scene(
                report.span(value.span()),
                format!(
                    "variant `{}` must be a table of parameter values, not {}",
                    name.value,
                    describe(other)
                ),
                "expected a table",
                "write e.g. `variants = { fast = { samples = 4 }, exact = { samples = 64 } }`",
            ),
        }
    }
    table.finish(report);
    if found.len() < 2 {
        report.bad_scene(
            header,
            "`variants` compares parameter sets: give at least two",
            "fewer than two variants",
            "write e.g. `variants = { fast = { samples = 4 }, exact = { samples = 64 } }`",
        );
        return (Vec::new(), 0);
    }
    let index = match reference {
        None => 0,
        Some(r) => match found.iter().position(|v| v.name.value == r.value) {
            Some(i) => i,
            None => {
                let names: Vec<&str> = found.iter().map(|v| v.name.value.as_str()).collect();
                report.bad_scene(
                    r.span,
                    format!("`{}` is not one of the test's variants", r.value),
                    "no such variant",
                    format!("the variants are {}", names.join(", ")),
                );
                0
            }
        },
    };
    (found, index)
}

/// A TOML value as the text `--set` takes.
pub(super) fn set_text(value: &DeValue) -> Option<String> {
    match value {
        DeValue::String(s) => Some(s.to_string()),
        DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix()).ok().map(|n| n.to_string()),
        DeValue::Float(f) => Some(f.as_str().to_string()),
        DeValue::Boolean(b) => Some(b.to_string()),
        DeValue::Array(items) => {
            let parts: Option<Vec<String>> = items
                .iter()
                .map(|item| match item.get_ref() {
                    DeValue::Integer(_) | DeValue::Float(_) => set_text(item.get_ref()),
                    _ => None,
                })
                .collect();
            parts.map(|p| p.join(", "))
        }
        DeValue::Datetime(_) | DeValue::Table(_) => None,
    }
}

/// A share or error bound: a number from 0 to 1.
pub(super) fn unit_interval(fields: &mut Fields, key: &'static str, report: &mut Report) -> Option<f64> {
    let n = fields.number(key, report)?;
    if (0.0..=1.0).contains(&n.value) {
        Some(n.value)
    } else {
        report.bad_scene(
            n.span,
            format!("`{key}` must be from 0 to 1, not {}", n.value),
            "outside 0..1",
            "FLIP errors and pixel shares are from 0 to 1",
        );
        None
    }
}

pub(super) fn flip_bound(mut fields: Fields, report: &mut Report) -> Option<FlipBound> {
    let header = fields.header();
    let mean = unit_interval(&mut fields, "mean", report);
    let percentiles: Vec<(f64, f64)> = PERCENTILES
        .iter()
        .filter_map(|(key, pct)| unit_interval(&mut fields, key, report).map(|b| (*pct, b)))
        .collect();
    fields.finish(report);
    if mean.is_none() && percentiles.is_empty() {
        report.bad_scene(
            header,
            "`flip` bounds nothing",
            "no `mean` or percentile",
            "write e.g. `flip = { mean = 0.01, p99 = 0.3 }`",
        );
        return None;
    }
    Some(FlipBound { mean, percentiles })
}

pub(super) fn per_pixel_bound(mut fields: Fields, report: &mut Report) -> Option<PerPixelBound> {
    let max = fields.integer("max", report);
    let outliers = unit_interval(&mut fields, "outliers", report);
    let header = fields.header();
    fields.finish(report);
    let max = match max {
        Some(m) if (0..=255).contains(&m.value) => m.value as u8,
        Some(m) => {
            report.bad_scene(
                m.span,
                format!("`max` must be from 0 to 255, not {}", m.value),
                "outside 0..255",
                "`max` is a difference in 8-bit levels",
            );
            return None;
        }
        None => {
            fields_missing(header, "per_pixel", "max", "max = 2", report);
            return None;
        }
    };
    Some(PerPixelBound {
        max,
        outliers: outliers.unwrap_or(0.0),
    })
}

pub(super) fn fields_missing(header: Span, table: &str, key: &str, example: &str, report: &mut Report) {
    report.bad_scene(
        header,
        format!("`{table}` has no `{key}`"),
        format!("`{key}` is required here"),
        format!("add `{example}`"),
    );
}

/// `coherence = { flicker = 0.02, sliding = 0.3, popping = 0.1, marks = "dark" }`:
/// bounds on the temporal coherence measures (`coherence.rs`), at least one.
pub(super) fn coherence_bound(mut fields: Fields, report: &mut Report) -> Option<At<CoherenceBound>> {
    let header = fields.header();
    let flicker = unit_interval(&mut fields, "flicker", report);
    let popping = unit_interval(&mut fields, "popping", report);
    let sliding = fields.number("sliding", report).and_then(|n| {
        if n.value >= 0.0 && n.value.is_finite() {
            Some(n.value)
        } else {
            report.bad_scene(
                n.span,
                format!("`sliding` must be a distance in px of 0 or more, not {}", n.value),
                "not a distance",
                "`sliding` bounds how many px per frame a pattern moves against its surface",
            );
            None
        }
    });
    let marks = match fields.string("marks", report) {
        None => Marks::Dark,
        Some(m) if m.value == "dark" => Marks::Dark,
        Some(m) if m.value == "light" => Marks::Light,
        Some(m) => {
            report.bad_scene(
                m.span,
                format!("`marks` is `dark` or `light`, not `{}`", m.value),
                "unknown marks",
                "`marks` says which pixels are the strokes or dots whose popping is counted",
            );
            return None;
        }
    };
    fields.finish(report);
    if flicker.is_none() && sliding.is_none() && popping.is_none() {
        report.bad_scene(
            header,
            "`coherence` bounds nothing",
            "no `flicker`, `sliding` or `popping`",
            "write e.g. `coherence = { flicker = 0.02, sliding = 0.5 }`",
        );
        return None;
    }
    Some(At {
        value: CoherenceBound {
            flicker,
            sliding,
            popping,
            marks,
        },
        span: header,
    })
}
