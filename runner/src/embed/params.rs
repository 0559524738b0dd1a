//! Style parameters set by name at run time ([`StyleRuntime::set_param`]),
//! read and typed from the manifest's parameter metadata by the rule
//! `--set` uses (`npr_abi::param_literal::read_literal`, then
//! `npr_abi::param_value::type_value`): one definition, in the ABI.

use super::{EmbedError, StyleRuntime};
use npr_abi::manifest::{ParamBinding, ParamManifest};
use npr_abi::param_literal::{did_you_mean, read_literal, SettingOrigin};
use npr_abi::param_value::{format_literal, type_value, ParamShape};
use npr_diag::{codes, Diagnostic};

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

/// Whether a host can change `p` at run time: a slot of the style's
/// uniform block (a folded one is a constant in the shaders).
fn settable(p: &ParamManifest) -> bool {
    p.binding == ParamBinding::Uniform
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
        let params = &self.program.manifest.params;
        let Some(index) = params.iter().position(|p| p.name == name) else {
            return Err(EmbedError::Param(Box::new(unknown_param(name, params))));
        };
        let param = &params[index];
        let shape = ParamShape::of_manifest(param);
        let typed =
            type_value(&shape, &read_literal(value.trim()), value.trim(), &SettingOrigin::Host).map_err(|r| {
                EmbedError::Param(Box::new(
                    Diagnostic::error(r.code, format!("{}: {}", SettingOrigin::Host.subject(name), r.message))
                        .with_help(format!("{} ({})", r.help, r.label)),
                ))
            })?;
        if !settable(param) {
            return Err(EmbedError::Param(Box::new(
                Diagnostic::error(
                    codes::BAD_ARGUMENT_VALUE,
                    format!(
                        "set_param(\"{name}\"): `{name}` cannot change at run time: {}",
                        if param.binding == ParamBinding::Removed {
                            "nothing the style's output depends on reads it"
                        } else {
                            "it was folded into the style's shaders when the style was compiled"
                        }
                    ),
                )
                .with_help(
                    "compile the style with `keep_params` (`CompileOptions::keep_params`, \
                     `npr compile --keep-params`) to change its parameters at run time",
                ),
            )));
        }
        for params in
            std::iter::once(&mut self.program.manifest.params).chain(self.renderer.as_mut().map(|r| r.params_mut()))
        {
            params[index].set_constant(&typed);
        }
        Ok(())
    }
}

/// E0101 for a name the style has no settable parameter of.
fn unknown_param(name: &str, params: &[ParamManifest]) -> Diagnostic {
    let names: Vec<&str> = params.iter().filter(|p| settable(p)).map(|p| p.name.as_str()).collect();
    let d = Diagnostic::error(
        codes::UNKNOWN_NAME,
        format!("set_param(\"{name}\"): the style has no parameter `{name}` that can change at run time"),
    );
    match did_you_mean(name, names.iter().copied()) {
        Some(close) => d.with_help(format!("did you mean `{close}`?")),
        None if names.is_empty() => d.with_help(
            "this style has no run-time parameters: compile it with `keep_params` to keep them \
             in a uniform block",
        ),
        None => d.with_help(format!("its parameters are: {}", names.join(", "))),
    }
}
