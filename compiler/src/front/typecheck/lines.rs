//! Typecheck a `lines` pass's shape settings: width, amplitude and
//! wavelength in px, phase in radians (or a plain number), taper a plain
//! number; constants inside the ranges the runner builds strips for; and
//! every setting affine in params and `time` (`line_settings::affine`),
//! since the runner evaluates them on the CPU; the same for each line set's
//! own settings, and a set's `color:` is a colour.

use super::Checker;
use crate::front::line_settings::affine;
use crate::ir::*;
use npr_abi::lines::{MAX_LINE_WIDTH_PX, MAX_TAPER, MIN_WAVELENGTH_PX};
use npr_diag::{codes, Diagnostic};
use npr_stdlib::Unit;

impl Checker<'_> {
    pub(super) fn line_settings(&mut self, pi: usize) {
        let PassKind::Lines(lines) = &self.ir.passes[pi].kind else {
            return;
        };
        // The pass's settings, then each set's own (a set's unset setting is
        // the pass's node: checked once).
        let mut settings: Vec<(&'static str, ExprId)> = lines.shape.named().to_vec();
        for set in &lines.sets {
            for (name, id) in set.shape.named() {
                if !settings.iter().any(|(_, seen)| *seen == id) {
                    settings.push((name, id));
                }
            }
        }
        let colors: Vec<ExprId> = lines.sets.iter().filter_map(|s| s.color).collect();
        for id in colors {
            if !self.is_error(id) && self.vt(id) != Ty::Vec4 {
                self.type_error(id, "a colour (vec4)", None);
            }
        }
        for (name, id) in settings {
            if self.is_error(id) {
                continue;
            }
            let (ty, unit) = (self.vt(id), self.unit(id));
            if !matches!(ty, Ty::Float | Ty::Int) {
                self.type_error(id, "one number", None);
                continue;
            }
            let px = matches!(name, "width" | "amplitude" | "wavelength");
            let unit_ok = match name {
                _ if px => unit == Unit::Px,
                "phase" => matches!(unit, Unit::None | Unit::Radians),
                _ => unit == Unit::None,
            };
            if !unit_ok {
                let (want, help) = if px {
                    ("px", format!("write `{name}: 2px`, or a px param"))
                } else if name == "phase" {
                    (
                        "radians (`deg` or a plain number)",
                        "write `phase: 90deg`; to animate it, `phase: time * 6Hz` (radians per second)".to_string(),
                    )
                } else {
                    (
                        "a plain number",
                        "write `taper: 0.2`: the share of a line's length that narrows at each end".to_string(),
                    )
                };
                self.err(
                    Diagnostic::error(codes::UNIT_MISMATCH, format!("`{name}` is in {want}"))
                        .with_primary(self.span(id), format!("this is {}", unit.name()))
                        .with_help(help),
                );
                continue;
            }
            let value = match affine(self.ir, id) {
                Ok(v) => v,
                Err(e) => {
                    self.err(
                        Diagnostic::error(
                            codes::BAD_ARGUMENT,
                            format!("`{name}` of a lines pass must be a sum of numbers, params and `time`"),
                        )
                        .with_primary(e.span, e.label)
                        .with_help(
                            "strips are built on the CPU, which evaluates each setting as constant + k·param + … + k·time; \
                             compute anything else in the fragment (`line.s`, `line.across`) or in a param's keyframes",
                        ),
                    );
                    continue;
                }
            };
            if !value.params.is_empty() || value.per_second != 0.0 {
                continue;
            }
            let v = value.constant;
            let range = match name {
                "width" => Some((0.0, MAX_LINE_WIDTH_PX, format!("0px..{MAX_LINE_WIDTH_PX}px"))),
                "amplitude" => Some((0.0, f64::INFINITY, "0px or more".to_string())),
                "wavelength" => Some((
                    MIN_WAVELENGTH_PX,
                    f64::INFINITY,
                    format!("{MIN_WAVELENGTH_PX}px or more"),
                )),
                "taper" => Some((0.0, MAX_TAPER, format!("0..{MAX_TAPER}"))),
                _ => None,
            };
            if let Some((lo, hi, text)) = range {
                if !(lo..=hi).contains(&v) {
                    self.err(
                        Diagnostic::error(codes::OUT_OF_RANGE, format!("`{name}` out of range"))
                            .with_primary(self.span(id), format!("{v} is outside {text}")),
                    );
                }
            }
        }
    }
}
