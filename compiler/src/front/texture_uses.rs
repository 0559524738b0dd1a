//! A rip-map is an atlas of levels, not a texture to sample directly: it is
//! read only by `sample_ripmap`, which selects a level per axis (Klein et
//! al. 2000 §4.2, Fig. 7–8), and `sample_ripmap` reads only a rip-map.
//! Checked after typecheck, on every use of a declared texture (E0201).

use crate::ir::{Callee, ExprKind, Ir, TextureSource};
use npr_diag::{codes, Diagnostic};
use std::collections::HashSet;

const RIPMAP_READER: &str = "sample_ripmap";

pub fn check(ir: &Ir, diags: &mut Vec<Diagnostic>) {
    let is_rip = |id: crate::ir::TextureId| {
        matches!(
            ir.textures[id.0 as usize].source,
            TextureSource::Artmap { rip: true, .. }
        )
    };
    let reader = npr_stdlib::all().iter().position(|o| o.name == RIPMAP_READER);
    let mut read_by_reader = HashSet::new();
    for e in &ir.exprs {
        let ExprKind::Call {
            callee: Callee::Operator(op),
            args,
        } = &e.kind
        else {
            continue;
        };
        if Some(*op as usize) != reader {
            continue;
        }
        let Some(&tex) = args.first() else { continue };
        read_by_reader.insert(tex);
        match ir.expr(tex).kind {
            ExprKind::Texture(id) if is_rip(id) => {}
            _ => diags.push(
                Diagnostic::error(codes::TYPE_MISMATCH, "`sample_ripmap` reads a rip-map")
                    .with_primary(ir.expr(tex).span, "not a `ripmap(...)` texture")
                    .with_help("declare `texture t = ripmap(image(\"…\"), filter: \"…\")`, or read this one with `sample_biased`"),
            ),
        }
    }
    for (i, e) in ir.exprs.iter().enumerate() {
        if let ExprKind::Texture(id) = e.kind {
            if is_rip(id) && !read_by_reader.contains(&crate::ir::ExprId(i as u32)) {
                diags.push(
                    Diagnostic::error(codes::TYPE_MISMATCH, "a rip-map is read with `sample_ripmap`")
                        .with_primary(e.span, format!("`{}` is a rip-map", ir.textures[id.0 as usize].name))
                        .with_help(format!(
                            "write `sample_ripmap({}, uv)`: it picks a level for each axis",
                            ir.textures[id.0 as usize].name
                        )),
                );
            }
        }
    }
}
