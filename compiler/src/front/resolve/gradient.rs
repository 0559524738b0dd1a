//! `param g: gradient = gradient(stop(0.0, #000000), stop(1.0, #ffffff))`
//! and `ramp(g, t)`: a colour ramp, as Blender's Color Ramp and Unity's
//! Gradients are (docs/decisions/0040-a-gradient-is-a-constant-ramp.md).
//!
//! A gradient is a constant unless kept live: its stops are read here from the declaration
//! (E0206 for no stops, unsorted stops, a position outside 0..1, a stop
//! that is not `stop(position, colour)`), and each `ramp(g, t)` becomes
//! nodes of the IR that the specializer folds with the stops:
//!
//! - linear: `r = c0`, then for each next stop `r = mix(r, c_i,
//!   saturate((t - p_{i-1}) / (p_i - p_{i-1})))` (a step where two stops
//!   share a position). With sorted stops every earlier segment's factor
//!   is 1 and every later one's 0, so `r` is the segment's own mix; below
//!   the first stop it is `c0`, past the last `c_last`.
//! - constant: `r = c0`, then `r = mix(r, c_i, step(p_i, t))`: each stop's
//!   colour from its position on.
//!
//! Under `keep_params` a gradient is also an IR param (`ParamTy::Gradient`,
//! the `npr_abi::gradient` slots) and `ramp(g, t)` is `Intrinsic::Ramp(g)` of
//! `t`, which the emitter writes as `npr_ramp_<g>`, the same rule as a loop
//! over the uniform's stops.

use super::*;
use npr_dsl::ast::BinOp;

/// The most stops a gradient has (a limit, E0404, so a ramp's chain of
/// nodes stays short).
pub const MAX_STOPS: usize = 16;

/// A declared gradient: its stops (position, straight-alpha colour), sorted.
#[derive(Debug, Clone, PartialEq)]
pub struct Gradient {
    pub stops: Vec<(f64, [f64; 4])>,
    pub constant: bool,
}

pub(super) fn is_gradient_type(ty: &ast::TypeExpr) -> bool {
    matches!(ty, ast::TypeExpr::Named(id) if id.name == "gradient")
}

