//! One value for one parameter, the rules `--set`, the studio's controls
//! and a filter's arguments share: what kind of value a parameter takes
//! ([`ValueKind`], read off its declared type), a value as written
//! ([`Literal`]), the typing of the one against the other ([`type_value`]:
//! canonical components, or why not), and the inverse, [`format_literal`],
//! which writes a value as the language spells it ("copy as --set",
//! rewriting a default in the file, the help of a refusal).
//!
//! The parameter is seen through a [`ParamShape`], made from the IR after
//! typecheck (`npr_compiler::front::param_values::shape_of_ir`, in the one
//! compile) or from a manifest entry (the studio, and a host's
//! `npr_runner::embed::StyleRuntime::set_param`, typing a value against the
//! running style without compiling). This is the one definition of the
//! rule; the compiler and the runner both call it.

use crate::manifest::{ParamBinding, ParamManifest, ParamOverride};
use crate::param_literal::{Literal, SettingOrigin};
use crate::Unit;

/// The unit a suffix writes: "" a plain number, `mm` metres; `None` for a
/// suffix that is no unit (`%` is a share of the image height, not a unit).
pub fn unit_of_suffix(suffix: &str) -> Option<Unit> {
    Some(match suffix {
        "" => Unit::None,
        "px" => Unit::Px,
        "m" | "mm" => Unit::Meters,
        "s" => Unit::Seconds,
        "Hz" => Unit::Hertz,
        "deg" => Unit::Radians,
        _ => return None,
    })
}

/// The suffix a value in `unit` is written with ("" for a plain number).
pub fn suffix_of(unit: Unit) -> &'static str {
    match unit {
        Unit::None => "",
        u => u.name(),
    }
}

/// What kind of value a parameter takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueKind {
    Float,
    Int,
    Bool,
    Colour,
    Enum,
    Range,
    /// A float with a unit: px, m, s, Hz or deg (radians inside).
    Unit(Unit),
    /// vec2..vec4 of plain numbers.
    Vector,
    /// A colour ramp kept live: its slots ([`crate::gradient`]), typed
    /// from stops (`0:#000000, 1:#ffffff`).
    Gradient,
    /// A type no single value sets (nothing the compiler declares today;
    /// an unknown type in a manifest from elsewhere).
    Unsupported,
}

impl ValueKind {
    /// The kind of a declared type as `Param::declared_type` (and so the
    /// manifest) writes it: the one mapping from types to kinds.
    pub fn of(declared: &str) -> ValueKind {
        match declared {
            "float" => ValueKind::Float,
            "int" => ValueKind::Int,
            "bool" => ValueKind::Bool,
            "color" => ValueKind::Colour,
            "range" => ValueKind::Range,
            "vec2" | "vec3" | "vec4" => ValueKind::Vector,
            crate::gradient::GRADIENT_TYPE => ValueKind::Gradient,
            t if t.starts_with("enum(") => ValueKind::Enum,
            t => match unit_of_suffix(t) {
                Some(u) if u != Unit::None => ValueKind::Unit(u),
                _ => ValueKind::Unsupported,
            },
        }
    }

    /// The suffix a value of this kind is written with (`px`, `deg`), or "".
    pub fn suffix(self) -> &'static str {
        match self {
            ValueKind::Unit(u) => suffix_of(u),
            _ => "",
        }
    }

    /// A canonical value as it is written (radians as degrees).
    pub fn to_written(self, v: f64) -> f64 {
        match self {
            ValueKind::Unit(Unit::Radians) => v.to_degrees(),
            _ => v,
        }
    }
}

/// What typing a value needs to know of a parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamShape {
    pub name: String,
    /// As declared (`Param::declared_type`): `color`, `px`, `enum(a|b)`.
    pub ty: String,
    pub kind: ValueKind,
    pub components: u32,
    pub range: Option<(f64, f64)>,
    pub variants: Vec<String>,
    /// Bound per object by the scene: no single value sets it.
    pub per_object: bool,
    /// In canonical units; a `%` default in percent.
    pub default: Vec<f64>,
    pub default_percent_of_height: bool,
}

