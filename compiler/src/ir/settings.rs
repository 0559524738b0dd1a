//! Parameter settings as data: a value as written ([`Literal`]) and a
//! setting of one parameter ([`ParamSetting`]) with where it was written
//! ([`SettingOrigin`]). The IR holds them (an art-map's filter arguments),
//! the CLI and the test harness build them, and `front::param_settings`
//! types them; they live here so that the IR imports no stage.

use diag::Span;
use serde::Serialize;

/// A value as written, before it meets a parameter: `--set` text read by
/// the CLI, or a filter's argument read by resolve from the host's AST.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum Literal {
    /// One number or several (`8`, `2px`, `50%`, `30deg`, `1, 0.5`,
    /// `vec2(1, 0.5)`), in canonical units when the suffix is a unit's (mm
    /// as m, deg as radians; see [`Literal::number`]), with the suffix as
    /// written ("" for none), and whether every number was written whole
    /// (without a `.` or an exponent).
    Numbers {
        values: Vec<f64>,
        suffix: String,
        whole: bool,
    },
    /// `#rrggbb` or `#rrggbbaa`, each component in 0..1.
    Colour([f64; 4]),
    Bool(bool),
    /// A bare name: the variant of an enum (`cubic`).
    Name(String),
    /// `lo..hi`.
    Range(f64, f64),
    /// `0:#000000, 0.5:#ff8800, 1:#ffffff`: a gradient's stops (position,
    /// colour), as written; only a `gradient` param takes it.
    Stops(Vec<(f64, [f64; 4])>),
    /// Text that reads as none of these (`#12`, `1..x`): only `--set` text
    /// can be this, and every parameter refuses it.
    Unreadable,
}

impl Literal {
    /// A number written with `suffix`, converted as resolve converts a
    /// number literal of the language (`50mm` is 0.05 m, `30deg` is π/6).
    pub fn number(written: f64, suffix: &str, whole: bool) -> Literal {
        let value = match suffix {
            "mm" => written * 1e-3,
            "deg" => written.to_radians(),
            _ => written,
        };
        Literal::Numbers {
            values: vec![value],
            suffix: suffix.to_string(),
            whole,
        }
    }
}

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

/// Where a setting was written, which decides how its diagnostics name it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum SettingOrigin {
    /// `--set name=value` (or a studio control): text in a `--set` file of
    /// the SourceMap.
    CommandLine,
    /// `filter("path", name: value)`: a constant expression in the host
    /// style; `filter` is the path as written.
    FilterArgument { filter: String },
    /// `set = { name = value }` in a style's `<style>.tests.toml`: typed as
    /// `--set` types it, named as the test file writes it.
    TestFile,
}

impl SettingOrigin {
    /// How a diagnostic's message starts: `--set bands`, `filter `hatch.npr``.
    pub(crate) fn subject(&self, name: &str) -> String {
        match self {
            SettingOrigin::CommandLine => format!("--set {name}"),
            SettingOrigin::FilterArgument { filter } => format!("filter `{filter}`"),
            SettingOrigin::TestFile => format!("set.{name}"),
        }
    }

    /// The style whose params are set, as the messages name it.
    pub(crate) fn owner(&self) -> &'static str {
        match self {
            SettingOrigin::CommandLine | SettingOrigin::TestFile => "style",
            SettingOrigin::FilterArgument { .. } => "filter",
        }
    }

    /// `name` given `value`, as this origin writes it (for the help).
    pub(crate) fn example(&self, name: &str, value: &str) -> String {
        match self {
            SettingOrigin::CommandLine => format!("{name}={value}"),
            SettingOrigin::FilterArgument { .. } => format!("{name}: {value}"),
            SettingOrigin::TestFile => format!("{name} = \"{value}\""),
        }
    }

    /// What a vector of `n` components looks like written this way.
    pub(crate) fn expected_vector(&self, n: u32) -> String {
        match self {
            SettingOrigin::CommandLine | SettingOrigin::TestFile => format!("{n} numbers separated by commas"),
            SettingOrigin::FilterArgument { .. } => format!("a vec{n} of plain numbers"),
        }
    }

    /// Whether a number without a unit fits a unit parameter. A filter's
    /// argument is an expression of the language, where a plain number fits
    /// any unit (as in a default); `--set` asks for the unit (`2px`), since
    /// `2` on the command line could as well have meant `2%` or `2mm`.
    pub(crate) fn plain_number_takes_any_unit(&self) -> bool {
        matches!(self, SettingOrigin::FilterArgument { .. })
    }
}
