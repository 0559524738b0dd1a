//! Swizzle names (`.xy`, `.rgb`): which components they pick.
//!
//! A swizzle spells its components from one letter set, `xyzw` or `rgba`,
//! as WGSL requires; `.xg` is refused here with a span on the first letter
//! from the other set, instead of being emitted for naga to reject.

use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::Ident;

const XYZW: &str = "xyzw";
const RGBA: &str = "rgba";

/// What a field name is as a swizzle.
pub(super) enum Swizzle {
    /// Component indices, 0..4, one to four of them.
    Components(Vec<u8>),
    /// Not a swizzle at all (a letter of neither set, or more than four).
    NotOne,
    /// Letters of both sets: the error to report.
    Mixed(Box<Diagnostic>),
}

pub(super) fn parse(field: &Ident) -> Swizzle {
    let name = field.name.as_str();
    if name.is_empty() || name.len() > 4 {
        return Swizzle::NotOne;
    }
    let mut set: Option<&str> = None;
    let mut components = Vec::with_capacity(name.len());
    for (i, c) in name.char_indices() {
        let Some(letters) = [XYZW, RGBA].into_iter().find(|s| s.contains(c)) else {
            return Swizzle::NotOne;
        };
        match set {
            None => set = Some(letters),
            Some(first) if first != letters => return Swizzle::Mixed(Box::new(mixed(field, i, first))),
            Some(_) => {}
        }
        components.extend(letters.find(c).map(|k| k as u8));
    }
    Swizzle::Components(components)
}

/// `field` mixes sets at byte `at`; `first` is the set its first letter is from.
fn mixed(field: &Ident, at: usize, first: &str) -> Diagnostic {
    let other = if first == XYZW { RGBA } else { XYZW };
    let at = field.span.start as usize + at;
    let fixed: String = field
        .name
        .chars()
        .map(|c| match other.find(c) {
            Some(k) => first.as_bytes()[k] as char,
            None => c,
        })
        .collect();
    Diagnostic::error(
        codes::UNKNOWN_TYPE,
        format!("swizzle `.{}` mixes `{XYZW}` and `{RGBA}` letters", field.name),
    )
    .with_primary(Span::new(field.span.file, at, at + 1), format!("a letter of `{other}`"))
    .with_secondary(field.span, format!("this swizzle started with `{first}` letters"))
    .with_help(format!(
        "a swizzle uses one set, `{XYZW}` or `{RGBA}`: write `.{fixed}`"
    ))
}
