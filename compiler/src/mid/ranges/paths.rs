//! Path sensitivity where a value is chosen by a condition on another
//! operand: `cross(n, if abs(n.x) < 0.9 { X } else { Y })` is
//! `if … { cross(n, X) } else { cross(n, Y) }`, and in each branch `n` is
//! narrowed by what the condition says of it there (`|n.x| ≤ 0.9`; or
//! `|n.x| ≥ 0.9`, which for a unit `n` bounds its other components by
//! √(1 − 0.81)). Each branch's result is then joined: sound, since the
//! call's result is the branch's wherever its condition holds.
//!
//! The cross product's length comes from Lagrange's identity,
//! |a × b|² = |a|²|b|² − (a·b)², so that a cross product of a unit vector
//! with an axis it is proved away from is proved non-zero (what makes
//! the tangent frame `normalize(cross(normal, axis))` safe).

use super::eval::Eval;
use super::interval::Iv;
use super::value::Val;
use crate::ir::*;
use npr_dsl::ast::BinOp;

impl Eval<'_> {
    /// The argument values of a call on each path its arguments split
    /// into: one path, unless an argument is an `if` whose condition
    /// narrows another argument; then the `then` path and the `else`
    /// path, each with that argument narrowed and the `if` replaced by
    /// its branch.
    pub fn paths(&self, args: &[ExprId], vals: &[Val]) -> Vec<Vec<Val>> {
        for (k, arg) in args.iter().enumerate() {
            let ExprKind::Select { cond, then, otherwise } = &self.ir.expr(*arg).kind else {
                continue;
            };
            let mut out = Vec::new();
            let mut narrowed_any = false;
            for (truth, branch) in [(true, *then), (false, *otherwise)] {
                let mut path = vals.to_vec();
                path[k] = self.val(branch);
                for (j, other) in args.iter().enumerate() {
                    if j == k {
                        continue;
                    }
                    if let Some(v) = self.narrowed(*other, &vals[j], *cond, truth) {
                        path[j] = v;
                        narrowed_any = true;
                    }
                }
                out.push(path);
            }
            if narrowed_any {
                return out;
            }
        }
        vec![vals.to_vec()]
    }

    /// `v`, the range of node `x`, where `cond` is `truth`; `None` when the
    /// condition says nothing of `x`. Understood: `abs(x.i) op c` and
    /// `x.i op c` with `op` one of `<`, `<=`, `>`, `>=` and `c` a constant
    /// (either side). A component that may be NaN is not narrowed (every
    /// comparison with NaN is false).
    fn narrowed(&self, x: ExprId, v: &Val, cond: ExprId, truth: bool) -> Option<Val> {
        let ExprKind::Binary { op, lhs, rhs } = &self.ir.expr(cond).kind else {
            return None;
        };
        let constant = |e: ExprId| match &self.ir.expr(e).kind {
            ExprKind::Const(Const::Float(c)) => Some(*c),
            _ => None,
        };
        // As `subject below c` (or `subject at or above c`).
        let (subject, c, below) = match (op, constant(*lhs), constant(*rhs)) {
            (BinOp::Lt | BinOp::Le, None, Some(c)) => (*lhs, c, truth),
            (BinOp::Gt | BinOp::Ge, None, Some(c)) => (*lhs, c, !truth),
            (BinOp::Lt | BinOp::Le, Some(c), None) => (*rhs, c, !truth),
            (BinOp::Gt | BinOp::Ge, Some(c), None) => (*rhs, c, truth),
            _ => return None,
        };
        let (inner, is_abs) = match &self.ir.expr(subject).kind {
            ExprKind::Call {
                callee: Callee::Intrinsic(Intrinsic::Map("abs")),
                args,
            } if args.len() == 1 => (args[0], true),
            _ => (subject, false),
        };
        let ExprKind::Swizzle { base, components } = &self.ir.expr(inner).kind else {
            return None;
        };
        if components.len() != 1 || !self.same(*base, x) {
            return None;
        }
        let i = components[0] as usize;
        let ci = *v.comps.get(i)?;
        if ci.nan {
            return None;
        }
        // The shader compares with `c` rounded to f32: an ulp either way.
        let ulp = c.abs() * f32::EPSILON as f64;
        let (c_down, c_up) = (c - ulp, c + ulp);
        let mut out = v.clone();
        match (is_abs, below) {
            // |x.i| ≤ c.
            (true, true) => out.comps[i] = ci.meet(Iv::new(-c_up.abs(), c_up.abs())),
            // |x.i| ≥ c: within a known length, the others are shorter.
            (true, false) => {
                let norm = v.norm?;
                let at_least = (c.abs() - ulp).max(0.0);
                let r = (norm.hi * norm.hi - at_least * at_least).max(0.0).sqrt();
                for (j, comp) in out.comps.iter_mut().enumerate() {
                    if j != i {
                        *comp = comp.meet(Iv::new(-r, r)).with_nan(comp.nan);
                    }
                }
            }
            (false, true) => out.comps[i] = ci.meet(Iv::new(f64::NEG_INFINITY, c_up)),
            (false, false) => out.comps[i] = ci.meet(Iv::new(c_down, f64::INFINITY)),
        }
        Some(out)
    }

    /// `cross(a, b)`: each component by interval arithmetic, and its
    /// length bounded below by Lagrange's identity where that is above 0.
    pub fn cross(a: &Val, b: &Val) -> Val {
        let c = |i: usize, j: usize| a.at(i).mul(b.at(j)).sub(a.at(j).mul(b.at(i)));
        let comps = vec![c(1, 2), c(2, 0), c(0, 1)];
        let dot = (0..3).map(|i| a.at(i).mul(b.at(i))).reduce(Iv::add).unwrap_or(Iv::TOP);
        let (la, lb) = (a.length(), b.length());
        let finite = la.is_finite() && lb.is_finite() && dot.is_finite() && !la.nan && !lb.nan && !dot.nan;
        let norm = finite.then(|| {
            let lower_sq = la.lo * la.lo * lb.lo * lb.lo - dot.sqr().hi;
            // f32 rounds each of the three products and differences: a
            // few ulps of |a||b| off the exact length.
            let rounding = 8.0 * f32::EPSILON as f64 * la.hi * lb.hi;
            let lower = (lower_sq.max(0.0).sqrt() - rounding).max(0.0);
            Iv::new(lower, la.hi * lb.hi + rounding)
        });
        Val { comps, norm }
    }
}
