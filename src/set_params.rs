//! `--set name=value`: a parameter's value given on the command line (or by
//! the studio), typed against the compiled manifest's parameters like a
//! default in the language: `5`, `2px`, `50%`, `50mm`, `30deg`, `#ff8800`,
//! `cubic`, `true`, `0.2..0.6`, `1, 0.5` (a vector).
//!
//! Every mistake is a diagnostic that points into the `--set` argument itself
//! (it is added to the [`SourceMap`] as a file named `--set`): an unknown
//! name with "did you mean" (E0101), a value of the wrong type (E0201) or
//! unit (E0202), a value outside the declared range (E0203), and a
//! per-object or texture parameter, which a single value cannot set (E0502).
//!
//! [`format_literal`] is the inverse of [`parse_value`]: it writes a value
//! back as the language spells it, for "copy as --set" and for rewriting a
//! default in the `.npr` file.

use crate::printer::Printer;
use abi::manifest::{ParamBinding, ParamManifest};
use compiler::mid::overrides::ParamOverride;
use compiler::{CompileError, CompileOptions, Compiled};
use diag::{codes, Diagnostic, SourceMap, Span};
use std::path::Path;

/// Compile `style` with `sets` applied, then `extra` (the studio's slider
/// values, which win over the command line): compiled once to learn its
/// parameters, the `--set`s typed against them, then compiled again with the
/// overrides, so they fold exactly like written defaults.
pub fn compile_with_sets(
    style: &Path,
    sets: &[String],
    extra: &[ParamOverride],
    sources: &mut SourceMap,
    opts: &CompileOptions,
) -> Result<Compiled, CompileError> {
    compile_with_sets_colours(style, sets, extra, sources, opts).map(|(c, _)| c)
}

/// [`compile_with_sets`], and the style's colour parameters
/// ([`declared_colours`]) when typing the overrides needed them, so that the
/// studio does not parse the style files a third time for its controls.
pub fn compile_with_sets_colours(
    style: &Path,
    sets: &[String],
    extra: &[ParamOverride],
    sources: &mut SourceMap,
    opts: &CompileOptions,
) -> Result<(Compiled, Option<Vec<String>>), CompileError> {
    let first = compiler::compile_file(style, sources, opts)?;
    if sets.is_empty() && extra.is_empty() {
        return Ok((first, None));
    }
    let colours = declared_colours(sources);
    let params = with_colours(&first.manifest.params, &colours);
    let mut overrides = resolve(sets, &params, sources).map_err(CompileError::User)?;
    for o in extra {
        overrides.retain(|x| x.name != o.name);
        overrides.push(o.clone());
    }
    let opts = CompileOptions {
        overrides,
        ..opts.clone()
    };
    compiler::compile_file(style, sources, &opts).map(|c| (c, Some(colours)))
}

/// [`compile_with_sets`] for the one-shot commands: diagnostics printed, the
/// error is the exit code.
pub(crate) fn compile(
    style: &Path,
    sets: &[String],
    sources: &mut SourceMap,
    opts: &CompileOptions,
    printer: &Printer,
) -> Result<Compiled, i32> {
    let result = compile_with_sets(style, sets, &[], sources, opts);
    crate::printer::report_compile(result, sources, printer)
}

/// The names of the parameters declared `color` in the style files of
/// `sources` (each parsed again: the manifest writes a colour's type as
/// `vec4`), so that a colour takes `#rrggbb` and gets a colour picker
/// ([`with_colours`]).
pub fn declared_colours(sources: &SourceMap) -> Vec<String> {
    let mut colours = Vec::new();
    for f in sources.files().iter().filter(|f| f.name.ends_with(".npr")) {
        let mut scratch = SourceMap::new();
        let id = scratch.add(f.name.clone(), f.text.clone());
        let (ast, _) = dsl::parse(id, &f.text);
        for item in &ast.items {
            if let dsl::ast::Item::Param(p) = item {
                if matches!(&p.ty, dsl::ast::TypeExpr::Named(t) if t.name == "color") {
                    colours.push(p.name.name.clone());
                }
            }
        }
    }
    colours
}

/// `params` with `ty` set to `color` for the names in `colours`.
pub fn with_colours(params: &[ParamManifest], colours: &[String]) -> Vec<ParamManifest> {
    params
        .iter()
        .map(|p| {
            let mut p = p.clone();
            if colours.contains(&p.name) {
                p.ty = "color".into();
            }
            p
        })
        .collect()
}

