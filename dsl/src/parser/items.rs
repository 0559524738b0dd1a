//! Top-level declarations (`use`, `param`, `texture`, `pass`, `output`)
//! and pass bodies, pest pairs → AST.

use super::*;

impl Builder {
    pub(super) fn use_decl(&self, p: P) -> Option<UseDecl> {
        let span = self.span(&p);
        let inner = p.into_inner().next()?;
        let target = match inner.as_rule() {
            Rule::string => UseTarget::File(self.string(inner)),
            _ => UseTarget::Module(inner.into_inner().map(|i| self.ident(i)).collect()),
        };
        Some(UseDecl { target, span })
    }

    pub(super) fn param_decl(&self, p: P) -> Option<ParamDecl> {
        let span = self.span(&p);
        let mut doc = String::new();
        let mut per_object = false;
        let mut name = None;
        let mut ty = None;
        let mut default = None;
        let mut range = None;
        let mut animate = None;
        let mut options = Vec::new();
        for i in p.into_inner() {
            match i.as_rule() {
                Rule::doc_comment => doc = self.doc(i),
                Rule::object_kw => per_object = true,
                Rule::ident => name = Some(self.ident(i)),
                Rule::type_expr => ty = Some(self.type_expr(i)?),
                Rule::param_default => default = Some(self.param_default(i)?),
                Rule::range_clause => range = Some(self.range(i)?),
                Rule::animate_clause => animate = Some(self.animate(i)?),
                Rule::settings_block => options = self.settings(i),
                _ => {}
            }
        }
        Some(ParamDecl {
            doc,
            per_object,
            name: name?,
            ty: ty?,
            default: default?,
            range,
            animate,
            options,
            span,
        })
    }

    pub(super) fn type_expr(&self, p: P) -> Option<TypeExpr> {
        let inner = p.into_inner().next()?;
        Some(match inner.as_rule() {
            Rule::enum_type => {
                let span = self.span(&inner);
                TypeExpr::Enum {
                    variants: inner.into_inner().map(|v| self.ident(v)).collect(),
                    span,
                }
            }
            _ => TypeExpr::Named(self.ident(inner)),
        })
    }

    pub(super) fn param_default(&self, p: P) -> Option<Expr> {
        let inner = p.into_inner().next()?;
        match inner.as_rule() {
            Rule::range_value => {
                let span = self.span(&inner);
                let mut it = inner.into_inner();
                let lo = self.expr(it.next()?)?;
                let hi = self.expr(it.next()?)?;
                Some(Expr {
                    kind: ExprKind::Range {
                        lo: Box::new(lo),
                        hi: Box::new(hi),
                    },
                    span,
                })
            }
            _ => self.expr(inner),
        }
    }

