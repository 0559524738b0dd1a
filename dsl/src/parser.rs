//! pest pairs → AST. One build function per grammar rule; syntax errors
//! become diagnostics, and parsing recovers at top-level items so one run
//! reports every broken declaration.

use crate::ast::*;
use crate::limits::{MAX_EXPR_DEPTH, MAX_SOURCE_BYTES};
use crate::{codes, Diagnostic, FileId, Span};
use pest::iterators::Pair;
use pest::Parser;
use std::cell::{Cell, RefCell};

#[derive(pest_derive::Parser)]
#[grammar = "grammar.pest"]
struct NprParser;

type P<'a> = Pair<'a, Rule>;

struct Builder {
    file: FileId,
    /// Limit errors found while building (an expression past
    /// [`MAX_EXPR_DEPTH`]); the item that holds one is dropped.
    limit_errors: RefCell<Vec<Diagnostic>>,
    /// Where the text being built starts in the file: 0, or a declaration's
    /// start when recovering item by item.
    offset: Cell<usize>,
}

/// Parse a whole file. On a syntax error, re-parse item by item.
///
/// A file over [`MAX_SOURCE_BYTES`] or nested past `MAX_NESTING` is refused
/// before pest sees it (pest recurses once per nesting level).
pub fn parse(file: FileId, source: &str) -> (Ast, Vec<Diagnostic>) {
    // The tokens tried at the furthest position make the syntax messages
    // (`syntax_error`).
    pest::set_error_detail(true);
    if let Some(d) = too_large(file, source)
        .or_else(|| crate::nesting::check(file, source))
        .or_else(|| crate::syntax_error::unclosed_comment_check(file, source))
    {
        return (Ast::default(), vec![d]);
    }
    let b = Builder {
        file,
        limit_errors: RefCell::new(Vec::new()),
        offset: Cell::new(0),
    };
    let (ast, mut diags) = parse_checked(&b, source);
    diags.append(&mut b.limit_errors.borrow_mut());
    (ast, diags)
}

fn too_large(file: FileId, source: &str) -> Option<Diagnostic> {
    if source.len() <= MAX_SOURCE_BYTES {
        return None;
    }
    let mut at = MAX_SOURCE_BYTES;
    while !source.is_char_boundary(at) {
        at -= 1;
    }
    Some(
        Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!(
                "the file is {} bytes, over the {MAX_SOURCE_BYTES}-byte limit",
                source.len()
            ),
        )
        .with_primary(Span::new(file, at, at), "the limit is reached here")
        .with_help("split the style into files joined with `use \"other.npr\"`"),
    )
}

fn parse_checked(b: &Builder, source: &str) -> (Ast, Vec<Diagnostic>) {
    match NprParser::parse(Rule::file, source) {
        Ok(mut pairs) => {
            let mut ast = Ast::default();
            let mut diags = Vec::new();
            if let Some(file_pair) = pairs.next() {
                for p in file_pair.into_inner() {
                    b.top_level(p, &mut ast, &mut diags);
                }
            }
            if ast.style.is_none() {
                diags.push(missing_header(b.file));
            }
            (ast, diags)
        }
        Err(e) => recover(b, source, e),
    }
}

fn missing_header(file: FileId) -> Diagnostic {
    Diagnostic::error(codes::STYLE_HEADER, "missing `style` header")
        .with_primary(Span::new(file, 0, 0), "expected `style \"Name\"` here")
        .with_help("start the file with `style \"Name\"`")
}

/// Split the source at top-level declaration starts and parse each chunk alone.
fn recover(b: &Builder, source: &str, first: pest::error::Error<Rule>) -> (Ast, Vec<Diagnostic>) {
    let mut ast = Ast::default();
    let mut diags = Vec::new();
    let starts = item_starts(source);
    if starts.is_empty() {
        diags.push(b.syntax_error(first, source, "end of file"));
        return (ast, diags);
    }
    let mut reported = false;
    for (i, &start) in starts.iter().enumerate() {
        let end = starts.get(i + 1).copied().unwrap_or(source.len());
        let chunk = &source[start..end];
        // Each chunk is parsed alone; spans are shifted to file offsets (the
        // chunk is not padded: that made recovery quadratic in the file).
        b.offset.set(start);
        match NprParser::parse(Rule::single_item, chunk) {
            Ok(mut pairs) => {
                if let Some(p) = pairs.next() {
                    for inner in p.into_inner() {
                        b.top_level(inner, &mut ast, &mut diags);
                    }
                }
            }
            Err(e) => {
                reported = true;
                let eof = if end == source.len() {
                    "end of file"
                } else {
                    "the next declaration"
                };
                diags.push(shifted(b.syntax_error(e, chunk, eof), start));
                if let Some(name) = declared_name(chunk) {
                    ast.broken.push(name.to_string());
                }
            }
        }
    }
    b.offset.set(0);
    if !reported {
        diags.push(b.syntax_error(first, source, "end of file"));
    }
    if ast.style.is_none()
        && !diags.iter().any(|d| d.code == codes::STYLE_HEADER)
        && !source.trim_start().starts_with("style")
    {
        diags.push(missing_header(b.file));
    }
    (ast, diags)
}

