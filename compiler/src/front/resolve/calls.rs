//! Resolve of calls: `scene_has`, `previous` / `other_eye`, WGSL
//! intrinsics and stdlib operators (arguments in parameter order, defaults
//! filled in), and the operator signature shown in help lines.

use super::*;

impl Resolver<'_> {
    /// `scene_has(tag)`: whether any object in the scene carries `tag`. With a
    /// known scene this is a constant, so `if scene_has(casters) { ... }` lets
    /// the compiler drop a shadow-caster depth pass the scene cannot use; with
    /// no scene it is `true`, which is always safe (an empty `render(tag)` pass
    /// leaves its targets at their clear value).
    pub(super) fn scene_has(&mut self, call: &ast::Call) -> ExprId {
        let span = call.span;
        let tag = match call.args.as_slice() {
            [a] if a.name.is_none() => match &a.value.kind {
                AK::Name(n) => Some(n.name.clone()),
                _ => None,
            },
            _ => None,
        };
        let Some(tag) = tag else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`scene_has` takes one object tag")
                    .with_primary(span, "expected `scene_has(tag)`")
                    .with_help("write the tag as a bare name, as in `render(tag)`: `scene_has(casters)`"),
            );
            return self.ir.add(ExprKind::Error, span);
        };
        let present = match self.scene {
            Some(scene) => {
                let present = scene.tags.contains(&tag);
                if !self.ir.scene_queries.iter().any(|(t, _)| *t == tag) {
                    self.ir.scene_queries.push((tag, present));
                }
                present
            }
            None => true,
        };
        self.ir
            .add_typed(ExprKind::Const(Const::Bool(present)), Ty::Bool, Unit::None, span)
    }

    /// `other_eye(pass.target)` (the other eye of a stereo frame: LSA
    /// contours' reprojection and consistency passes) and
    /// `previous(pass.target)` (the previous frame: temporal filters,
    /// feedback): another copy of a target.
    pub(super) fn target_copy(&mut self, call: &ast::Call, name: &str, copy: TargetCopy) -> ExprId {
        let span = call.span;
        let example = if copy == TargetCopy::Previous {
            "name a target of any pass, this one included, e.g. `previous(final.color)`"
        } else {
            "name a target of an earlier pass, e.g. `other_eye(lines.e)`"
        };
        if let [a] = call.args.as_slice() {
            if a.name.is_none() {
                let v = self.expr(&a.value);
                if let ExprKind::Target {
                    target,
                    copy: TargetCopy::This,
                } = self.ir.expr(v).kind
                {
                    return self
                        .ir
                        .add_typed(ExprKind::Target { target, copy }, Ty::Target(target), Unit::None, span);
                }
                if matches!(self.ir.expr(v).kind, ExprKind::Error) {
                    return v;
                }
            }
        }
        self.error(
            Diagnostic::error(codes::BAD_ARGUMENT, format!("`{name}` takes one pass target"))
                .with_primary(span, format!("expected `{name}(pass.target)`"))
                .with_help(example),
        );
        self.ir.add(ExprKind::Error, span)
    }

    pub(super) fn call(&mut self, call: &ast::Call) -> ExprId {
        let name = call.callee.name.as_str();
        let span = call.span;
        if name == "scene_has" {
            return self.scene_has(call);
        }
        if name == "ramp" {
            return self.ramp(call);
        }
        if let Some(copy) = target_copy_call(name) {
            return self.target_copy(call, name, copy);
        }
        if let Some(intr) = Intrinsic::lookup(name) {
            let mut args = Vec::new();
            for a in &call.args {
                if let Some(n) = &a.name {
                    self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, format!("`{name}` takes no named arguments"))
                            .with_primary(n.span, "named argument")
                            .with_help("pass the arguments by position"),
                    );
                }
                args.push(self.expr(&a.value));
            }
            return self.ir.add(
                ExprKind::Call {
                    callee: Callee::Intrinsic(intr),
                    args,
                },
                span,
            );
        }
        let Some(index) = npr_stdlib::all().iter().position(|o| o.name == name) else {
            let mut names: Vec<&str> = npr_stdlib::all().iter().map(|o| o.name).collect();
            names.extend(Intrinsic::names());
            let mut d = Diagnostic::error(codes::UNKNOWN_OPERATOR, format!("unknown operator `{name}`"))
                .with_primary(call.callee.span, "no such operator or function");
            d = match did_you_mean(name, names) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help("`npr doc` lists the stdlib operators"),
            };
            self.error(d);
            for a in &call.args {
                self.expr(&a.value);
            }
            return self.ir.add(ExprKind::Error, span);
        };
        let op = &npr_stdlib::all()[index];
        let mut slots: Vec<Option<ExprId>> = vec![None; op.params.len()];
        let mut positional = 0usize;
        let mut ok = true;
        for a in &call.args {
            let slot = match &a.name {
                None => {
                    // Positional arguments fill the parameters not yet given, in order.
                    while positional < slots.len() && slots[positional].is_some() {
                        positional += 1;
                    }
                    if positional >= slots.len() {
                        self.error(
                            Diagnostic::error(codes::BAD_ARGUMENT, format!("too many arguments to `{name}`"))
                                .with_primary(a.span, "extra argument")
                                .with_help(format!("`{name}` takes {}", signature(op))),
                        );
                        ok = false;
                        continue;
                    }
                    positional
                }
                Some(n) => match op.params.iter().position(|p| p.name == n.name) {
                    Some(i) if slots[i].is_none() => i,
                    Some(_) => {
                        self.error(
                            Diagnostic::error(codes::BAD_ARGUMENT, format!("argument `{}` given twice", n.name))
                                .with_primary(n.span, "given again here"),
                        );
                        ok = false;
                        continue;
                    }
                    None => {
                        let mut d =
                            Diagnostic::error(codes::BAD_ARGUMENT, format!("`{name}` has no parameter `{}`", n.name))
                                .with_primary(n.span, "unknown argument name");
                        d = match did_you_mean(&n.name, op.params.iter().map(|p| p.name)) {
                            Some(s) => d.with_help(format!("did you mean `{s}`?")),
                            None => d.with_help(format!("`{name}` takes {}", signature(op))),
                        };
                        self.error(d);
                        ok = false;
                        continue;
                    }
                },
            };
            let param = &op.params[slot];
            let value = match (param.ty, &a.value.kind) {
                (npr_stdlib::Ty::Enum(variants), AK::Name(v)) if !self.is_bound(&v.name) => {
                    match variants.iter().position(|x| *x == v.name) {
                        Some(i) => {
                            self.ir
                                .add_typed(ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None, v.span)
                        }
                        None => {
                            let mut d = Diagnostic::error(
                                codes::BAD_ARGUMENT,
                                format!("`{}` is not a choice of `{}`", v.name, param.name),
                            )
                            .with_primary(v.span, "unknown variant");
                            d = match did_you_mean(&v.name, variants.iter().copied()) {
                                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                                None => d.with_help(format!("choices are: {}", variants.join(", "))),
                            };
                            self.error(d);
                            ok = false;
                            continue;
                        }
                    }
                }
                _ => self.expr(&a.value),
            };
            slots[slot] = Some(value);
        }
        let mut args = Vec::new();
        for (i, p) in op.params.iter().enumerate() {
            if let Some(v) = slots[i] {
                args.push(v);
                continue;
            }
            let v = match p.default {
                npr_stdlib::Default::Required => {
                    if ok {
                        self.error(
                            Diagnostic::error(
                                codes::BAD_ARGUMENT,
                                format!("missing argument `{}` to `{name}`", p.name),
                            )
                            .with_primary(span, format!("`{}` is required", p.name))
                            .with_help(format!("`{name}` takes {}", signature(op))),
                        );
                    }
                    ok = false;
                    self.ir.add(ExprKind::Error, span)
                }
                _ => match operator_default(p) {
                    Ok((kind, ty, unit)) => self.ir.add_typed(kind, ty, unit, span),
                    Err(detail) => {
                        self.internal.get_or_insert(InternalError {
                            message: format!("the stdlib default of `{}` in `{name}` is invalid", p.name),
                            detail,
                            span: Some(span),
                            wgsl: None,
                        });
                        ok = false;
                        self.ir.add(ExprKind::Error, span)
                    }
                },
            };
            args.push(v);
        }
        if !ok {
            return self.ir.add(ExprKind::Error, span);
        }
        self.ir.add(
            ExprKind::Call {
                callee: Callee::Operator(index as u32),
                args,
            },
            span,
        )
    }
}