    pub(super) fn range(&self, p: P) -> Option<RangeExpr> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let lo = self.expr(it.next()?)?;
        let hi = self.expr(it.next()?)?;
        let span = Span {
            start: lo.span.start,
            ..span
        };
        Some(RangeExpr {
            lo: Box::new(lo),
            hi: Box::new(hi),
            span,
        })
    }

    pub(super) fn animate(&self, p: P) -> Option<Animation> {
        let span = self.span(&p);
        let mut interpolation = None;
        let mut keys = Vec::new();
        for i in p.into_inner() {
            match i.as_rule() {
                Rule::ident => interpolation = Some(self.ident(i)),
                Rule::keyframe => {
                    let kspan = self.span(&i);
                    let mut it = i.into_inner();
                    let time = self.expr(it.next()?)?;
                    let value = self.expr(it.next()?)?;
                    keys.push(Keyframe {
                        time,
                        value,
                        span: kspan,
                    });
                }
                _ => {}
            }
        }
        Some(Animation {
            interpolation,
            keys,
            span,
        })
    }

    pub(super) fn texture_decl(&self, p: P) -> Option<TextureDecl> {
        let span = self.span(&p);
        let mut doc = String::new();
        let mut name = None;
        let mut source = None;
        let mut options = Vec::new();
        for i in p.into_inner() {
            match i.as_rule() {
                Rule::doc_comment => doc = self.doc(i),
                Rule::ident => name = Some(self.ident(i)),
                Rule::call => source = Some(self.call(i)?),
                Rule::settings_block => options = self.settings(i),
                _ => {}
            }
        }
        Some(TextureDecl {
            doc,
            name: name?,
            source: source?,
            options,
            span,
        })
    }

    pub(super) fn settings(&self, p: P) -> Vec<Setting> {
        p.into_inner().filter_map(|s| self.setting(s)).collect()
    }

    pub(super) fn setting(&self, p: P) -> Option<Setting> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let key = self.ident(it.next()?);
        let value = self.expr(it.next()?)?;
        Some(Setting { key, value, span })
    }

    pub(super) fn pass_decl(&self, p: P) -> Option<PassDecl> {
        let span = self.span(&p);
        let mut doc = String::new();
        let mut name = None;
        let mut kind = None;
        let mut scale = None;
        let mut modifiers = Vec::new();
        let mut body = PassBody::default();
        for i in p.into_inner() {
            match i.as_rule() {
                Rule::doc_comment => doc = self.doc(i),
                Rule::ident => name = Some(self.ident(i)),
                Rule::pass_kind => {
                    let kspan = self.span(&i);
                    let mut it = i.into_inner();
                    let k = self.ident(it.next()?);
                    kind = Some(PassKind {
                        kind: k,
                        args: it
                            .map(|a| {
                                let span = self.span(&a);
                                let mut parts = a.into_inner();
                                let name = parts.next().map(|n| self.ident(n));
                                let field = parts.next().map(|f| self.ident(f));
                                name.map(|name| KindArg { name, field, span })
                            })
                            .collect::<Option<Vec<_>>>()?,
                        span: kspan,
                    });
                }
                Rule::scale_clause => scale = Some(self.expr(i.into_inner().next()?)?),
                Rule::pass_modifier => {
                    let mspan = self.span(&i);
                    let mut it = i.into_inner();
                    let key = self.ident(it.next()?);
                    let value = self.expr(it.next()?)?;
                    modifiers.push(Setting {
                        key,
                        value,
                        span: mspan,
                    });
                }
                Rule::pass_body => body = self.pass_body(i)?,
                _ => {}
            }
        }
        Some(PassDecl {
            doc,
            name: name?,
            kind: kind?,
            scale,
            modifiers,
            body,
            span,
        })
    }

    pub(super) fn pass_body(&self, p: P) -> Option<PassBody> {
        let mut body = PassBody::default();
        for stmt in p.into_inner() {
            let Some(s) = stmt.into_inner().next() else { continue };
            match s.as_rule() {
                Rule::line_set => body.line_sets.push(self.line_set(s)?),
                Rule::vertex_block => {
                    if let Some(block) = s.into_inner().next() {
                        body.vertex.extend(self.settings(block));
                    }
                }
                Rule::let_stmt => body.lets.push(self.let_stmt(s)?),
                Rule::out_stmt => {
                    let span = self.span(&s);
                    let mut it = s.into_inner();
                    let name = self.ident(it.next()?);
                    let format = self.ident(it.next()?);
                    let value = self.expr(it.next()?)?;
                    let settings = it.next().map(|b| self.settings(b)).unwrap_or_default();
                    body.outputs.push(OutputTarget {
                        name,
                        format,
                        value,
                        settings,
                        span,
                    });
                }
                Rule::setting => body.settings.push(self.setting(s)?),
                Rule::state_stmt => {
                    let span = self.span(&s);
                    let mut it = s.into_inner();
                    let name = self.ident(it.next()?);
                    let ty = self.ident(it.next()?);
                    let first = self.expr(it.next()?)?;
                    body.states.push(StateDecl { name, ty, first, span });
                }
                Rule::reduce_stmt => {
                    let span = self.span(&s);
                    let mut it = s.into_inner();
                    let name = self.ident(it.next()?);
                    let ty = self.ident(it.next()?);
                    let op = self.ident(it.next()?);
                    let value = self.expr(it.next()?)?;
                    body.reductions.push(Reduction {
                        name,
                        ty,
                        op,
                        value,
                        span,
                    });
                }
                Rule::update_stmt => {
                    let span = self.span(&s);
                    let mut it = s.into_inner();
                    let name = self.ident(it.next()?);
                    let value = self.expr(it.next()?)?;
                    body.updates.push(StateUpdate { name, value, span });
                }
                _ => {}
            }
        }
        Some(body)
    }

    /// `set name { edges: a | b(arg), key: value, ... }`.
    fn line_set(&self, p: P) -> Option<LineSetDecl> {
        let span = self.span(&p);
        let mut it = p.into_inner().filter(|i| i.as_rule() != Rule::set_keyword);
        let name = self.ident(it.next()?);
        let (mut edges, mut settings) = (Vec::new(), Vec::new());
        for item in it {
            let Some(inner) = item.into_inner().next() else {
                continue;
            };
            match inner.as_rule() {
                Rule::edge_union => {
                    let union_span = self.span(&inner);
                    let mut terms = Vec::new();
                    for term in inner.into_inner().filter(|t| t.as_rule() == Rule::edge_term) {
                        let term_span = self.span(&term);
                        let mut parts = term.into_inner();
                        let name = self.ident(parts.next()?);
                        let arg = match parts.next() {
                            Some(e) => Some(self.expr(e)?),
                            None => None,
                        };
                        terms.push(EdgeTerm {
                            name,
                            arg,
                            span: term_span,
                        });
                    }
                    edges.push(EdgeUnion {
                        terms,
                        span: union_span,
                    });
                }
                Rule::setting => settings.push(self.setting(inner)?),
                _ => {}
            }
        }
        Some(LineSetDecl {
            name,
            edges,
            settings,
            span,
        })
    }

    pub(super) fn let_stmt(&self, p: P) -> Option<LetBinding> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let name = self.ident(it.next()?);
        let value = self.expr(it.next()?)?;
        Some(LetBinding { name, value, span })
    }

    pub(super) fn output_decl(&self, p: P) -> Option<OutputDecl> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let pass = self.ident(it.next()?);
        let target = self.ident(it.next()?);
        Some(OutputDecl { pass, target, span })
    }
}
