//! The names in a document that hover and go-to-definition act on: every
//! name read, `pass.target` field, call, named argument, format and
//! declared name of the document's own AST, with its span; [`at`] finds the
//! innermost one under the cursor.

use npr_dsl::ast::{Ast, Call, Expr, ExprKind, Ident, Item, PassDecl};

pub enum Token<'a> {
    /// A bare name read (`bands`, `uv`, `shade` in `shade.c`); `member` is
    /// the field written after it, if any (`dir` of `light.dir`).
    Name {
        ident: &'a Ident,
        member: Option<&'a Ident>,
    },
    /// The field of `base.field`, where the base is a name.
    Field { base: &'a Ident, field: &'a Ident },
    /// The callee of a call.
    Callee(&'a Call),
    /// The name of a named argument of `call`.
    ArgName { call: &'a Call, name: &'a Ident },
    /// A target format after `out x:`.
    Format(&'a Ident),
    /// A pass kind (`render`, `image`, `compute`).
    PassKind(&'a Ident),
    /// The name in a declaration (a param, texture, pass, let, output).
    Declared(&'a Ident),
}

impl Token<'_> {
    fn span(&self) -> npr_diag::Span {
        match self {
            Token::Name { ident, .. } => ident.span,
            Token::Field { field, .. } => field.span,
            Token::Callee(call) => call.callee.span,
            Token::ArgName { name, .. } => name.span,
            Token::Format(i) | Token::PassKind(i) | Token::Declared(i) => i.span,
        }
    }
}

/// The innermost token whose span holds byte `offset` (the end counts, so
/// a cursor just after a name is on it), and the pass it is in.
pub fn at(ast: &Ast, offset: usize) -> Option<(Token<'_>, Option<&PassDecl>)> {
    let offset = offset as u32;
    let mut tokens = Vec::new();
    let mut in_pass = None;
    for item in &ast.items {
        let span = item_span(item);
        if offset < span.start || offset > span.end {
            continue;
        }
        if let Item::Pass(p) = item {
            in_pass = Some(p);
        }
        collect_item(item, &mut tokens);
    }
    tokens
        .into_iter()
        .filter(|t| t.span().start <= offset && offset <= t.span().end)
        .min_by_key(|t| t.span().end - t.span().start)
        .map(|t| (t, in_pass))
}

fn item_span(item: &Item) -> npr_diag::Span {
    match item {
        Item::Use(u) => u.span,
        Item::Param(p) => p.span,
        Item::Texture(t) => t.span,
        Item::Pass(p) => p.span,
        Item::Output(o) => o.span,
    }
}

fn collect_item<'a>(item: &'a Item, out: &mut Vec<Token<'a>>) {
    match item {
        Item::Use(_) => {}
        Item::Param(p) => {
            out.push(Token::Declared(&p.name));
            collect_expr(&p.default, out);
            if let Some(r) = &p.range {
                collect_expr(&r.lo, out);
                collect_expr(&r.hi, out);
            }
        }
        Item::Texture(t) => {
            out.push(Token::Declared(&t.name));
            collect_call(&t.source, out);
            for s in &t.options {
                collect_expr(&s.value, out);
            }
        }
        Item::Pass(p) => {
            out.push(Token::Declared(&p.name));
            out.push(Token::PassKind(&p.kind.kind));
            for arg in &p.kind.args {
                out.push(Token::Name {
                    ident: &arg.name,
                    member: arg.field.as_ref(),
                });
                if let Some(f) = &arg.field {
                    out.push(Token::Field {
                        base: &arg.name,
                        field: f,
                    });
                }
            }
            for e in p.scale.iter().chain(p.modifiers.iter().map(|s| &s.value)) {
                collect_expr(e, out);
            }
            let b = &p.body;
            for l in &b.lets {
                out.push(Token::Declared(&l.name));
                collect_expr(&l.value, out);
            }
            for o in &b.outputs {
                out.push(Token::Declared(&o.name));
                out.push(Token::Format(&o.format));
                collect_expr(&o.value, out);
                for s in &o.settings {
                    collect_expr(&s.value, out);
                }
            }
            for s in b.vertex.iter().chain(&b.settings) {
                collect_expr(&s.value, out);
            }
            for s in &b.states {
                out.push(Token::Declared(&s.name));
                collect_expr(&s.first, out);
            }
            for r in &b.reductions {
                out.push(Token::Declared(&r.name));
                collect_expr(&r.value, out);
            }
            for u in &b.updates {
                out.push(Token::Name {
                    ident: &u.name,
                    member: None,
                });
                collect_expr(&u.value, out);
            }
        }
        Item::Output(o) => {
            out.push(Token::Name {
                ident: &o.pass,
                member: Some(&o.target),
            });
            out.push(Token::Field {
                base: &o.pass,
                field: &o.target,
            });
        }
    }
}

fn collect_call<'a>(call: &'a Call, out: &mut Vec<Token<'a>>) {
    out.push(Token::Callee(call));
    for a in &call.args {
        if let Some(n) = &a.name {
            out.push(Token::ArgName { call, name: n });
        }
        collect_expr(&a.value, out);
    }
}

/// Every token of an expression tree, walked with an explicit stack (the
/// tree may be as deep as the parser allows).
fn collect_expr<'a>(e: &'a Expr, out: &mut Vec<Token<'a>>) {
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match &e.kind {
            ExprKind::Name(ident) => out.push(Token::Name { ident, member: None }),
            ExprKind::Field { base, field } => {
                if let ExprKind::Name(b) = &base.kind {
                    out.push(Token::Name {
                        ident: b,
                        member: Some(field),
                    });
                    out.push(Token::Field { base: b, field });
                    continue;
                }
                stack.push(base);
                continue;
            }
            ExprKind::Call(call) => {
                out.push(Token::Callee(call));
                for a in &call.args {
                    if let Some(n) = &a.name {
                        out.push(Token::ArgName { call, name: n });
                    }
                }
            }
            ExprKind::Block { lets, .. } => {
                for l in lets {
                    out.push(Token::Declared(&l.name));
                }
            }
            _ => {}
        }
        stack.extend(e.children());
    }
}
