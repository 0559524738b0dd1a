//! Style parameters set by name at run time ([`super::StyleRuntime::set_param`]),
//! typed and range-checked from the manifest's parameter metadata by the
//! rule `--set` uses (`abi::param_value`).

use super::{EmbedError, StyleRuntime};

/// A parameter the host can set: what [`StyleRuntime::params`] lists.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamInfo {
    pub name: String,
    /// As declared: `float`, `int`, `bool`, `color`, `px`, `enum(a|b)`, …
    pub ty: String,
    /// The declared `in lo..hi`, in canonical units (px, m, s, Hz, radians).
    pub range: Option<(f64, f64)>,
    /// The current value, written as `--set` takes it.
    pub value: String,
}

impl StyleRuntime {
    /// The style's parameters a host can set (not per-object ones), with
    /// their current values.
    pub fn params(&self) -> Vec<ParamInfo> {
        self.program
            .manifest
            .params
            .iter()
            .filter(|p| p.binding != abi::manifest::ParamBinding::PerObject)
            .map(|p| ParamInfo {
                name: p.name.clone(),
                ty: p.ty.clone(),
                range: p.range,
                value: format!("{:?}", p.default),
            })
            .collect()
    }

    /// Set style parameter `name` to `value`, written as `--set` takes it
    /// (`5`, `2px`, `50%`, `30deg`, `#ff8800`, `true`, `cubic`,
    /// `0.2..0.6`, `1, 0.5`). From the next frame on. An unknown name is
    /// E0101 (with "did you mean"), a value of the wrong type E0201, unit
    /// E0202, outside the declared range E0203, a per-object param E0502.
    pub fn set_param(&mut self, name: &str, value: &str) -> Result<(), EmbedError> {
        let _ = (name, value);
        Err(crate::RunError::Internal("set_param: not yet implemented".into()).into())
    }
}