/// The copy of a target a call selects: `other_eye(t)`, `previous(t)`.
pub(super) fn target_copy_call(name: &str) -> Option<TargetCopy> {
    match name {
        "other_eye" => Some(TargetCopy::OtherEye),
        "previous" => Some(TargetCopy::Previous),
        _ => None,
    }
}

/// `(x: float, steps: int = 3)` — an operator's signature for help lines.
pub fn signature(op: &npr_stdlib::Operator) -> String {
    let params: Vec<String> = op
        .params
        .iter()
        .map(|p| {
            let ty = match p.ty {
                npr_stdlib::Ty::Enum(v) => v.join("|"),
                t => format!("{t:?}").to_lowercase(),
            };
            match p.default {
                npr_stdlib::Default::Required => format!("{}: {ty}", p.name),
                npr_stdlib::Default::Number(x) => format!("{}: {ty} = {x}", p.name),
                npr_stdlib::Default::Builtin(b) => format!("{}: {ty} = {b}", p.name),
                npr_stdlib::Default::Variant(v) => format!("{}: {ty} = {v}", p.name),
            }
        })
        .collect();
    format!("({})", params.join(", "))
}

/// The node an operator parameter's stdlib default stands for (any default
/// but `Required`). The defaults are stdlib data, not style text: one that
/// names no variant of its enum or no builtin is a bug in npr (E9001), so
/// it is an error here, never a silent fallback (and a test checks that
/// every operator's defaults resolve).
pub(super) fn operator_default(p: &npr_stdlib::Param) -> Result<(ExprKind, Ty, Unit), String> {
    match p.default {
        npr_stdlib::Default::Required => Err(format!("`{}` has no default", p.name)),
        npr_stdlib::Default::Number(x) => {
            let (ty, c) = match p.ty {
                npr_stdlib::Ty::Int => (Ty::Int, Const::Int(x as i64)),
                npr_stdlib::Ty::Bool => (Ty::Bool, Const::Bool(x != 0.0)),
                _ => (Ty::Float, Const::Float(x)),
            };
            Ok((ExprKind::Const(c), ty, p.unit))
        }
        npr_stdlib::Default::Variant(v) => match p.ty {
            npr_stdlib::Ty::Enum(vs) => match vs.iter().position(|x| *x == v) {
                Some(i) => Ok((ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None)),
                None => Err(format!("`{v}` is not one of its variants {}", vs.join("|"))),
            },
            other => Err(format!("the variant default `{v}` is on a parameter of type {other:?}")),
        },
        npr_stdlib::Default::Builtin(b) => match Builtin::SPELLINGS.iter().find(|(s, _)| *s == b) {
            Some((_, bi)) => {
                let (ty, unit) = bi.ty_unit();
                Ok((ExprKind::Builtin(*bi), ty, unit))
            }
            None => Err(format!("`{b}` is not a builtin")),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn param(ty: npr_stdlib::Ty, default: npr_stdlib::Default) -> npr_stdlib::Param {
        npr_stdlib::Param {
            name: "p",
            ty,
            unit: Unit::None,
            default,
            range: None,
            doc: "",
        }
    }

    #[test]
    fn every_stdlib_default_resolves() {
        for op in npr_stdlib::all() {
            for p in op.params {
                if p.default != npr_stdlib::Default::Required {
                    let r = operator_default(p);
                    assert!(r.is_ok(), "`{}({})`: {:?}", op.name, p.name, r.err());
                }
            }
        }
    }

    #[test]
    fn a_bad_stdlib_default_is_an_error_not_a_fallback() {
        let e = npr_stdlib::Ty::Enum(&["x", "y"]);
        assert_eq!(
            operator_default(&param(e, npr_stdlib::Default::Variant("y"))).map(|(k, ..)| k),
            Ok(ExprKind::Const(Const::Int(1)))
        );
        let err = operator_default(&param(e, npr_stdlib::Default::Variant("z"))).unwrap_err();
        assert!(err.contains("`z` is not one of its variants x|y"), "{err}");
        let err = operator_default(&param(npr_stdlib::Ty::Float, npr_stdlib::Default::Variant("x"))).unwrap_err();
        assert!(err.contains("on a parameter of type Float"), "{err}");
        let err =
            operator_default(&param(npr_stdlib::Ty::Vec2, npr_stdlib::Default::Builtin("screen_xy"))).unwrap_err();
        assert!(err.contains("`screen_xy` is not a builtin"), "{err}");
        assert_eq!(
            operator_default(&param(npr_stdlib::Ty::Vec2, npr_stdlib::Default::Builtin("screen_uv"))).map(|(k, ..)| k),
            Ok(ExprKind::Builtin(Builtin::ScreenUv))
        );
    }
}
