//! Typed, spanned access to the fields of a parsed TOML table, reporting
//! every problem as a diagnostic that points into the file: E0405 in a
//! scene file, the code the [`Report`] was made with in other TOML files
//! (`npr test`'s `<style>.tests.toml` gives E0407).
//!
//! The scene is read from toml's spanned document tree ([`DeTable`]) rather
//! than through serde derive, so that one pass can report several errors
//! (wrong types, bad values and unknown keys together) instead of stopping at
//! the first, and so that every value keeps its byte span.

use glam::Vec3;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, FileId, Span};
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// A value and where it was written.
#[derive(Debug, Clone, PartialEq)]
pub struct At<T> {
    pub value: T,
    pub span: Span,
}

/// Where diagnostics go while a scene file is read.
pub struct Report {
    pub file: FileId,
    /// The code of every problem [`Report::bad_scene`] records: E0405
    /// ([`Report::for_scene`]), or another file format's own.
    pub code: &'static str,
    pub diagnostics: Vec<Diagnostic>,
    /// Which files the scene may name (`npr_diag::paths`); `None` reads any.
    pub paths: Option<npr_diag::paths::PathPolicy>,
}

impl Report {
    /// A report on the scene file `file`, read under `paths`.
    pub fn for_scene(file: FileId, paths: Option<npr_diag::paths::PathPolicy>) -> Report {
        Report {
            file,
            code: codes::BAD_SCENE,
            diagnostics: Vec::new(),
            paths,
        }
    }

    /// Whether the file `written` at `span` (resolved to `resolved`) may be
    /// read; a refusal (E0406) is recorded at `span`.
    pub fn path_allowed(&mut self, span: Span, written: &str, resolved: &std::path::Path) -> bool {
        let Some(refusal) = self.paths.as_ref().and_then(|p| p.check(written, resolved).err()) else {
            return true;
        };
        self.diagnostics.push(refusal.with_primary(span, "this file"));
        false
    }

    pub fn span(&self, range: std::ops::Range<usize>) -> Span {
        Span::new(self.file, range.start, range.end)
    }

    /// Records an error with the report's code (E0405 in a scene) at `span`.
    pub fn bad_scene(
        &mut self,
        span: Span,
        message: impl Into<String>,
        label: impl Into<String>,
        help: impl Into<String>,
    ) {
        self.push(
            Diagnostic::error(self.code, message)
                .with_primary(span, label)
                .with_help(help),
        );
    }

    pub fn push(&mut self, diagnostic: Diagnostic) {
        self.diagnostics.push(diagnostic);
    }

    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// One TOML table being read. Remembers which keys were asked for, so that
/// [`Fields::finish`] can report the rest as unknown (with did-you-mean).
pub struct Fields<'t, 'i> {
    table: &'t DeTable<'i>,
    /// Where to point when a required key is missing (the table's header).
    header: Span,
    /// How messages name this table: `"[camera]"`, `"object 'spot'"`.
    context: String,
    asked: Vec<&'static str>,
    /// Set by [`Fields::entries`]: any key is allowed.
    free_form: bool,
}

impl<'t, 'i> Fields<'t, 'i> {
    pub fn new(table: &'t DeTable<'i>, header: Span, context: impl Into<String>) -> Self {
        Fields {
            table,
            header,
            context: context.into(),
            asked: Vec::new(),
            free_form: false,
        }
    }

    pub fn header(&self) -> Span {
        self.header
    }

    pub fn context(&self) -> &str {
        &self.context
    }

    /// Renames the table in messages (an object once its name is known).
    pub fn set_context(&mut self, context: impl Into<String>) {
        self.context = context.into();
    }

    /// The raw value of `key`, if present. Marks the key as known.
    pub fn raw(&mut self, key: &'static str) -> Option<&'t Spanned<DeValue<'i>>> {
        self.asked.push(key);
        self.table.get(key)
    }

    /// The span of `key`'s value, if present (does not mark it as known).
    pub fn span_of(&self, key: &str, report: &Report) -> Option<Span> {
        self.table.get(key).map(|value| report.span(value.span()))
    }

    /// Reports a missing required key at the table header.
    pub fn missing(&self, key: &str, example: &str, report: &mut Report) {
        report.bad_scene(
            self.header,
            format!("{} has no `{key}`", self.context),
            format!("`{key}` is required here"),
            format!("add `{example}`"),
        );
    }

    pub fn number(&mut self, key: &'static str, report: &mut Report) -> Option<At<f64>> {
        let value = self.raw(key)?;
        expect_number(value, key, report)
    }

