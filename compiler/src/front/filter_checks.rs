//! What a filter style must be (Klein et al. 2000 §4.2: "apply an NPR
//! filter to each level independently"): it runs on one mip level of an
//! image and no scene, so it reads exactly one `filter_input()` texture and
//! has image passes only, and it builds no art-map of its own. A style is a
//! filter when an art-map names it or when it reads `filter_input()` (so
//! `npr check filter.npr` checks it as one). Checked on the resolved IR
//! (E0310), with the span of what is wrong.

use crate::ir::{Ir, PassKind, TextureSource};
use npr_diag::{codes, Diagnostic, Span};

/// Whether the style reads `filter_input()`: it is a filter.
pub fn reads_a_level(ir: &Ir) -> bool {
    ir.textures.iter().any(|t| t.source == TextureSource::FilterInput)
}

pub fn check(ir: &Ir, header: Option<Span>, diags: &mut Vec<Diagnostic>) {
    let inputs: Vec<_> = ir
        .textures
        .iter()
        .filter(|t| t.source == TextureSource::FilterInput)
        .collect();
    match inputs.as_slice() {
        [] => {
            let mut d = Diagnostic::error(codes::BAD_FILTER, "this filter style reads no level")
                .with_help("declare the level it filters: `texture level = filter_input()`");
            if let Some(span) = header {
                d = d.with_primary(span, "a filter of an art-map");
            }
            diags.push(d);
        }
        [_] => {}
        [_, second, ..] => diags.push(
            Diagnostic::error(codes::BAD_FILTER, "a filter reads one `filter_input()`")
                .with_primary(second.span, "a second input")
                .with_help("read the one level through a single `texture level = filter_input()`"),
        ),
    }
    for t in &ir.textures {
        if matches!(t.source, TextureSource::Artmap { .. }) {
            diags.push(
                Diagnostic::error(codes::BAD_FILTER, "an art-map inside a filter style")
                    .with_primary(t.span, "a filter cannot build art-maps of its own")
                    .with_help("filters run on one level of an image; declare the art-map in the style that uses it"),
            );
        }
    }
    for pass in &ir.passes {
        let kind = match pass.kind {
            PassKind::Image { .. } => continue,
            PassKind::Render { .. } => "a render pass",
            PassKind::Compute { .. } => "a compute pass",
            PassKind::Lines(_) => "a lines pass",
        };
        diags.push(
            Diagnostic::error(codes::BAD_FILTER, format!("{kind} in a filter style"))
                .with_primary(pass.name_span, "a filter has image passes only")
                .with_help("a filter runs on a texture level, with no scene: write `pass name: image(...) { ... }`"),
        );
    }
}
