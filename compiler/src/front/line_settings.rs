//! A `lines` pass's shape settings as the runner evaluates them: each must
//! be affine in the style's parameters and the frame's time (`width: w`,
//! `phase: time * 3Hz`, `amplitude: 2px + wobble * 0.5`), because the strips
//! are built on the CPU (`npr_runner::lines`) and the runner has no expression
//! evaluator of its own: it evaluates `npr_abi::lines::LineScalar`s. Typecheck
//! calls [`affine`] to report what is not affine; the manifest writer calls
//! it again after specialization, when a folded parameter is a constant.

use crate::ir::*;
use npr_abi::lines::{LineScalar, ParamTerm};
use npr_diag::Span;
use npr_dsl::ast::{BinOp, UnOp};

/// Why a setting is not affine: where, and what to say there.
#[derive(Debug, Clone, PartialEq)]
pub struct NotAffine {
    pub span: Span,
    pub label: String,
}

fn not_affine(ir: &Ir, id: ExprId, label: impl Into<String>) -> NotAffine {
    NotAffine {
        span: ir.expr(id).span,
        label: label.into(),
    }
}

fn scale(s: LineScalar, k: f64) -> LineScalar {
    LineScalar {
        constant: s.constant * k,
        params: s
            .params
            .into_iter()
            .map(|t| ParamTerm {
                param: t.param,
                coefficient: t.coefficient * k,
            })
            .collect(),
        per_second: s.per_second * k,
    }
}

fn sum(a: LineScalar, b: LineScalar) -> LineScalar {
    let mut params = a.params;
    for t in b.params {
        match params.iter_mut().find(|p| p.param == t.param) {
            Some(p) => p.coefficient += t.coefficient,
            None => params.push(t),
        }
    }
    LineScalar {
        constant: a.constant + b.constant,
        params,
        per_second: a.per_second + b.per_second,
    }
}

fn is_constant(s: &LineScalar) -> bool {
    s.params.is_empty() && s.per_second == 0.0
}

/// The setting `id` as `constant + Σ k·param + k_t·time`, or where it is not.
pub fn affine(ir: &Ir, id: ExprId) -> Result<LineScalar, NotAffine> {
    let e = ir.expr(id);
    match &e.kind {
        ExprKind::Const(Const::Float(v)) => Ok(LineScalar::constant(*v)),
        ExprKind::Const(Const::Int(v)) => Ok(LineScalar::constant(*v as f64)),
        ExprKind::Const(_) => Err(not_affine(ir, id, "a setting of a lines pass is one number")),
        ExprKind::Param(p) => {
            let param = &ir.params[p.0 as usize];
            if param.per_object {
                return Err(not_affine(
                    ir,
                    id,
                    "a per-object param: the strips of all objects share one shape",
                ));
            }
            if !matches!(param.value_ty, Ty::Float | Ty::Int) || matches!(param.ty, ParamTy::Enum(_)) {
                return Err(not_affine(ir, id, "this param is not a plain number"));
            }
            Ok(LineScalar {
                params: vec![ParamTerm {
                    param: param.name.clone(),
                    coefficient: 1.0,
                }],
                ..LineScalar::default()
            })
        }
        ExprKind::Builtin(Builtin::Time) => Ok(LineScalar {
            per_second: 1.0,
            ..LineScalar::default()
        }),
        ExprKind::Convert {
            conversion: Conversion::IntToFloat,
            operand,
        } => affine(ir, *operand),
        ExprKind::Unary { op: UnOp::Neg, operand } => Ok(scale(affine(ir, *operand)?, -1.0)),
        ExprKind::Binary { op, lhs, rhs } => {
            let (a, b) = (affine(ir, *lhs), affine(ir, *rhs));
            match op {
                BinOp::Add => Ok(sum(a?, b?)),
                BinOp::Sub => Ok(sum(a?, scale(b?, -1.0))),
                BinOp::Mul => {
                    let (a, b) = (a?, b?);
                    if is_constant(&a) {
                        Ok(scale(b, a.constant))
                    } else if is_constant(&b) {
                        Ok(scale(a, b.constant))
                    } else {
                        Err(not_affine(
                            ir,
                            id,
                            "a product of two varying values: the runner evaluates settings as a sum of params and time, each times a constant",
                        ))
                    }
                }
                BinOp::Div => {
                    let (a, b) = (a?, b?);
                    if !is_constant(&b) {
                        return Err(not_affine(ir, *rhs, "a division by a varying value"));
                    }
                    if b.constant == 0.0 {
                        return Err(not_affine(ir, *rhs, "a division by zero"));
                    }
                    Ok(scale(a, 1.0 / b.constant))
                }
                _ => Err(not_affine(ir, id, format!("`{}` in a lines setting", op.as_str()))),
            }
        }
        ExprKind::PercentOfHeight(_) => Err(not_affine(
            ir,
            id,
            "a % of the image height: write the setting in px",
        )),
        _ => Err(not_affine(
            ir,
            id,
            "the runner evaluates lines settings on the CPU: only numbers, params, `time`, + - and products or quotients with constants",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ir_with_param() -> (Ir, ParamId) {
        let mut ir = Ir::default();
        let default = ir.add(ExprKind::Const(Const::Float(2.0)), Span::default());
        ir.params.push(Param {
            name: "w".into(),
            doc: String::new(),
            ty: ParamTy::Value(Ty::Float),
            value_ty: Ty::Float,
            unit: npr_stdlib::Unit::Px,
            per_object: false,
            default,
            range: None,
            keys: Vec::new(),
            interpolation: "linear".into(),
            span: Span::default(),
            name_span: Span::default(),
        });
        (ir, ParamId(0))
    }

    fn bin(ir: &mut Ir, op: BinOp, lhs: ExprId, rhs: ExprId) -> ExprId {
        ir.add(ExprKind::Binary { op, lhs, rhs }, Span::default())
    }

    #[test]
    fn sums_and_constant_products_fold() {
        let (mut ir, p) = ir_with_param();
        let w = ir.add(ExprKind::Param(p), Span::default());
        let two = ir.add(ExprKind::Const(Const::Float(2.0)), Span::default());
        let t = ir.add(ExprKind::Builtin(Builtin::Time), Span::default());
        let half = ir.add(ExprKind::Const(Const::Float(0.5)), Span::default());
        // (w * 2 + time / 0.5) - w  =  w + 2·time
        let w2 = bin(&mut ir, BinOp::Mul, w, two);
        let t2 = bin(&mut ir, BinOp::Div, t, half);
        let s = bin(&mut ir, BinOp::Add, w2, t2);
        let d = bin(&mut ir, BinOp::Sub, s, w);
        let a = affine(&ir, d).unwrap();
        assert_eq!(a.constant, 0.0);
        assert_eq!(a.per_second, 2.0);
        assert_eq!(
            a.params,
            vec![ParamTerm {
                param: "w".into(),
                coefficient: 1.0
            }]
        );
    }

    #[test]
    fn products_of_varying_values_are_refused() {
        let (mut ir, p) = ir_with_param();
        let w = ir.add(ExprKind::Param(p), Span::default());
        let t = ir.add(ExprKind::Builtin(Builtin::Time), Span::default());
        let wt = bin(&mut ir, BinOp::Mul, w, t);
        assert!(affine(&ir, wt).unwrap_err().label.contains("product"));
        let zero = ir.add(ExprKind::Const(Const::Float(0.0)), Span::default());
        let q = bin(&mut ir, BinOp::Div, w, zero);
        assert!(affine(&ir, q).unwrap_err().label.contains("zero"));
    }
}
