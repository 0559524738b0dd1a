//! Where each texture's file is named in the style: the span of the path
//! in `image("…")`, so that errors found when the file is opened (by
//! `npr check` and `npr render`, in the runner, which knows no spans) point
//! at it. The IR keeps the declaration's span; the path's is found again
//! inside it, in the source text.

use crate::ir::{Ir, TextureSource};
use npr_diag::{SourceMap, Span};

/// Per texture, in manifest order (the IR's): the path literal of an
/// `image(...)` source, or the whole declaration for generated sources
/// (and should the literal not be found).
pub fn texture_spans(ir: &Ir, sources: &SourceMap) -> Vec<Span> {
    ir.textures
        .iter()
        .map(|t| match &t.source {
            TextureSource::Image { .. } | TextureSource::Artmap { .. } => {
                path_literal(sources, t.span).unwrap_or(t.span)
            }
            _ => t.span,
        })
        .collect()
}

/// The first string literal after `image(` within `decl`, past its doc
/// comment (which may quote anything).
fn path_literal(sources: &SourceMap, decl: Span) -> Option<Span> {
    let text = sources.get(decl.file)?.text.get(decl.range())?;
    let mut code = 0;
    for line in text.split_inclusive('\n') {
        if !line.trim_start().starts_with("///") {
            break;
        }
        code += line.len();
    }
    let call = code
        + text[code..]
            .match_indices("image")
            .find(|(i, m)| text[code + i + m.len()..].trim_start().starts_with('('))?
            .0;
    let open = call + text[call..].find('"')?;
    let mut escaped = false;
    for (i, c) in text[open + 1..].char_indices() {
        match c {
            '\\' if !escaped => escaped = true,
            '"' if !escaped => {
                let start = decl.start as usize + open;
                return Some(Span::new(decl.file, start, start + i + 2));
            }
            _ => escaped = false,
        }
    }
    None
}
