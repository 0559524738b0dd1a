//! Typecheck with units: give every node a type and a unit, insert implicit
//! conversions, and check arguments, defaults, ranges and target formats.
//!
//! Unit rules: a plain number (no unit) fits anywhere, so `2 * width` and
//! `sigma: 3` work; two different units never mix (`2px + 1m` is an error).
//! `*` and `/` combine units where the result is meaningful (`s * Hz` is a
//! plain number, `px / px` too); other products are errors.

use crate::consteval::const_eval;
use crate::ir::*;
use dsl::ast::{BinOp, UnOp};
use dsl::{codes, Diagnostic, Span};
use stdlib::Unit;

mod compute;
mod defaults;

pub fn typecheck(ir: &mut Ir, diags: &mut Vec<Diagnostic>) {
    let mut tc = Checker { ir, diags };
    let n = tc.ir.exprs.len();
    for i in 0..n {
        tc.node(ExprId(i as u32));
    }
    tc.params();
    tc.passes();
}

struct Checker<'a> {
    ir: &'a mut Ir,
    diags: &'a mut Vec<Diagnostic>,
}

/// Type of a node when used as a value: handles read as their texel.
pub fn value_ty(ir: &Ir, id: ExprId) -> Ty {
    match ir.expr(id).ty {
        Ty::Target(t) => {
            let fmt = ir.pass(t.pass).outputs.get(t.output as usize).map(|o| o.format);
            Ty::float_vec(fmt.map_or(4, |f| f.channels()))
        }
        Ty::Texture(_) => Ty::Vec4,
        t => t,
    }
}

