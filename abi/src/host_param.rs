//! A host setting a compiled style's parameter by name at run time: the
//! embedding API's `StyleRuntime::set_param` and the web module's
//! `Style.setParam` follow this one rule, each naming itself in messages
//! ([`HostApi`]). The value is written as `--set` takes it, read by
//! [`crate::param_literal::read_literal`] and typed by
//! [`crate::param_value::type_value`]; only a parameter with a slot in the
//! style's uniform block can change. An unknown name is E0101 (with "did
//! you mean"), a wrong type, unit or range E0201-E0203, a parameter folded
//! into the shaders, bound per object or read by nothing E0502.

use crate::manifest::{ParamBinding, ParamManifest, ParamOverride};
use crate::param_literal::{did_you_mean, read_literal, SettingOrigin};
use crate::param_value::{codes, type_value, ParamShape};

/// Why a host's setting was refused: a code (as `npr_diag::codes` defines
/// it), the message and a hint, which the host API reports as a
/// diagnostic (it has no source span).
#[derive(Debug, Clone, PartialEq)]
pub struct HostRefusal {
    pub code: &'static str,
    pub message: String,
    pub help: String,
}

/// How a host API spells itself in messages.
#[derive(Debug, Clone, Copy)]
pub struct HostApi {
    /// The call, as the user wrote it: `set_param`, `setParam`.
    pub set_param: &'static str,
    /// How to compile a style so that its parameters stay settable.
    pub keep_params: &'static str,
}

/// The Rust embedding API (`npr_runner::embed::StyleRuntime`).
pub const RUST_API: HostApi = HostApi {
    set_param: "set_param",
    keep_params: "`keep_params` (`CompileOptions::keep_params`, `npr compile --keep-params`)",
};

/// The web module (`npr-web`'s `Style`).
pub const JS_API: HostApi = HostApi {
    set_param: "setParam",
    keep_params: "`{ keepParams: true }`",
};

/// Whether a host can change `p` at run time: a slot of the style's
/// uniform block (a folded one is a constant in the shaders).
pub fn settable(p: &ParamManifest) -> bool {
    p.binding == ParamBinding::Uniform
}

/// `value` for parameter `name` of `params`, typed: its index and the
/// constant to give it ([`ParamManifest::set_constant`]). The caller
/// changes nothing on an error.
pub fn type_host_setting(
    params: &[ParamManifest],
    name: &str,
    value: &str,
    api: &HostApi,
) -> Result<(usize, ParamOverride), HostRefusal> {
    let Some(index) = params.iter().position(|p| p.name == name) else {
        return Err(unknown_param(name, params, api));
    };
    let param = &params[index];
    let typed = type_value(
        &ParamShape::of_manifest(param),
        &read_literal(value.trim()),
        value.trim(),
        &SettingOrigin::Host,
    )
    .map_err(|r| HostRefusal {
        code: r.code,
        message: format!("{}: {}", SettingOrigin::Host.subject(name), r.message),
        help: format!("{} ({})", r.help, r.label),
    })?;
    if !settable(param) {
        return Err(HostRefusal {
            code: codes::BAD_ARGUMENT_VALUE,
            message: format!(
                "{}(\"{name}\"): `{name}` cannot change at run time: {}",
                api.set_param,
                if param.binding == ParamBinding::Removed {
                    "nothing the style's output depends on reads it"
                } else {
                    "it was folded into the style's shaders when the style was compiled"
                }
            ),
            help: format!(
                "compile the style with {} to change its parameters at run time",
                api.keep_params
            ),
        });
    }
    Ok((index, typed))
}

/// E0101 for a name the style has no settable parameter of.
fn unknown_param(name: &str, params: &[ParamManifest], api: &HostApi) -> HostRefusal {
    let names: Vec<&str> = params.iter().filter(|p| settable(p)).map(|p| p.name.as_str()).collect();
    let help = match did_you_mean(name, names.iter().copied()) {
        Some(close) => format!("did you mean `{close}`?"),
        None if names.is_empty() => format!(
            "this style has no run-time parameters: compile it with {} to keep them in a uniform block",
            api.keep_params
        ),
        None => format!("its parameters are: {}", names.join(", ")),
    };
    HostRefusal {
        code: codes::UNKNOWN_NAME,
        message: format!(
            "{}(\"{name}\"): the style has no parameter `{name}` that can change at run time",
            api.set_param
        ),
        help,
    }
}