/// `d` with its labels moved `by` bytes later (from a chunk into its file).
fn shifted(mut d: Diagnostic, by: usize) -> Diagnostic {
    for l in &mut d.labels {
        l.span.start += by as u32;
        l.span.end += by as u32;
    }
    d
}

/// The name a declaration chunk declares (`pass shade: ...` → `shade`),
/// read from its first words, so that a declaration that does not parse
/// still suppresses errors about its name being unknown.
fn declared_name(chunk: &str) -> Option<&str> {
    let code = chunk
        .lines()
        .map(str::trim_start)
        .find(|l| !l.is_empty() && !l.starts_with("//"))?;
    let mut words = code
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty());
    let mut first = words.next()?;
    if first == "object" {
        first = words.next()?;
    }
    match first {
        "param" | "pass" | "texture" => words.next(),
        _ => None,
    }
}

const ITEM_KEYWORDS: &[&str] = &["style", "use", "param", "object", "texture", "pass", "output", "///"];

/// Byte offsets where a top-level item starts: a keyword (or a doc comment)
/// at the start of a line, at brace depth 0 or in column 0. A doc comment run and the item
/// after it start together.
fn item_starts(source: &str) -> Vec<usize> {
    let mut starts = Vec::new();
    let mut depth: i32 = 0;
    let mut offset = 0;
    let mut in_doc_run = false;
    for line in source.split_inclusive('\n') {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        // A keyword at column 0 starts an item even inside an unclosed bracket:
        // that is the usual shape of a broken declaration followed by good ones.
        if depth <= 0 || indent == 0 {
            let starts_item = ITEM_KEYWORDS.iter().any(|k| {
                trimmed.starts_with(k)
                    && trimmed[k.len()..]
                        .chars()
                        .next()
                        .is_none_or(|c| !(c.is_alphanumeric() || c == '_'))
            });
            if starts_item {
                depth = 0;
                let is_doc = trimmed.starts_with("///");
                if !in_doc_run {
                    starts.push(offset + indent);
                }
                in_doc_run = is_doc;
            } else if !trimmed.is_empty() && !trimmed.starts_with("//") {
                in_doc_run = false;
            }
        }
        let code = line.split("//").next().unwrap_or("");
        for c in code.chars() {
            match c {
                '{' | '(' => depth += 1,
                '}' | ')' => depth -= 1,
                _ => {}
            }
        }
        if depth < 0 {
            depth = 0;
        }
        offset += line.len();
    }
    starts
}

/// The length of `text` up to the end of its last token (whitespace and
/// comments after it left out).
fn content_len(text: &str) -> usize {
    let ends_in_code = text.chars().next_back().is_some_and(|c| !c.is_whitespace() && c != '/');
    if ends_in_code {
        return text.len();
    }
    let bytes = text.as_bytes();
    let (mut i, mut end) = (0, 0);
    while i < bytes.len() {
        match bytes[i] {
            b'/' if bytes.get(i + 1) == Some(&b'/') && bytes.get(i + 2) != Some(&b'/') => {
                i = text[i..].find('\n').map_or(bytes.len(), |n| i + n);
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i = text[i + 2..].find("*/").map_or(bytes.len(), |n| i + 2 + n + 2);
            }
            b'"' => {
                // Strings inside a pair are whole: skip to the closing quote.
                let mut j = i + 1;
                while j < bytes.len() && bytes[j] != b'"' {
                    j += if bytes[j] == b'\\' { 2 } else { 1 };
                }
                i = (j + 1).min(bytes.len());
                end = i;
            }
            c if c.is_ascii_whitespace() => i += 1,
            _ => {
                i += 1;
                end = i;
            }
        }
    }
    end
}

