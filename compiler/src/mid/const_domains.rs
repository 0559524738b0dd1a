//! Intrinsic calls on constants that have no finite value: `sqrt(-0.5)`,
//! `log(0.0)`, `pow(-1.0, 0.5)`, `exp(100.0)` (past the f32 range).
//!
//! naga evaluates a call whose arguments are all constant when it parses
//! the WGSL, and rejects one outside its function's domain, so such a call
//! in a style used to fail validation as an internal error (E9001; found by
//! `tests/general/fuzz_generated.rs`). After specialize (folded params are
//! constants too), every call the emitter will write is evaluated here in
//! f64 when its arguments are constant; one whose value is not a finite f32
//! is E0203 at the call, naming the argument.

use crate::ir::*;
use crate::mid::prune::Live;
use npr_diag::{codes, Diagnostic};
use npr_dsl::ast::BinOp;
use std::collections::HashMap;

/// E0203 for each live intrinsic call on constants that has no finite value.
pub fn check(ir: &Ir, live: &Live) -> Vec<Diagnostic> {
    let roots: Vec<ExprId> = live.passes.iter().flat_map(|p| ir.pass(*p).roots().all()).collect();
    // Operands come before users in `reachable`'s order, so one forward
    // sweep knows every operand's constant value (if any) before its user.
    let mut values: HashMap<ExprId, Vec<f64>> = HashMap::new();
    let mut out = Vec::new();
    for id in ir.reachable(&roots) {
        let Some(v) = value(ir, id, &values) else { continue };
        if v.iter().all(|y| y.is_finite() && y.abs() <= f32::MAX as f64) {
            values.insert(id, v);
            continue;
        }
        // Reported once, where it arises; its users are not constants.
        let span = ir.expr(id).span;
        out.push(match &ir.expr(id).kind {
            ExprKind::Call {
                callee: Callee::Intrinsic(intrinsic),
                args,
            } => {
                let name = mapped_name(*intrinsic).unwrap_or("this function");
                let shown: Vec<String> = args.iter().map(|a| show(&values[a])).collect();
                Diagnostic::error(
                    codes::OUT_OF_RANGE,
                    format!("`{name}({})` has no finite value", shown.join(", ")),
                )
                .with_primary(span, "a constant outside the function's domain")
                .with_help(domain_help(name))
            }
            _ => Diagnostic::error(codes::OUT_OF_RANGE, "this constant expression has no finite f32 value")
                .with_primary(span, format!("evaluates to {}", show(&v)))
                .with_help("f32 holds magnitudes up to about 3.4e38, and division by zero has no value"),
        });
    }
    out
}

fn show(v: &[f64]) -> String {
    match v {
        [x] => format!("{x}"),
        _ => format!(
            "vec{}({})",
            v.len(),
            v.iter().map(|x| format!("{x}")).collect::<Vec<_>>().join(", ")
        ),
    }
}

/// The node's constant value from its operands' in `known` (components;
/// a scalar has one), if it has one this sweep evaluates. Non-finite
/// operands give none: they were reported where they arose.
fn value(ir: &Ir, id: ExprId, known: &HashMap<ExprId, Vec<f64>>) -> Option<Vec<f64>> {
    let get = |e: &ExprId| known.get(e).filter(|v| v.iter().all(|x| x.is_finite()));
    match &ir.expr(id).kind {
        ExprKind::Const(c @ (Const::Float(_) | Const::Int(_) | Const::Vec(_))) => Some(c.as_f64s()),
        ExprKind::Unary {
            op: npr_dsl::ast::UnOp::Neg,
            operand,
        } => Some(get(operand)?.iter().map(|x| -x).collect()),
        ExprKind::Binary { op, lhs, rhs } => {
            let (a, b) = (get(lhs)?, get(rhs)?);
            let f: fn(f64, f64) -> f64 = match op {
                BinOp::Add => |x, y| x + y,
                BinOp::Sub => |x, y| x - y,
                BinOp::Mul => |x, y| x * y,
                BinOp::Div => |x, y| x / y,
                // WGSL's float `%` truncates: x - y · trunc(x / y).
                BinOp::Rem => |x, y| x - y * (x / y).trunc(),
                // Booleans as 1 and 0, so a constant `if` can pick its branch.
                BinOp::Lt => |x, y| f64::from(u8::from(x < y)),
                BinOp::Le => |x, y| f64::from(u8::from(x <= y)),
                BinOp::Gt => |x, y| f64::from(u8::from(x > y)),
                BinOp::Ge => |x, y| f64::from(u8::from(x >= y)),
                BinOp::Eq => |x, y| f64::from(u8::from(x == y)),
                BinOp::Ne => |x, y| f64::from(u8::from(x != y)),
                BinOp::And => |x, y| f64::from(u8::from(x != 0.0 && y != 0.0)),
                BinOp::Or => |x, y| f64::from(u8::from(x != 0.0 || y != 0.0)),
            };
            zip(&[a.clone(), b.clone()], |xs| f(xs[0], xs[1]))
        }
        ExprKind::Convert { conversion, operand } => {
            let v = get(operand)?;
            Some(match conversion {
                Conversion::IntToFloat => v.clone(),
                Conversion::Splat(n) => vec![*v.first()?; *n as usize],
                Conversion::Rgb1 => v.iter().copied().chain([1.0]).collect(),
                Conversion::Rgb => v.iter().copied().take(3).collect(),
                Conversion::Stored(f) => v.iter().map(|x| f.storage().stored(*x)).collect::<Option<_>>()?,
            })
        }
        ExprKind::Swizzle { base, components } => {
            let v = get(base)?;
            components.iter().map(|c| v.get(*c as usize).copied()).collect()
        }
        ExprKind::Call {
            callee: Callee::Intrinsic(intrinsic),
            args,
        } => {
            let vals: Vec<Vec<f64>> = args.iter().map(|a| get(a).cloned()).collect::<Option<_>>()?;
            match intrinsic {
                Intrinsic::Construct(n) => {
                    let comps: Vec<f64> = vals.concat();
                    Some(if comps.len() == 1 {
                        vec![comps[0]; *n as usize]
                    } else {
                        comps
                    })
                }
                Intrinsic::Map(n) | Intrinsic::Map2(n) | Intrinsic::Map3(n) => zip(&vals, |xs| apply(n, xs)),
                Intrinsic::Length => Some(vec![vals.first()?.iter().map(|x| x * x).sum::<f64>().sqrt()]),
                Intrinsic::Dot => {
                    let (a, b) = (vals.first()?, vals.get(1)?);
                    Some(vec![a.iter().zip(b).map(|(x, y)| x * y).sum()])
                }
                Intrinsic::Distance => {
                    let (a, b) = (vals.first()?, vals.get(1)?);
                    Some(vec![a
                        .iter()
                        .zip(b)
                        .map(|(x, y)| (x - y) * (x - y))
                        .sum::<f64>()
                        .sqrt()])
                }
                // As the emitter writes it: v · inverseSqrt(max(v·v, 1e-30)).
                Intrinsic::Normalize => {
                    let v = vals.first()?;
                    let inv = 1.0 / v.iter().map(|x| x * x).sum::<f64>().max(1e-30).sqrt();
                    Some(v.iter().map(|x| x * inv).collect())
                }
                Intrinsic::Cross => match (vals.first()?.as_slice(), vals.get(1)?.as_slice()) {
                    ([a0, a1, a2], [b0, b1, b2]) => Some(vec![a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0]),
                    _ => None,
                },
                // Projections depend on the camera: never constants.
                Intrinsic::Project | Intrinsic::ProjectOtherEye | Intrinsic::ProjectPrevious => None,
                // A live gradient's stops are a uniform: never constants.
                Intrinsic::Ramp(_) => None,
            }
        }
        // naga evaluates both arms of a constant `select`; each arm's own
        // calls were checked where they arose, so only the value is picked.
        ExprKind::Select { cond, then, otherwise } => {
            let c = get(cond)?;
            let chosen = if *c.first()? != 0.0 { then } else { otherwise };
            get(chosen).cloned()
        }
        _ => None,
    }
}

