//! Recovery after a syntax error: the file is split at top-level
//! declaration starts and each chunk parsed alone (spans shifted), and the
//! names of declarations that do not parse are kept (`Ast::broken`).

use super::*;
/// Split the source at top-level declaration starts and parse each chunk alone.
pub(super) fn recover(b: &Builder, source: &str, first: pest::error::Error<Rule>) -> (Ast, Vec<Diagnostic>) {
    let mut ast = Ast::default();
    let mut diags = Vec::new();
    let starts = item_starts(source);
    if starts.is_empty() {
        diags.push(b.syntax_error(first, source, "end of file"));
        return (ast, diags);
    }
    let mut reported = false;
    for (i, &start) in starts.iter().enumerate() {
        let end = starts.get(i + 1).copied().unwrap_or(source.len());
        let chunk = &source[start..end];
        // Each chunk is parsed alone; spans are shifted to file offsets (the
        // chunk is not padded: that made recovery quadratic in the file).
        b.offset.set(start);
        match NprParser::parse(Rule::single_item, chunk) {
            Ok(mut pairs) => {
                if let Some(p) = pairs.next() {
                    for inner in p.into_inner() {
                        b.top_level(inner, &mut ast, &mut diags);
                    }
                }
            }
            Err(e) => {
                reported = true;
                let eof = if end == source.len() {
                    "end of file"
                } else {
                    "the next declaration"
                };
                diags.push(shifted(b.syntax_error(e, chunk, eof), start));
                if let Some(name) = declared_name(chunk) {
                    ast.broken.push(name.to_string());
                }
            }
        }
    }
    b.offset.set(0);
    if !reported {
        diags.push(b.syntax_error(first, source, "end of file"));
    }
    if ast.style.is_none()
        && !diags.iter().any(|d| d.code == codes::STYLE_HEADER)
        && !source.trim_start().starts_with("style")
    {
        diags.push(missing_header(b.file));
    }
    (ast, diags)
}

/// `d` with its labels moved `by` bytes later (from a chunk into its file).
fn shifted(mut d: Diagnostic, by: usize) -> Diagnostic {
    for l in &mut d.labels {
        l.span.start += by as u32;
        l.span.end += by as u32;
    }
    d
}

/// The name a declaration chunk declares (`pass shade: ...` → `shade`),
/// read from its first words, so that a declaration that does not parse
/// still suppresses errors about its name being unknown.
fn declared_name(chunk: &str) -> Option<&str> {
    let code = chunk
        .lines()
        .map(str::trim_start)
        .find(|l| !l.is_empty() && !l.starts_with("//"))?;
    let mut words = code
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty());
    let mut first = words.next()?;
    if first == "object" {
        first = words.next()?;
    }
    match first {
        "param" | "pass" | "texture" => words.next(),
        _ => None,
    }
}

const ITEM_KEYWORDS: &[&str] = &["style", "use", "param", "object", "texture", "pass", "output", "///"];

/// Byte offsets where a top-level item starts: a keyword (or a doc comment)
/// at the start of a line, at brace depth 0 or in column 0. A doc comment run and the item
/// after it start together.
fn item_starts(source: &str) -> Vec<usize> {
    let mut starts = Vec::new();
    let mut depth: i32 = 0;
    let mut offset = 0;
    let mut in_doc_run = false;
    for line in source.split_inclusive('\n') {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        // A keyword at column 0 starts an item even inside an unclosed bracket:
        // that is the usual shape of a broken declaration followed by good ones.
        if depth <= 0 || indent == 0 {
            let starts_item = ITEM_KEYWORDS.iter().any(|k| {
                trimmed.starts_with(k)
                    && trimmed[k.len()..]
                        .chars()
                        .next()
                        .is_none_or(|c| !(c.is_alphanumeric() || c == '_'))
            });
            if starts_item {
                depth = 0;
                let is_doc = trimmed.starts_with("///");
                if !in_doc_run {
                    starts.push(offset + indent);
                }
                in_doc_run = is_doc;
            } else if !trimmed.is_empty() && !trimmed.starts_with("//") {
                in_doc_run = false;
            }
        }
        let code = line.split("//").next().unwrap_or("");
        for c in code.chars() {
            match c {
                '{' | '(' => depth += 1,
                '}' | ')' => depth -= 1,
                _ => {}
            }
        }
        if depth < 0 {
            depth = 0;
        }
        offset += line.len();
    }
    starts
}

/// The length of `text` up to the end of its last token (whitespace and
/// comments after it left out).
pub(super) fn content_len(text: &str) -> usize {
    let ends_in_code = text.chars().next_back().is_some_and(|c| !c.is_whitespace() && c != '/');
    if ends_in_code {
        return text.len();
    }
    let bytes = text.as_bytes();
    let (mut i, mut end) = (0, 0);
    while i < bytes.len() {
        match bytes[i] {
            b'/' if bytes.get(i + 1) == Some(&b'/') && bytes.get(i + 2) != Some(&b'/') => {
                i = text[i..].find('\n').map_or(bytes.len(), |n| i + n);
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i = text[i + 2..].find("*/").map_or(bytes.len(), |n| i + 2 + n + 2);
            }
            b'"' => {
                // Strings inside a pair are whole: skip to the closing quote.
                let mut j = i + 1;
                while j < bytes.len() && bytes[j] != b'"' {
                    j += if bytes[j] == b'\\' { 2 } else { 1 };
                }
                i = (j + 1).min(bytes.len());
                end = i;
            }
            c if c.is_ascii_whitespace() => i += 1,
            _ => {
                i += 1;
                end = i;
            }
        }
    }
    end
}