    pub fn integer(&mut self, key: &'static str, report: &mut Report) -> Option<At<i64>> {
        let value = self.raw(key)?;
        let span = report.span(value.span());
        match value.get_ref() {
            DeValue::Integer(int) => match i64::from_str_radix(int.as_str(), int.radix()) {
                Ok(parsed) => Some(At { value: parsed, span }),
                Err(_) => {
                    report.bad_scene(
                        span,
                        format!("`{key}` is too large"),
                        "does not fit in 64 bits",
                        "use a smaller count",
                    );
                    None
                }
            },
            other => {
                report.bad_scene(
                    span,
                    format!("`{key}` must be a whole number, not {}", describe(other)),
                    "expected an integer",
                    format!("write it without a decimal point, e.g. `{key} = 32`"),
                );
                None
            }
        }
    }

    pub fn string(&mut self, key: &'static str, report: &mut Report) -> Option<At<String>> {
        let value = self.raw(key)?;
        expect_string(value, key, report)
    }

    pub fn boolean(&mut self, key: &'static str, report: &mut Report) -> Option<At<bool>> {
        let value = self.raw(key)?;
        let span = report.span(value.span());
        match value.get_ref() {
            DeValue::Boolean(flag) => Some(At { value: *flag, span }),
            other => {
                report.bad_scene(
                    span,
                    format!("`{key}` must be `true` or `false`, not {}", describe(other)),
                    "expected a boolean",
                    format!("write `{key} = true` or `{key} = false`"),
                );
                None
            }
        }
    }

    /// Three numbers: `[x, y, z]`.
    pub fn vec3(&mut self, key: &'static str, report: &mut Report) -> Option<At<Vec3>> {
        let value = self.raw(key)?;
        expect_vec3(value, key, report)
    }

    /// A number (uniform) or three numbers, e.g. a scale.
    pub fn number_or_vec3(&mut self, key: &'static str, report: &mut Report) -> Option<At<Vec3>> {
        let value = self.raw(key)?;
        if matches!(value.get_ref(), DeValue::Array(_)) {
            return expect_vec3(value, key, report);
        }
        let uniform = expect_number(value, key, report)?;
        Some(At {
            value: Vec3::splat(uniform.value as f32),
            span: uniform.span,
        })
    }

    /// A colour: `"#rrggbb"`, `"#rrggbbaa"`, `[r, g, b]` or `[r, g, b, a]`.
    /// Alpha is 1 unless written.
    pub fn color(&mut self, key: &'static str, report: &mut Report) -> Option<At<[f32; 4]>> {
        let value = self.raw(key)?;
        let span = report.span(value.span());
        let components = match value.get_ref() {
            DeValue::String(text) => parse_hex_color(text).or_else(|| {
                report.bad_scene(
                    span,
                    format!("`{key}` is not a colour"),
                    "expected `#rrggbb` or `#rrggbbaa`",
                    COLOR_HELP,
                );
                None
            })?,
            DeValue::Array(_) => {
                let numbers = expect_numbers(value, key, report)?;
                match numbers.value.as_slice() {
                    [r, g, b] => vec![*r, *g, *b, 1.0],
                    [r, g, b, a] => vec![*r, *g, *b, *a],
                    other => {
                        report.bad_scene(
                            span,
                            format!("`{key}` must have 3 or 4 numbers, not {}", other.len()),
                            "expected `[r, g, b]`",
                            COLOR_HELP,
                        );
                        return None;
                    }
                }
            }
            other => {
                report.bad_scene(
                    span,
                    format!("`{key}` must be a colour, not {}", describe(other)),
                    "expected a colour",
                    COLOR_HELP,
                );
                return None;
            }
        };
        if components.iter().any(|c| *c < 0.0) {
            report.bad_scene(
                span,
                format!("`{key}` has a negative component"),
                "colours cannot be negative",
                COLOR_HELP,
            );
            return None;
        }
        Some(At {
            value: [
                components[0] as f32,
                components[1] as f32,
                components[2] as f32,
                components[3] as f32,
            ],
            span,
        })
    }

    /// A strings array, e.g. tags.
    pub fn strings(&mut self, key: &'static str, report: &mut Report) -> Option<Vec<At<String>>> {
        let value = self.raw(key)?;
        let DeValue::Array(items) = value.get_ref() else {
            report.bad_scene(
                report.span(value.span()),
                format!("`{key}` must be an array of strings, not {}", describe(value.get_ref())),
                "expected `[\"...\", ...]`",
                format!("write e.g. `{key} = [\"caster\"]`"),
            );
            return None;
        };
        let strings: Vec<Option<At<String>>> = items.iter().map(|item| expect_string(item, key, report)).collect();
        strings.into_iter().collect()
    }