/// clap's value parser: `name=value` with a name, else a usage error (E0501).
pub fn parse_set_arg(s: &str) -> Result<String, String> {
    match s.split_once('=') {
        Some((name, _)) if !name.trim().is_empty() => Ok(s.to_string()),
        _ => Err("expected NAME=VALUE, e.g. --set bands=5 or --set base=#3080ff".into()),
    }
}

/// Type every `--set` against `params`. All mistakes are reported at once.
pub fn resolve(
    sets: &[String],
    params: &[ParamManifest],
    sources: &mut SourceMap,
) -> Result<Vec<ParamOverride>, Vec<Diagnostic>> {
    let mut overrides: Vec<ParamOverride> = Vec::new();
    let mut diags = Vec::new();
    for arg in sets {
        let file = sources.add("--set", arg.clone());
        let (name, value) = arg.split_once('=').unwrap_or((arg.as_str(), ""));
        let name_span = Span::new(file, 0, name.len());
        let value_span = Span::new(file, name.len() + 1, arg.len());
        let name = name.trim();
        let Some(param) = params.iter().find(|p| p.name == name) else {
            diags.push(unknown_name(name, name_span, params));
            continue;
        };
        match parse_value(param, value.trim()) {
            Ok(o) => {
                // A later `--set` of the same name wins, as in most CLIs.
                overrides.retain(|x| x.name != o.name);
                overrides.push(o);
            }
            Err(e) => diags.push(
                Diagnostic::error(e.code, format!("--set {name}: {}", e.message))
                    .with_primary(value_span, e.label)
                    .with_help(e.help),
            ),
        }
    }
    if diags.is_empty() {
        Ok(overrides)
    } else {
        Err(diags)
    }
}

fn unknown_name(name: &str, span: Span, params: &[ParamManifest]) -> Diagnostic {
    let settable: Vec<&str> = params.iter().filter(|p| settable(p)).map(|p| p.name.as_str()).collect();
    let d = Diagnostic::error(
        codes::UNKNOWN_NAME,
        format!("--set {name}: the style has no parameter `{name}`"),
    )
    .with_primary(span, "no parameter of this name");
    match diag::diagnostic::did_you_mean(name, settable.iter().copied()) {
        Some(close) => d.with_help(format!("did you mean `{close}`?")),
        None if settable.is_empty() => d.with_help("this style declares no parameter that --set can change"),
        None => d.with_help(format!("its parameters are: {}", settable.join(", "))),
    }
}

/// Whether one value can set this parameter (not per object, not a texture).
pub fn settable(p: &ParamManifest) -> bool {
    p.binding != ParamBinding::PerObject && p.ty != "texture"
}

/// Why a value was refused: a code, the message, the label under the value, a hint.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueError {
    pub code: &'static str,
    pub message: String,
    pub label: String,
    pub help: String,
}

fn refuse(
    code: &'static str,
    message: impl Into<String>,
    label: impl Into<String>,
    help: impl Into<String>,
) -> ValueError {
    ValueError {
        code,
        message: message.into(),
        label: label.into(),
        help: help.into(),
    }
}

/// What kind of value a parameter takes, read off its manifest entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Float,
    Int,
    Bool,
    Color,
    Enum,
    Range,
    /// A float with a unit: px, m, s, Hz or deg.
    Unit(UnitKind),
    /// vec2..vec4 of plain numbers.
    Vector,
    Unsupported,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnitKind {
    Px,
    Meters,
    Seconds,
    Hertz,
    Degrees,
}

impl UnitKind {
    pub fn suffix(self) -> &'static str {
        match self {
            UnitKind::Px => "px",
            UnitKind::Meters => "m",
            UnitKind::Seconds => "s",
            UnitKind::Hertz => "Hz",
            UnitKind::Degrees => "deg",
        }
    }

    /// Canonical value → the number written before the suffix.
    fn to_written(self, v: f64) -> f64 {
        match self {
            UnitKind::Degrees => v.to_degrees(),
            _ => v,
        }
    }
}

