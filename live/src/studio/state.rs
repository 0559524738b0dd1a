//! The JSON the page renders: the controls (one per parameter, from the
//! manifest) and the diagnostics (code, message, labelled source lines with
//! line and column, help). One definition for the render thread, which
//! writes it, and the tests, which read it.

use npr_abi::manifest::{ParamBinding, ParamManifest};
use npr_abi::param_value::{format_literal, ParamShape, ValueKind};
use npr_abi::ParamOverride;
use npr_diag::{Diagnostic, SourceMap};
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// One control: the manifest's parameter plus what the page needs to draw it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ParamState {
    #[serde(flatten)]
    pub manifest: ParamManifest,
    /// `float`, `int`, `bool`, `enum`, `color`, `range`, `unit`, `vector`,
    /// `gradient` (a ramp strip; `manifest.default` holds its `npr_abi::gradient`
    /// slots), or `none` (no control).
    pub control: String,
    /// The unit suffix a slider's number is written with (`px`, `deg`, ...), or "".
    pub suffix: String,
    /// The range in written units (degrees for angles), for a slider.
    pub range_written: Option<(f64, f64)>,
    pub step: f64,
    /// The current value as the language writes it (what "copy as --set" copies).
    pub literal: String,
    /// Whether a control moved it away from the file's default.
    pub overridden: bool,
    /// Not read by the output (the compiler removed it): its control is disabled.
    pub unused: bool,
}

/// What each parameter shows as written, by name, where it differs from
/// the value formatted in its canonical unit (`50mm`, not `0.05m`).
pub type Written = std::collections::BTreeMap<String, String>;

/// The controls of every parameter that is not per object.
pub fn params_json(params: &[ParamManifest], overrides: &[ParamOverride], written: &Written) -> Value {
    let list: Vec<ParamState> = params
        .iter()
        .filter(|p| p.binding != ParamBinding::PerObject)
        .map(|p| param_state(p, overrides, written))
        .collect();
    serde_json::to_value(list).unwrap_or(Value::Null)
}

fn param_state(p: &ParamManifest, overrides: &[ParamOverride], written: &Written) -> ParamState {
    let shape = ParamShape::of_manifest(p);
    let kind = shape.kind;
    let control = match kind {
        ValueKind::Float => "float",
        ValueKind::Int => "int",
        ValueKind::Bool => "bool",
        ValueKind::Enum => "enum",
        ValueKind::Colour => "color",
        ValueKind::Range => "range",
        ValueKind::Vector => "vector",
        ValueKind::Unit(_) => "unit",
        ValueKind::Gradient => "gradient",
        ValueKind::Unsupported => "none",
    };
    let range_written = p.range.map(|(lo, hi)| (kind.to_written(lo), kind.to_written(hi)));
    let step = match (kind, range_written) {
        (ValueKind::Int, _) => 1.0,
        (_, Some((lo, hi))) if hi > lo => (hi - lo) / 200.0,
        _ => 0.01,
    };
    let set = overrides.iter().find(|o| o.name == p.name);
    let literal = match set {
        _ if written.contains_key(&p.name) => written[&p.name].clone(),
        Some(o) if o.percent_of_height => format!("{}%", o.value[0]),
        Some(o) => format_literal(&shape, &o.value).unwrap_or_default(),
        None if p.default_percent_of_height => format!("{}%", p.default.first().copied().unwrap_or(0.0)),
        None => format_literal(&shape, &p.default).unwrap_or_default(),
    };
    let mut manifest = p.clone();
    if let Some(o) = set {
        manifest.default = o.value.clone();
        manifest.default_percent_of_height = o.percent_of_height;
    }
    ParamState {
        manifest,
        control: control.into(),
        suffix: kind.suffix().into(),
        range_written,
        step,
        literal,
        overridden: set.is_some(),
        unused: p.binding == ParamBinding::Removed,
    }
}

/// Bring the controls' values up to date after a slider moved (no rebuild).
pub fn set_values(params: &mut [Value], overrides: &[ParamOverride], written: &Written) {
    for v in params.iter_mut() {
        let Ok(mut p) = serde_json::from_value::<ParamState>(v.clone()) else {
            continue;
        };
        if overrides.iter().any(|o| o.name == p.manifest.name) {
            p = param_state(&p.manifest, overrides, written);
            *v = serde_json::to_value(p).unwrap_or(Value::Null);
        }
    }
}

/// Diagnostics as the page shows them: `dsl`'s JSON form (code, message,
/// help, labels with file, line and column, and the rendered text with the
/// source lines and the span marked), plus the stage that produced them.
pub fn diagnostics_json(diags: &[Diagnostic], sources: &SourceMap, stage: &str) -> Value {
    let list: Vec<Value> = npr_diag::diagnostic::render_json(diags, sources)
        .lines()
        .filter_map(|line| serde_json::from_str::<Value>(line).ok())
        .map(|mut d| {
            d["stage"] = stage.into();
            d
        })
        .collect();
    Value::Array(list)
}