    /// A sub-table (`[camera]` or an inline `{ ... }`).
    pub fn table(&mut self, key: &'static str, context: &str, report: &mut Report) -> Option<Fields<'t, 'i>> {
        let value = self.raw(key)?;
        let span = report.span(value.span());
        match value.get_ref() {
            DeValue::Table(table) => Some(Fields::new(table, span, context)),
            other => {
                report.bad_scene(
                    span,
                    format!("`{key}` must be a table, not {}", describe(other)),
                    "expected a table",
                    format!("write `[{key}]` on its own line followed by its fields, or `{key} = {{ ... }}`"),
                );
                None
            }
        }
    }

    /// An array of tables (`[[object]]`), each with its header span. The
    /// context of table `i` is `context(i)`.
    pub fn tables(
        &mut self,
        key: &'static str,
        context: impl Fn(usize) -> String,
        report: &mut Report,
    ) -> Vec<Fields<'t, 'i>> {
        let Some(value) = self.raw(key) else {
            return Vec::new();
        };
        let DeValue::Array(items) = value.get_ref() else {
            report.bad_scene(
                report.span(value.span()),
                format!("`{key}` must be an array of tables, not {}", describe(value.get_ref())),
                "expected `[[...]]` tables",
                format!("write each entry as a `[[{key}]]` section"),
            );
            return Vec::new();
        };
        let mut tables = Vec::new();
        for (index, item) in items.iter().enumerate() {
            let span = report.span(item.span());
            match item.get_ref() {
                DeValue::Table(table) => tables.push(Fields::new(table, span, context(index))),
                other => report.bad_scene(
                    span,
                    format!("each `{key}` entry must be a table, not {}", describe(other)),
                    "expected a table",
                    format!("write each entry as a `[[{key}]]` section"),
                ),
            }
        }
        tables
    }

    /// All entries of a free-form table (per-object params): each key with
    /// its span, and the raw value. Every key counts as known.
    pub fn entries(&mut self, report: &Report) -> Vec<(At<String>, &'t Spanned<DeValue<'i>>)> {
        self.free_form = true;
        self.table
            .iter()
            .map(|(key, value)| {
                let name = At {
                    value: key.get_ref().to_string(),
                    span: report.span(key.span()),
                };
                (name, value)
            })
            .collect()
    }

