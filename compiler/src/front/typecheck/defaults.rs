//! Parameter defaults must be constants.
//!
//! A default is the value a parameter has before any scene, frame or
//! object exists: the manifest stores it as numbers and the runner writes
//! it into the uniform block with `--keep-params`. A default that reads a
//! builtin (`= normal.x`), another parameter or a texture has no such
//! value, and folding it instead (substituting the expression) would make
//! `--keep-params` render differently: E0204, at the part that is not
//! constant.

use crate::ir::*;
use crate::mid::consteval::const_eval;
use npr_diag::{codes, Diagnostic};

/// E0204 for `param`'s default, unless it is a constant (or a lone `50%`,
/// which the manifest stores as a percentage of the image height).
pub(super) fn not_constant(ir: &Ir, param: &Param) -> Option<Diagnostic> {
    let d = param.default;
    if matches!(ir.expr(d).kind, ExprKind::PercentOfHeight(_)) || const_eval(ir, d).is_some() {
        return None;
    }
    // Operands come before users: the first culprit is the innermost one.
    let (at, what) = ir
        .reachable(&[d])
        .into_iter()
        .find_map(|id| culprit(ir, id).map(|w| (id, w)))
        .unwrap_or((d, "not known at compile time".to_string()));
    Some(
        Diagnostic::error(
            codes::NOT_CONSTANT,
            format!("the default of `{}` is not a constant", param.name),
        )
        .with_primary(ir.expr(at).span, what)
        .with_secondary(param.name_span, "parameter declared here")
        .with_help(
            "a default is written with literals, arithmetic and `vecN(...)` of them (`0.5`, `2px * 3`, `#ff8800`); \
             compute values from builtins in a pass, e.g. `let x = normal.x`",
        ),
    )
}

/// Why node `id` is not a constant, if it is a reason by itself.
fn culprit(ir: &Ir, id: ExprId) -> Option<String> {
    Some(match &ir.expr(id).kind {
        ExprKind::Builtin(_) => "a builtin has a value only while rendering".into(),
        ExprKind::Param(p) => format!("`{}` is a parameter, not a constant", ir.params[p.0 as usize].name),
        ExprKind::Texture(_) | ExprKind::Target { .. } => "a texture has values only while rendering".into(),
        ExprKind::ObjectValue { .. } | ExprKind::StateOld { .. } => {
            "a per-object value is computed while rendering".into()
        }
        ExprKind::PercentOfHeight(_) => "`%` is of the image height, known only while rendering".into(),
        ExprKind::Call {
            callee: Callee::Intrinsic(Intrinsic::Construct(_)),
            ..
        } => return None,
        ExprKind::Call { .. } => "a call is evaluated while rendering, not at compile time".into(),
        _ => return None,
    })
}