impl ParamShape {
    /// A compiled style's parameter, as the manifest describes it.
    pub fn of_manifest(p: &ParamManifest) -> ParamShape {
        ParamShape {
            name: p.name.clone(),
            ty: p.ty.clone(),
            kind: ValueKind::of(&p.ty),
            components: p.components,
            range: p.range,
            variants: p.enum_variants.clone(),
            per_object: p.binding == ParamBinding::PerObject,
            default: p.default.clone(),
            default_percent_of_height: p.default_percent_of_height,
        }
    }
}

/// The diagnostic codes of refusals, as `npr_diag::codes` defines them (the
/// ABI depends on no other npr crate; `abi/tests/refusal_codes.rs` holds
/// these equal to diag's).
pub mod codes {
    pub const UNKNOWN_NAME: &str = "E0101";
    pub const BAD_ARGUMENT_VALUE: &str = "E0502";
    pub const TYPE_MISMATCH: &str = "E0201";
    pub const UNIT_MISMATCH: &str = "E0202";
    pub const OUT_OF_RANGE: &str = "E0203";
    pub const BAD_GRADIENT: &str = "E0206";
}

/// Why a value was refused: a code, the message, the label under the value, a hint.
#[derive(Debug, Clone, PartialEq)]
pub struct Refusal {
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
) -> Refusal {
    Refusal {
        code,
        message: message.into(),
        label: label.into(),
        help: help.into(),
    }
}

