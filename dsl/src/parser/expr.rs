//! Expressions, pest pairs → AST: operator, field, unary and `else if`
//! chains are built in loops that count the tree's depth (E0006 past
//! `MAX_EXPR_DEPTH`), so no chain makes the parser or the AST recurse.

use super::*;

impl Builder {
    // ----------------------------------------------------------- expressions

    pub(super) fn expr(&self, p: P) -> Option<Expr> {
        match p.as_rule() {
            Rule::expr => self.expr(p.into_inner().next()?),
            Rule::or_expr | Rule::and_expr | Rule::sum | Rule::product | Rule::comparison => self.binary_chain(p),
            Rule::unary => self.unary(p),
            Rule::postfix => self.postfix(p),
            Rule::primary => self.primary(p),
            _ => self.primary_inner(p),
        }
    }

    /// An expression tree deeper than [`MAX_EXPR_DEPTH`]: recorded, and
    /// `None`, so the tree is not built further (its derived `Clone` and
    /// `Drop` recurse, and so does every compiler stage).
    pub(super) fn too_deep(&self, at: Span) -> Option<Expr> {
        self.limit_errors.borrow_mut().push(
            Diagnostic::error(
                codes::EXPRESSION_TOO_DEEP,
                format!("expression more than {MAX_EXPR_DEPTH} levels deep"),
            )
            .with_primary(at, format!("level {} is here", MAX_EXPR_DEPTH + 1))
            .with_help("each operator of a chain like `a + b + c` is a level; give parts of it names with `let`"),
        );
        None
    }

