//! Resolve of expressions: literals with units, names (innermost scope
//! first), fields (`pass.target`, builtins, swizzles).
use super::*;

impl Resolver<'_> {
    // ----------------------------------------------------------- expressions

    pub(super) fn expr(&mut self, e: &ast::Expr) -> ExprId {
        let span = e.span;
        match &e.kind {
            AK::Number { value, is_int, unit } => {
                let (v, unit) = match unit {
                    None => (*value, Unit::None),
                    Some(UnitSuffix::Px) => (*value, Unit::Px),
                    Some(UnitSuffix::Percent) => {
                        return self
                            .ir
                            .add_typed(ExprKind::PercentOfHeight(*value / 100.0), Ty::Float, Unit::Px, span)
                    }
                    Some(UnitSuffix::M) => (*value, Unit::Meters),
                    Some(UnitSuffix::Mm) => (*value * 1e-3, Unit::Meters),
                    Some(UnitSuffix::S) => (*value, Unit::Seconds),
                    Some(UnitSuffix::Hz) => (*value, Unit::Hertz),
                    Some(UnitSuffix::Deg) => (value.to_radians(), Unit::Radians),
                };
                if *is_int && unit == Unit::None && v.abs() < 2f64.powi(31) {
                    self.ir
                        .add_typed(ExprKind::Const(Const::Int(v as i64)), Ty::Int, unit, span)
                } else {
                    self.ir
                        .add_typed(ExprKind::Const(Const::Float(v)), Ty::Float, unit, span)
                }
            }
            AK::Bool(b) => self
                .ir
                .add_typed(ExprKind::Const(Const::Bool(*b)), Ty::Bool, Unit::None, span),
            AK::Color(c) => self
                .ir
                .add_typed(ExprKind::Const(Const::Vec(c.to_vec())), Ty::Vec4, Unit::None, span),
            AK::Str(_) => {
                self.error(
                    Diagnostic::error(codes::TYPE_MISMATCH, "a string is not a value")
                        .with_primary(span, "strings are only used for file paths")
                        .with_help("to pick an enum variant, write its name without quotes"),
                );
                self.ir.add(ExprKind::Error, span)
            }
            AK::Name(id) => self.name(id),
            AK::Field { base, field } => self.field(base, field, span),
            AK::Call(call) => self.call(call),
            AK::Unary { op, operand } => {
                let o = self.expr(operand);
                self.ir.add(ExprKind::Unary { op: *op, operand: o }, span)
            }
            AK::Binary { op, lhs, rhs } => {
                let l = self.expr(lhs);
                let r = self.expr(rhs);
                self.ir.add(
                    ExprKind::Binary {
                        op: *op,
                        lhs: l,
                        rhs: r,
                    },
                    span,
                )
            }
            AK::If { cond, then, otherwise } => {
                let c = self.expr(cond);
                let t = self.expr(then);
                let o = self.expr(otherwise);
                self.ir.add(
                    ExprKind::Select {
                        cond: c,
                        then: t,
                        otherwise: o,
                    },
                    span,
                )
            }
            AK::Block { lets, value } => {
                self.scopes.push(Vec::new());
                for l in lets {
                    let v = self.expr(&l.value);
                    if let Some(s) = self.scopes.last_mut() {
                        s.push((l.name.name.clone(), v));
                    }
                }
                let v = self.expr(value);
                self.scopes.pop();
                v
            }
            AK::Range { lo, hi } => {
                let l = self.expr(lo);
                let h = self.expr(hi);
                self.ir.add(
                    ExprKind::Call {
                        callee: Callee::Intrinsic(Intrinsic::Construct(2)),
                        args: vec![l, h],
                    },
                    span,
                )
            }
        }
    }

    /// A builtin named in a pass: in an image pass over a host's frame,
    /// the reads of the inputs it stands for (`host_builtins.rs`).
    fn builtin_read(&mut self, b: Builtin, span: Span) -> ExprId {
        if self.in_image_pass && !self.in_vertex {
            if let Some(read) = self.host_builtin(b, span) {
                return read;
            }
        }
        let (ty, unit) = b.ty_unit();
        self.ir.add_typed(ExprKind::Builtin(b), ty, unit, span)
    }

    pub(super) fn name(&mut self, id: &ast::Ident) -> ExprId {
        let span = id.span;
        for scope in self.scopes.iter().rev() {
            if let Some((_, v)) = scope.iter().rev().find(|(n, _)| *n == id.name) {
                return *v;
            }
        }
        if let Some(v) = self.state_read(id) {
            return v;
        }
        match self.names.get(&id.name).copied() {
            Some((Symbol::Param(p), _)) => {
                let param = &self.ir.params[p.0 as usize];
                let (ty, unit) = (param.value_ty, param.unit);
                return self.ir.add_typed(ExprKind::Param(p), ty, unit, span);
            }
            Some((Symbol::Texture(t), _)) => {
                if self.in_vertex {
                    let d = Diagnostic::error(
                        codes::BAD_PASS_INPUT,
                        format!("texture `{}` read in a `vertex {{ }}` modifier", id.name),
                    )
                    .with_primary(span, "textures are sampled per fragment, not per vertex")
                    .with_help("use a parameter or a per-object param for the vertex modifier");
                    self.error(d);
                    return self.ir.add(ExprKind::Error, span);
                }
                if self.ir.textures[t.0 as usize].per_object && !self.draws_objects {
                    let d = Diagnostic::error(
                        codes::BAD_PASS_INPUT,
                        format!("`{}` is a per-object texture, read outside a render pass", id.name),
                    )
                    .with_primary(span, "no object is being drawn here")
                    .with_help(format!(
                        "read `{}` in a `render(...)` pass, write what you need to a target, and read that target here",
                        id.name
                    ));
                    self.error(d);
                    return self.ir.add(ExprKind::Error, span);
                }
                return self
                    .ir
                    .add_typed(ExprKind::Texture(t), Ty::Texture(t), Unit::None, span);
            }
            Some((Symbol::Gradient(_), _)) => {
                let d = Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`{}` is a gradient, not a value", id.name),
                )
                .with_primary(span, "a gradient")
                .with_help(format!(
                    "read its colour at a position from 0 to 1 with `ramp({}, t)`",
                    id.name
                ));
                self.error(d);
                return self.ir.add(ExprKind::Error, span);
            }
            Some((Symbol::Pass(p), _)) => {
                let outs = self.pass_outputs[p.0 as usize].clone();
                let d = Diagnostic::error(codes::TYPE_MISMATCH, format!("`{}` is a pass, not a value", id.name))
                    .with_primary(span, "a pass")
                    .with_help(match outs.first() {
                        Some(o) => format!("read one of its targets, e.g. `{}.{o}`", id.name),
                        None => "this pass has no outputs".to_string(),
                    });
                self.error(d);
                return self.ir.add(ExprKind::Error, span);
            }
            None => {}
        }
        if let Some((_, b)) = Builtin::SPELLINGS.iter().find(|(s, _)| *s == id.name) {
            return self.builtin_read(*b, span);
        }
        // Enum variants are global constants (their index).
        for p in &self.ir.params {
            if let ParamTy::Enum(vs) = &p.ty {
                if let Some(i) = vs.iter().position(|v| *v == id.name) {
                    return self
                        .ir
                        .add_typed(ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None, span);
                }
            }
        }
        let mut candidates: Vec<String> = self.names.keys().cloned().collect();
        candidates.extend(Builtin::SPELLINGS.iter().map(|(s, _)| s.to_string()));
        for scope in &self.scopes {
            candidates.extend(scope.iter().map(|(n, _)| n.clone()));
        }
        let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("unknown name `{}`", id.name))
            .with_primary(span, "not found in this scope");
        if let Some(s) = did_you_mean(&id.name, candidates.iter().map(String::as_str)) {
            d = d.with_help(format!("did you mean `{s}`?"));
        } else {
            d = d.with_help("declare it with `param` or `let`, or use a builtin such as `uv`, `normal`, `time`");
        }
        self.error(d);
        self.ir.add(ExprKind::Error, span)
    }

    pub(super) fn field(&mut self, base: &ast::Expr, field: &ast::Ident, span: Span) -> ExprId {
        if let AK::Name(b) = &base.kind {
            let shadowed = self.scopes.iter().any(|s| s.iter().any(|(n, _)| *n == b.name));
            if !shadowed {
                if let Some(p) = self.is_compute_pass(&b.name) {
                    return self.value_of(p, field, span);
                }
                if let Some((Symbol::Pass(p), _)) = self.names.get(&b.name).copied() {
                    return match self.target_of(p, field) {
                        Some(t) => self.ir.add_typed(
                            ExprKind::Target {
                                target: t,
                                copy: TargetCopy::This,
                            },
                            Ty::Target(t),
                            Unit::None,
                            span,
                        ),
                        None => self.ir.add(ExprKind::Error, span),
                    };
                }
                let spelled = format!("{}.{}", b.name, field.name);
                if matches!(spelled.as_str(), "line.color" | "line.set") {
                    return self.line_set_value(&spelled, span);
                }
                if let Some((_, bi)) = Builtin::SPELLINGS.iter().find(|(s, _)| *s == spelled) {
                    return self.builtin_read(*bi, span);
                }
                if matches!(b.name.as_str(), "light" | "camera") {
                    let members: Vec<&str> = Builtin::SPELLINGS
                        .iter()
                        .filter_map(|(s, _)| s.strip_prefix(&format!("{}.", b.name)))
                        .collect();
                    let mut d = Diagnostic::error(
                        codes::UNKNOWN_NAME,
                        format!("`{}` has no member `{}`", b.name, field.name),
                    )
                    .with_primary(field.span, "unknown member");
                    d = match did_you_mean(&field.name, members.iter().copied()) {
                        Some(s) => d.with_help(format!("did you mean `{}.{s}`?", b.name)),
                        None => d.with_help(format!("its members are: {}", members.join(", "))),
                    };
                    self.error(d);
                    return self.ir.add(ExprKind::Error, span);
                }
            }
        }
        let b = self.expr(base);
        if matches!(self.ir.expr(b).kind, ExprKind::Error) {
            // The base's error is reported; its field would only repeat it.
            return b;
        }
        match swizzle::parse(field) {
            swizzle::Swizzle::Components(c) => self.ir.add(ExprKind::Swizzle { base: b, components: c }, span),
            swizzle::Swizzle::Mixed(d) => {
                self.error(*d);
                self.ir.add(ExprKind::Error, span)
            }
            swizzle::Swizzle::NotOne => {
                self.error(
                    Diagnostic::error(codes::UNKNOWN_TYPE, format!("unknown field `{}`", field.name))
                        .with_primary(field.span, "not a swizzle or member")
                        .with_help("swizzles use up to four of x, y, z, w (or r, g, b, a)"),
                );
                self.ir.add(ExprKind::Error, span)
            }
        }
    }
}
