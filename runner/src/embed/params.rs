//! Style parameters set by name at run time ([`StyleRuntime::set_param`]),
//! by the rule every host API follows (`npr_abi::host_param`, which types
//! values as `--set` does): one definition, in the ABI.

use super::{EmbedError, StyleRuntime};
use npr_abi::host_param::{settable, type_host_setting, RUST_API};
use npr_abi::manifest::ParamManifest;
use npr_abi::param_value::{format_literal, ParamShape};
use npr_diag::Diagnostic;

/// A parameter the host can set: what [`StyleRuntime::params`] lists.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamInfo {
    pub name: String,
    /// As declared: `float`, `int`, `bool`, `color`, `px`, `enum(a|b)`, …
    pub ty: String,
    /// The declared `in lo..hi`, in canonical units (px, m, s, Hz, radians).
    pub range: Option<(f64, f64)>,
    /// The current value, written as [`StyleRuntime::set_param`] takes it.
    pub value: String,
}

fn value_text(p: &ParamManifest) -> String {
    if p.default_percent_of_height {
        return format!("{}%", p.default.first().copied().unwrap_or(0.0));
    }
    format_literal(&ParamShape::of_manifest(p), &p.default).unwrap_or_default()
}

impl StyleRuntime {
    /// The style's parameters a host can set at run time (those with a
    /// slot in the style's uniform block: animated ones, or every one of
    /// a style compiled with `keep_params`), with their current values.
    pub fn params(&self) -> Vec<ParamInfo> {
        self.program
            .manifest
            .params
            .iter()
            .filter(|p| settable(p))
            .map(|p| ParamInfo {
                name: p.name.clone(),
                ty: p.ty.clone(),
                range: p.range,
                value: value_text(p),
            })
            .collect()
    }

    /// Set style parameter `name` to `value`, written as `--set` takes it
    /// (`5`, `2px`, `50%`, `30deg`, `#ff8800`, `true`, `cubic`,
    /// `0.2..0.6`, `1, 0.5`), from the next frame on; an animated
    /// parameter becomes this constant. An unknown name is E0101 (with
    /// "did you mean"), a value of the wrong type E0201, of the wrong unit
    /// E0202, outside the declared range E0203; a per-object parameter, or
    /// one the compiler folded into the shaders, E0502. On an error
    /// nothing changes.
    pub fn set_param(&mut self, name: &str, value: &str) -> Result<(), EmbedError> {
        let (index, typed) = type_host_setting(&self.program.manifest.params, name, value, &RUST_API)
            .map_err(|r| EmbedError::Param(Box::new(Diagnostic::error(r.code, r.message).with_help(r.help))))?;
        for params in
            std::iter::once(&mut self.program.manifest.params).chain(self.renderer.as_mut().map(|r| r.params_mut()))
        {
            params[index].set_constant(&typed);
        }
        Ok(())
    }
}