/// Type `literal` (written as `text`) as a value of `p`: its canonical
/// components, or the [`Refusal`]. `origin` says how the value was
/// written, for the one rule that differs (a plain number for a unit
/// parameter) and for the examples in the help.
pub fn type_value(
    p: &ParamShape,
    literal: &Literal,
    text: &str,
    origin: &SettingOrigin,
) -> Result<ParamOverride, Refusal> {
    let name = &p.name;
    if p.per_object {
        return Err(refuse(
            codes::BAD_ARGUMENT_VALUE,
            format!("`{name}` is a per-object parameter"),
            "the scene binds this per object",
            format!("set it in the scene, in an [[object]]'s `params = {{ {name} = ... }}`"),
        ));
    }
    let one = |values: &Vec<f64>| values.len() == 1;
    let value = match (p.kind, literal) {
        (ValueKind::Unsupported, _) => {
            return Err(refuse(
                codes::TYPE_MISMATCH,
                format!("`{name}` is {}, which no single value can set", p.ty),
                "not settable from outside the style",
                "change it in the style file",
            ))
        }
        (ValueKind::Bool, Literal::Bool(b)) => vec![if *b { 1.0 } else { 0.0 }],
        (ValueKind::Bool, _) => return Err(type_error(p, text, "`true` or `false`")),
        (ValueKind::Enum, literal) => {
            let chosen = match literal {
                Literal::Name(v) => p.variants.iter().position(|x| x == v),
                _ => None,
            };
            match chosen {
                Some(i) => vec![i as f64],
                None => return Err(not_a_variant(p, text)),
            }
        }
        (ValueKind::Colour, Literal::Colour(c)) => c[..(p.components as usize).clamp(3, 4)].to_vec(),
        (ValueKind::Colour, _) => return Err(type_error(p, text, "a colour `#rrggbb` or `#rrggbbaa`")),
        (ValueKind::Int, Literal::Numbers { values, suffix, whole }) if one(values) => {
            match (suffix.as_str(), *whole) {
                ("", true) => values.clone(),
                ("", false) => {
                    return Err(refuse(
                        codes::TYPE_MISMATCH,
                        format!("`{name}` is an int, but `{text}` has a fraction"),
                        "expected a whole number",
                        format!(
                            "write a whole number, e.g. `{}`",
                            origin.example(name, &default_text(p))
                        ),
                    ))
                }
                (suffix, _) => return Err(unit_error(p, text, suffix)),
            }
        }
        (ValueKind::Int, _) => return Err(type_error(p, text, "a whole number")),
        (ValueKind::Float, Literal::Numbers { values, suffix, .. }) if one(values) => match suffix.as_str() {
            "" => values.clone(),
            suffix => return Err(unit_error(p, text, suffix)),
        },
        (ValueKind::Float, _) => return Err(type_error(p, text, "a number")),
        (ValueKind::Unit(unit), Literal::Numbers { values, suffix, .. }) if one(values) => match suffix.as_str() {
            // Resolved against the image height per frame, like a `%`
            // default; its range is checked in px only once the height is known.
            "%" if unit == Unit::Px => {
                return Ok(ParamOverride {
                    name: name.clone(),
                    value: values.clone(),
                    percent_of_height: true,
                })
            }
            "" if origin.plain_number_takes_any_unit() => values.clone(),
            suffix if !suffix.is_empty() && unit_of_suffix(suffix) == Some(unit) => values.clone(),
            suffix => return Err(unit_error(p, text, suffix)),
        },
        (ValueKind::Unit(unit), _) => {
            return Err(type_error(p, text, &format!("a number in {}", suffix_of(unit))));
        }
        (ValueKind::Range, Literal::Range(a, b)) if a <= b => vec![*a, *b],
        (ValueKind::Range, Literal::Range(a, b)) => {
            return Err(refuse(
                codes::OUT_OF_RANGE,
                format!("the range {a}..{b} is empty"),
                "the start is after the end",
                format!("write it low to high: `{b}..{a}`"),
            ))
        }
        (ValueKind::Range, _) => return Err(type_error(p, text, "a range `a..b`")),
        (ValueKind::Vector, Literal::Numbers { values, suffix, .. }) if values.len() == p.components as usize => {
            match suffix.as_str() {
                "" => values.clone(),
                suffix => return Err(unit_error(p, text, suffix)),
            }
        }
        (ValueKind::Vector, _) => return Err(type_error(p, text, &origin.expected_vector(p.components))),
        (ValueKind::Gradient, literal) => gradient_value(p, literal, text, origin)?,
    };
    check_range(p, &value)?;
    Ok(ParamOverride {
        name: name.clone(),
        value,
        percent_of_height: false,
    })
}

/// The slots of a gradient set to `literal`'s stops, in the declared mode
/// (the default's); E0206 for text that is no list of sorted stops in 0..1.
fn gradient_value(p: &ParamShape, literal: &Literal, text: &str, origin: &SettingOrigin) -> Result<Vec<f64>, Refusal> {
    use crate::gradient;
    let help = format!(
        "write the stops as `position:#colour`, comma-separated, positions from 0 to 1 in order: `{}`",
        origin.example(&p.name, "0:#000000, 0.5:#ff8800, 1:#ffffff")
    );
    let Literal::Stops(stops) = literal else {
        return Err(refuse(
            codes::BAD_GRADIENT,
            format!(
                "`{text}` is not a value of `{}`: a gradient's value is a list of stops",
                p.name
            ),
            "not `position:#colour, ...`",
            help,
        ));
    };
    if let Some(why) = gradient::check_stops(stops) {
        return Err(refuse(
            codes::BAD_GRADIENT,
            format!("`{text}` is no gradient"),
            why,
            help,
        ));
    }
    let constant = gradient::unpack(&p.default).is_some_and(|(_, constant)| constant);
    Ok(gradient::pack(stops, constant))
}

