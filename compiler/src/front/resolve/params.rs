//! Resolve of declarations: params (type, default, range, animation,
//! per-object binding) and per-object textures (`object param t: texture`).
use super::*;

impl Resolver<'_> {
    // ---------------------------------------------------------------- params

    pub(super) fn param_shell(&mut self, p: &ast::ParamDecl) -> Param {
        let (ty, value_ty, unit) = self.param_type(&p.ty);
        Param {
            name: p.name.name.clone(),
            doc: p.doc.clone(),
            ty,
            value_ty,
            unit,
            per_object: p.per_object,
            default: ExprId(0),
            range: None,
            keys: Vec::new(),
            interpolation: "linear".into(),
            span: p.span,
            name_span: p.name.span,
        }
    }

    pub(super) fn param_type(&mut self, t: &ast::TypeExpr) -> (ParamTy, Ty, Unit) {
        match t {
            ast::TypeExpr::Enum { variants, .. } => (
                ParamTy::Enum(variants.iter().map(|v| v.name.clone()).collect()),
                Ty::Int,
                Unit::None,
            ),
            ast::TypeExpr::Named(id) => {
                let v = |ty| (ParamTy::Value(ty), ty, Unit::None);
                let u = |unit| (ParamTy::Value(Ty::Float), Ty::Float, unit);
                match id.name.as_str() {
                    "float" => v(Ty::Float),
                    "int" => v(Ty::Int),
                    "bool" => v(Ty::Bool),
                    "vec2" => v(Ty::Vec2),
                    "vec3" => v(Ty::Vec3),
                    "vec4" => v(Ty::Vec4),
                    "color" => (ParamTy::Color, Ty::Vec4, Unit::None),
                    "px" => u(Unit::Px),
                    "m" | "mm" => u(Unit::Meters),
                    "s" => u(Unit::Seconds),
                    "Hz" => u(Unit::Hertz),
                    "deg" => u(Unit::Radians),
                    "range" => (ParamTy::Range(Ty::Vec2), Ty::Vec2, Unit::None),
                    "blend" => (
                        ParamTy::Enum(vec!["linear".into(), "cubic".into(), "quintic".into()]),
                        Ty::Int,
                        Unit::None,
                    ),
                    other => {
                        let known = [
                            "float", "int", "bool", "vec2", "vec3", "vec4", "color", "px", "m", "mm", "s", "Hz", "deg",
                            "range", "blend",
                        ];
                        let mut d = Diagnostic::error(codes::UNKNOWN_TYPE, format!("unknown parameter type `{other}`"))
                            .with_primary(id.span, "not a type");
                        d = match did_you_mean(other, known) {
                            Some(s) => d.with_help(format!("did you mean `{s}`?")),
                            None if other == "texture" => d.with_help(
                                "textures are declared with `texture name = image(\"file.png\")`, not as parameters",
                            ),
                            None => {
                                d.with_help(format!("parameter types are: {}, or enum(a, b, ...)", known.join(", ")))
                            }
                        };
                        self.error(d);
                        (ParamTy::Value(Ty::Float), Ty::Unknown, Unit::None)
                    }
                }
            }
        }
    }

    pub(super) fn param_body(&mut self, id: ParamId, p: &ast::ParamDecl) {
        let variants = match &self.ir.params[id.0 as usize].ty {
            ParamTy::Enum(v) => Some(v.clone()),
            _ => None,
        };
        let default = match (&variants, &p.default.kind) {
            (Some(vs), AK::Name(n)) => match vs.iter().position(|v| *v == n.name) {
                Some(i) => self
                    .ir
                    .add_typed(ExprKind::Const(Const::Int(i as i64)), Ty::Int, Unit::None, n.span),
                None => {
                    let mut d = Diagnostic::error(
                        codes::UNKNOWN_NAME,
                        format!("`{}` is not a variant of this enum", n.name),
                    )
                    .with_primary(n.span, "unknown variant");
                    d = match did_you_mean(&n.name, vs.iter().map(String::as_str)) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help(format!("the variants are: {}", vs.join(", "))),
                    };
                    self.error(d);
                    self.ir.add(ExprKind::Error, n.span)
                }
            },
            _ => self.expr(&p.default),
        };
        let range = p.range.as_ref().and_then(|r| {
            let lo = self.expr(&r.lo);
            let hi = self.expr(&r.hi);
            let lo_v = self.const_scalar(lo, "a range bound");
            let hi_v = self.const_scalar(hi, "a range bound");
            let (lo_v, hi_v) = (lo_v?, hi_v?);
            if lo_v > hi_v {
                self.error(
                    Diagnostic::error(codes::OUT_OF_RANGE, "empty range")
                        .with_primary(r.span, format!("{lo_v} is greater than {hi_v}"))
                        .with_help("write the lower bound first: `in lo..hi`"),
                );
                return None;
            }
            Some((lo_v, hi_v))
        });
        let mut keys = Vec::new();
        let mut interpolation = String::from("linear");
        if let Some(anim) = &p.animate {
            if let Some(i) = &anim.interpolation {
                if !["linear", "step", "smooth"].contains(&i.name.as_str()) {
                    self.error(
                        Diagnostic::error(codes::UNKNOWN_NAME, format!("unknown interpolation `{}`", i.name))
                            .with_primary(i.span, "not an interpolation")
                            .with_help("use `linear`, `step` or `smooth`"),
                    );
                }
                interpolation = i.name.clone();
            }
            for k in &anim.keys {
                let t = self.expr(&k.time);
                let v = self.expr(&k.value);
                let t_unit = self.ir.expr(t).unit;
                if t_unit != Unit::Seconds && t_unit != Unit::None {
                    self.error(
                        Diagnostic::error(codes::UNIT_MISMATCH, "keyframe time must be in seconds")
                            .with_primary(k.time.span, format!("this is in {}", t_unit.name()))
                            .with_help("write times like `2s` or `0.5s`"),
                    );
                }
                let (Some(tv), Some(vv)) = (self.const_scalar(t, "a keyframe time"), self.const_values(v)) else {
                    continue;
                };
                if let Some(prev) = keys.last().map(|k: &Keyframe| k.time_s) {
                    if tv <= prev {
                        self.error(
                            Diagnostic::error(codes::OUT_OF_RANGE, "keyframe times must increase")
                                .with_primary(k.time.span, format!("{tv}s is not after {prev}s"))
                                .with_help("list keyframes in time order"),
                        );
                    }
                }
                if let Some((lo, hi)) = range {
                    if let Some(bad) = vv.iter().find(|x| **x < lo || **x > hi) {
                        self.error(
                            Diagnostic::error(codes::OUT_OF_RANGE, "keyframe value outside the parameter's range")
                                .with_primary(k.value.span, format!("{bad} is outside {lo}..{hi}"))
                                .with_secondary(
                                    p.range.as_ref().map(|r| r.span).unwrap_or(p.span),
                                    "range declared here",
                                ),
                        );
                    }
                }
                keys.push(Keyframe { time_s: tv, value: vv });
            }
        }
        let param = &mut self.ir.params[id.0 as usize];
        param.default = default;
        param.range = range;
        param.keys = keys;
        param.interpolation = interpolation;
    }

    pub(super) fn const_scalar(&mut self, id: ExprId, what: &str) -> Option<f64> {
        let v = self.const_values(id)?;
        if v.len() != 1 {
            let span = self.ir.expr(id).span;
            self.error(
                Diagnostic::error(codes::TYPE_MISMATCH, format!("{what} must be a single number"))
                    .with_primary(span, format!("this has {} components", v.len())),
            );
            return None;
        }
        Some(v[0])
    }

    pub(super) fn const_values(&mut self, id: ExprId) -> Option<Vec<f64>> {
        self.constant(id).map(|c| c.as_f64s())
    }

    /// [`Self::const_values`], keeping the constant's kind (an int, a bool).
    pub(super) fn constant(&mut self, id: ExprId) -> Option<Const> {
        if matches!(self.ir.expr(id).kind, ExprKind::Error) {
            return None;
        }
        match const_eval(&self.ir, id) {
            Some(c) => Some(c),
            None => {
                let span = self.ir.expr(id).span;
                self.error(
                    Diagnostic::error(codes::NOT_CONSTANT, "this must be a constant")
                        .with_primary(span, "not known at compile time")
                        .with_help("use literals such as `0.5`, `2px`, `#ff0000` or `vec2(0.1, 0.2)`"),
                );
                None
            }
        }
    }

    // -------------------------------------------------------------- textures

    /// `object param name: texture = image("file.png", srgb) { options }`:
    /// the default image and sampler options of a texture the scene may bind
    /// per object (`params = { name = "file.png" }`). A default is required,
    /// as for every parameter, so an object without a binding still draws.
    pub(super) fn object_texture(&mut self, p: &ast::ParamDecl, dir: &Path) -> Option<Texture> {
        if !p.per_object {
            self.error(
                Diagnostic::error(codes::UNKNOWN_TYPE, "only object params may be textures")
                    .with_primary(p.ty.span(), "a style-wide texture parameter")
                    .with_help(format!(
                        "declare a style texture as `texture {0} = image(\"file.png\")`, or one the scene binds per object as `object param {0}: texture = image(\"file.png\")`",
                        p.name.name
                    )),
            );
            return None;
        }
        if let Some(extra) = p.range.as_ref().map(|r| r.span).or(p.animate.as_ref().map(|a| a.span)) {
            self.error(
                Diagnostic::error(
                    codes::BAD_ARGUMENT,
                    format!("texture param `{}` has no range or keyframes", p.name.name),
                )
                .with_primary(extra, "not for a texture")
                .with_help("remove it; a texture param only has a default image and `{ wrap, filter, mips }` options"),
            );
        }
        let AK::Call(call) = &p.default.kind else {
            self.error(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("the default of texture param `{}` is not an image", p.name.name),
                )
                .with_primary(p.default.span, "expected `image(\"file.png\", srgb)`")
                .with_help("write `object param lit: texture = image(\"textures/paper.png\", srgb)`"),
            );
            return None;
        };
        let decl = ast::TextureDecl {
            doc: p.doc.clone(),
            name: p.name.clone(),
            source: call.clone(),
            options: p.options.clone(),
            span: p.span,
        };
        let mut tex = self.texture(&decl, dir);
        if matches!(tex.source, TextureSource::Input(_)) {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "a host input is one image for the whole frame")
                    .with_primary(call.span, "not a per-object texture")
                    .with_help(format!(
                        "declare it as a texture: `texture {} = input(...)`",
                        p.name.name
                    )),
            );
        }
        tex.per_object = true;
        Some(tex)
    }
}
