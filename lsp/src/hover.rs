//! Hover: the Markdown shown for what is under the cursor. Operators,
//! builtins, pass kinds and formats say what `npr doc` says
//! (`npr_compiler::describe`); params, textures, passes and targets show their
//! declaration and doc comment.

use super::analysis::{snippet, Analysis};
use super::symbol::Symbol;
use npr_compiler::describe;

pub fn markdown(a: &Analysis, symbol: &Symbol) -> String {
    match symbol {
        Symbol::Let(l) => format!("```npr\nlet {} = {}\n```", l.name.name, snippet(a, l.value.span)),
        Symbol::Param(p) => {
            let mut s = format!(
                "```npr\n{}param {}: {} = {}",
                if p.per_object { "object " } else { "" },
                p.name.name,
                snippet(a, p.ty.span()),
                snippet(a, p.default.span)
            );
            if let Some(r) = &p.range {
                s.push_str(&format!(" in {}", snippet(a, r.span)));
            }
            s.push_str("\n```");
            with_doc(s, &p.doc)
        }
        Symbol::Texture(t) => with_doc(
            format!("```npr\ntexture {} = {}\n```", t.name.name, snippet(a, t.source.span)),
            &t.doc,
        ),
        Symbol::Pass(p) => {
            let mut s = format!("```npr\npass {}: {}\n```", p.name.name, snippet(a, p.kind.span));
            let targets = super::analysis::targets(p);
            if !targets.is_empty() {
                s.push_str("\n\n");
                for t in targets {
                    s.push_str(&format!("- `{} {}: {}`\n", t.kind, t.name, t.ty));
                }
            }
            with_doc(s, &p.doc)
        }
        Symbol::Target(p, t) => format!(
            "```npr\n{} {}: {}\n```\n\nof pass `{}`",
            t.kind, t.name, t.ty, p.name.name
        ),
        Symbol::Builtin(spelling, b) => describe::builtins::markdown(spelling, *b),
        Symbol::Operator(op) => describe::operator_markdown(op, "###"),
        Symbol::Intrinsic(name, i) => format!("```npr\n{name}(...)\n```\n\n{}", describe::language::intrinsic_doc(*i)),
        Symbol::Special(written, what) => format!("```npr\n{written}\n```\n\n{what}"),
        Symbol::OperatorParam(op, p) => {
            let range = describe::range_text(p);
            format!(
                "```npr\n{}: {}\n```\n\n{}\n\n- unit: {}\n- default: {}\n- range: {}\n\nparameter of `{}`",
                p.name,
                describe::ty_name(p.ty),
                p.doc,
                if p.unit == npr_stdlib::Unit::None {
                    "none".into()
                } else {
                    p.unit.name().to_string()
                },
                describe::default_text(p),
                if range.is_empty() { "any".into() } else { range },
                op.name
            )
        }
        Symbol::PassKind(kind) => {
            let matching: Vec<String> = describe::language::PASS_KINDS
                .iter()
                .filter(|(k, _)| k.split('(').next() == Some(kind.as_str()))
                .map(|(k, what)| format!("- `{k}`: {what}"))
                .collect();
            if matching.is_empty() {
                format!("`{kind}`: not a pass kind npr has")
            } else {
                format!("**{kind}** pass\n\n{}", matching.join("\n"))
            }
        }
        Symbol::Format(name, f) => format!(
            "```npr\n{name}\n```\n\nTarget format: {}.",
            describe::language::format_text(*f)
        ),
    }
}

fn with_doc(mut s: String, doc: &str) -> String {
    if !doc.trim().is_empty() {
        s.push_str("\n\n");
        s.push_str(doc.trim());
    }
    s
}
