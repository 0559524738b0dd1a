//! Typecheck of operators: both operands brought to a common numeric type,
//! and the units of `+ - * /` and comparisons (px + m is E0202; `*` and `/`
//! combine units where the result means something).

use super::*;

impl Checker<'_> {
    /// Bring two operands to a common numeric type.
    pub(super) fn unify(&mut self, a: ExprId, b: ExprId) -> Option<(ExprId, ExprId, Ty)> {
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

    pub(super) fn binary(&mut self, id: ExprId, op: BinOp, lhs: ExprId, rhs: ExprId, span: Span) {
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
                if ty == Ty::Vec4 && self.color_binary(id, op, l, r, unit) {
                    return;
                }
                self.ir.expr_mut(id).kind = ExprKind::Binary { op, lhs: l, rhs: r };
                self.set(id, ty, unit);
            }
        }
    }

    pub(super) fn mul_unit(&mut self, a: ExprId, b: ExprId, span: Span) -> Unit {
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

    pub(super) fn div_unit(&mut self, a: ExprId, b: ExprId, span: Span) -> Unit {
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
