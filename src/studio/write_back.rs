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
    runner::output::write_atomic(style, new.as_bytes()).map_err(|e| format!("cannot write {}: {e}", style.display()))
}

/// `text` with `name`'s default replaced by `literal`.
pub fn replace_default(text: &str, name: &str, literal: &str) -> Result<String, String> {
    let mut sources = diag::SourceMap::new();
    let file = sources.add("style", text.to_string());
    let (ast, _) = dsl::parse(file, text);
    let decl = ast
        .items
        .iter()
        .find_map(|item| match item {
            dsl::ast::Item::Param(p) if p.name.name == name => Some(p),
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

#[cfg(test)]
mod tests {
    use super::replace_default;

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
