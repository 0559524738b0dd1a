//! Typecheck with units: give every node a type and a unit, insert implicit
//! conversions, and check arguments, defaults, ranges and target formats.
//!
//! Unit rules: a plain number (no unit) fits anywhere, so `2 * width` and
//! `sigma: 3` work; two different units never mix (`2px + 1m` is an error).
//! `*` and `/` combine units where the result is meaningful (`s * Hz` is a
//! plain number, `px / px` too); other products are errors.
//!
//! This file holds the checker and the sweep over the arena (`node`);
//! `arith.rs` types operators and their units, `calls.rs` intrinsics and
//! stdlib operator calls with their arguments, `decls.rs` the declarations
//! (params, passes, vertex modifiers, depth tests), `defaults.rs` constant
//! defaults, `compute.rs` what each pass kind may read and `lines.rs` the
//! shape settings of lines passes.

use crate::ir::*;
use crate::mid::consteval::const_eval;
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::{BinOp, UnOp};
use npr_stdlib::Unit;

mod arith;
mod calls;
mod color;
mod compute;
mod decls;
mod defaults;
mod lines;

pub fn typecheck(ir: &mut Ir, diags: &mut Vec<Diagnostic>) {
    let mut tc = Checker {
        ir,
        diags,
        colors: Default::default(),
    };
    let n = tc.ir.exprs.len();
    for i in 0..n {
        tc.node(ExprId(i as u32));
        tc.note_color(ExprId(i as u32));
    }
    tc.params();
    tc.passes();
}

struct Checker<'a> {
    ir: &'a mut Ir,
    diags: &'a mut Vec<Diagnostic>,
    /// Nodes built from colours that stay colours (`color.rs`); leaves
    /// are recognised by their kind.
    colors: std::collections::HashSet<ExprId>,
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
            Conversion::Stored(f) => Ty::float_vec(f.channels()),
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
}
