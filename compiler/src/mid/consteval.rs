//! Constant evaluation of IR expressions (defaults, ranges, scales, folded params).
//!
//! Evaluation is iterative (an explicit stack) and memoized per node: a
//! chain of `let`s makes the IR as deep as the file is long, which the
//! recursive version overflowed the stack on, and a `let` used twice in the
//! next one made it exponential.

use crate::ir::*;
use npr_dsl::ast::{BinOp, UnOp};
use std::collections::HashMap;

/// Evaluate `id` if it is built only from constants; `None` otherwise.
///
/// Parameters, builtins and targets are not constants here: the specialize
/// pass substitutes folded parameters first, then calls this.
pub fn const_eval(ir: &Ir, id: ExprId) -> Option<Const> {
    ConstCache::default().eval(ir, id)
}

/// The constant value (or not) of every node evaluated so far. Valid while
/// no node's value changes: folding a node into the constant it evaluates to
/// keeps it valid, so `specialize` keeps one across its whole fold.
#[derive(Debug, Default)]
pub struct ConstCache {
    known: HashMap<ExprId, Option<Const>>,
}

/// What a node needs before it can be folded.
enum Need {
    /// This operand's value, not yet known.
    Operand(ExprId),
    /// Nothing more: every operand it reads is known (or one is not constant).
    Ready,
}

impl ConstCache {
    /// [`const_eval`], reusing and extending what is known.
    pub fn eval(&mut self, ir: &Ir, root: ExprId) -> Option<Const> {
        let mut stack = vec![root];
        while let Some(&id) = stack.last() {
            if self.known.contains_key(&id) {
                stack.pop();
                continue;
            }
            match self.need(ir, id) {
                // The IR is acyclic, so the stack never holds more than
                // every node; past that something is wrong: not a constant.
                Need::Operand(_) if stack.len() > ir.exprs.len() => return None,
                Need::Operand(o) => stack.push(o),
                Need::Ready => {
                    let value = self.fold(ir, id);
                    self.known.insert(id, value);
                    stack.pop();
                }
            }
        }
        self.known.get(&root).cloned().flatten()
    }

    fn value(&self, id: ExprId) -> Option<&Const> {
        self.known.get(&id).and_then(Option::as_ref)
    }

    /// The next operand to evaluate, in order, stopping at the first that is
    /// not a constant; for a `Select`, its condition and then only the
    /// branch it chooses.
    fn need(&self, ir: &Ir, id: ExprId) -> Need {
        let operands: Vec<ExprId> = match &ir.expr(id).kind {
            ExprKind::Unary { operand, .. } | ExprKind::Convert { operand, .. } => vec![*operand],
            ExprKind::Swizzle { base, .. } => vec![*base],
            ExprKind::Binary { lhs, rhs, .. } => vec![*lhs, *rhs],
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Construct(_)),
                args,
            } => args.clone(),
            ExprKind::Select { cond, then, otherwise } => match self.known.get(cond) {
                None => vec![*cond],
                Some(Some(Const::Bool(true))) => vec![*then],
                Some(Some(Const::Bool(false))) => vec![*otherwise],
                Some(_) => Vec::new(),
            },
            _ => Vec::new(),
        };
        for o in operands {
            match self.known.get(&o) {
                None => return Need::Operand(o),
                Some(None) => return Need::Ready,
                Some(Some(_)) => {}
            }
        }
        Need::Ready
    }

    /// The node's value from its operands' (all known, by [`Self::need`]).
    fn fold(&self, ir: &Ir, id: ExprId) -> Option<Const> {
        match &ir.expr(id).kind {
            ExprKind::Const(c) => Some(c.clone()),
            ExprKind::Unary { op, operand } => match (op, self.value(*operand)?.clone()) {
                (UnOp::Neg, Const::Float(x)) => Some(Const::Float(-x)),
                (UnOp::Neg, Const::Int(x)) => Some(Const::Int(x.checked_neg()?)),
                (UnOp::Neg, Const::Vec(v)) => Some(Const::Vec(v.iter().map(|x| -x).collect())),
                (UnOp::Not, Const::Bool(b)) => Some(Const::Bool(!b)),
                _ => None,
            },
            ExprKind::Binary { op, lhs, rhs } => binary(*op, self.value(*lhs)?, self.value(*rhs)?),
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Construct(n)),
                args,
            } => {
                let mut comps = Vec::new();
                for a in args {
                    comps.extend(self.value(*a)?.as_f64s());
                }
                if comps.len() == 1 {
                    comps = vec![comps[0]; *n as usize];
                }
                (comps.len() == *n as usize).then_some(Const::Vec(comps))
            }
            ExprKind::Convert { conversion, operand } => {
                let v = self.value(*operand)?;
                match conversion {
                    Conversion::IntToFloat => Some(Const::Float(v.scalar()?)),
                    Conversion::Splat(n) => Some(Const::Vec(vec![v.scalar()?; *n as usize])),
                    Conversion::Rgb1 => {
                        let mut c = v.as_f64s();
                        c.push(1.0);
                        Some(Const::Vec(c))
                    }
                    Conversion::Rgb => Some(Const::Vec(v.as_f64s().into_iter().take(3).collect())),
                    Conversion::Stored(f) => {
                        let c: Vec<f64> = v
                            .as_f64s()
                            .into_iter()
                            .map(|x| f.storage().stored(x))
                            .collect::<Option<_>>()?;
                        Some(match c.as_slice() {
                            [x] => Const::Float(*x),
                            _ => Const::Vec(c),
                        })
                    }
                }
            }
            ExprKind::Swizzle { base, components } => {
                let v = self.value(*base)?.as_f64s();
                let picked: Option<Vec<f64>> = components.iter().map(|c| v.get(*c as usize).copied()).collect();
                let picked = picked?;
                Some(if picked.len() == 1 {
                    Const::Float(picked[0])
                } else {
                    Const::Vec(picked)
                })
            }
            ExprKind::Select { cond, then, otherwise } => match self.value(*cond)? {
                Const::Bool(true) => self.value(*then).cloned(),
                Const::Bool(false) => self.value(*otherwise).cloned(),
                _ => None,
            },
            _ => None,
        }
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
