//! Go to definition: where a param, texture, pass, target or `let` is
//! declared, in the document or in a file it `use`s.

use super::analysis::Analysis;
use super::position::LineIndex;
use super::symbol::Symbol;
use lsp_types::Location;
use npr_diag::Span;

/// The span of the name in the symbol's declaration.
pub fn declared_at(symbol: &Symbol) -> Option<Span> {
    match symbol {
        Symbol::Let(l) => Some(l.name.span),
        Symbol::Param(p) => Some(p.name.span),
        Symbol::Texture(t) => Some(t.name.span),
        Symbol::Pass(p) => Some(p.name.span),
        Symbol::Target(_, t) => Some(t.span),
        _ => None,
    }
}

/// A span of any file of the analysis as an LSP location.
pub fn location(a: &Analysis, span: Span) -> Option<Location> {
    let path = a.file_path(span.file)?;
    let absolute = if path.is_absolute() {
        path
    } else {
        std::env::current_dir().ok()?.join(path)
    };
    let uri = super::uri::from_path(&absolute)?;
    let index = LineIndex::new(a.text(span.file));
    Some(Location::new(uri, index.range(span.start as usize, span.end as usize)))
}
