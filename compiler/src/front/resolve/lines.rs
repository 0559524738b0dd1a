//! Resolve a `lines(tag)` pass (Klein et al. 2000, §5): which objects, which
//! edges (`silhouettes: true|false`, `creases: 40deg|off`) and the strips'
//! shape settings (`width`, `amplitude`, `wavelength`, `phase`, `taper`),
//! each an expression checked by `typecheck::lines`. Its depth test is the
//! render passes' `depth: test(pass, bias: ...)` (`settings.rs`).

use super::Resolver;
use crate::ir::*;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::{self, ExprKind as AK, UnitSuffix};
use npr_stdlib::Unit;

/// The settings of a lines pass besides `depth` and `clear`.
pub(super) const LINE_SETTINGS: [&str; 7] = [
    "silhouettes",
    "creases",
    "width",
    "amplitude",
    "wavelength",
    "phase",
    "taper",
];

/// The shape a lines pass has where the style says nothing: Klein et al.'s
/// wavy ink, 2 px wide, waving 1.5 px every 24 px.
const DEFAULT_WIDTH_PX: f64 = 2.0;
const DEFAULT_AMPLITUDE_PX: f64 = 1.5;
const DEFAULT_WAVELENGTH_PX: f64 = 24.0;

impl Resolver<'_> {
    /// `lines(scene)` or `lines(tag)`, with the default edges (silhouettes,
    /// no creases) and shape.
    pub(super) fn lines_kind(&mut self, p: &ast::PassDecl) -> PassKind {
        let tag = self.scene_or_tag(p, "a lines pass draws the edges of one set of objects");
        let span = p.kind.span;
        let px = |r: &mut Self, v: f64| {
            r.ir.add_typed(ExprKind::Const(Const::Float(v)), Ty::Float, Unit::Px, span)
        };
        let plain = |r: &mut Self, v: f64| {
            r.ir.add_typed(ExprKind::Const(Const::Float(v)), Ty::Float, Unit::None, span)
        };
        let shape = LineSettings {
            width: px(self, DEFAULT_WIDTH_PX),
            amplitude: px(self, DEFAULT_AMPLITUDE_PX),
            wavelength: px(self, DEFAULT_WAVELENGTH_PX),
            phase: plain(self, 0.0),
            taper: plain(self, 0.0),
        };
        PassKind::Lines(LinesKind {
            tag,
            edges: npr_abi::lines::LineEdges {
                silhouettes: true,
                crease_deg: None,
            },
            shape,
            depth: PassDepth::Own,
            sets: Vec::new(),
        })
    }

    /// One of [`LINE_SETTINGS`]; `seen` holds the settings written so far.
    pub(super) fn line_setting(&mut self, lines: &mut LinesKind, s: &ast::Setting, seen: &mut Vec<(String, Span)>) {
        let key = s.key.name.as_str();
        let here = s.key.span.to(s.value.span);
        if let Some((_, first)) = seen.iter().find(|(k, _)| k == key) {
            self.error(
                Diagnostic::error(codes::DUPLICATE_NAME, format!("`{key}` is set twice"))
                    .with_primary(here, format!("second `{key}`"))
                    .with_secondary(*first, format!("first `{key}`")),
            );
            return;
        }
        seen.push((key.to_string(), here));
        match key {
            "silhouettes" => match &s.value.kind {
                AK::Bool(b) => lines.edges.silhouettes = *b,
                _ => self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, "`silhouettes` is `true` or `false`")
                        .with_primary(s.value.span, "not a boolean literal")
                        .with_help("write `silhouettes: true` (the default) or `silhouettes: false`"),
                ),
            },
            "creases" => self.crease_setting(lines, s),
            _ => {
                let value = self.expr(&s.value);
                if let Some(slot) = lines.shape.get_mut(key) {
                    *slot = value;
                }
            }
        }
    }

    /// `creases: 40deg` (a dihedral angle in 0..180°) or `creases: off`.
    fn crease_setting(&mut self, lines: &mut LinesKind, s: &ast::Setting) {
        let usage = "write `creases: 40deg` (edges whose faces turn by more than 40°) or `creases: off`";
        match &s.value.kind {
            AK::Name(n) if n.name == "off" => lines.edges.crease_deg = None,
            AK::Bool(false) => lines.edges.crease_deg = None,
            AK::Number {
                value,
                unit: Some(UnitSuffix::Deg),
                ..
            } => {
                if (0.0..=180.0).contains(value) {
                    lines.edges.crease_deg = Some(*value);
                } else {
                    self.error(
                        Diagnostic::error(codes::OUT_OF_RANGE, "crease angle out of range")
                            .with_primary(s.value.span, format!("{value}° is outside 0deg..180deg"))
                            .with_help("a dihedral angle is between 0° (every edge) and 180° (none)"),
                    );
                }
            }
            AK::Number { unit, .. } => {
                let written = unit.map_or("no unit", |u| u.as_str());
                self.error(
                    Diagnostic::error(codes::UNIT_MISMATCH, "a crease threshold is an angle in `deg`")
                        .with_primary(s.value.span, format!("this has {written}"))
                        .with_help(usage),
                );
            }
            other => {
                let written = match other {
                    AK::Name(n) => n.name.as_str(),
                    _ => "",
                };
                let mut d = Diagnostic::error(codes::BAD_ARGUMENT, "`creases` takes an angle or `off`")
                    .with_primary(s.value.span, "not an angle");
                d = match did_you_mean(written, ["off"]) {
                    Some(_) => d.with_help("did you mean `off`?"),
                    None => d.with_help(usage),
                };
                self.error(d);
            }
        }
    }
}
