//! Completion, from the text before the cursor (a document being typed
//! rarely parses there): `pass.` → that pass's targets, `light.` → the
//! builtin's members, `out x:` → target formats, inside an operator's
//! parentheses its named arguments first; elsewhere operators, intrinsics,
//! params, textures, passes, the pass's `let`s and builtins.

use super::analysis::{self, Analysis};
use lsp_types::{CompletionItem, CompletionItemKind, Documentation, InsertTextFormat, MarkupContent, MarkupKind};
use npr_compiler::describe;
use npr_compiler::ir::{Builtin, Intrinsic};
use npr_dsl::ast::Item;

pub fn complete(a: &Analysis, text: &str, offset: usize) -> Vec<CompletionItem> {
    let before = &text[..floor_boundary(text, offset)];
    let line = before.rsplit('\n').next().unwrap_or(before);
    let word_start = before.len()
        - before
            .chars()
            .rev()
            .take_while(|c| is_ident(*c))
            .map(char::len_utf8)
            .sum::<usize>();
    let head = &before[..word_start];
    if let Some(base) = head.strip_suffix('.') {
        let base_start = base.len()
            - base
                .chars()
                .rev()
                .take_while(|c| is_ident(*c))
                .map(char::len_utf8)
                .sum::<usize>();
        return members(a, &base[base_start..]);
    }
    if after_out_colon(line) {
        return describe::language::formats()
            .map(|(name, f)| {
                item(
                    name,
                    CompletionItemKind::ENUM_MEMBER,
                    &describe::language::format_text(f),
                    None,
                )
            })
            .collect();
    }
    let mut items = Vec::new();
    if let Some(op) = enclosing_call(head).and_then(npr_stdlib::find) {
        for p in op.params {
            let mut it = item(
                p.name,
                CompletionItemKind::PROPERTY,
                &format!(
                    "{}: {} (default {})",
                    p.name,
                    describe::ty_name(p.ty),
                    describe::default_text(p)
                ),
                Some(p.doc.to_string()),
            );
            it.insert_text = Some(format!("{}: ", p.name));
            it.sort_text = Some(format!("0{}", p.name));
            items.push(it);
        }
    }
    items.extend(everything(a, offset));
    items
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

fn floor_boundary(text: &str, mut offset: usize) -> usize {
    offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    offset
}

/// `  out color: rgba8` — the cursor is where a format goes.
fn after_out_colon(line: &str) -> bool {
    let t = line.trim_start();
    let Some(rest) = t.strip_prefix("out ") else {
        return false;
    };
    let Some((name, format)) = rest.split_once(':') else {
        return false;
    };
    name.trim().chars().all(is_ident) && format.trim_start().chars().all(is_ident)
}

/// The callee of the innermost call whose `(` is open before the cursor.
fn enclosing_call(head: &str) -> Option<&str> {
    let mut depth = 0i32;
    for (i, c) in head.char_indices().rev() {
        match c {
            ')' => depth += 1,
            '(' if depth == 0 => {
                let callee = &head[..i];
                let start = callee.len()
                    - callee
                        .chars()
                        .rev()
                        .take_while(|c| is_ident(*c))
                        .map(char::len_utf8)
                        .sum::<usize>();
                return Some(&callee[start..]);
            }
            '(' => depth -= 1,
            '{' | '}' if depth == 0 => return None,
            _ => {}
        }
    }
    None
}

/// After `base.`: a pass's targets, or a builtin's members.
fn members(a: &Analysis, base: &str) -> Vec<CompletionItem> {
    if let Some(p) = a.pass(base) {
        return analysis::targets(p)
            .into_iter()
            .map(|t| {
                item(
                    t.name,
                    CompletionItemKind::FIELD,
                    &format!("{} {}: {}", t.kind, t.name, t.ty),
                    None,
                )
            })
            .collect();
    }
    let prefix = format!("{base}.");
    Builtin::SPELLINGS
        .iter()
        .filter_map(|(s, b)| s.strip_prefix(&prefix).map(|m| (m, s, b)))
        .map(|(m, s, b)| {
            item(
                m,
                CompletionItemKind::FIELD,
                &describe::builtins::signature(s, *b),
                Some(describe::builtins::doc(*b).to_string()),
            )
        })
        .collect()
}

fn everything(a: &Analysis, offset: usize) -> Vec<CompletionItem> {
    let mut items = Vec::new();
    for op in npr_stdlib::all() {
        let mut it = item(
            op.name,
            CompletionItemKind::FUNCTION,
            &describe::signature(op),
            Some(describe::operator_markdown(op, "###")),
        );
        it.insert_text = Some(format!("{}($0)", op.name));
        it.insert_text_format = Some(InsertTextFormat::SNIPPET);
        items.push(it);
    }
    for (name, i) in Intrinsic::TABLE {
        items.push(item(
            name,
            CompletionItemKind::FUNCTION,
            &format!("{name}(...)"),
            Some(describe::language::intrinsic_doc(*i)),
        ));
    }
    for (name, written, what) in describe::language::SPECIAL_CALLS {
        items.push(item(
            name,
            CompletionItemKind::FUNCTION,
            written,
            Some(what.to_string()),
        ));
    }
    for it in a.items() {
        match it {
            Item::Param(p) => items.push(item(
                &p.name.name,
                CompletionItemKind::VARIABLE,
                &format!("param {}: {}", p.name.name, analysis::snippet(a, p.ty.span())),
                Some(p.doc.clone()),
            )),
            Item::Texture(t) => items.push(item(
                &t.name.name,
                CompletionItemKind::CONSTANT,
                &format!("texture {}", t.name.name),
                Some(t.doc.clone()),
            )),
            Item::Pass(p) => items.push(item(
                &p.name.name,
                CompletionItemKind::MODULE,
                &format!("pass {}: {}", p.name.name, analysis::snippet(a, p.kind.span)),
                Some(p.doc.clone()),
            )),
            _ => {}
        }
    }
    // The `let`s of the pass the cursor is in.
    for it in &a.loaded.root.items {
        if let Item::Pass(p) = it {
            if (p.span.start as usize) <= offset && offset <= p.span.end as usize {
                for l in &p.body.lets {
                    items.push(item(&l.name.name, CompletionItemKind::VARIABLE, "let", None));
                }
            }
        }
    }
    let mut seen = std::collections::BTreeSet::new();
    for (spelling, b) in Builtin::SPELLINGS {
        let top = spelling.split('.').next().unwrap_or(spelling);
        if seen.insert(top) {
            let detail = if top == *spelling {
                describe::builtins::signature(spelling, *b)
            } else {
                format!("{top}.… (builtin)")
            };
            items.push(item(top, CompletionItemKind::KEYWORD, &detail, None));
        }
    }
    items
}

fn item(label: &str, kind: CompletionItemKind, detail: &str, doc: Option<String>) -> CompletionItem {
    CompletionItem {
        label: label.to_string(),
        kind: Some(kind),
        detail: Some(detail.to_string()),
        documentation: doc.filter(|d| !d.is_empty()).map(|d| {
            Documentation::MarkupContent(MarkupContent {
                kind: MarkupKind::Markdown,
                value: d,
            })
        }),
        ..CompletionItem::default()
    }
}
