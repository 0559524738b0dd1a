//! One value for one parameter: the rule is the ABI's
//! (`npr_abi::param_value`: kinds, typing, range checks, formatting), shared
//! with the runner, which types a host's values by it. Here: the shape of
//! a parameter of the IR, after typecheck.

pub use npr_abi::param_value::*;

use crate::ir::{ExprKind, Ir, Param, ParamTy};
use crate::mid::consteval::const_eval;

/// The [`ParamShape`] of `p` of `ir`, after typecheck (its default is a constant).
pub fn shape_of_ir(ir: &Ir, p: &Param) -> ParamShape {
    let (default, default_percent_of_height) = match &ir.expr(p.default).kind {
        ExprKind::PercentOfHeight(f) => (vec![f * 100.0], true),
        _ => (
            const_eval(ir, p.default).map(|c| c.as_f64s()).unwrap_or_default(),
            false,
        ),
    };
    let ty = p.declared_type();
    ParamShape {
        name: p.name.clone(),
        kind: ValueKind::of(&ty),
        ty,
        components: if p.ty == ParamTy::Gradient {
            4
        } else {
            p.value_ty.components().unwrap_or(1)
        },
        range: p.range,
        variants: match &p.ty {
            ParamTy::Enum(v) => v.clone(),
            _ => Vec::new(),
        },
        per_object: p.per_object,
        default,
        default_percent_of_height,
    }
}
