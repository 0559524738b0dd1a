//! Typecheck of calls: intrinsics (builtin functions) and stdlib operator
//! calls, each argument coerced to its parameter's type and unit and
//! checked against its range.

use super::*;

impl Checker<'_> {
    pub(super) fn intrinsic(&mut self, id: ExprId, intr: Intrinsic, args: Vec<ExprId>, span: Span) {
        if args.iter().any(|a| self.is_error(*a)) {
            return;
        }
        let name = intr.name();
        let want_args = match intr {
            Intrinsic::Construct(_) => None,
            Intrinsic::Map(_)
            | Intrinsic::Length
            | Intrinsic::Normalize
            | Intrinsic::Project
            | Intrinsic::ProjectOtherEye
            | Intrinsic::ProjectPrevious
            | Intrinsic::Ramp(_) => Some(1),
            Intrinsic::Map2(_) | Intrinsic::Dot | Intrinsic::Distance | Intrinsic::Cross => Some(2),
            Intrinsic::Map3(_) => Some(3),
        };
        if let Some(n) = want_args {
            if args.len() != n {
                self.err(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        format!("`{name}` takes {n} argument(s), found {}", args.len()),
                    )
                    .with_primary(span, "wrong number of arguments"),
                );
                return;
            }
        }
        for a in &args {
            if !self.vt(*a).is_numeric() {
                return self.type_error(*a, "a number or vector", None);
            }
        }
        let first_unit = args.first().map(|a| self.unit(*a)).unwrap_or(Unit::None);
        let (new_args, ty, unit) = match intr {
            Intrinsic::Construct(n) => {
                let total: u32 = args.iter().map(|a| self.vt(*a).components().unwrap_or(1)).sum();
                if !(total == n || (args.len() == 1 && total == 1)) {
                    self.err(
                        Diagnostic::error(
                            codes::TYPE_MISMATCH,
                            format!("`{name}` needs {n} components, found {total}"),
                        )
                        .with_primary(span, "wrong number of components")
                        .with_help(format!("give {n} numbers, or one number to repeat")),
                    );
                    return;
                }
                let mut out = Vec::new();
                let mut unit = Unit::None;
                for a in &args {
                    let a2 = self.promote_int(*a);
                    unit = self.same_unit(a2, out.last().copied().unwrap_or(a2), "combine", span);
                    out.push(a2);
                }
                (out, Ty::float_vec(n), unit)
            }
            Intrinsic::Map(f) => {
                let a = self.promote_int(args[0]);
                let t = self.vt(a);
                let trig = ["sin", "cos", "tan"].contains(&f);
                if trig && !matches!(first_unit, Unit::None | Unit::Radians) {
                    self.err(
                        Diagnostic::error(
                            codes::UNIT_MISMATCH,
                            format!("`{f}` needs an angle, found {}", first_unit.name()),
                        )
                        .with_primary(span, "not an angle")
                        .with_help("angles are written in `deg` (converted to radians) or as plain numbers"),
                    );
                }
                let unit = match f {
                    "abs" | "floor" | "ceil" | "round" | "sign" | "fract" => first_unit,
                    _ => Unit::None,
                };
                (vec![a], t, unit)
            }
            Intrinsic::Map2(f) => {
                let Some((a, b, t)) = self.unify(args[0], args[1]) else {
                    return self.type_error(args[1], self.vt(args[0]).describe(), None);
                };
                // WGSL has `min` and `max` of integers, not `pow`, `step`, `atan2`.
                let (a, b, t) = if t == Ty::Int && !matches!(f, "min" | "max") {
                    (self.promote_int(a), self.promote_int(b), Ty::Float)
                } else {
                    (a, b, t)
                };
                let unit = if matches!(f, "min" | "max") {
                    self.same_unit(a, b, "compare", span)
                } else {
                    Unit::None
                };
                (vec![a, b], t, unit)
            }
            Intrinsic::Map3(f) => {
                if f == "mix" {
                    let Some((a, b, t)) = self.unify(args[0], args[1]) else {
                        return self.type_error(args[1], self.vt(args[0]).describe(), None);
                    };
                    // WGSL's `mix` is of floats only: two ints are mixed as floats.
                    let (a, b, t) = if t == Ty::Int {
                        (self.promote_int(a), self.promote_int(b), Ty::Float)
                    } else {
                        (a, b, t)
                    };
                    let unit = self.same_unit(a, b, "mix", span);
                    // mix(a, b, t): t is a scalar or the same type as a and b.
                    let w = if self.vt(args[2]).components() == Some(1) {
                        self.promote_int(args[2])
                    } else {
                        match self.coerce(args[2], t) {
                            Some(w) => w,
                            None => return self.type_error(args[2], "a number or a vector like the others", None),
                        }
                    };
                    (vec![a, b, w], t, unit)
                } else {
                    let widest = args
                        .iter()
                        .map(|a| self.vt(*a).components().unwrap_or(1))
                        .max()
                        .unwrap_or(1);
                    let t = Ty::float_vec(widest);
                    let mut out = Vec::new();
                    for a in &args {
                        match self.coerce(*a, t) {
                            Some(c) => out.push(c),
                            None => return self.type_error(*a, t.describe(), None),
                        }
                    }
                    let unit = if f == "clamp" {
                        let u = self.same_unit(out[0], out[1], "clamp", span);
                        self.same_unit(out[0], out[2], "clamp", span);
                        u
                    } else {
                        self.same_unit(out[0], out[1], "compare", span);
                        Unit::None
                    };
                    (out, t, unit)
                }
            }
            Intrinsic::Length | Intrinsic::Normalize => {
                let a = self.promote_int(args[0]);
                let t = self.vt(a);
                if t.components() == Some(1) {
                    return self.type_error(a, "a vector", None);
                }
                if intr == Intrinsic::Length {
                    (vec![a], Ty::Float, first_unit)
                } else {
                    (vec![a], t, Unit::None)
                }
            }
            // A live gradient's colour at `t`: a colour, as the folded chain of `mix` is.
            Intrinsic::Ramp(_) => {
                let t = self.promote_int(args[0]);
                if self.vt(t) != Ty::Float {
                    return self.type_error(t, "a number from 0 to 1", None);
                }
                (vec![t], Ty::Vec4, Unit::None)
            }
            Intrinsic::Project | Intrinsic::ProjectOtherEye | Intrinsic::ProjectPrevious => {
                if self.vt(args[0]) != Ty::Vec3 {
                    return self.type_error(args[0], "a world-space point (vec3)", None);
                }
                (vec![args[0]], Ty::Vec3, Unit::None)
            }
            Intrinsic::Dot | Intrinsic::Distance | Intrinsic::Cross => {
                let Some((a, b, t)) = self.unify(args[0], args[1]) else {
                    return self.type_error(args[1], self.vt(args[0]).describe(), None);
                };
                if t.components() == Some(1) || (intr == Intrinsic::Cross && t != Ty::Vec3) {
                    let want = if intr == Intrinsic::Cross { "vec3" } else { "a vector" };
                    return self.type_error(a, want, None);
                }
                match intr {
                    Intrinsic::Dot => (vec![a, b], Ty::Float, Unit::None),
                    Intrinsic::Distance => {
                        let u = self.same_unit(a, b, "measure between", span);
                        (vec![a, b], Ty::Float, u)
                    }
                    _ => (vec![a, b], Ty::Vec3, Unit::None),
                }
            }
        };
        self.ir.expr_mut(id).kind = ExprKind::Call {
            callee: Callee::Intrinsic(intr),
            args: new_args,
        };
        self.set(id, ty, unit);
    }

    pub(super) fn operator(&mut self, id: ExprId, index: u32, args: Vec<ExprId>, span: Span) {
        let op = &npr_stdlib::all()[index as usize];
        if args.iter().any(|a| self.is_error(*a)) {
            return;
        }
        let mut out = Vec::new();
        for (p, a) in op.params.iter().zip(args) {
            let Some(a2) = self.argument(op, p, a) else {
                return;
            };
            out.push(a2);
        }
        if op.returns == npr_stdlib::Ty::Color {
            self.colors.insert(id);
        }
        let ty = match op.returns {
            npr_stdlib::Ty::Float => Ty::Float,
            npr_stdlib::Ty::Int | npr_stdlib::Ty::Enum(_) => Ty::Int,
            npr_stdlib::Ty::Bool => Ty::Bool,
            npr_stdlib::Ty::Vec2 => Ty::Vec2,
            npr_stdlib::Ty::Vec3 => Ty::Vec3,
            _ => Ty::Vec4,
        };
        let _ = span;
        self.ir.expr_mut(id).kind = ExprKind::Call {
            callee: Callee::Operator(index),
            args: out,
        };
        self.set(id, ty, Unit::None);
    }

    pub(super) fn argument(&mut self, op: &npr_stdlib::Operator, p: &npr_stdlib::Param, a: ExprId) -> Option<ExprId> {
        let have = self.ir.expr(a).ty;
        let help = Some(format!("`{}` takes {}", op.name, crate::front::resolve::signature(op)));
        let converted = match p.ty {
            npr_stdlib::Ty::Texture | npr_stdlib::Ty::SampledTexture => {
                let ok = match have {
                    Ty::Target(t) => {
                        let fmt = self.ir.pass(t.pass).outputs[t.output as usize].format;
                        if p.ty == npr_stdlib::Ty::SampledTexture && !fmt.is_filterable() {
                            self.err(
                                Diagnostic::error(codes::FORMAT_MISMATCH, format!("`{}` cannot be filtered", fmt.name()))
                                    .with_primary(self.span(a), format!("this target is {}", fmt.name()))
                                    .with_help("32-bit float targets cannot be sampled with filtering; declare the target as rgba16float, or read it with an operator that loads texels"),
                            );
                            return None;
                        }
                        true
                    }
                    Ty::Texture(_) => true,
                    _ => false,
                };
                if !ok {
                    self.type_error(a, "a texture or pass target", help);
                    return None;
                }
                return Some(a);
            }
            npr_stdlib::Ty::Float => self.coerce(a, Ty::Float),
            npr_stdlib::Ty::Int | npr_stdlib::Ty::Enum(_) => (self.vt(a) == Ty::Int).then_some(a),
            npr_stdlib::Ty::Bool => (self.vt(a) == Ty::Bool).then_some(a),
            npr_stdlib::Ty::Vec2 => self.coerce(a, Ty::Vec2),
            npr_stdlib::Ty::Vec3 => match self.vt(a) {
                Ty::Vec4 => Some(self.convert(a, Conversion::Rgb)),
                _ => self.coerce(a, Ty::Vec3),
            },
            npr_stdlib::Ty::Vec4 | npr_stdlib::Ty::Color => match self.vt(a) {
                Ty::Vec3 => Some(self.convert(a, Conversion::Rgb1)),
                _ => self.coerce(a, Ty::Vec4),
            },
        };
        let Some(c) = converted else {
            let want = match p.ty {
                npr_stdlib::Ty::Enum(v) => format!("one of {}", v.join(", ")),
                t => format!("{t:?}").to_lowercase(),
            };
            self.type_error(a, &format!("{want} for `{}`", p.name), help);
            return None;
        };
        let unit = self.unit(a);
        if unit != Unit::None && unit != p.unit {
            self.err(
                Diagnostic::error(
                    codes::UNIT_MISMATCH,
                    format!(
                        "`{}` of `{}` expects {}, found {}",
                        p.name,
                        op.name,
                        p.unit.name(),
                        unit.name()
                    ),
                )
                .with_primary(self.span(a), format!("this is in {}", unit.name()))
                .with_help(match p.unit {
                    Unit::None => "pass a plain number".to_string(),
                    u => format!("write the value in {}", u.name()),
                }),
            );
            return None;
        }
        if let (Some((lo, hi)), Some(v)) = (p.range, const_eval(self.ir, a).and_then(|c| c.scalar())) {
            if v < lo || v > hi {
                self.err(
                    Diagnostic::error(
                        codes::OUT_OF_RANGE,
                        format!("`{}` of `{}` is out of range", p.name, op.name),
                    )
                    .with_primary(self.span(a), format!("{v} is outside {lo}..{hi}"))
                    .with_help(format!(
                        "`{}` takes a value in {lo}..{hi} ({})",
                        p.name,
                        p.doc.trim_end_matches('.')
                    )),
                );
                return None;
            }
        }
        Some(c)
    }
}