impl Checker<'_> {
    fn err(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    fn span(&self, id: ExprId) -> Span {
        self.ir.expr(id).span
    }

    fn vt(&self, id: ExprId) -> Ty {
        value_ty(self.ir, id)
    }

    fn unit(&self, id: ExprId) -> Unit {
        self.ir.expr(id).unit
    }

    fn set(&mut self, id: ExprId, ty: Ty, unit: Unit) {
        let e = self.ir.expr_mut(id);
        e.ty = ty;
        e.unit = unit;
    }

    fn convert(&mut self, id: ExprId, conversion: Conversion) -> ExprId {
        let (span, unit) = (self.span(id), self.unit(id));
        let ty = match conversion {
            Conversion::IntToFloat => Ty::Float,
            Conversion::Splat(n) => Ty::float_vec(n),
            Conversion::Rgb1 => Ty::Vec4,
            Conversion::Rgb => Ty::Vec3,
        };
        self.ir.add_typed(
            ExprKind::Convert {
                conversion,
                operand: id,
            },
            ty,
            unit,
            span,
        )
    }

    fn promote_int(&mut self, id: ExprId) -> ExprId {
        if self.vt(id) == Ty::Int {
            self.convert(id, Conversion::IntToFloat)
        } else {
            id
        }
    }

    /// Bring a numeric operand to type `want` (int → float, scalar → vector).
    fn coerce(&mut self, id: ExprId, want: Ty) -> Option<ExprId> {
        let have = self.vt(id);
        if have == want {
            return Some(id);
        }
        let id = if have == Ty::Int && want != Ty::Int {
            self.convert(id, Conversion::IntToFloat)
        } else {
            id
        };
        let have = self.vt(id);
        match (have, want) {
            (a, b) if a == b => Some(id),
            (Ty::Float, Ty::Vec2 | Ty::Vec3 | Ty::Vec4) => {
                Some(self.convert(id, Conversion::Splat(want.components().unwrap_or(4))))
            }
            _ => None,
        }
    }

    fn is_error(&self, id: ExprId) -> bool {
        matches!(self.ir.expr(id).kind, ExprKind::Error) || self.ir.expr(id).ty == Ty::Unknown
    }

    fn type_error(&mut self, id: ExprId, expected: &str, help: Option<String>) {
        let found = self.vt(id).describe();
        let mut d = Diagnostic::error(codes::TYPE_MISMATCH, format!("expected {expected}, found {found}"))
            .with_primary(self.span(id), format!("this is {found}"));
        if let Some(h) = help {
            d = d.with_help(h);
        }
        self.err(d);
    }

    /// Units of `+`, `-`, comparisons, and same-typed intrinsic operands.
    fn same_unit(&mut self, a: ExprId, b: ExprId, what: &str, span: Span) -> Unit {
        let (ua, ub) = (self.unit(a), self.unit(b));
        match (ua, ub) {
            (x, Unit::None) | (Unit::None, x) => x,
            (x, y) if x == y => x,
            (x, y) => {
                self.err(
                    Diagnostic::error(
                        codes::UNIT_MISMATCH,
                        format!("cannot {what} {} and {}", x.name(), y.name()),
                    )
                    .with_primary(span, format!("{} and {} do not mix", x.name(), y.name()))
                    .with_secondary(self.span(a), format!("this is in {}", x.name()))
                    .with_secondary(self.span(b), format!("this is in {}", y.name()))
                    .with_help("convert one side first, or use plain numbers where no unit is meant"),
                );
                x
            }
        }
    }

    fn node(&mut self, id: ExprId) {
        if self.ir.expr(id).ty != Ty::Unknown {
            return;
        }
        let kind = self.ir.expr(id).kind.clone();
        let span = self.span(id);
        match kind {
            ExprKind::Error => {}
            ExprKind::Swizzle { base, components } => {
                if self.is_error(base) {
                    return;
                }
                let bt = self.vt(base);
                let n = bt.components().unwrap_or(0);
                if !matches!(bt, Ty::Vec2 | Ty::Vec3 | Ty::Vec4) || components.iter().any(|c| *c as u32 >= n) {
                    let d = Diagnostic::error(codes::TYPE_MISMATCH, format!("cannot swizzle {}", bt.describe()))
                        .with_primary(span, format!("{} has {} component(s)", bt.describe(), n))
                        .with_help("swizzles pick components of a vector: `.x`, `.rg`, `.xyz`");
                    self.err(d);
                    return;
                }
                let u = self.unit(base);
                self.set(id, Ty::float_vec(components.len() as u32), u);
            }
            ExprKind::Unary { op, operand } => {
                if self.is_error(operand) {
                    return;
                }
                let t = self.vt(operand);
                let u = self.unit(operand);
                match op {
                    UnOp::Neg if t.is_numeric() => self.set(id, t, u),
                    UnOp::Not if t == Ty::Bool => self.set(id, t, u),
                    UnOp::Neg => self.type_error(operand, "a number or vector", None),
                    UnOp::Not => self.type_error(operand, "bool", None),
                }
            }
            ExprKind::Binary { op, lhs, rhs } => self.binary(id, op, lhs, rhs, span),
            ExprKind::Select { cond, then, otherwise } => {
                if self.is_error(cond) || self.is_error(then) || self.is_error(otherwise) {
                    return;
                }
                if self.vt(cond) != Ty::Bool {
                    self.type_error(cond, "bool", Some("conditions compare values, e.g. `x > 0.5`".into()));
                    return;
                }
                let Some((t, o, ty)) = self.unify(then, otherwise) else {
                    let (a, b) = (self.vt(then).describe(), self.vt(otherwise).describe());
                    self.err(
                        Diagnostic::error(codes::TYPE_MISMATCH, "`if` branches have different types")
                            .with_primary(span, format!("{a} and {b}"))
                            .with_help("both branches must give the same type"),
                    );
                    return;
                };
                let unit = self.same_unit(t, o, "choose between", span);
                self.ir.expr_mut(id).kind = ExprKind::Select {
                    cond,
                    then: t,
                    otherwise: o,
                };
                self.set(id, ty, unit);
            }
            ExprKind::Call {
                callee: Callee::Intrinsic(intr),
                args,
            } => self.intrinsic(id, intr, args, span),
            ExprKind::Call {
                callee: Callee::Operator(index),
                args,
            } => self.operator(id, index, args, span),
            // Leaves are typed at creation.
            _ => {}
        }
    }

    /// Bring two operands to a common numeric type.
    fn unify(&mut self, a: ExprId, b: ExprId) -> Option<(ExprId, ExprId, Ty)> {
        let (ta, tb) = (self.vt(a), self.vt(b));
        if ta == tb && (ta.is_numeric() || ta == Ty::Bool) {
            return Some((a, b, ta));
        }
        if !ta.is_numeric() || !tb.is_numeric() {
            return None;
        }
        let (na, nb) = (ta.components()?, tb.components()?);
        let want = if na == 1 && nb == 1 {
            Ty::Float
        } else if na == 1 || na == nb {
            Ty::float_vec(nb)
        } else if nb == 1 {
            Ty::float_vec(na)
        } else {
            return None;
        };
        Some((self.coerce(a, want)?, self.coerce(b, want)?, want))
    }

    fn binary(&mut self, id: ExprId, op: BinOp, lhs: ExprId, rhs: ExprId, span: Span) {
        if self.is_error(lhs) || self.is_error(rhs) {
            return;
        }
        let (tl, tr) = (self.vt(lhs), self.vt(rhs));
        match op {
            BinOp::And | BinOp::Or => {
                if tl != Ty::Bool {
                    return self.type_error(lhs, "bool", None);
                }
                if tr != Ty::Bool {
                    return self.type_error(rhs, "bool", None);
                }
                self.set(id, Ty::Bool, Unit::None);
            }
            BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge | BinOp::Eq | BinOp::Ne => {
                let scalar =
                    |t: Ty| matches!(t, Ty::Float | Ty::Int) || (t == Ty::Bool && matches!(op, BinOp::Eq | BinOp::Ne));
                if !scalar(tl) {
                    return self.type_error(
                        lhs,
                        "a number",
                        Some("compare single components, e.g. `c.r > 0.5`".into()),
                    );
                }
                if !scalar(tr) {
                    return self.type_error(
                        rhs,
                        "a number",
                        Some("compare single components, e.g. `c.r > 0.5`".into()),
                    );
                }
                let Some((l, r, _)) = self.unify(lhs, rhs) else {
                    return self.type_error(rhs, tl.describe(), None);
                };
                self.same_unit(l, r, "compare", span);
                self.ir.expr_mut(id).kind = ExprKind::Binary { op, lhs: l, rhs: r };
                self.set(id, Ty::Bool, Unit::None);
            }
            _ => {
                if !tl.is_numeric() {
                    return self.type_error(lhs, "a number or vector", None);
                }
                if !tr.is_numeric() {
                    return self.type_error(rhs, "a number or vector", None);
                }
                let (nl, nr) = (tl.components().unwrap_or(1), tr.components().unwrap_or(1));
                if nl != 1 && nr != 1 && nl != nr {
                    self.err(
                        Diagnostic::error(
                            codes::TYPE_MISMATCH,
                            format!("cannot {} {} and {}", verb(op), tl.describe(), tr.describe()),
                        )
                        .with_primary(span, "vectors of different sizes")
                        .with_help("use a swizzle such as `.rgb` or `.xy` to match sizes"),
                    );
                    return;
                }
                // Int with float: promote the int. Vector with scalar: WGSL broadcasts.
                let (l, r) = if tl == Ty::Int && tr == Ty::Int {
                    (lhs, rhs)
                } else {
                    (self.promote_int(lhs), self.promote_int(rhs))
                };
                let ty = if tl == Ty::Int && tr == Ty::Int {
                    Ty::Int
                } else {
                    Ty::float_vec(nl.max(nr))
                };
                let unit = match op {
                    BinOp::Add | BinOp::Sub | BinOp::Rem => self.same_unit(l, r, verb(op), span),
                    BinOp::Mul => self.mul_unit(l, r, span),
                    _ => self.div_unit(l, r, span),
                };
                self.ir.expr_mut(id).kind = ExprKind::Binary { op, lhs: l, rhs: r };
                self.set(id, ty, unit);
            }
        }
    }

    fn mul_unit(&mut self, a: ExprId, b: ExprId, span: Span) -> Unit {
        match (self.unit(a), self.unit(b)) {
            (x, Unit::None) | (Unit::None, x) => x,
            (Unit::Seconds, Unit::Hertz) | (Unit::Hertz, Unit::Seconds) => Unit::None,
            (x, y) => {
                self.err(
                    Diagnostic::error(
                        codes::UNIT_MISMATCH,
                        format!("cannot multiply {} by {}", x.name(), y.name()),
                    )
                    .with_primary(span, "this product has no unit npr knows")
                    .with_help("scale by a plain number instead"),
                );
                x
            }
        }
    }

    fn div_unit(&mut self, a: ExprId, b: ExprId, span: Span) -> Unit {
        match (self.unit(a), self.unit(b)) {
            (x, Unit::None) => x,
            (x, y) if x == y => Unit::None,
            (Unit::None, Unit::Seconds) => Unit::Hertz,
            (Unit::None, Unit::Hertz) => Unit::Seconds,
            (x, y) => {
                self.err(
                    Diagnostic::error(
                        codes::UNIT_MISMATCH,
                        format!("cannot divide {} by {}", x.name(), y.name()),
                    )
                    .with_primary(span, "this quotient has no unit npr knows")
                    .with_help("divide by a plain number or by the same unit"),
                );
                x
            }
        }
    }

    fn intrinsic(&mut self, id: ExprId, intr: Intrinsic, args: Vec<ExprId>, span: Span) {
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
            | Intrinsic::ProjectPrevious => Some(1),
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

    fn operator(&mut self, id: ExprId, index: u32, args: Vec<ExprId>, span: Span) {
        let op = &stdlib::all()[index as usize];
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
        let ty = match op.returns {
            stdlib::Ty::Float => Ty::Float,
            stdlib::Ty::Int | stdlib::Ty::Enum(_) => Ty::Int,
            stdlib::Ty::Bool => Ty::Bool,
            stdlib::Ty::Vec2 => Ty::Vec2,
            stdlib::Ty::Vec3 => Ty::Vec3,
            _ => Ty::Vec4,
        };
        let _ = span;
        self.ir.expr_mut(id).kind = ExprKind::Call {
            callee: Callee::Operator(index),
            args: out,
        };
        self.set(id, ty, Unit::None);
    }

    fn argument(&mut self, op: &stdlib::Operator, p: &stdlib::Param, a: ExprId) -> Option<ExprId> {
        let have = self.ir.expr(a).ty;
        let help = Some(format!("`{}` takes {}", op.name, crate::resolve::signature(op)));
        let converted = match p.ty {
            stdlib::Ty::Texture | stdlib::Ty::SampledTexture => {
                let ok = match have {
                    Ty::Target(t) => {
                        let fmt = self.ir.pass(t.pass).outputs[t.output as usize].format;
                        if p.ty == stdlib::Ty::SampledTexture && !fmt.is_filterable() {
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
            stdlib::Ty::Float => self.coerce(a, Ty::Float),
            stdlib::Ty::Int | stdlib::Ty::Enum(_) => (self.vt(a) == Ty::Int).then_some(a),
            stdlib::Ty::Bool => (self.vt(a) == Ty::Bool).then_some(a),
            stdlib::Ty::Vec2 => self.coerce(a, Ty::Vec2),
            stdlib::Ty::Vec3 => match self.vt(a) {
                Ty::Vec4 => Some(self.convert(a, Conversion::Rgb)),
                _ => self.coerce(a, Ty::Vec3),
            },
            stdlib::Ty::Vec4 | stdlib::Ty::Color => match self.vt(a) {
                Ty::Vec3 => Some(self.convert(a, Conversion::Rgb1)),
                _ => self.coerce(a, Ty::Vec4),
            },
        };
        let Some(c) = converted else {
            let want = match p.ty {
                stdlib::Ty::Enum(v) => format!("one of {}", v.join(", ")),
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
                    .with_help(p.doc.to_string()),
                );
                return None;
            }
        }
        Some(c)
    }

    // ---------------------------------------------------------------- params

    fn params(&mut self) {
        for i in 0..self.ir.params.len() {
            let p = self.ir.params[i].clone();
            let d = p.default;
            if self.is_error(d) {
                continue;
            }
            let have = self.vt(d);
            let want = p.value_ty;
            if want == Ty::Unknown {
                continue;
            }
            let ok = have == want
                || (have == Ty::Int && want == Ty::Float)
                || (have == Ty::Vec3 && want == Ty::Vec4 && matches!(p.ty, ParamTy::Value(_)));
            if !ok {
                self.err(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("default of `{}` has the wrong type", p.name),
                    )
                    .with_primary(
                        self.span(d),
                        format!("expected {}, found {}", want.describe(), have.describe()),
                    )
                    .with_secondary(p.name_span, "parameter declared here"),
                );
                continue;
            }
            let du = self.unit(d);
            if du != Unit::None && du != p.unit {
                self.err(
                    Diagnostic::error(
                        codes::UNIT_MISMATCH,
                        format!(
                            "default of `{}` is in {}, but the parameter is {}",
                            p.name,
                            du.name(),
                            p.unit.name()
                        ),
                    )
                    .with_primary(self.span(d), format!("this is in {}", du.name()))
                    .with_secondary(p.name_span, "parameter declared here")
                    .with_help(format!("write the default in {}", p.unit.name())),
                );
                continue;
            }
            if let Some(d) = defaults::not_constant(self.ir, &p) {
                self.err(d);
            }
            if let (Some((lo, hi)), Some(c)) = (p.range, const_eval(self.ir, d)) {
                if let Some(bad) = c.as_f64s().into_iter().find(|v| *v < lo || *v > hi) {
                    self.err(
                        Diagnostic::error(
                            codes::OUT_OF_RANGE,
                            format!("default of `{}` is outside its range", p.name),
                        )
                        .with_primary(self.span(d), format!("{bad} is outside {lo}..{hi}"))
                        .with_help("change the default or widen the range"),
                    );
                }
            }
            if p.per_object && !p.keys.is_empty() {
                self.err(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        format!("object param `{}` cannot be animated", p.name),
                    )
                    .with_primary(p.name_span, "per object and animated")
                    .with_help("animate a style param and multiply it by the object param"),
                );
            }
        }
    }

    // ---------------------------------------------------------------- passes

    /// `vertex { inflate, shadow_warp }`: a width in px and a plain number,
    /// promoted to float; an ill-typed one is reported and left as it was.
    fn vertex_modifiers(&mut self, mut vertex: VertexModifiers) -> VertexModifiers {
        if let Some(inflate) = vertex.inflate {
            if !self.is_error(inflate) {
                let u = self.unit(inflate);
                if self.vt(inflate) != Ty::Float && self.vt(inflate) != Ty::Int {
                    self.type_error(inflate, "a width in px", None);
                } else if u != Unit::Px && u != Unit::None {
                    self.err(
                        Diagnostic::error(
                            codes::UNIT_MISMATCH,
                            format!("`inflate` is a width in px, found {}", u.name()),
                        )
                        .with_primary(self.span(inflate), format!("this is in {}", u.name()))
                        .with_help("write it in px, or in % of the image height"),
                    );
                } else {
                    vertex.inflate = Some(self.promote_int(inflate));
                }
            }
        }
        if let Some(k) = vertex.shadow_warp {
            if !self.is_error(k) {
                if self.vt(k) != Ty::Float && self.vt(k) != Ty::Int {
                    self.type_error(k, "a plain number (the sigmoid strength)", None);
                } else {
                    vertex.shadow_warp = Some(self.promote_int(k));
                }
            }
        }
        vertex
    }

    /// `depth: test(other)`: `other` is a render pass that keeps its depth
    /// (E0308 otherwise), is not this pass, and has this pass's scale and
    /// view, so that its depth texture fits this pass's attachment and holds
    /// depths of the same projection.
    fn depth_test(&mut self, pi: usize) {
        let pass = &self.ir.passes[pi];
        let Some((tested, span)) = pass.depth_test() else {
            return;
        };
        let other = self.ir.pass(tested);
        let (name, other_name) = (pass.name.clone(), other.name.clone());
        if tested.0 as usize == pi {
            self.err(
                Diagnostic::error(codes::BAD_PASS_INPUT, format!("pass `{name}` tests against its own depth"))
                    .with_primary(span, "this pass")
                    .with_help("a pass always tests against its own depth; `depth: test(...)` names an earlier pass with `depth: keep`"),
            );
            return;
        }
        if !other.keeps_depth() {
            let (label, help) = if other.kind.draws_objects() {
                (
                    format!("`{other_name}` discards its depth after it runs"),
                    format!("add `depth: keep` to pass `{other_name}`, so its depth buffer outlives the pass"),
                )
            } else {
                (format!("`{other_name}` has no depth buffer"),
                format!("`{other_name}` is not a render pass, so it has no depth buffer; test against a render pass with `depth: keep`"))
            };
            self.err(
                Diagnostic::error(
                    codes::DEPTH_NOT_KEPT,
                    format!("pass `{name}` tests against the depth of `{other_name}`, which keeps none"),
                )
                .with_primary(span, "depth test here")
                .with_secondary(other.name_span, label)
                .with_help(help),
            );
            return;
        }
        let view = |p: &Pass| match p.kind {
            PassKind::Render { view, .. } => Some(view),
            _ => None,
        };
        if other.scale != pass.scale {
            let (a, b) = (other.scale, pass.scale);
            self.err(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("pass `{name}` tests against the depth of `{other_name}`, which has another size"),
                )
                .with_primary(span, format!("`{name}` renders at scale {b}"))
                .with_secondary(other.name_span, format!("`{other_name}` renders at scale {a}"))
                .with_help("a depth test needs both passes at the same scale"),
            );
        } else if view(other) != view(pass) {
            self.err(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("pass `{name}` tests against the depth of `{other_name}`, seen from another view"),
                )
                .with_primary(span, "depth test here")
                .with_secondary(other.name_span, "projected with another camera")
                .with_help("give both passes the same `view(...)`"),
            );
        }
    }

    fn passes(&mut self) {
        for pi in 0..self.ir.passes.len() {
            self.depth_test(pi);
            let pass = self.ir.passes[pi].clone();
            if let PassKind::Render { vertex, .. } = &pass.kind {
                let checked = self.vertex_modifiers(*vertex);
                if let PassKind::Render { vertex, .. } = &mut self.ir.passes[pi].kind {
                    *vertex = checked;
                }
            }
            // Vertex modifiers run per vertex: no fragment varyings there.
            for id in self.ir.reachable(&Ir::vertex_roots(&pass)) {
                let e = self.ir.expr(id).clone();
                if let ExprKind::Builtin(b) = e.kind {
                    if b.is_per_fragment() {
                        self.err(
                            Diagnostic::error(
                                codes::BAD_PASS_INPUT,
                                format!("`{}` read in a `vertex {{ }}` modifier", b.name()),
                            )
                            .with_primary(e.span, "this value exists per fragment, not per vertex")
                            .with_help(
                                "vertex modifiers may read parameters, per-object params and frame values such as `time`, `resolution`, `camera.*` and `light.*`",
                            ),
                        );
                    }
                }
            }
            let mut roots: Vec<ExprId> = pass.outputs.iter().map(|o| o.value).collect();
            roots.extend(pass.kind.values().iter().flat_map(ObjectValue::roots));
            for id in self.ir.reachable(&roots) {
                let e = self.ir.expr(id).clone();
                match e.kind {
                    ExprKind::Builtin(b) => self.builtin_in_kind(b, &pass.kind, e.span),
                    // A previous-frame read is no dependency within the frame,
                    // so it needs no input listing.
                    ExprKind::Target { target: t, copy } if copy != TargetCopy::Previous => {
                        if let PassKind::Image { inputs } = &pass.kind {
                            if t.pass.0 as usize != pi && !inputs.contains(&t.pass) {
                                let other = self.ir.pass(t.pass).name.clone();
                                self.err(
                                    Diagnostic::error(
                                        codes::BAD_PASS_INPUT,
                                        format!("pass `{}` reads `{other}` without listing it", pass.name),
                                    )
                                    .with_primary(e.span, "read here")
                                    .with_secondary(pass.name_span, "inputs declared here")
                                    .with_help(format!("add `{other}` to the inputs: `image(..., {other})`")),
                                );
                            }
                        }
                    }
                    _ => {}
                }
            }
            for (oi, o) in pass.outputs.iter().enumerate() {
                if self.is_error(o.value) {
                    continue;
                }
                let mut v = o.value;
                let t = self.vt(v);
                if t == Ty::Int {
                    v = self.convert(v, Conversion::IntToFloat);
                }
                let t = self.vt(v);
                let want = o.format.channels();
                let fits = t.components() == Some(want) && t != Ty::Bool;
                if !fits {
                    let n = t.components().unwrap_or(0);
                    let help = match (n, want) {
                        (1, 4) => "write `vec4(x, x, x, 1.0)`, or use a one-channel format such as r8unorm".to_string(),
                        (4, 1) => {
                            "pick one channel, e.g. `.r`, or use a four-channel format such as rgba8unorm".to_string()
                        }
                        (3, 4) => "add alpha: `vec4(c, 1.0)`, or use a colour (`#rrggbb`)".to_string(),
                        _ => format!(
                            "{} has {want} channel(s): write a value with {want} component(s)",
                            o.format.name()
                        ),
                    };
                    self.err(
                        Diagnostic::error(
                            codes::FORMAT_MISMATCH,
                            format!("cannot write {} into a {} target", t.describe(), o.format.name()),
                        )
                        .with_primary(self.span(o.value), format!("this is {}", t.describe()))
                        .with_secondary(o.span, format!("`{}` is {}", o.name, o.format.name()))
                        .with_help(help),
                    );
                    continue;
                }
                self.ir.passes[pi].outputs[oi].value = v;
            }
            self.compute_values(pi);
        }
    }
}

fn verb(op: BinOp) -> &'static str {
    match op {
        BinOp::Add => "add",
        BinOp::Sub => "subtract",
        BinOp::Mul => "multiply",
        BinOp::Div => "divide",
        BinOp::Rem => "take the remainder of",
        _ => "combine",
    }
}
