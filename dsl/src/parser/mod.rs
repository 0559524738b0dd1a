//! pest pairs → AST. One build function per grammar rule; syntax errors
//! become diagnostics, and parsing recovers at top-level items so one run
//! reports every broken declaration.
//!
//! - `recovery.rs`: re-parsing a file item by item after a syntax error;
//! - `items.rs`: the top-level declarations and pass bodies;
//! - `expr.rs`: expressions, built in loops that keep the tree's depth.

mod expr;
mod items;
mod recovery;

use recovery::{content_len, recover};

use crate::ast::*;
use crate::grammar::{NprParser, Rule};
use npr_diag::limits::{MAX_EXPR_DEPTH, MAX_SOURCE_BYTES};
use npr_diag::{codes, Diagnostic, FileId, Span};
use pest::iterators::Pair;
use pest::Parser;
use std::cell::{Cell, RefCell};

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