    /// Left-associative chains: `a op b op c`. Built in a loop, with the
    /// tree's depth kept as it grows.
    pub(super) fn binary_chain(&self, p: P) -> Option<Expr> {
        let mut it = p.into_inner();
        let mut lhs = self.expr(it.next()?)?;
        let mut depth = lhs.depth();
        while let Some(op) = it.next() {
            let rhs = self.expr(it.next()?)?;
            depth = 1 + depth.max(rhs.depth());
            if depth > MAX_EXPR_DEPTH {
                return self.too_deep(self.span(&op));
            }
            let op = match op.as_str() {
                "+" => BinOp::Add,
                "-" => BinOp::Sub,
                "*" => BinOp::Mul,
                "/" => BinOp::Div,
                "%" => BinOp::Rem,
                "<" => BinOp::Lt,
                "<=" => BinOp::Le,
                ">" => BinOp::Gt,
                ">=" => BinOp::Ge,
                "==" => BinOp::Eq,
                "!=" => BinOp::Ne,
                "&&" => BinOp::And,
                _ => BinOp::Or,
            };
            let span = lhs.span.to(rhs.span);
            lhs = Expr {
                kind: ExprKind::Binary {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span,
            };
        }
        Some(lhs)
    }

    pub(super) fn unary(&self, p: P) -> Option<Expr> {
        let mut ops = Vec::new();
        let mut operand = None;
        for i in p.into_inner() {
            match i.as_rule() {
                Rule::unary_op => ops.push((if i.as_str() == "-" { UnOp::Neg } else { UnOp::Not }, self.span(&i))),
                _ => operand = Some(self.expr(i)?),
            }
        }
        let mut e = operand?;
        let mut depth = e.depth();
        for (op, span) in ops.into_iter().rev() {
            depth += 1;
            if depth > MAX_EXPR_DEPTH {
                return self.too_deep(span);
            }
            let span = span.to(e.span);
            // Fold `-literal` so that `-1` is a literal (ranges, defaults).
            if let (UnOp::Neg, ExprKind::Number { value, is_int, unit }) = (op, &e.kind) {
                e = Expr {
                    kind: ExprKind::Number {
                        value: -value,
                        is_int: *is_int,
                        unit: *unit,
                    },
                    span,
                };
                continue;
            }
            e = Expr {
                kind: ExprKind::Unary {
                    op,
                    operand: Box::new(e),
                },
                span,
            };
        }
        Some(e)
    }

    pub(super) fn postfix(&self, p: P) -> Option<Expr> {
        let mut it = p.into_inner();
        let mut e = self.expr(it.next()?)?;
        let mut depth = e.depth();
        for f in it {
            let field = self.ident(f);
            depth += 1;
            if depth > MAX_EXPR_DEPTH {
                return self.too_deep(field.span);
            }
            let span = e.span.to(field.span);
            e = Expr {
                kind: ExprKind::Field {
                    base: Box::new(e),
                    field,
                },
                span,
            };
        }
        Some(e)
    }

    pub(super) fn primary(&self, p: P) -> Option<Expr> {
        let span = self.span(&p);
        let inner = p.into_inner().next()?;
        if inner.as_rule() == Rule::expr {
            // Parenthesised: keep the inner expression, widen the span to the parentheses.
            let e = self.expr(inner)?;
            return Some(Expr { span, ..e });
        }
        self.primary_inner(inner)
    }

    pub(super) fn primary_inner(&self, p: P) -> Option<Expr> {
        let span = self.span(&p);
        let kind = match p.as_rule() {
            Rule::number => {
                let mut it = p.into_inner();
                let digits = it.next()?.as_str();
                let value: f64 = digits.parse().ok()?;
                let is_int = !digits.contains(['.', 'e', 'E']);
                let unit = it.next().map(|u| match u.as_str() {
                    "px" => UnitSuffix::Px,
                    "%" => UnitSuffix::Percent,
                    "mm" => UnitSuffix::Mm,
                    "m" => UnitSuffix::M,
                    "s" => UnitSuffix::S,
                    "Hz" => UnitSuffix::Hz,
                    _ => UnitSuffix::Deg,
                });
                ExprKind::Number { value, is_int, unit }
            }
            Rule::boolean => ExprKind::Bool(p.as_str() == "true"),
            Rule::color => {
                let hex = &p.as_str()[1..];
                let byte =
                    |i: usize| u8::from_str_radix(hex.get(i..i + 2).unwrap_or("ff"), 16).unwrap_or(255) as f64 / 255.0;
                let a = if hex.len() == 8 { byte(6) } else { 1.0 };
                ExprKind::Color([byte(0), byte(2), byte(4), a])
            }
            Rule::string => ExprKind::Str(self.string(p)),
            Rule::ident | Rule::object_name => ExprKind::Name(self.ident(p)),
            Rule::call => ExprKind::Call(self.call(p)?),
            Rule::if_expr => return self.if_expr(p),
            Rule::block_expr => return self.block(p),
            _ => self.expr(p)?.kind,
        };
        Some(Expr { kind, span })
    }

    /// `if c { a } else if d { b } ... else { z }`: the `else if`s are a
    /// flat list in the grammar, folded here from the last into nested `If`s
    /// (each spanning from its `if` to the end), in a loop.
    pub(super) fn if_expr(&self, p: P) -> Option<Expr> {
        let end = self.offset.get() + p.as_span().end();
        let start = self.offset.get() + p.as_span().start();
        let mut parts = p.into_inner();
        let cond = self.expr(parts.next()?)?;
        let then = self.block(parts.next()?)?;
        let mut branches = vec![(start, cond, then)];
        let mut otherwise = None;
        for part in parts {
            if part.as_rule() == Rule::else_if {
                let at = self.offset.get() + part.as_span().start();
                let mut it = part.into_inner();
                let cond = self.expr(it.next()?)?;
                let then = self.block(it.next()?)?;
                branches.push((at, cond, then));
            } else {
                otherwise = Some(self.block(part)?);
            }
        }
        let mut e = otherwise?;
        let mut depth = e.depth();
        for (at, cond, then) in branches.into_iter().rev() {
            depth = 1 + depth.max(cond.depth()).max(then.depth());
            let span = Span::new(self.file, at, end);
            if depth > MAX_EXPR_DEPTH {
                return self.too_deep(Span::new(self.file, at, at + 2));
            }
            e = Expr {
                kind: ExprKind::If {
                    cond: Box::new(cond),
                    then: Box::new(then),
                    otherwise: Box::new(e),
                },
                span,
            };
        }
        Some(e)
    }

    pub(super) fn block(&self, p: P) -> Option<Expr> {
        let span = self.span(&p);
        let mut lets = Vec::new();
        let mut value = None;
        for i in p.into_inner() {
            match i.as_rule() {
                Rule::let_stmt => lets.push(self.let_stmt(i)?),
                _ => value = Some(self.expr(i)?),
            }
        }
        let value = value?;
        if lets.is_empty() {
            return Some(Expr { span, ..value });
        }
        Some(Expr {
            kind: ExprKind::Block {
                lets,
                value: Box::new(value),
            },
            span,
        })
    }

    pub(super) fn call(&self, p: P) -> Option<Call> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let callee = self.ident(it.next()?);
        let mut args = Vec::new();
        for a in it {
            let aspan = self.span(&a);
            let parts: Vec<P> = a.into_inner().collect();
            let (name, value) = match parts.len() {
                2 => (Some(self.ident(parts[0].clone())), self.expr(parts[1].clone())?),
                _ => (None, self.expr(parts.into_iter().next()?)?),
            };
            args.push(Arg {
                name,
                value,
                span: aspan,
            });
        }
        Some(Call { callee, args, span })
    }
}
