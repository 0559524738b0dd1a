//! Domain findings as warnings (W0203–W0210): the operation's span, its
//! operands' proved ranges, the params and builtins those ranges come
//! from, and the safe form where one exists.

use super::eval::{Domain, Finding};
use super::inputs;
use crate::ir::*;
use npr_diag::{codes, Diagnostic};

/// One warning per operation (the first finding at it), for the findings
/// whose operands' ranges are known (no NaN possible): where an operand
/// may be NaN, what reached the bad case is an earlier operation (warned
/// about there) or an input the analysis knows nothing of (an operator
/// without a declared range, a per-object sum), and the operation is only
/// unproved, not shown reachable. Those are returned apart: `npr check
/// --ranges` lists them as what stops a proof.
pub fn warnings(ir: &Ir, mut findings: Vec<Finding>) -> (Vec<Diagnostic>, Vec<Finding>) {
    findings.sort_by_key(|f| (ir.expr(f.at).span.file, ir.expr(f.at).span.start, f.domain));
    findings.dedup_by_key(|f| f.at);
    let (known, unknown): (Vec<Finding>, Vec<Finding>) = findings
        .into_iter()
        .partition(|f| f.operands.iter().all(|(_, v)| v.comps.iter().all(|c| !c.nan)));
    (known.iter().map(|f| warning(ir, f)).collect(), unknown)
}

/// The warning code of a domain.
pub fn code_of(d: Domain) -> &'static str {
    match d {
        Domain::Log => codes::LOG_DOMAIN,
        Domain::Sqrt => codes::SQRT_DOMAIN,
        Domain::Pow => codes::POW_DOMAIN,
        Domain::Division => codes::DIVISION_BY_ZERO,
        Domain::InverseTrig => codes::INVERSE_TRIG_DOMAIN,
        Domain::Normalize => codes::NORMALIZE_ZERO,
        Domain::Atan2 => codes::ATAN2_ORIGIN,
        Domain::F16Overflow => codes::F16_OVERFLOW,
    }
}

/// The function's name at a call, or the operator at a division.
pub fn what(ir: &Ir, at: ExprId) -> String {
    match &ir.expr(at).kind {
        ExprKind::Call {
            callee: Callee::Intrinsic(i),
            ..
        } => i.name().to_string(),
        ExprKind::Binary { op, .. } => op.as_str().to_string(),
        _ => "this value".into(),
    }
}

fn warning(ir: &Ir, f: &Finding) -> Diagnostic {
    let name = what(ir, f.at);
    let range = |i: usize| f.operands.get(i).map(|(_, v)| v.to_string()).unwrap_or_default();
    let (message, label, help) = match f.domain {
        Domain::Log => (
            format!("`{name}` of a value that may be 0 or negative"),
            format!("its argument ranges over {}", range(0)),
            format!("`{name}(max(x, 1e-6))` keeps the argument positive"),
        ),
        Domain::Sqrt => (
            "`sqrt` of a value that may be negative".to_string(),
            format!("its argument ranges over {}", range(0)),
            "`sqrt(max(x, 0.0))` keeps the argument non-negative".to_string(),
        ),
        Domain::Pow => (
            "`pow(x, y)` may be undefined: WGSL leaves x < 0, and x = 0 with y ≤ 0, undefined".to_string(),
            format!("x ranges over {}, y over {}", range(0), range(1)),
            "`pow(max(x, 1e-6), y)` keeps x positive (some drivers return 0 there, others +inf or NaN)".to_string(),
        ),
        Domain::Division => match name.as_str() {
            "smoothstep" => (
                "`smoothstep(e0, e1, x)` with edges that may be equal divides by zero".to_string(),
                format!("e0 ranges over {}, e1 over {}", range(0), range(1)),
                "keep the edges apart, e.g. `smoothstep(e0, max(e1, e0 + 1e-4), x)`".to_string(),
            ),
            _ => (
                format!("division (`{name}`) by a value that may be 0"),
                format!("the divisor ranges over {}", range(0)),
                "divide by `max(d, 1e-6)` (or by a value whose declared range excludes 0)".to_string(),
            ),
        },
        Domain::InverseTrig => (
            format!("`{name}` of a value that may leave [-1, 1]"),
            format!("its argument ranges over {}", range(0)),
            format!("`{name}(clamp(x, -1.0, 1.0))` keeps the argument in its domain"),
        ),
        Domain::Normalize => (
            "`normalize` of a vector that may be zero".to_string(),
            format!("its components range over {}", range(0)),
            "guard the length: `v / max(length(v), 1e-6)`".to_string(),
        ),
        Domain::Atan2 => (
            "`atan2(y, x)` may be called at (0, 0), where WGSL leaves it undefined".to_string(),
            format!("y ranges over {}, x over {}", range(0), range(1)),
            "move x off 0: `atan2(y, select(x, 1e-6, x == 0.0))`, or test the origin first".to_string(),
        ),
        Domain::F16Overflow => (
            "a value that may pass 65504, the largest f16, is stored in an f16 target".to_string(),
            format!("the value ranges over {}", range(0)),
            "clamp it (`clamp(v, -65504.0, 65504.0)`) or store it in a 32-bit float format".to_string(),
        ),
    };
    let mut d = Diagnostic::warning(code_of(f.domain), message).with_primary(ir.expr(f.at).span, label);
    let sources = sources(ir, &f.operands.iter().map(|(o, _)| *o).collect::<Vec<_>>());
    if !sources.is_empty() {
        d = d.with_note(format!("the range comes from {}", sources.join("; ")));
    }
    d.with_help(help)
}

/// The inputs an operand's range comes from: params with their ranges,
/// builtins with theirs, targets and textures read (four at most).
fn sources(ir: &Ir, operands: &[ExprId]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for id in ir.reachable(operands) {
        let s = match &ir.expr(id).kind {
            ExprKind::Param(p) => {
                let p = &ir.params[p.0 as usize];
                format!("param `{}` in {}", p.name, inputs::param(p))
            }
            ExprKind::Builtin(b) => format!("`{}` in {}", b.name(), inputs::builtin(*b)),
            ExprKind::Target { target, .. } => format!("target `{}`", ir.target_name(*target)),
            ExprKind::Texture(t) => format!("texture `{}`", ir.textures[t.0 as usize].name),
            _ => continue,
        };
        if !out.contains(&s) {
            out.push(s);
        }
    }
    if out.len() > 4 {
        let more = out.len() - 4;
        out.truncate(4);
        out.push(format!("{more} more"));
    }
    out
}