/// The range check of a typed value: the declared `in lo..hi` of a number,
/// a unit value or a vector (not of a range, an enum, a colour or a bool).
pub fn check_range(p: &ParamShape, value: &[f64]) -> Result<(), Refusal> {
    let Some((lo, hi)) = p.range else { return Ok(()) };
    if matches!(
        p.kind,
        ValueKind::Range | ValueKind::Enum | ValueKind::Colour | ValueKind::Bool
    ) {
        return Ok(());
    }
    if value.iter().all(|v| (lo..=hi).contains(v)) {
        return Ok(());
    }
    let shown = |v: f64| format!("{}{}", fmt_num(p.kind.to_written(v)), p.kind.suffix());
    let range = format!("{}..{}", shown(lo), shown(hi));
    Err(refuse(
        codes::OUT_OF_RANGE,
        format!("`{}` is declared `in {range}`", p.name),
        format!("outside {range}"),
        format!("give a value from {} to {}", shown(lo), shown(hi)),
    ))
}

fn not_a_variant(p: &ParamShape, text: &str) -> Refusal {
    let help = match crate::param_literal::did_you_mean(text, p.variants.iter().map(String::as_str)) {
        Some(close) => format!("did you mean `{close}`?"),
        None => format!("one of: {}", p.variants.join(", ")),
    };
    refuse(
        codes::TYPE_MISMATCH,
        format!("`{text}` is not a variant of `{}`", p.name),
        format!("expected one of {}", p.variants.join(" | ")),
        help,
    )
}

fn type_error(p: &ParamShape, text: &str, expected: &str) -> Refusal {
    refuse(
        codes::TYPE_MISMATCH,
        format!("`{text}` is not a value of `{}` ({})", p.name, p.ty),
        format!("expected {expected}"),
        format!("its default is `{}`", default_text(p)),
    )
}

fn unit_error(p: &ParamShape, text: &str, found: &str) -> Refusal {
    let want = match p.kind {
        ValueKind::Unit(Unit::Px) => "px (or % of the image height)".to_string(),
        ValueKind::Unit(Unit::Meters) => "m or mm".to_string(),
        ValueKind::Unit(u) => suffix_of(u).to_string(),
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

/// A number as short as it can be written and still read back exactly.
fn fmt_num(v: f64) -> String {
    let s = format!("{v}");
    if s.contains('e') {
        format!("{v:.6}")
    } else {
        s
    }
}

fn default_text(p: &ParamShape) -> String {
    if p.default_percent_of_height {
        return format!("{}%", fmt_num(p.default.first().copied().unwrap_or(0.0)));
    }
    format_literal(p, &p.default).unwrap_or_else(|| "?".into())
}

/// `value` (canonical components) written as the language spells it, so
/// that [`type_value`] reads it back. `None` for a kind no value sets.
pub fn format_literal(p: &ParamShape, value: &[f64]) -> Option<String> {
    let first = *value.first()?;
    Some(match p.kind {
        ValueKind::Float => fmt_num(first),
        ValueKind::Int => format!("{}", first.round() as i64),
        ValueKind::Bool => (first != 0.0).to_string(),
        ValueKind::Enum => p.variants.get(first as usize)?.clone(),
        ValueKind::Unit(_) => format!("{}{}", fmt_num(p.kind.to_written(first)), p.kind.suffix()),
        ValueKind::Colour => {
            let b = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
            let mut s = format!("#{:02x}{:02x}{:02x}", b(first), b(*value.get(1)?), b(*value.get(2)?));
            if let Some(a) = value.get(3).filter(|a| **a < 1.0) {
                s.push_str(&format!("{:02x}", b(*a)));
            }
            s
        }
        ValueKind::Range => format!("{}..{}", fmt_num(first), fmt_num(*value.get(1)?)),
        ValueKind::Vector => value.iter().map(|v| fmt_num(*v)).collect::<Vec<_>>().join(", "),
        ValueKind::Gradient => crate::gradient::stops_text(&crate::gradient::unpack(value)?.0),
        ValueKind::Unsupported => return None,
    })
}