impl Builder {
    /// The pair's span, ending at its last token: a rule whose last part is
    /// optional (`range_clause?`) also holds the whitespace and comments
    /// pest skipped looking for it, which would run the span onto the lines
    /// after the construct.
    fn span(&self, p: &P) -> Span {
        let s = p.as_span();
        let start = self.offset.get() + s.start();
        Span::new(self.file, start, start + content_len(s.as_str()))
    }

    fn syntax_error(&self, e: pest::error::Error<Rule>, source: &str, eof: &str) -> Diagnostic {
        crate::syntax_error::syntax_error(self.file, &e, source, eof)
    }

    fn top_level(&self, p: P, ast: &mut Ast, diags: &mut Vec<Diagnostic>) {
        match p.as_rule() {
            Rule::style_header => {
                let span = self.span(&p);
                let name = p.into_inner().next().map(|s| self.string(s)).unwrap_or_default();
                if ast.style.is_some() {
                    diags.push(
                        Diagnostic::error(codes::STYLE_HEADER, "the `style` header is repeated")
                            .with_primary(span, "second header")
                            .with_help("a file has one `style \"Name\"` line"),
                    );
                } else {
                    ast.style = Some(StyleHeader { name, span });
                }
            }
            Rule::item => {
                if let Some(inner) = p.into_inner().next() {
                    if let Some(item) = self.item(inner) {
                        ast.items.push(item);
                    }
                }
            }
            _ => {}
        }
    }

    fn item(&self, p: P) -> Option<Item> {
        Some(match p.as_rule() {
            Rule::use_decl => Item::Use(self.use_decl(p)?),
            Rule::param_decl => Item::Param(self.param_decl(p)?),
            Rule::texture_decl => Item::Texture(self.texture_decl(p)?),
            Rule::pass_decl => Item::Pass(self.pass_decl(p)?),
            Rule::output_decl => Item::Output(self.output_decl(p)?),
            _ => return None,
        })
    }

    fn ident(&self, p: P) -> Ident {
        Ident {
            name: p.as_str().to_string(),
            span: self.span(&p),
        }
    }

    fn string(&self, p: P) -> String {
        let raw = p.into_inner().next().map(|i| i.as_str()).unwrap_or("");
        let mut out = String::new();
        let mut chars = raw.chars();
        while let Some(c) = chars.next() {
            if c == '\\' {
                match chars.next() {
                    Some('n') => out.push('\n'),
                    Some(other) => out.push(other),
                    None => {}
                }
            } else {
                out.push(c);
            }
        }
        out
    }

    fn doc(&self, p: P) -> String {
        p.into_inner()
            .filter(|d| d.as_rule() == Rule::doc_text)
            .map(|d| {
                d.as_str()
                    .strip_prefix(' ')
                    .unwrap_or(d.as_str())
                    .trim_end()
                    .to_string()
            })
            .collect::<Vec<_>>()
            .join("\n")
    }

    fn use_decl(&self, p: P) -> Option<UseDecl> {
        let span = self.span(&p);
        let inner = p.into_inner().next()?;
        let target = match inner.as_rule() {
            Rule::string => UseTarget::File(self.string(inner)),
            _ => UseTarget::Module(inner.into_inner().map(|i| self.ident(i)).collect()),
        };
        Some(UseDecl { target, span })
    }

