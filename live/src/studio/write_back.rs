//! "Write into the file": replace a parameter's default in the `.npr`
//! source with a new literal, touching only the default's own bytes, so the
//! file's formatting, comments, range and animation stay as written. The
//! file is found by parsing it (spans, not text search), and written
//! atomically; the watcher then sees the save like any other.

use std::path::Path;

/// Rewrite `name`'s default in `style` to `literal`.
pub fn rewrite_default(style: &Path, name: &str, literal: &str) -> Result<(), String> {
    let text = std::fs::read_to_string(style).map_err(|e| format!("cannot read {}: {e}", style.display()))?;
    let new = replace_default(&text, name, literal)?;
    npr_runner::output::write_atomic(style, new.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", style.display()))
}

/// `text` with `name`'s default replaced by `literal`.
pub fn replace_default(text: &str, name: &str, literal: &str) -> Result<String, String> {
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("style", text.to_string());
    let (ast, _) = npr_dsl::parse(file, text);
    let decl = ast
        .items
        .iter()
        .find_map(|item| match item {
            npr_dsl::ast::Item::Param(p) if p.name.name == name => Some(p),
            _ => None,
        })
        .ok_or_else(|| format!("`{name}` is not declared in this file (is it in a file it `use`s?)"))?;
    let range = decl.default.span.range();
    let mut out = String::with_capacity(text.len() + literal.len());
    out.push_str(&text[..range.start]);
    out.push_str(literal);
    out.push_str(&text[range.end..]);
    Ok(out)
}

/// Each parameter whose default is a number written with a unit (`50mm`,
/// `2px`, `45deg`): its default's text as written, by name. The studio
/// shows these as written, not converted to the canonical unit.
pub fn unit_defaults_as_written(text: &str) -> std::collections::BTreeMap<String, String> {
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("style", text.to_string());
    let (ast, _) = npr_dsl::parse(file, text);
    ast.items
        .iter()
        .filter_map(|item| match item {
            npr_dsl::ast::Item::Param(p) => match &p.default.kind {
                npr_dsl::ast::ExprKind::Number { unit: Some(_), .. } => {
                    Some((p.name.name.clone(), text[p.default.span.range()].to_string()))
                }
                _ => None,
            },
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{replace_default, unit_defaults_as_written};

    #[test]
    fn unit_defaults_are_read_as_written() {
        let text = "style \"S\"\nparam reach: m = 50mm in 0m..1m\nparam w: px = 2px\nparam k: float = 0.5\n";
        let written = unit_defaults_as_written(text);
        assert_eq!(written.get("reach").map(String::as_str), Some("50mm"));
        assert_eq!(written.get("w").map(String::as_str), Some("2px"));
        assert!(!written.contains_key("k"), "a plain number formats as written already");
    }

    #[test]
    fn only_the_default_changes() {
        let text =
            "style \"S\"\n/// Bands of light.\nparam bands: int = 3   in 1..8 // few\nparam base: color = #e07a3a\n";
        let out = replace_default(text, "bands", "5").expect("rewritten");
        assert_eq!(out, text.replace("= 3   in", "= 5   in"));
        let out = replace_default(text, "base", "#3080ff").expect("rewritten");
        assert_eq!(out, text.replace("#e07a3a", "#3080ff"));
        assert!(replace_default(text, "missing", "1").is_err());
    }
}
