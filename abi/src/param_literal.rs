//! A parameter's value as written, before it meets the parameter: the
//! [`Literal`] `--set` text reads as ([`read_literal`]: `5`, `2px`, `50%`,
//! `50mm`, `30deg`, `#ff8800`, `cubic`, `true`, `0.2..0.6`, `1, 0.5`), and
//! where the setting came from ([`SettingOrigin`]), which decides how
//! refusals name it. The compiler types `--set`, filter arguments and test
//! files' settings with these; the runner types a host's
//! `StyleRuntime::set_param` with the same (`param_value`).

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
    /// `StyleRuntime::set_param(name, value)`: a host application's call,
    /// typed as `--set` types it.
    Host,
}

impl SettingOrigin {
    /// How a diagnostic's message starts: `--set bands`, `filter `hatch.npr``.
    pub fn subject(&self, name: &str) -> String {
        match self {
            SettingOrigin::CommandLine => format!("--set {name}"),
            SettingOrigin::FilterArgument { filter } => format!("filter `{filter}`"),
            SettingOrigin::TestFile => format!("set.{name}"),
            SettingOrigin::Host => format!("set_param(\"{name}\")"),
        }
    }

    /// The style whose params are set, as the messages name it.
    pub fn owner(&self) -> &'static str {
        match self {
            SettingOrigin::CommandLine | SettingOrigin::TestFile | SettingOrigin::Host => "style",
            SettingOrigin::FilterArgument { .. } => "filter",
        }
    }

    /// `name` given `value`, as this origin writes it (for the help).
    pub fn example(&self, name: &str, value: &str) -> String {
        match self {
            SettingOrigin::CommandLine => format!("{name}={value}"),
            SettingOrigin::FilterArgument { .. } => format!("{name}: {value}"),
            SettingOrigin::TestFile => format!("{name} = \"{value}\""),
            SettingOrigin::Host => format!("set_param(\"{name}\", \"{value}\")"),
        }
    }

    /// What a vector of `n` components looks like written this way.
    pub fn expected_vector(&self, n: u32) -> String {
        match self {
            SettingOrigin::CommandLine | SettingOrigin::TestFile | SettingOrigin::Host => {
                format!("{n} numbers separated by commas")
            }
            SettingOrigin::FilterArgument { .. } => format!("a vec{n} of plain numbers"),
        }
    }

    /// Whether a number without a unit fits a unit parameter. A filter's
    /// argument is an expression of the language, where a plain number fits
    /// any unit (as in a default); `--set` asks for the unit (`2px`), since
    /// `2` on the command line could as well have meant `2%` or `2mm`.
    pub fn plain_number_takes_any_unit(&self) -> bool {
        matches!(self, SettingOrigin::FilterArgument { .. })
    }
}

/// `text` (one `--set` value, trimmed) as the literal it writes, whatever
/// the parameter: which literals a parameter takes is the compiler's to say.
pub fn read_literal(text: &str) -> Literal {
    match text {
        "true" => return Literal::Bool(true),
        "false" => return Literal::Bool(false),
        _ => {}
    }
    if text.starts_with('#') {
        return parse_colour(text).map_or(Literal::Unreadable, Literal::Colour);
    }
    if text.contains(':') {
        // A gradient's stops: `position:#colour`, comma-separated.
        let stops: Option<Vec<(f64, [f64; 4])>> = text
            .split(',')
            .map(|stop| {
                let (p, c) = stop.split_once(':')?;
                match split_number(p.trim()) {
                    Some((v, "", _)) => Some((v, parse_colour(c.trim())?)),
                    _ => None,
                }
            })
            .collect();
        return stops.map_or(Literal::Unreadable, Literal::Stops);
    }
    if let Some((lo, hi)) = text.split_once("..") {
        return match (split_number(lo.trim()), split_number(hi.trim())) {
            (Some((a, "", _)), Some((b, "", _))) => Literal::Range(a, b),
            _ => Literal::Unreadable,
        };
    }
    if text.contains(',') {
        // A vector: plain numbers only (no vector parameter has a unit).
        let parts: Option<Vec<(f64, bool)>> = text
            .split(',')
            .map(|s| match split_number(s.trim()) {
                Some((v, "", whole)) => Some((v, whole)),
                _ => None,
            })
            .collect();
        return parts.map_or(Literal::Unreadable, |parts| Literal::Numbers {
            whole: parts.iter().all(|(_, whole)| *whole),
            values: parts.into_iter().map(|(v, _)| v).collect(),
            suffix: String::new(),
        });
    }
    if let Some((v, suffix, whole)) = split_number(text) {
        return Literal::number(v, suffix, whole);
    }
    let is_name = text.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if is_name {
        Literal::Name(text.to_string())
    } else {
        Literal::Unreadable
    }
}

/// A number with an optional unit suffix, as the language writes it: the
/// longest prefix that reads as a finite number, the rest as the suffix, and
/// whether the number was written as a whole number.
fn split_number(text: &str) -> Option<(f64, &str, bool)> {
    // Rust also reads `inf` and `nan`; the language has neither.
    if !text.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '.' | '-' | '+')) {
        return None;
    }
    (1..=text.len())
        .rev()
        .filter(|&i| text.is_char_boundary(i))
        .find_map(|i| {
            let (digits, suffix) = text.split_at(i);
            let value: f64 = digits.parse().ok()?;
            value
                .is_finite()
                .then(|| (value, suffix.trim(), !digits.contains(['.', 'e', 'E'])))
        })
}

/// `#rrggbb` or `#rrggbbaa` as four components in 0..1.
fn parse_colour(text: &str) -> Option<[f64; 4]> {
    let hex = text.strip_prefix('#')?;
    if !(hex.len() == 6 || hex.len() == 8) || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
        return None;
    }
    let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok().map(|b| b as f64 / 255.0);
    Some([
        byte(0)?,
        byte(2)?,
        byte(4)?,
        if hex.len() == 8 { byte(6)? } else { 1.0 },
    ])
}

/// The candidate closest to `name` when one is close enough (Jaro-Winkler
/// above 0.8), for "did you mean" in refusals: the rule
/// `npr_diag::diagnostic::did_you_mean` applies to every other name.
pub fn did_you_mean<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (strsim::jaro_winkler(name, c), c))
        .filter(|(score, _)| *score > 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}