    fn param_decl(&self, p: P) -> Option<ParamDecl> {
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

    fn type_expr(&self, p: P) -> Option<TypeExpr> {
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

    fn param_default(&self, p: P) -> Option<Expr> {
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

    fn range(&self, p: P) -> Option<RangeExpr> {
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

    fn animate(&self, p: P) -> Option<Animation> {
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

    fn texture_decl(&self, p: P) -> Option<TextureDecl> {
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

    fn settings(&self, p: P) -> Vec<Setting> {
        p.into_inner().filter_map(|s| self.setting(s)).collect()
    }

    fn setting(&self, p: P) -> Option<Setting> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let key = self.ident(it.next()?);
        let value = self.expr(it.next()?)?;
        Some(Setting { key, value, span })
    }

    fn pass_decl(&self, p: P) -> Option<PassDecl> {
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

    fn pass_body(&self, p: P) -> Option<PassBody> {
        let mut body = PassBody::default();
        for stmt in p.into_inner() {
            let Some(s) = stmt.into_inner().next() else { continue };
            match s.as_rule() {
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

    fn let_stmt(&self, p: P) -> Option<LetBinding> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let name = self.ident(it.next()?);
        let value = self.expr(it.next()?)?;
        Some(LetBinding { name, value, span })
    }

    fn output_decl(&self, p: P) -> Option<OutputDecl> {
        let span = self.span(&p);
        let mut it = p.into_inner();
        let pass = self.ident(it.next()?);
        let target = self.ident(it.next()?);
        Some(OutputDecl { pass, target, span })
    }

    // ----------------------------------------------------------- expressions

    fn expr(&self, p: P) -> Option<Expr> {
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
    fn too_deep(&self, at: Span) -> Option<Expr> {
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
    fn binary_chain(&self, p: P) -> Option<Expr> {
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

    fn unary(&self, p: P) -> Option<Expr> {
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

    fn postfix(&self, p: P) -> Option<Expr> {
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

    fn primary(&self, p: P) -> Option<Expr> {
        let span = self.span(&p);
        let inner = p.into_inner().next()?;
        if inner.as_rule() == Rule::expr {
            // Parenthesised: keep the inner expression, widen the span to the parentheses.
            let e = self.expr(inner)?;
            return Some(Expr { span, ..e });
        }
        self.primary_inner(inner)
    }

    fn primary_inner(&self, p: P) -> Option<Expr> {
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
    fn if_expr(&self, p: P) -> Option<Expr> {
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

    fn block(&self, p: P) -> Option<Expr> {
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

    fn call(&self, p: P) -> Option<Call> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_ok(src: &str) -> Ast {
        let (ast, d) = parse(FileId(0), src);
        assert!(d.is_empty(), "{d:?}");
        ast
    }

    fn first_param_default(src: &str) -> Expr {
        let ast = parse_ok(src);
        match &ast.items[0] {
            Item::Param(p) => p.default.clone(),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn precedence_and_units() {
        let e = first_param_default("style \"S\"\nparam a: px = 1px + 2px * 3");
        let ExprKind::Binary {
            op: BinOp::Add, rhs, ..
        } = e.kind
        else {
            panic!("{e:?}")
        };
        assert!(matches!(rhs.kind, ExprKind::Binary { op: BinOp::Mul, .. }));
        let e = first_param_default("style \"S\"\nparam a: px = 50%");
        assert!(matches!(
            e.kind,
            ExprKind::Number {
                unit: Some(UnitSuffix::Percent),
                ..
            }
        ));
        let e = first_param_default("style \"S\"\nparam a: m = 10mm");
        assert!(matches!(e.kind, ExprKind::Number { value, unit: Some(UnitSuffix::Mm), .. } if value == 10.0));
    }

    #[test]
    fn colours_and_docs_and_spans() {
        let src = "style \"S\"\n/// Line one.\n/// Line two.\nobject param c: color = #ff800080 in 0..1\n";
        let ast = parse_ok(src);
        let Item::Param(p) = &ast.items[0] else { panic!() };
        assert_eq!(p.doc, "Line one.\nLine two.");
        assert!(p.per_object);
        let ExprKind::Color(c) = p.default.kind else { panic!() };
        assert!((c[1] - 128.0 / 255.0).abs() < 1e-12 && (c[3] - 128.0 / 255.0).abs() < 1e-12);
        assert_eq!(&src[p.default.span.range()], "#ff800080");
        assert_eq!(&src[p.name.span.range()], "c");
    }

    #[test]
    fn recovery_reports_each_broken_item() {
        let src = "style \"S\"\nparam a: float = (1 +\nparam b: float = 2\npass p: image() {\n  out c: r8unorm = ]\n}\noutput p.c\n";
        let (ast, d) = parse(FileId(0), src);
        assert_eq!(d.iter().filter(|d| d.code == codes::SYNTAX).count(), 2, "{d:?}");
        assert!(ast
            .items
            .iter()
            .any(|i| matches!(i, Item::Param(p) if p.name.name == "b")));
        assert!(ast.items.iter().any(|i| matches!(i, Item::Output(_))));
    }

    #[test]
    fn negative_literals_fold() {
        let e = first_param_default("style \"S\"\nparam a: float = -0.5");
        assert!(matches!(e.kind, ExprKind::Number { value, .. } if value == -0.5));
    }
}