/// `f` component-wise over `vals` (a one-component value broadcast).
fn zip(vals: &[Vec<f64>], f: impl Fn(&[f64]) -> f64) -> Option<Vec<f64>> {
    let n = vals.iter().map(Vec::len).max()?;
    if vals.iter().any(|v| v.len() != n && v.len() != 1) {
        return None;
    }
    Some(
        (0..n)
            .map(|i| {
                let xs: Vec<f64> = vals.iter().map(|v| if v.len() == 1 { v[0] } else { v[i] }).collect();
                f(&xs)
            })
            .collect(),
    )
}

/// The component-wise intrinsics evaluated here, by their WGSL name.
fn mapped_name(i: Intrinsic) -> Option<&'static str> {
    match i {
        Intrinsic::Map(n) | Intrinsic::Map2(n) | Intrinsic::Map3(n) => Some(n),
        _ => None,
    }
}

/// The WGSL function `name` at `xs`, in f64.
fn apply(name: &str, xs: &[f64]) -> f64 {
    let x = xs[0];
    let y = xs.get(1).copied().unwrap_or(0.0);
    let z = xs.get(2).copied().unwrap_or(0.0);
    match name {
        "abs" => x.abs(),
        "floor" => x.floor(),
        "ceil" => x.ceil(),
        "fract" => x - x.floor(),
        "round" => x.round_ties_even(),
        "sqrt" => x.sqrt(),
        "exp" => x.exp(),
        "exp2" => x.exp2(),
        "log" => x.ln(),
        "log2" => x.log2(),
        "sin" => x.sin(),
        "cos" => x.cos(),
        "tan" => x.tan(),
        "asin" => x.asin(),
        "acos" => x.acos(),
        "atan" => x.atan(),
        "sign" => {
            if x == 0.0 {
                0.0
            } else {
                x.signum()
            }
        }
        "saturate" => x.clamp(0.0, 1.0),
        "min" => x.min(y),
        "max" => x.max(y),
        // WGSL defines pow(x, y) as exp2(y · log2(x)): no negative base.
        "pow" if x < 0.0 => f64::NAN,
        "pow" => x.powf(y),
        "step" => {
            if y >= x {
                1.0
            } else {
                0.0
            }
        }
        "atan2" => x.atan2(y),
        "clamp" => x.max(y).min(z),
        "smoothstep" => {
            let t = ((z - x) / (y - x)).clamp(0.0, 1.0);
            t * t * (3.0 - 2.0 * t)
        }
        "mix" => x * (1.0 - z) + y * z,
        _ => f64::NAN,
    }
}

fn domain_help(name: &str) -> String {
    match name {
        "sqrt" => "sqrt needs x ≥ 0; write `sqrt(abs(x))` or `sqrt(max(x, 0.0))` if that is meant".into(),
        "log" | "log2" => format!("{name} needs x > 0; clamp it with `max(x, 1e-6)`"),
        "exp" | "exp2" => format!("{name} of this argument is past the largest f32 (about 3.4e38)"),
        "asin" | "acos" => format!("{name} needs -1 ≤ x ≤ 1; clamp it with `clamp(x, -1.0, 1.0)`"),
        "pow" => "pow(x, y) needs x ≥ 0 (WGSL's pow is exp2(y · log2(x))); write `pow(abs(x), y)`".into(),
        _ => format!("the value of `{name}` here is past the f32 range"),
    }
}
