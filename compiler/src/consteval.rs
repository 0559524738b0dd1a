//! Constant evaluation of IR expressions (defaults, ranges, scales, folded params).

use crate::ir::*;
use dsl::ast::{BinOp, UnOp};

/// Evaluate `id` if it is built only from constants; `None` otherwise.
///
/// Parameters, builtins and targets are not constants here: the specialize
/// pass substitutes folded parameters first, then calls this.
pub fn const_eval(ir: &Ir, id: ExprId) -> Option<Const> {
    match &ir.expr(id).kind {
        ExprKind::Const(c) => Some(c.clone()),
        ExprKind::Unary { op, operand } => {
            let v = const_eval(ir, *operand)?;
            match (op, v) {
                (UnOp::Neg, Const::Float(x)) => Some(Const::Float(-x)),
                (UnOp::Neg, Const::Int(x)) => Some(Const::Int(x.checked_neg()?)),
                (UnOp::Neg, Const::Vec(v)) => Some(Const::Vec(v.iter().map(|x| -x).collect())),
                (UnOp::Not, Const::Bool(b)) => Some(Const::Bool(!b)),
                _ => None,
            }
        }
        ExprKind::Binary { op, lhs, rhs } => {
            let a = const_eval(ir, *lhs)?;
            let b = const_eval(ir, *rhs)?;
            binary(*op, &a, &b)
        }
        ExprKind::Call {
            callee: Callee::Intrinsic(Intrinsic::Construct(n)),
            args,
        } => {
            let mut comps = Vec::new();
            for a in args {
                comps.extend(const_eval(ir, *a)?.as_f64s());
            }
            if comps.len() == 1 {
                comps = vec![comps[0]; *n as usize];
            }
            (comps.len() == *n as usize).then_some(Const::Vec(comps))
        }
        ExprKind::Convert { conversion, operand } => {
            let v = const_eval(ir, *operand)?;
            match conversion {
                Conversion::IntToFloat => Some(Const::Float(v.scalar()?)),
                Conversion::Splat(n) => Some(Const::Vec(vec![v.scalar()?; *n as usize])),
                Conversion::Rgb1 => {
                    let mut c = v.as_f64s();
                    c.push(1.0);
                    Some(Const::Vec(c))
                }
                Conversion::Rgb => Some(Const::Vec(v.as_f64s().into_iter().take(3).collect())),
            }
        }
        ExprKind::Swizzle { base, components } => {
            let v = const_eval(ir, *base)?.as_f64s();
            let picked: Option<Vec<f64>> = components.iter().map(|c| v.get(*c as usize).copied()).collect();
            let picked = picked?;
            Some(if picked.len() == 1 {
                Const::Float(picked[0])
            } else {
                Const::Vec(picked)
            })
        }
        ExprKind::Select { cond, then, otherwise } => match const_eval(ir, *cond)? {
            Const::Bool(true) => const_eval(ir, *then),
            Const::Bool(false) => const_eval(ir, *otherwise),
            _ => None,
        },
        _ => None,
    }
}

fn binary(op: BinOp, a: &Const, b: &Const) -> Option<Const> {
    use Const::*;
    Some(match (a, b) {
        (Int(x), Int(y)) => match op {
            BinOp::Add => Int(x.checked_add(*y)?),
            BinOp::Sub => Int(x.checked_sub(*y)?),
            BinOp::Mul => Int(x.checked_mul(*y)?),
            // Integer division of literals like `1/2` is almost always meant as a
            // fraction (e.g. `scale 1/2`), so constant division is real division.
            BinOp::Div => Float(*x as f64 / *y as f64),
            BinOp::Rem => Int(x.checked_rem(*y)?),
            _ => return compare(op, *x as f64, *y as f64),
        },
        (Bool(x), Bool(y)) => match op {
            BinOp::And => Bool(*x && *y),
            BinOp::Or => Bool(*x || *y),
            BinOp::Eq => Bool(x == y),
            BinOp::Ne => Bool(x != y),
            _ => return None,
        },
        (Vec(_), _) | (_, Vec(_)) => {
            let av = a.as_f64s();
            let bv = b.as_f64s();
            let n = av.len().max(bv.len());
            if !(av.len() == n || av.len() == 1) || !(bv.len() == n || bv.len() == 1) {
                return None;
            }
            let get = |v: &[f64], i: usize| if v.len() == 1 { v[0] } else { v[i] };
            let out: Option<std::vec::Vec<f64>> = (0..n).map(|i| arith(op, get(&av, i), get(&bv, i))).collect();
            Vec(out?)
        }
        _ => {
            let (x, y) = (a.scalar()?, b.scalar()?);
            match arith(op, x, y) {
                Some(v) => Float(v),
                None => return compare(op, x, y),
            }
        }
    })
}

fn arith(op: BinOp, x: f64, y: f64) -> Option<f64> {
    Some(match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => x / y,
        BinOp::Rem => x % y,
        _ => return None,
    })
}

fn compare(op: BinOp, x: f64, y: f64) -> Option<Const> {
    Some(Const::Bool(match op {
        BinOp::Lt => x < y,
        BinOp::Le => x <= y,
        BinOp::Gt => x > y,
        BinOp::Ge => x >= y,
        BinOp::Eq => x == y,
        BinOp::Ne => x != y,
        _ => return None,
    }))
}
