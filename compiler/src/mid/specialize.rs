//! Specialize: fold parameters that can never change into constants, then
//! fold constant expressions, so that `if` on a folded parameter leaves only
//! the branch taken (a disabled feature emits no code).
//!
//! A parameter stays a uniform when it is animated, when `--keep-params` asks
//! for live tweaking; per-object parameters go to the object block.

use crate::ir::*;
use crate::mid::consteval::{const_eval, ConstCache};
use crate::mid::prune::Live;
use crate::report::Report;
use npr_abi::manifest::ParamBinding;

pub fn specialize(ir: &mut Ir, live: &Live, keep_params: bool, report: &mut Report) -> Vec<ParamBinding> {
    let mut bindings = vec![ParamBinding::Removed; ir.params.len()];
    for (i, p) in ir.params.iter().enumerate() {
        if !live.params.contains(&ParamId(i as u32)) {
            report.removed(format!("param `{}`", p.name), "no live expression reads it");
            continue;
        }
        bindings[i] = if p.per_object {
            report.push(
                "kept",
                format!("param `{}`", p.name),
                "per object: the scene binds it".into(),
            );
            ParamBinding::PerObject
        } else if !p.keys.is_empty() {
            report.push(
                "kept",
                format!("param `{}`", p.name),
                "animated: a uniform updated each frame".into(),
            );
            ParamBinding::Uniform
        } else if keep_params {
            report.push(
                "kept",
                format!("param `{}`", p.name),
                "--keep-params: a uniform for live tweaking".into(),
            );
            ParamBinding::Uniform
        } else {
            report.push(
                "folded",
                format!("param `{}`", p.name),
                "neither animated nor per object: a constant".into(),
            );
            ParamBinding::Folded
        };
    }
    // Substitute folded parameters with their default's node kind.
    for i in 0..ir.exprs.len() {
        if let ExprKind::Param(p) = ir.exprs[i].kind {
            if bindings[p.0 as usize] == ParamBinding::Folded {
                let d = ir.params[p.0 as usize].default;
                let folded = match const_eval(ir, d) {
                    Some(c) => ExprKind::Const(retype(c, ir.exprs[i].ty)),
                    None => ir.expr(d).kind.clone(),
                };
                ir.exprs[i].kind = folded;
            }
        }
    }
    // Fold constants bottom-up (operands precede users, except conversions
    // added by the typechecker, so iterate until nothing changes). One cache
    // for the whole fold: a node folds into the value it evaluated to, so
    // what is known stays true, and each node is evaluated once.
    let mut consts = ConstCache::default();
    loop {
        let mut changed = false;
        for i in 0..ir.exprs.len() {
            let id = ExprId(i as u32);
            let foldable = matches!(
                ir.exprs[i].kind,
                ExprKind::Unary { .. }
                    | ExprKind::Binary { .. }
                    | ExprKind::Convert { .. }
                    | ExprKind::Swizzle { .. }
                    | ExprKind::Call {
                        callee: Callee::Intrinsic(Intrinsic::Construct(_)),
                        ..
                    }
            );
            if foldable {
                if let Some(c) = consts.eval(ir, id) {
                    ir.exprs[i].kind = ExprKind::Const(retype(c, ir.exprs[i].ty));
                    changed = true;
                }
            }
            if let ExprKind::Select { cond, then, otherwise } = ir.exprs[i].kind {
                if let Some(Const::Bool(b)) = consts.eval(ir, cond) {
                    let chosen = if b { then } else { otherwise };
                    ir.exprs[i].kind = ir.expr(chosen).kind.clone();
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    specialize_operators(ir, report);
    bindings
}

/// Swap calls for cheaper operators where a constant argument allows it
/// (`npr_stdlib::Specialization`), e.g. 4-tap MetaTexture when `skew` is 0.
/// The replacement's arguments are matched by parameter name, and a
/// replacement may itself specialize further (contour orientation off, then
/// skew 0: `metatexture_contour_grad` → `metatexture_grad` → `metatexture4_grad`).
fn specialize_operators(ir: &mut Ir, report: &mut Report) {
    for i in 0..ir.exprs.len() {
        // Bounded: each step moves to a different operator of the finite table.
        for _ in 0..npr_stdlib::all().len() {
            let ExprKind::Call {
                callee: Callee::Operator(index),
                args,
            } = &ir.exprs[i].kind
            else {
                break;
            };
            let op = &npr_stdlib::all()[*index as usize];
            let mut swapped = None;
            for s in op.specializations {
                let Some(pos) = op.params.iter().position(|p| p.name == s.param) else {
                    continue;
                };
                let Some(value) = args.get(pos).and_then(|a| const_eval(ir, *a)).and_then(|c| c.scalar()) else {
                    continue;
                };
                let Some(alt) = npr_stdlib::all().iter().position(|o| o.name == s.use_operator) else {
                    continue;
                };
                if value != s.value {
                    continue;
                }
                let by_name: Option<Vec<ExprId>> = npr_stdlib::all()[alt]
                    .params
                    .iter()
                    .map(|p| {
                        op.params
                            .iter()
                            .position(|q| q.name == p.name)
                            .and_then(|j| args.get(j).copied())
                    })
                    .collect();
                let Some(new_args) = by_name else {
                    continue;
                };
                report.push(
                    "special",
                    format!("call `{}`", op.name),
                    format!("`{}` is {} here: calls `{}` instead", s.param, s.value, s.use_operator),
                );
                swapped = Some(ExprKind::Call {
                    callee: Callee::Operator(alt as u32),
                    args: new_args,
                });
                break;
            }
            match swapped {
                Some(kind) => ir.exprs[i].kind = kind,
                None => break,
            }
        }
    }
}

/// Make a constant match the node's type (e.g. integer division folds to a float).
fn retype(c: Const, ty: Ty) -> Const {
    match ty {
        Ty::Int => Const::Int(c.scalar().unwrap_or(0.0) as i64),
        Ty::Float => Const::Float(c.scalar().unwrap_or(0.0)),
        Ty::Bool => Const::Bool(c.scalar().unwrap_or(0.0) != 0.0),
        Ty::Vec2 | Ty::Vec3 | Ty::Vec4 => {
            let n = ty.components().unwrap_or(4) as usize;
            let v = c.as_f64s();
            Const::Vec(if v.len() == 1 {
                vec![v[0]; n]
            } else {
                v.into_iter().take(n).collect()
            })
        }
        _ => c,
    }
}
