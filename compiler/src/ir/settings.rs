//! Parameter settings as data: a value as written ([`Literal`]) and a
//! setting of one parameter ([`ParamSetting`]) with where it was written
//! ([`SettingOrigin`]). The IR holds them (an art-map's filter arguments),
//! the CLI and the test harness build them, and `front::param_settings`
//! types them; they live here so that the IR imports no stage. The value
//! and its origin are the ABI's (`npr_abi::param_literal`): the runner types
//! a host's values by the same rule.

pub use npr_abi::param_literal::{Literal, SettingOrigin};
use npr_diag::Span;
use serde::Serialize;

/// One setting: `name` given the value `value`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamSetting {
    pub name: String,
    pub name_span: Span,
    pub value: Literal,
    /// The value as written (the text diagnostics quote is read here).
    pub value_span: Span,
    pub origin: SettingOrigin,
}
