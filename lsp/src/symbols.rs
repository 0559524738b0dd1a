//! Document symbols: the outline of the document's own params, textures,
//! passes (with their targets and `let`s) and output.

use super::analysis::{self, Analysis};
use super::position::LineIndex;
use lsp_types::{DocumentSymbol, SymbolKind};
use npr_diag::Span;
use npr_dsl::ast::Item;

pub fn outline(a: &Analysis) -> Vec<DocumentSymbol> {
    let index = LineIndex::new(a.text(a.root()));
    let sym =
        |name: &str, detail: String, kind: SymbolKind, span: Span, name_span: Span, children: Vec<DocumentSymbol>| {
            #[allow(deprecated)] // `deprecated` is a field every client still reads
            DocumentSymbol {
                name: name.to_string(),
                detail: Some(detail),
                kind,
                tags: None,
                deprecated: None,
                range: index.range(span.start as usize, span.end as usize),
                selection_range: index.range(name_span.start as usize, name_span.end as usize),
                children: (!children.is_empty()).then_some(children),
            }
        };
    let mut out = Vec::new();
    for item in &a.loaded.root.items {
        match item {
            Item::Param(p) => out.push(sym(
                &p.name.name,
                analysis::snippet(a, p.ty.span()).to_string(),
                if p.per_object {
                    SymbolKind::FIELD
                } else {
                    SymbolKind::VARIABLE
                },
                p.span,
                p.name.span,
                Vec::new(),
            )),
            Item::Texture(t) => out.push(sym(
                &t.name.name,
                format!("{}(...)", t.source.callee.name),
                SymbolKind::CONSTANT,
                t.span,
                t.name.span,
                Vec::new(),
            )),
            Item::Pass(p) => {
                let mut children: Vec<DocumentSymbol> = analysis::targets(p)
                    .into_iter()
                    .map(|t| {
                        sym(
                            t.name,
                            format!("{} {}", t.kind, t.ty),
                            SymbolKind::FIELD,
                            t.span,
                            t.span,
                            Vec::new(),
                        )
                    })
                    .collect();
                children.extend(p.body.lets.iter().map(|l| {
                    sym(
                        &l.name.name,
                        "let".into(),
                        SymbolKind::VARIABLE,
                        l.span,
                        l.name.span,
                        Vec::new(),
                    )
                }));
                out.push(sym(
                    &p.name.name,
                    analysis::snippet(a, p.kind.span).to_string(),
                    SymbolKind::CLASS,
                    p.span,
                    p.name.span,
                    children,
                ));
            }
            Item::Output(o) => out.push(sym(
                "output",
                format!("{}.{}", o.pass.name, o.target.name),
                SymbolKind::EVENT,
                o.span,
                o.span,
                Vec::new(),
            )),
            Item::Use(_) => {}
        }
    }
    out
}
