//! Typecheck of declarations: params (defaults, ranges, keyframes), and
//! passes (outputs against their formats, vertex modifiers, depth tests).

use super::*;

impl Checker<'_> {
    // ---------------------------------------------------------------- params

    pub(super) fn params(&mut self) {
        for i in 0..self.ir.params.len() {
            let p = self.ir.params[i].clone();
            let d = p.default;
            if self.is_error(d) {
                continue;
            }
            let have = self.vt(d);
            let want = p.value_ty;
            if want == Ty::Unknown {
                continue;
            }
            let ok = have == want
                || (have == Ty::Int && want == Ty::Float)
                || (have == Ty::Vec3 && want == Ty::Vec4 && matches!(p.ty, ParamTy::Value(_) | ParamTy::Color));
            if !ok {
                self.err(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("default of `{}` has the wrong type", p.name),
                    )
                    .with_primary(
                        self.span(d),
                        format!("expected {}, found {}", want.describe(), have.describe()),
                    )
                    .with_secondary(p.name_span, "parameter declared here"),
                );
                continue;
            }
            let du = self.unit(d);
            if du != Unit::None && du != p.unit {
                self.err(
                    Diagnostic::error(
                        codes::UNIT_MISMATCH,
                        format!(
                            "default of `{}` is in {}, but the parameter is {}",
                            p.name,
                            du.name(),
                            p.unit.name()
                        ),
                    )
                    .with_primary(self.span(d), format!("this is in {}", du.name()))
                    .with_secondary(p.name_span, "parameter declared here")
                    .with_help(format!("write the default in {}", p.unit.name())),
                );
                continue;
            }
            if let Some(d) = defaults::not_constant(self.ir, &p) {
                self.err(d);
            }
            if let (Some((lo, hi)), Some(c)) = (p.range, const_eval(self.ir, d)) {
                if let Some(bad) = c.as_f64s().into_iter().find(|v| *v < lo || *v > hi) {
                    self.err(
                        Diagnostic::error(
                            codes::OUT_OF_RANGE,
                            format!("default of `{}` is outside its range", p.name),
                        )
                        .with_primary(self.span(d), format!("{bad} is outside {lo}..{hi}"))
                        .with_help("change the default or widen the range"),
                    );
                }
            }
            if p.per_object && !p.keys.is_empty() {
                self.err(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        format!("object param `{}` cannot be animated", p.name),
                    )
                    .with_primary(p.name_span, "per object and animated")
                    .with_help("animate a style param and multiply it by the object param"),
                );
            }
        }
    }

    // ---------------------------------------------------------------- passes

    /// `vertex { inflate, shadow_warp }`: a width in px and a plain number,
    /// promoted to float; an ill-typed one is reported and left as it was.
    pub(super) fn vertex_modifiers(&mut self, mut vertex: VertexModifiers) -> VertexModifiers {
        if let Some(inflate) = vertex.inflate {
            if !self.is_error(inflate) {
                let u = self.unit(inflate);
                if self.vt(inflate) != Ty::Float && self.vt(inflate) != Ty::Int {
                    self.type_error(inflate, "a width in px", None);
                } else if u != Unit::Px && u != Unit::None {
                    self.err(
                        Diagnostic::error(
                            codes::UNIT_MISMATCH,
                            format!("`inflate` is a width in px, found {}", u.name()),
                        )
                        .with_primary(self.span(inflate), format!("this is in {}", u.name()))
                        .with_help("write it in px, or in % of the image height"),
                    );
                } else {
                    vertex.inflate = Some(self.promote_int(inflate));
                }
            }
        }
        if let Some(k) = vertex.shadow_warp {
            if !self.is_error(k) {
                if self.vt(k) != Ty::Float && self.vt(k) != Ty::Int {
                    self.type_error(k, "a plain number (the sigmoid strength)", None);
                } else {
                    vertex.shadow_warp = Some(self.promote_int(k));
                }
            }
        }
        vertex
    }

    /// `depth: test(other)`: `other` is a render pass that keeps its depth
    /// (E0308 otherwise), is not this pass, and has this pass's scale and
    /// view, so that its depth texture fits this pass's attachment and holds
    /// depths of the same projection.
    pub(super) fn depth_test(&mut self, pi: usize) {
        let pass = &self.ir.passes[pi];
        let Some((tested, span)) = pass.depth_test() else {
            return;
        };
        let other = self.ir.pass(tested);
        let (name, other_name) = (pass.name.clone(), other.name.clone());
        if tested.0 as usize == pi {
            let help = if matches!(pass.kind, PassKind::Lines(_)) {
                "a lines pass has no depth of its own; `depth: test(...)` names an earlier render pass with `depth: keep`"
            } else {
                "a pass always tests against its own depth; `depth: test(...)` names an earlier pass with `depth: keep`"
            };
            self.err(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("pass `{name}` tests against its own depth"),
                )
                .with_primary(span, "this pass")
                .with_help(help),
            );
            return;
        }
        if !other.keeps_depth() {
            let (label, help) = if other.kind.draws_objects() {
                (
                    format!("`{other_name}` discards its depth after it runs"),
                    format!("add `depth: keep` to pass `{other_name}`, so its depth buffer outlives the pass"),
                )
            } else {
                (format!("`{other_name}` has no depth buffer"),
                format!("`{other_name}` is not a render pass, so it has no depth buffer; test against a render pass with `depth: keep`"))
            };
            self.err(
                Diagnostic::error(
                    codes::DEPTH_NOT_KEPT,
                    format!("pass `{name}` tests against the depth of `{other_name}`, which keeps none"),
                )
                .with_primary(span, "depth test here")
                .with_secondary(other.name_span, label)
                .with_help(help),
            );
            return;
        }
        let view = |p: &Pass| match p.kind {
            PassKind::Render { view, .. } => Some(view),
            // Strips are built from the camera's eyes.
            PassKind::Lines(_) => Some(PassView::Camera),
            _ => None,
        };
        if other.scale != pass.scale {
            let (a, b) = (other.scale, pass.scale);
            self.err(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("pass `{name}` tests against the depth of `{other_name}`, which has another size"),
                )
                .with_primary(span, format!("`{name}` renders at scale {b}"))
                .with_secondary(other.name_span, format!("`{other_name}` renders at scale {a}"))
                .with_help("a depth test needs both passes at the same scale"),
            );
        } else if view(other) != view(pass) {
            self.err(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("pass `{name}` tests against the depth of `{other_name}`, seen from another view"),
                )
                .with_primary(span, "depth test here")
                .with_secondary(other.name_span, "projected with another camera")
                .with_help("give both passes the same `view(...)`"),
            );
        }
    }

    /// `depth: test(input)` against the host's depth: the input is the
    /// camera's view at the output's size, so the pass renders at scale 1
    /// through the camera (E0320 otherwise).
    pub(super) fn input_depth_test(&mut self, pi: usize) {
        let pass = &self.ir.passes[pi];
        let Some((texture, span)) = pass.input_depth_test() else {
            return;
        };
        let input = &self.ir.textures[texture.0 as usize];
        let light = matches!(
            pass.kind,
            PassKind::Render {
                view: PassView::Light,
                ..
            }
        );
        let (problem, label, help) = if pass.scale != 1.0 {
            (
                "at another size",
                format!("`{}` renders at scale {}", pass.name, pass.scale),
                "the host's depth has the output's size: render this pass at scale 1".to_string(),
            )
        } else if light {
            (
                "from another view",
                format!("`{}` is seen from the light", pass.name),
                "the host's depth is seen from the camera: test a `view(light)` pass against a pass with `depth: keep`"
                    .to_string(),
            )
        } else {
            return;
        };
        let d = Diagnostic::error(
            codes::INPUT_DEPTH_MISMATCH,
            format!(
                "pass `{}` tests against the host's depth `{}` {problem}",
                pass.name, input.name
            ),
        )
        .with_primary(span, label)
        .with_secondary(input.span, "the host's depth: the camera's view, at the output's size")
        .with_help(help);
        self.err(d);
    }

    pub(super) fn passes(&mut self) {
        for pi in 0..self.ir.passes.len() {
            self.depth_test(pi);
            self.input_depth_test(pi);
            self.line_settings(pi);
            let pass = self.ir.passes[pi].clone();
            if let PassKind::Render { vertex, .. } = &pass.kind {
                let checked = self.vertex_modifiers(*vertex);
                if let PassKind::Render { vertex, .. } = &mut self.ir.passes[pi].kind {
                    *vertex = checked;
                }
            }
            // Vertex modifiers run per vertex: no fragment varyings there.
            for id in self.ir.reachable(&pass.roots().vertex) {
                let e = self.ir.expr(id).clone();
                if let ExprKind::Builtin(b) = e.kind {
                    if b.is_per_fragment() {
                        self.err(
                            Diagnostic::error(
                                codes::BAD_PASS_INPUT,
                                format!("`{}` read in a `vertex {{ }}` modifier", b.name()),
                            )
                            .with_primary(e.span, "this value exists per fragment, not per vertex")
                            .with_help(
                                "vertex modifiers may read parameters, per-object params and frame values such as `time`, `resolution`, `camera.*` and `light.*`",
                            ),
                        );
                    }
                }
            }
            let mut roots: Vec<ExprId> = pass.outputs.iter().map(|o| o.value).collect();
            roots.extend(pass.kind.values().iter().flat_map(ObjectValue::roots));
            let mut patch_weight: Option<Span> = None;
            for id in self.ir.reachable(&roots) {
                let e = self.ir.expr(id).clone();
                match e.kind {
                    ExprKind::Builtin(b) => {
                        if b == Builtin::PatchWeight && patch_weight.is_none_or(|s| e.span.start < s.start) {
                            patch_weight = Some(e.span);
                        }
                        self.builtin_in_kind(b, &pass.kind, e.span)
                    }
                    // A previous-frame read is no dependency within the frame,
                    // so it needs no input listing.
                    ExprKind::Target { target: t, copy } if copy != TargetCopy::Previous => {
                        if let PassKind::Image { inputs, .. } = &pass.kind {
                            if t.pass.0 as usize != pi && !inputs.contains(&t.pass) {
                                let other = self.ir.pass(t.pass).name.clone();
                                self.err(
                                    Diagnostic::error(
                                        codes::BAD_PASS_INPUT,
                                        format!("pass `{}` reads `{other}` without listing it", pass.name),
                                    )
                                    .with_primary(e.span, "read here")
                                    .with_secondary(pass.name_span, "inputs declared here")
                                    .with_help(format!("add `{other}` to the inputs: `image(..., {other})`")),
                                );
                            }
                        }
                    }
                    _ => {}
                }
            }
            if let Some(span) = patch_weight {
                self.patch_weight_occlusion(&pass, span);
            }
            for (oi, o) in pass.outputs.iter().enumerate() {
                if self.is_error(o.value) {
                    continue;
                }
                let mut v = o.value;
                let t = self.vt(v);
                if t == Ty::Int {
                    v = self.convert(v, Conversion::IntToFloat);
                }
                let t = self.vt(v);
                let want = o.format.channels();
                let fits = t.components() == Some(want) && t != Ty::Bool;
                if !fits {
                    let n = t.components().unwrap_or(0);
                    let help = match (n, want) {
                        (1, 4) => "write `vec4(x, x, x, 1.0)`, or use a one-channel format such as r8unorm".to_string(),
                        (4, 1) => {
                            "pick one channel, e.g. `.r`, or use a four-channel format such as rgba8unorm".to_string()
                        }
                        (3, 4) => "add alpha: `vec4(c, 1.0)`, or use a colour (`#rrggbb`)".to_string(),
                        _ => format!(
                            "{} has {want} channel(s): write a value with {want} component(s)",
                            o.format.name()
                        ),
                    };
                    self.err(
                        Diagnostic::error(
                            codes::FORMAT_MISMATCH,
                            format!("cannot write {} into a {} target", t.describe(), o.format.name()),
                        )
                        .with_primary(self.span(o.value), format!("this is {}", t.describe()))
                        .with_secondary(o.span, format!("`{}` is {}", o.name, o.format.name()))
                        .with_help(help),
                    );
                    continue;
                }
                self.ir.passes[pi].outputs[oi].value = v;
            }
            self.compute_values(pi);
        }
    }
}
