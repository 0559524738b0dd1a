//! Parameter overrides (`--set name=value`, the studio's controls, a
//! filter's arguments): a typed value replaces its parameter's default in
//! the IR, after typecheck and before specialize, so that folding, the
//! manifest's `default` and everything downstream see the override exactly
//! as if it had been written in the file.
//!
//! `front::param_settings::type_settings` types them just before, checking
//! names, types, units and ranges with diagnostics that point at each
//! setting; a name that reaches this stage unchecked is a bug, so it is an
//! internal error rather than a silent no-op.

use crate::ir::{Const, ExprKind, Ir, Ty};
use crate::InternalError;

/// One parameter's new default: the ABI's, which typing a value gives.
use npr_abi::ParamOverride;

/// Replace the defaults of the overridden parameters. An animated parameter
/// loses its keyframes: a set value is a constant.
pub fn apply(ir: &mut Ir, overrides: &[ParamOverride]) -> Result<(), InternalError> {
    for o in overrides {
        let Some(i) = ir.params.iter().position(|p| p.name == o.name) else {
            return Err(InternalError {
                message: format!("an override names no parameter `{}`", o.name),
                detail: "param_settings::type_settings checks every name before apply".into(),
                span: None,
                wgsl: None,
            });
        };
        let old = ir.params[i].default;
        let (ty, unit, span) = {
            let e = ir.expr(old);
            (e.ty, e.unit, e.span)
        };
        let value_ty = ir.params[i].value_ty;
        let kind = if o.percent_of_height {
            ExprKind::PercentOfHeight(o.value.first().copied().unwrap_or(0.0) / 100.0)
        } else {
            ExprKind::Const(constant(value_ty, &o.value).ok_or_else(|| InternalError {
                message: format!("override of `{}` has {} component(s)", o.name, o.value.len()),
                detail: format!("the parameter is {}", value_ty.describe()),
                span: Some(span),
                wgsl: None,
            })?)
        };
        ir.params[i].default = ir.add_typed(kind, ty, unit, span);
        ir.params[i].keys.clear();
    }
    Ok(())
}

/// The constant of type `ty` with these components, if they fit it.
fn constant(ty: Ty, v: &[f64]) -> Option<Const> {
    let want = ty.components()? as usize;
    if v.len() != want {
        return None;
    }
    Some(match ty {
        Ty::Float => Const::Float(v[0]),
        Ty::Int => Const::Int(v[0].round() as i64),
        Ty::Bool => Const::Bool(v[0] != 0.0),
        _ => Const::Vec(v.to_vec()),
    })
}