impl Resolver<'_> {
    fn bad_gradient(&mut self, span: Span, message: &str, label: &str, help: &str) {
        self.error(
            Diagnostic::error(codes::BAD_GRADIENT, message.to_string())
                .with_primary(span, label.to_string())
                .with_help(help.to_string()),
        );
    }

    /// The gradient a `param g: gradient = gradient(...)` declares, or
    /// `None` with its errors reported.
    pub(super) fn gradient_decl(&mut self, p: &ast::ParamDecl) -> Option<Gradient> {
        const FORM: &str = "write `gradient(stop(0.0, #000000), stop(1.0, #ffffff))`, stops in order of position, \
             and `mode: constant` for hard bands";
        if p.per_object || p.range.is_some() || p.animate.is_some() {
            self.bad_gradient(
                p.span,
                "a gradient is one constant ramp",
                "not per object, ranged or animated",
                FORM,
            );
            return None;
        }
        let ast::ExprKind::Call(call) = &p.default.kind else {
            self.bad_gradient(
                p.default.span,
                "a gradient's value is `gradient(...)`",
                "not a gradient",
                FORM,
            );
            return None;
        };
        if call.callee.name != "gradient" {
            self.bad_gradient(
                call.callee.span,
                "a gradient's value is `gradient(...)`",
                "not `gradient`",
                FORM,
            );
            return None;
        }
        let mut stops = Vec::new();
        let mut constant = false;
        let mut ok = true;
        for a in &call.args {
            match (&a.name, &a.value.kind) {
                (Some(n), ast::ExprKind::Name(m))
                    if n.name == "mode" && (m.name == "linear" || m.name == "constant") =>
                {
                    constant = m.name == "constant";
                }
                (Some(n), _) if n.name == "mode" => {
                    self.bad_gradient(
                        a.value.span,
                        "unknown gradient mode",
                        "not a mode",
                        "`mode` is `linear` (the default) or `constant`",
                    );
                    ok = false;
                }
                (None, ast::ExprKind::Call(stop)) if stop.callee.name == "stop" => match self.stop(stop) {
                    Some(s) => stops.push((s, a.span)),
                    None => ok = false,
                },
                _ => {
                    self.bad_gradient(a.span, "a gradient takes stops", "not `stop(position, colour)`", FORM);
                    ok = false;
                }
            }
        }
        if !ok {
            return None;
        }
        if stops.is_empty() {
            self.bad_gradient(call.span, "a gradient with no stops", "no `stop(...)` here", FORM);
            return None;
        }
        if stops.len() > MAX_STOPS {
            self.error(
                Diagnostic::error(codes::LIMIT_EXCEEDED, format!("a gradient of {} stops", stops.len()))
                    .with_primary(call.span, format!("more than {MAX_STOPS} stops"))
                    .with_help(format!("a gradient has at most {MAX_STOPS} stops")),
            );
            return None;
        }
        for w in stops.windows(2) {
            if w[1].0 .0 < w[0].0 .0 {
                self.error(
                    Diagnostic::error(codes::BAD_GRADIENT, "a gradient's stops are out of order")
                        .with_primary(w[1].1, format!("at {} after a stop at {}", w[1].0 .0, w[0].0 .0))
                        .with_secondary(w[0].1, "the stop before it")
                        .with_help("write the stops in order of position, from 0 to 1"),
                );
                return None;
            }
        }
        Some(Gradient {
            stops: stops.into_iter().map(|(s, _)| s).collect(),
            constant,
        })
    }

    /// `g` with its stops replaced by the last setting of `name`, if any
    /// (`--set g="0:#000000, 1:#ffffff"`); `None` with E0206 at the
    /// setting's value when it is no list of sorted stops in 0..1.
    pub(super) fn set_gradient(&mut self, name: &str, g: Gradient) -> Option<Gradient> {
        let Some(s) = self.gradient_settings.iter().rev().find(|s| s.name == name) else {
            return Some(g);
        };
        self.gradients_set.push(name.to_string());
        let span = s.value_span;
        let form = "write the stops as `position:#colour`, comma-separated, positions from 0 to 1 in order: `--set g=\"0:#000000, 0.5:#ff8800, 1:#ffffff\"`";
        let Literal::Stops(stops) = &s.value else {
            self.bad_gradient(
                span,
                &format!("`{name}` is a gradient: its value is a list of stops"),
                "not `position:#colour, ...`",
                form,
            );
            return None;
        };
        if stops.is_empty() || stops.len() > MAX_STOPS {
            self.bad_gradient(
                span,
                &format!("a gradient of {} stops", stops.len()),
                &format!("a gradient has 1 to {MAX_STOPS} stops"),
                form,
            );
            return None;
        }
        if let Some((p, _)) = stops.iter().find(|(p, _)| !(0.0..=1.0).contains(p)) {
            self.bad_gradient(
                span,
                "a stop's position is outside 0..1",
                &format!("{p} is outside 0..1"),
                form,
            );
            return None;
        }
        if stops.windows(2).any(|w| w[1].0 < w[0].0) {
            self.bad_gradient(
                span,
                "a gradient's stops are out of order",
                "positions must not decrease",
                form,
            );
            return None;
        }
        Some(Gradient {
            stops: stops.clone(),
            constant: g.constant,
        })
    }

    /// Under `keep_params`: `g` as a parameter of the IR, a uniform of
    /// [`npr_abi::gradient`]'s slots whose default is its stops packed, so
    /// `--set`, the studio and a host's `set_param` change it without a
    /// recompile. `None` (with E0404) past the parameter limit.
    pub(super) fn live_gradient(&mut self, p: &ast::ParamDecl, g: &Gradient) -> Option<ParamId> {
        if self.ir.params.len() == MAX_PARAMS {
            self.error(
                Diagnostic::error(codes::LIMIT_EXCEEDED, "too many parameters")
                    .with_primary(p.name.span, format!("parameter number {}", MAX_PARAMS + 1))
                    .with_help(format!("a style may have at most {MAX_PARAMS} parameters")),
            );
            return None;
        }
        let slots = npr_abi::gradient::pack(&g.stops, g.constant);
        let default = self.ir.add_typed(
            ExprKind::Const(Const::Vec(slots)),
            Ty::Unknown,
            Unit::None,
            p.default.span,
        );
        let id = ParamId(self.ir.params.len() as u32);
        self.ir.params.push(Param {
            name: p.name.name.clone(),
            doc: p.doc.clone(),
            ty: ParamTy::Gradient,
            // No value type: only `ramp` reads it (`Intrinsic::Ramp`).
            value_ty: Ty::Unknown,
            unit: Unit::None,
            per_object: false,
            default,
            range: None,
            keys: Vec::new(),
            interpolation: "linear".into(),
            span: p.span,
            name_span: p.name.span,
        });
        Some(id)
    }

    /// `stop(position, colour)`: a position in 0..1 and a colour literal.
    fn stop(&mut self, stop: &ast::Call) -> Option<(f64, [f64; 4])> {
        let [pos, colour] = stop.args.as_slice() else {
            self.bad_gradient(
                stop.span,
                "a stop is `stop(position, colour)`",
                "not two arguments",
                "write `stop(0.5, #ff8800)`",
            );
            return None;
        };
        let position = match &pos.value.kind {
            ast::ExprKind::Number { value, unit: None, .. } => *value,
            _ => {
                self.bad_gradient(
                    pos.span,
                    "a stop's position is a number",
                    "not a plain number",
                    "write a position from 0 to 1, e.g. `0.5`",
                );
                return None;
            }
        };
        if !(0.0..=1.0).contains(&position) {
            self.bad_gradient(
                pos.span,
                "a stop's position is outside 0..1",
                &format!("{position} is outside 0..1"),
                "a gradient runs from 0 to 1: `ramp(g, t)` takes `t` in 0..1",
            );
            return None;
        }
        let ast::ExprKind::Color(c) = colour.value.kind else {
            self.bad_gradient(
                colour.span,
                "a stop's colour is a colour literal",
                "not `#rrggbb`",
                "write `#rrggbb` or `#rrggbbaa`",
            );
            return None;
        };
        Some((position, c))
    }

    /// `ramp(g, t)`: the nodes of the module's rule over `g`'s stops.
    pub(super) fn ramp(&mut self, call: &ast::Call) -> ExprId {
        let span = call.span;
        let usage = "write `ramp(g, t)`: a gradient param and a number from 0 to 1";
        let gradient = match call.args.as_slice() {
            [g, t] if g.name.is_none() && t.name.is_none() => {
                match &g.value.kind {
                    ast::ExprKind::Name(n) => match self.names.get(&n.name) {
                        Some((Symbol::Gradient(i), _)) => {
                            let i = *i;
                            if let (Some(param), Some(_)) = (self.gradient_params[i], &self.gradients[i]) {
                                // Kept live: the uniform's stops, read by `npr_ramp_<g>`.
                                let t = self.expr(&t.value);
                                return self.ir.add(
                                    ExprKind::Call {
                                        callee: Callee::Intrinsic(Intrinsic::Ramp(param)),
                                        args: vec![t],
                                    },
                                    span,
                                );
                            }
                            self.gradients[i].clone().map(|g| (g, t))
                        }
                        _ => {
                            self.error(
                            Diagnostic::error(codes::TYPE_MISMATCH, format!("`{}` is not a gradient", n.name))
                                .with_primary(n.span, "not a gradient param")
                                .with_help("declare `param g: gradient = gradient(stop(0.0, #000000), stop(1.0, #ffffff))`"),
                        );
                            None
                        }
                    },
                    _ => {
                        self.error(
                            Diagnostic::error(codes::TYPE_MISMATCH, "`ramp` reads a gradient param by name")
                                .with_primary(g.span, "not a gradient's name")
                                .with_help(usage),
                        );
                        None
                    }
                }
            }
            _ => {
                self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, "`ramp` takes a gradient and a position")
                        .with_primary(span, "not `ramp(g, t)`")
                        .with_help(usage),
                );
                None
            }
        };
        let Some((g, t)) = gradient else {
            // The other arguments' errors, not a gradient's again.
            for a in &call.args {
                let is_gradient = matches!(&a.value.kind, ast::ExprKind::Name(n)
                    if matches!(self.names.get(&n.name), Some((Symbol::Gradient(_), _))));
                if !is_gradient {
                    self.expr(&a.value);
                }
            }
            return self.ir.add(ExprKind::Error, span);
        };
        let t = self.expr(&t.value);
        let colour = |r: &mut Self, c: [f64; 4]| {
            r.ir.add_typed(ExprKind::Const(Const::Vec(c.to_vec())), Ty::Vec4, Unit::None, span)
        };
        let number = |r: &mut Self, v: f64| {
            r.ir.add_typed(ExprKind::Const(Const::Float(v)), Ty::Float, Unit::None, span)
        };
        let call = |r: &mut Self, intr: Intrinsic, args: Vec<ExprId>| {
            r.ir.add(
                ExprKind::Call {
                    callee: Callee::Intrinsic(intr),
                    args,
                },
                span,
            )
        };
        let mut result = colour(self, g.stops[0].1);
        for w in g.stops.windows(2) {
            let ((p0, _), (p1, c1)) = (w[0], w[1]);
            let factor = if g.constant || p1 == p0 {
                let at = number(self, p1);
                call(self, Intrinsic::Map2("step"), vec![at, t])
            } else {
                let from = number(self, p0);
                let width = number(self, p1 - p0);
                let offset = self.ir.add(
                    ExprKind::Binary {
                        op: BinOp::Sub,
                        lhs: t,
                        rhs: from,
                    },
                    span,
                );
                let scaled = self.ir.add(
                    ExprKind::Binary {
                        op: BinOp::Div,
                        lhs: offset,
                        rhs: width,
                    },
                    span,
                );
                call(self, Intrinsic::Map("saturate"), vec![scaled])
            };
            let next = colour(self, c1);
            result = call(self, Intrinsic::Map3("mix"), vec![result, next, factor]);
        }
        result
    }
}