pub fn kind(p: &ParamManifest) -> Kind {
    if !p.enum_variants.is_empty() {
        return Kind::Enum;
    }
    match (p.ty.as_str(), p.unit.as_str()) {
        ("range", _) => Kind::Range,
        ("bool", _) => Kind::Bool,
        ("int", _) => Kind::Int,
        ("color", _) => Kind::Color,
        ("float", _) => Kind::Float,
        ("vec2" | "vec3" | "vec4", _) => Kind::Vector,
        (_, "px") => Kind::Unit(UnitKind::Px),
        (_, "m") => Kind::Unit(UnitKind::Meters),
        (_, "s") => Kind::Unit(UnitKind::Seconds),
        (_, "Hz") => Kind::Unit(UnitKind::Hertz),
        (_, "deg") => Kind::Unit(UnitKind::Degrees),
        _ => Kind::Unsupported,
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

/// Type `text` as a value of `p`: its canonical components.
pub fn parse_value(p: &ParamManifest, text: &str) -> Result<ParamOverride, ValueError> {
    let name = &p.name;
    if p.binding == ParamBinding::PerObject {
        return Err(refuse(
            codes::BAD_ARGUMENT_VALUE,
            format!("`{name}` is a per-object parameter"),
            "the scene binds this per object",
            format!("set it in the scene, in an [[object]]'s `params = {{ {name} = ... }}`"),
        ));
    }
    let done = |value: Vec<f64>| ParamOverride {
        name: name.clone(),
        value,
        percent_of_height: false,
    };
    let kind = kind(p);
    let value = match kind {
        Kind::Unsupported => {
            return Err(refuse(
                codes::TYPE_MISMATCH,
                format!("`{name}` is {}, which --set cannot change", p.ty),
                "not settable from the command line",
                "change it in the style file",
            ))
        }
        Kind::Bool => match text {
            "true" => vec![1.0],
            "false" => vec![0.0],
            _ => return Err(type_error(p, text, "`true` or `false`")),
        },
        Kind::Enum => match p.enum_variants.iter().position(|v| v == text) {
            Some(i) => vec![i as f64],
            None => {
                let help = match diag::diagnostic::did_you_mean(text, p.enum_variants.iter().map(String::as_str)) {
                    Some(close) => format!("did you mean `{close}`?"),
                    None => format!("one of: {}", p.enum_variants.join(", ")),
                };
                return Err(refuse(
                    codes::TYPE_MISMATCH,
                    format!("`{text}` is not a variant of `{name}`"),
                    format!("expected one of {}", p.enum_variants.join(" | ")),
                    help,
                ));
            }
        },
        Kind::Color => match parse_color(text) {
            Some(c) => c[..(p.components as usize).clamp(3, 4)].to_vec(),
            None => return Err(type_error(p, text, "a colour `#rrggbb` or `#rrggbbaa`")),
        },
        Kind::Int => match split_number(text) {
            Some((v, "", true)) => vec![v],
            Some((_, "", false)) => {
                return Err(refuse(
                    codes::TYPE_MISMATCH,
                    format!("`{name}` is an int, but `{text}` has a fraction"),
                    "expected a whole number",
                    format!("write a whole number, e.g. `{name}={}`", default_text(p)),
                ))
            }
            Some((_, unit, _)) => return Err(unit_error(p, text, unit)),
            None => return Err(type_error(p, text, "a whole number")),
        },
        Kind::Float => match split_number(text) {
            Some((v, "", _)) => vec![v],
            Some((_, unit, _)) => return Err(unit_error(p, text, unit)),
            None => return Err(type_error(p, text, "a number")),
        },
        Kind::Unit(unit) => match split_number(text) {
            Some((v, "%", _)) if unit == UnitKind::Px => {
                // Resolved against the image height per frame, like a `%` default;
                // its range is checked in px only once the height is known.
                return Ok(ParamOverride {
                    name: name.clone(),
                    value: vec![v],
                    percent_of_height: true,
                });
            }
            Some((v, suffix, _)) => match canonical(unit, v, suffix) {
                Some(v) => vec![v],
                None => return Err(unit_error(p, text, suffix)),
            },
            None => return Err(type_error(p, text, &format!("a number in {}", unit.suffix()))),
        },
        Kind::Range => {
            let parsed = text
                .split_once("..")
                .and_then(|(a, b)| Some((split_number(a.trim())?, split_number(b.trim())?)));
            match parsed {
                Some(((a, "", _), (b, "", _))) if a <= b => vec![a, b],
                Some(((a, "", _), (b, "", _))) => {
                    return Err(refuse(
                        codes::OUT_OF_RANGE,
                        format!("the range {a}..{b} is empty"),
                        "the start is after the end",
                        format!("write it low to high: `{b}..{a}`"),
                    ))
                }
                _ => return Err(type_error(p, text, "a range `a..b`")),
            }
        }
        Kind::Vector => {
            let parts: Vec<_> = text.split(',').map(|s| split_number(s.trim())).collect();
            match parts
                .iter()
                .map(|x| x.filter(|(_, u, _)| u.is_empty()).map(|(v, _, _)| v))
                .collect::<Option<Vec<f64>>>()
            {
                Some(v) if v.len() == p.components as usize => v,
                _ => {
                    return Err(type_error(
                        p,
                        text,
                        &format!("{} numbers separated by commas", p.components),
                    ))
                }
            }
        }
    };
    check_range(p, &value)?;
    Ok(done(value))
}

/// `v` written with `suffix`, in the unit's canonical form (mm → m, deg → radians).
fn canonical(unit: UnitKind, v: f64, suffix: &str) -> Option<f64> {
    match (unit, suffix) {
        (UnitKind::Px, "px") | (UnitKind::Meters, "m") | (UnitKind::Seconds, "s") | (UnitKind::Hertz, "Hz") => Some(v),
        (UnitKind::Meters, "mm") => Some(v * 1e-3),
        (UnitKind::Degrees, "deg") => Some(v.to_radians()),
        _ => None,
    }
}

/// The range check of a typed value (also used for the studio's controls).
pub fn check_range(p: &ParamManifest, value: &[f64]) -> Result<(), ValueError> {
    let Some((lo, hi)) = p.range else { return Ok(()) };
    if matches!(kind(p), Kind::Range | Kind::Enum | Kind::Color | Kind::Bool) {
        return Ok(());
    }
    if value.iter().all(|v| (lo..=hi).contains(v)) {
        return Ok(());
    }
    let shown = |v: f64| match kind(p) {
        Kind::Unit(u) => format!("{}{}", fmt_num(u.to_written(v)), u.suffix()),
        _ => fmt_num(v),
    };
    let range = format!("{}..{}", shown(lo), shown(hi));
    Err(refuse(
        codes::OUT_OF_RANGE,
        format!("`{}` is declared `in {range}`", p.name),
        format!("outside {range}"),
        format!("give a value from {} to {}", shown(lo), shown(hi)),
    ))
}

fn type_error(p: &ParamManifest, text: &str, expected: &str) -> ValueError {
    refuse(
        codes::TYPE_MISMATCH,
        format!("`{text}` is not a value of `{}` ({})", p.name, p.ty),
        format!("expected {expected}"),
        format!("its default is `{}`", default_text(p)),
    )
}

fn unit_error(p: &ParamManifest, text: &str, found: &str) -> ValueError {
    let want = match kind(p) {
        Kind::Unit(UnitKind::Px) => "px (or % of the image height)".to_string(),
        Kind::Unit(UnitKind::Meters) => "m or mm".to_string(),
        Kind::Unit(u) => u.suffix().to_string(),
        _ => "no unit".to_string(),
    };
    let found = if found.is_empty() { "no unit" } else { found };
    refuse(
        codes::UNIT_MISMATCH,
        format!("`{}` takes {want}, but `{text}` has {found}", p.name),
        format!("expected {want}"),
        format!("write it like its default, `{}`", default_text(p)),
    )
}

fn parse_color(text: &str) -> Option<[f64; 4]> {
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

/// A number as short as it can be written and still read back exactly.
fn fmt_num(v: f64) -> String {
    let s = format!("{v}");
    if s.contains('e') {
        format!("{v:.6}")
    } else {
        s
    }
}

fn default_text(p: &ParamManifest) -> String {
    if p.default_percent_of_height {
        return format!("{}%", fmt_num(p.default.first().copied().unwrap_or(0.0)));
    }
    format_literal(p, &p.default).unwrap_or_else(|| "?".into())
}

/// `value` (canonical components) written as the language spells it, so
/// that [`parse_value`] reads it back. `None` for kinds --set cannot set.
pub fn format_literal(p: &ParamManifest, value: &[f64]) -> Option<String> {
    let first = *value.first()?;
    Some(match kind(p) {
        Kind::Float => fmt_num(first),
        Kind::Int => format!("{}", first.round() as i64),
        Kind::Bool => (first != 0.0).to_string(),
        Kind::Enum => p.enum_variants.get(first as usize)?.clone(),
        Kind::Unit(u) => format!("{}{}", fmt_num(u.to_written(first)), u.suffix()),
        Kind::Color => {
            let b = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
            let mut s = format!("#{:02x}{:02x}{:02x}", b(first), b(*value.get(1)?), b(*value.get(2)?));
            if let Some(a) = value.get(3).filter(|a| **a < 1.0) {
                s.push_str(&format!("{:02x}", b(*a)));
            }
            s
        }
        Kind::Range => format!("{}..{}", fmt_num(first), fmt_num(*value.get(1)?)),
        Kind::Vector => value.iter().map(|v| fmt_num(*v)).collect::<Vec<_>>().join(", "),
        Kind::Unsupported => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn param(ty: &str, unit: &str, default: Vec<f64>, range: Option<(f64, f64)>) -> ParamManifest {
        ParamManifest {
            name: "p".into(),
            doc: String::new(),
            ty: ty.into(),
            unit: unit.into(),
            components: default.len() as u32,
            default,
            default_percent_of_height: false,
            range,
            enum_variants: Vec::new(),
            keyframes: Vec::new(),
            interpolation: "linear".into(),
            binding: ParamBinding::Folded,
            offset: None,
        }
    }

    #[test]
    fn values_are_read_in_canonical_units() {
        let deg = param("deg", "deg", vec![0.0], None);
        let v = parse_value(&deg, "90deg").expect("deg").value[0];
        assert!((v - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let m = param("m", "m", vec![1.0], None);
        assert_eq!(parse_value(&m, "50mm").expect("mm").value, vec![0.05]);
        let px = param("px", "px", vec![2.0], Some((0.0, 16.0)));
        assert!(parse_value(&px, "50%").expect("%").percent_of_height);
        assert_eq!(parse_value(&px, "16px").expect("px").value, vec![16.0]);
        assert_eq!(parse_value(&px, "17px").unwrap_err().code, codes::OUT_OF_RANGE);
        assert_eq!(parse_value(&px, "2").unwrap_err().code, codes::UNIT_MISMATCH);
        assert_eq!(parse_value(&px, "2m").unwrap_err().code, codes::UNIT_MISMATCH);
        let int = param("int", "a plain number", vec![3.0], Some((1.0, 8.0)));
        assert_eq!(parse_value(&int, "2.5").unwrap_err().code, codes::TYPE_MISMATCH);
        assert_eq!(parse_value(&int, "1e1").unwrap_err().code, codes::TYPE_MISMATCH);
        let f = param("float", "a plain number", vec![0.5], None);
        assert_eq!(parse_value(&f, "1e-3").expect("exponent").value, vec![1e-3]);
        assert_eq!(parse_value(&f, "x").unwrap_err().code, codes::TYPE_MISMATCH);
    }

    #[test]
    fn every_literal_written_reads_back_to_its_value() {
        let mut e = param("enum(a|b)", "a plain number", vec![1.0], None);
        e.enum_variants = vec!["a".into(), "b".into()];
        let cases = [
            (param("float", "a plain number", vec![0.25], None), vec![0.1]),
            (param("int", "a plain number", vec![3.0], None), vec![7.0]),
            (param("bool", "a plain number", vec![1.0], None), vec![0.0]),
            (param("px", "px", vec![2.0], None), vec![3.5]),
            (param("deg", "deg", vec![0.5], None), vec![30f64.to_radians()]),
            (
                param("color", "a plain number", vec![1.0, 0.5, 0.0, 1.0], None),
                vec![48.0 / 255.0, 128.0 / 255.0, 1.0, 1.0],
            ),
            (param("range", "a plain number", vec![0.2, 0.6], None), vec![0.1, 0.9]),
            (
                param("vec3", "a plain number", vec![0.0; 3], None),
                vec![1.0, -2.5, 0.125],
            ),
            (e, vec![0.0]),
        ];
        for (p, v) in cases {
            let text = format_literal(&p, &v).expect("formattable");
            let back = parse_value(&p, &text)
                .unwrap_or_else(|e| panic!("{} `{text}`: {e:?}", p.ty))
                .value;
            assert_eq!(back.len(), v.len(), "{} `{text}`", p.ty);
            for (a, b) in back.iter().zip(&v) {
                assert!((a - b).abs() < 1e-12, "{} `{text}`: {a} vs {b}", p.ty);
            }
        }
    }
}