    /// Reports every key that was never asked for, suggesting the closest
    /// known one.
    pub fn finish(self, report: &mut Report) {
        if self.free_form {
            return;
        }
        for (key, _) in self.table.iter() {
            let name: &str = key.get_ref();
            if self.asked.contains(&name) {
                continue;
            }
            let help = match did_you_mean(name, self.asked.iter().copied()) {
                Some(suggestion) => format!("did you mean `{suggestion}`?"),
                None => format!("the fields of {} are: {}", self.context, list(&self.asked)),
            };
            report.bad_scene(
                report.span(key.span()),
                format!("unknown field `{name}` in {}", self.context),
                "unknown field",
                help,
            );
        }
    }
}

const COLOR_HELP: &str = "write a colour as `\"#rrggbb\"`, `\"#rrggbbaa\"` or `[r, g, b]` with components from 0 to 1";

/// `#rrggbb` or `#rrggbbaa` as bytes / 255, alpha 1 unless written: the
/// same convention as colour literals in `.npr` styles (no sRGB decoding).
pub fn parse_hex_color(text: &str) -> Option<Vec<f64>> {
    let digits = text.strip_prefix('#')?;
    if !(digits.len() == 6 || digits.len() == 8) || !digits.is_ascii() {
        return None;
    }
    let mut components = (0..digits.len())
        .step_by(2)
        .map(|at| {
            u8::from_str_radix(&digits[at..at + 2], 16)
                .ok()
                .map(|byte| f64::from(byte) / 255.0)
        })
        .collect::<Option<Vec<f64>>>()?;
    if components.len() == 3 {
        components.push(1.0);
    }
    Some(components)
}

/// A number (TOML integer or float), finite.
pub fn expect_number(value: &Spanned<DeValue>, key: &str, report: &mut Report) -> Option<At<f64>> {
    let span = report.span(value.span());
    let number = match value.get_ref() {
        DeValue::Integer(int) => i64::from_str_radix(int.as_str(), int.radix()).ok().map(|n| n as f64),
        DeValue::Float(float) => float.as_str().parse::<f64>().ok(),
        other => {
            report.bad_scene(
                span,
                format!("`{key}` must be a number, not {}", describe(other)),
                "expected a number",
                format!("write e.g. `{key} = 1.0`"),
            );
            return None;
        }
    };
    match number {
        // Scene values end up as f32: anything larger would become infinite.
        Some(number) if number.is_finite() && number.abs() <= f64::from(f32::MAX) => Some(At { value: number, span }),
        _ => {
            report.bad_scene(
                span,
                format!("`{key}` must be a finite number of ordinary size"),
                "not finite",
                "use an ordinary number (no `inf`, `nan` or magnitudes past 3.4e38)",
            );
            None
        }
    }
}

/// An array of numbers (any length, including zero).
pub fn expect_numbers(value: &Spanned<DeValue>, key: &str, report: &mut Report) -> Option<At<Vec<f64>>> {
    let span = report.span(value.span());
    let DeValue::Array(items) = value.get_ref() else {
        report.bad_scene(
            span,
            format!("`{key}` must be an array of numbers, not {}", describe(value.get_ref())),
            "expected `[...]`",
            format!("write e.g. `{key} = [0.0, 1.0, 0.0]`"),
        );
        return None;
    };
    let numbers: Vec<Option<At<f64>>> = items.iter().map(|item| expect_number(item, key, report)).collect();
    let numbers: Option<Vec<f64>> = numbers.into_iter().map(|n| n.map(|n| n.value)).collect();
    Some(At { value: numbers?, span })
}

/// Three numbers: `[x, y, z]`.
pub fn expect_vec3(value: &Spanned<DeValue>, key: &str, report: &mut Report) -> Option<At<Vec3>> {
    let numbers = expect_numbers(value, key, report)?;
    match numbers.value.as_slice() {
        [x, y, z] => Some(At {
            value: Vec3::new(*x as f32, *y as f32, *z as f32),
            span: numbers.span,
        }),
        other => {
            report.bad_scene(
                numbers.span,
                format!("`{key}` must have 3 numbers, not {}", other.len()),
                "expected `[x, y, z]`",
                format!("write e.g. `{key} = [0.0, 1.0, 0.0]`"),
            );
            None
        }
    }
}

pub fn expect_string(value: &Spanned<DeValue>, key: &str, report: &mut Report) -> Option<At<String>> {
    let span = report.span(value.span());
    match value.get_ref() {
        DeValue::String(text) => Some(At {
            value: text.to_string(),
            span,
        }),
        other => {
            report.bad_scene(
                span,
                format!("`{key}` must be a string, not {}", describe(other)),
                "expected a string",
                format!("put the value in double quotes: `{key} = \"...\"`"),
            );
            None
        }
    }
}

/// "a string", "an array": the value's type for messages.
pub fn describe(value: &DeValue) -> &'static str {
    match value {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) => "an integer",
        DeValue::Float(_) => "a float",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

/// "`a`, `b` and `c`".
pub fn list(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|name| format!("`{name}`")).collect();
    match quoted.split_last() {
        None => "none".to_string(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_colours_are_bytes_over_255_with_alpha_one_by_default() {
        assert_eq!(parse_hex_color("#ff0080"), Some(vec![1.0, 0.0, 128.0 / 255.0, 1.0]));
        assert_eq!(parse_hex_color("#FF000000"), Some(vec![1.0, 0.0, 0.0, 0.0]));
        for bad in ["ff0080", "#ff008", "#gg0080", "#ff00800", "#ffé080", ""] {
            assert_eq!(parse_hex_color(bad), None, "{bad}");
        }
    }

    #[test]
    fn lists_read_as_english() {
        assert_eq!(list(&[]), "none");
        assert_eq!(list(&["a"]), "`a`");
        assert_eq!(list(&["a", "b", "c"]), "`a`, `b` and `c`");
    }

    #[test]
    fn unknown_keys_are_reported_once_each() {
        let document = DeTable::parse("fov = 1\nfob = 2\nzzz = 3\n").expect("valid TOML");
        let mut report = Report::for_scene(FileId(0), None);
        let mut fields = Fields::new(document.get_ref(), Span::default(), "[camera]");
        assert_eq!(fields.number("fov", &mut report).map(|n| n.value), Some(1.0));
        fields.finish(&mut report);
        let helps: Vec<&str> = report.diagnostics.iter().filter_map(|d| d.help.as_deref()).collect();
        assert_eq!(helps, ["did you mean `fov`?", "the fields of [camera] are: `fov`"]);
    }
}
