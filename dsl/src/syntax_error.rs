//! Syntax errors: a pest error turned into a diagnostic that says what was
//! expected, points at the missing or unexpected token, and never
//! contradicts itself.
//!
//! pest reports the position of the last *rule* that failed, which is often
//! the start of a whole statement ("expected `out` … found `out`" when a
//! `:` is missing inside it). With `pest::set_error_detail` it also records
//! the literal tokens tried at the furthest position reached; that position
//! and those tokens are what the message uses. Three cases get their own
//! message: an unclosed `/*` comment, a keyword where a name goes
//! (`param scale: …`), and a token missing at the end of a line (the caret
//! goes after the last token, not on the next line).

use crate::grammar::Rule;
use npr_diag::{codes, Diagnostic, FileId, Span};
use pest::error::{Error, ErrorVariant, InputLocation};

/// The grammar's keywords (rule `keyword`), which cannot be names.
const KEYWORDS: &[&str] = &[
    "style", "use", "param", "object", "texture", "pass", "output", "let", "out", "vertex", "if", "else", "in",
    "animate", "scale", "state", "reduce", "true", "false",
];

/// Keywords that begin a declaration or a statement: at the start of a line
/// they are most likely the next statement, after something unfinished.
const STATEMENT_KEYWORDS: &[&str] = &[
    "style", "use", "param", "object", "texture", "pass", "output", "let", "out", "vertex", "state", "reduce",
];

/// Keywords that are values or begin one, so they are fine where an
/// expression goes.
const VALUE_KEYWORDS: &[&str] = &["true", "false", "if", "object"];

const OPERATORS: &[&str] = &["+", "-", "*", "/", "%", "<", ">", "<=", ">=", "==", "!=", "&&", "||"];

/// The diagnostic for `e`, found parsing `source` (file offsets); `eof`
/// names what ends the text (the file, or the next declaration when
/// recovering item by item).
pub(crate) fn syntax_error(file: FileId, e: &Error<Rule>, source: &str, eof: &str) -> Diagnostic {
    let loc = match e.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((a, _)) => a,
    }
    .min(source.len());
    let attempts = e.parse_attempts();
    let pos = attempts
        .as_ref()
        .map_or(loc, |a| a.max_position.clamp(loc, source.len()));
    // pest's `ParsingToken` is not exported: its display is the token
    // (a range as `a..z`).
    let tokens: Vec<String> = attempts
        .map(|a| a.expected_tokens().iter().map(|t| t.to_string()).collect())
        .unwrap_or_default();
    if tokens.iter().any(|t| t == "*/") {
        return unclosed_comment(file, source, pos);
    }
    if let Some(d) = keyword_as_name(file, source, loc) {
        return d;
    }
    let positives: &[Rule] = match &e.variant {
        ErrorVariant::ParsingError { positives, .. } => positives,
        ErrorVariant::CustomError { message } => {
            return Diagnostic::error(codes::SYNTAX, message.clone())
                .with_primary(Span::new(file, loc, loc), message.clone())
        }
    };
    if token_at(source, loc).starts_with('"') && !source[loc + 1..].contains('"') {
        return unterminated_string(file, loc);
    }
    // Where pest got no further than the rule it reports, the rules name what
    // may come (`a type`, `an expression`), with the closing brackets it
    // tried; past it, or inside one token, the tokens tried further on.
    let inside_token = loc < pos && !source[loc..pos].contains(char::is_whitespace);
    let (at, mut names) = if pos == loc || inside_token {
        let mut names: Vec<String> = match positives {
            [] => Vec::new(),
            rules if rules.iter().all(|r| *r == Rule::EOI) => vec![rule_name(&Rule::item), rule_name(&Rule::EOI)],
            rules => rules.iter().map(rule_name).collect(),
        };
        if pos == loc {
            names.extend(
                tokens
                    .iter()
                    .filter(|t| [")", "]", "}"].contains(&t.as_str()))
                    .map(|t| format!("`{t}`")),
            );
        }
        (loc, names)
    } else {
        (pos, token_names(&tokens))
    };
    if names.is_empty() {
        names = token_names(&tokens);
    }
    names.sort();
    names.dedup();
    // After a complete construct, the next token is what is wrong; inside an
    // unfinished one, something is missing after the last token.
    let complete = names
        .iter()
        .any(|n| n == &rule_name(&Rule::EOI) || n == &rule_name(&Rule::item));
    let found_at = skip_trivia(source, at);
    let found = token_at(source, found_at);
    let contradiction = contradicts(&names, found);
    let expected = join_or(names);
    let found_text = if found.is_empty() {
        eof.to_string()
    } else {
        format!("`{found}`")
    };
    // A token missing at the end of a line belongs after the last one there.
    let before = trim_trivia_end(source, at);
    let missing_at_line_end = found.is_empty() || !complete && source[before..found_at].contains('\n');
    let span = if missing_at_line_end {
        Span::new(file, before, before)
    } else {
        Span::new(file, found_at, found_at + found.len())
    };
    // Never "expected `x`, found `x`": the token was fine, what follows it was not.
    let message = if contradiction {
        format!("expected {expected}")
    } else {
        format!("expected {expected}, found {found_text}")
    };
    let d = Diagnostic::error(codes::SYNTAX, message).with_primary(span, format!("expected {expected}"));
    match help(source, found_at, found) {
        Some(h) => d.with_help(h),
        None => d,
    }
}

/// Whether "found `found`" would contradict "expected `names`": the token
/// is one of them (a keyword, a name, a number).
fn contradicts(names: &[String], found: &str) -> bool {
    if found.is_empty() {
        return false;
    }
    let is_name = found.starts_with(|c: char| c.is_alphabetic() || c == '_') && !KEYWORDS.contains(&found);
    let is_number = found.starts_with(|c: char| c.is_ascii_digit());
    names.iter().any(|n| {
        *n == format!("`{found}`")
            || (n == "a name" && is_name)
            || (n == "a number" && is_number)
            || n.starts_with(&format!("`{found} "))
    })
}

/// E0001 at the `"` of a string that no `"` closes on its line.
fn unterminated_string(file: FileId, at: usize) -> Diagnostic {
    Diagnostic::error(codes::SYNTAX, "unterminated string")
        .with_primary(Span::new(file, at, at + 1), "this string is never closed")
        .with_help("a string is missing its closing `\"` (strings end on the line they start)")
}

/// The `/*` that no `*/` closes, outside strings and line comments: it
/// makes the rest of the file a comment, so the parser reports only this
/// (splitting the text into declarations would find some inside it).
pub(crate) fn unclosed_comment_check(file: FileId, source: &str) -> Option<Diagnostic> {
    let bytes = source.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                i = source[i..].find('\n').map_or(bytes.len(), |n| i + n);
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => match source[i + 2..].find("*/") {
                Some(n) => i += 2 + n + 2,
                None => return Some(unclosed_comment(file, source, i)),
            },
            b'"' => {
                // A string ends at its quote or at the end of its line.
                let mut j = i + 1;
                while j < bytes.len() && bytes[j] != b'"' && bytes[j] != b'\n' {
                    j += if bytes[j] == b'\\' { 2 } else { 1 };
                }
                i = j + 1;
            }
            _ => i += 1,
        }
    }
    None
}

/// E0001 at the `/*` at `open`, or (from a pest error) the first `/*` with
/// no `*/` after it (comments do not nest).
fn unclosed_comment(file: FileId, source: &str, pos: usize) -> Diagnostic {
    let open = if source[pos..].starts_with("/*") {
        pos
    } else {
        source[..pos.max(2).min(source.len())]
            .match_indices("/*")
            .map(|(i, _)| i)
            .find(|i| !source[i + 2..].contains("*/"))
            .unwrap_or(pos)
    };
    Diagnostic::error(codes::SYNTAX, "unclosed block comment")
        .with_primary(
            Span::new(file, open, (open + 2).min(source.len())),
            "this `/*` is never closed",
        )
        .with_help("end the comment with `*/`; everything after the `/*` is part of it")
}

/// A keyword where a name goes: `param scale: float`, `vec4(scale)`. Not
/// a statement keyword at the start of its line (that is the next
/// statement after an unfinished one), nor a keyword that is a value.
fn keyword_as_name(file: FileId, source: &str, at: usize) -> Option<Diagnostic> {
    let word = token_at(source, at);
    if !KEYWORDS.contains(&word) || VALUE_KEYWORDS.contains(&word) {
        return None;
    }
    let line_start = source[..at].rfind('\n').map_or(0, |i| i + 1);
    let starts_line = source[line_start..at].trim().is_empty();
    if starts_line && STATEMENT_KEYWORDS.contains(&word) {
        return None;
    }
    Some(
        Diagnostic::error(codes::SYNTAX, format!("`{word}` is a keyword and cannot be a name"))
            .with_primary(Span::new(file, at, at + word.len()), "a keyword")
            .with_help(format!(
                "choose another name, such as `{word}_factor`; the keywords are: {}",
                KEYWORDS.join(", ")
            )),
    )
}

/// English for the literal tokens pest tried, with whitespace and comment
/// starts left out, operators as one entry and expression starts as one.
fn token_names(tokens: &[String]) -> Vec<String> {
    let mut literal: Vec<&str> = Vec::new();
    let mut name_chars = false;
    let mut digits = false;
    for t in tokens {
        match t.as_str() {
            " " | "\t" | "\n" | "\r" | "/*" | "//" => {}
            "_" | "a..z" | "A..Z" => name_chars = true,
            "a..f" | "A..F" => literal.push("a hex digit"),
            "0..9" => digits = true,
            // `^"e"` of an exponent (shown upper-case) and pest's built-ins:
            // nothing a user would type for.
            "E" | "BUILTIN_RULE" => {}
            other => literal.push(other),
        }
    }
    let mut names = Vec::new();
    let expression = name_chars && literal.contains(&"(") && literal.contains(&"!");
    if expression {
        names.push("an expression".to_string());
        literal.retain(|t| !["(", "-", "!", "\"", "#", "{", "true", "false", "if", "object"].contains(t));
    } else if name_chars {
        names.push("a name".to_string());
    } else if digits {
        names.push("a digit".to_string());
    }
    if literal.iter().any(|t| OPERATORS.contains(t)) {
        literal.retain(|t| !OPERATORS.contains(t));
        names.push("an operator".to_string());
    }
    names.extend(literal.into_iter().map(|t| match t {
        "a hex digit" => t.to_string(),
        _ => format!("`{t}`"),
    }));
    names
}

fn join_or(mut names: Vec<String>) -> String {
    match names.len() {
        0 => "something else".to_string(),
        1 => names.remove(0),
        _ => {
            let last = names.pop().unwrap_or_default();
            format!("{} or {last}", names.join(", "))
        }
    }
}

/// `at` moved past whitespace and comments.
fn skip_trivia(source: &str, mut at: usize) -> usize {
    loop {
        let rest = &source[at..];
        let trimmed = rest.trim_start();
        at += rest.len() - trimmed.len();
        if trimmed.starts_with("//") && !trimmed.starts_with("///") {
            at += trimmed.find('\n').unwrap_or(trimmed.len());
        } else if let Some(body) = trimmed.strip_prefix("/*") {
            match body.find("*/") {
                Some(end) => at += 2 + end + 2,
                None => return source.len(),
            }
        } else {
            return at;
        }
    }
}

/// The end of the last token before `at`: `at` moved back over whitespace.
fn trim_trivia_end(source: &str, at: usize) -> usize {
    source[..at].trim_end().len()
}

/// The token that starts at `at`: a word, a number with its unit, a string
/// start, or a run of punctuation (at most a few characters).
fn token_at(source: &str, at: usize) -> &str {
    let rest = &source[at..];
    let run = |skip: usize, keep: &dyn Fn(char) -> bool| {
        rest.char_indices()
            .skip(skip)
            .find(|(_, c)| !keep(*c))
            .map_or(rest.len(), |(i, _)| i)
    };
    let end = match rest.chars().next() {
        None => 0,
        Some(c) if c.is_ascii_digit() => run(0, &|c| c.is_alphanumeric() || c == '.' || c == '%'),
        Some(c) if c.is_alphanumeric() || c == '_' => run(0, &|c| c.is_alphanumeric() || c == '_'),
        Some('#') => run(1, &|c| c.is_alphanumeric()),
        Some('"') => 1,
        Some(c) => {
            // Operators are at most two characters (`<=`, `&&`, `..`).
            let punct = |c: char| !(c.is_whitespace() || c.is_alphanumeric() || c == '_' || c == '"');
            let first = c.len_utf8();
            match rest[first..].chars().next() {
                Some(d) if punct(d) => first + d.len_utf8(),
                _ => first,
            }
        }
    };
    &rest[..end]
}

/// A hint from what is around the error.
fn help(source: &str, at: usize, found: &str) -> Option<String> {
    let before = &source[..at];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = source[line_start..].lines().next().unwrap_or("").trim_start();
    Some(
        if (line.starts_with("param") || line.starts_with("object param")) && !line.contains('=') {
            "a parameter needs a default: `param name: type = value`".into()
        } else if before.matches('"').count() % 2 == 1 || found.starts_with('"') && !source[at + 1..].contains('"') {
            "a string is missing its closing `\"`".into()
        } else if found.starts_with('%') {
            "write `a % b` with spaces for modulo; `50%` (no space) is a percentage".into()
        } else if found.starts_with('#') {
            "colours are written `#rrggbb` or `#rrggbbaa` with hex digits".into()
        } else if before.matches('(').count() > before.matches(')').count() {
            "a `(` is not closed".into()
        } else if source[at..].trim_start().is_empty() && before.matches('{').count() > before.matches('}').count() {
            "a `{` is not closed".into()
        } else {
            return None;
        },
    )
}

/// English names for rules in "expected ..." messages.
pub(crate) fn rule_name(r: &Rule) -> String {
    match r {
        Rule::expr
        | Rule::or_expr
        | Rule::and_expr
        | Rule::comparison
        | Rule::sum
        | Rule::product
        | Rule::unary
        | Rule::postfix
        | Rule::primary => "an expression",
        Rule::ident => "a name",
        Rule::number | Rule::number_value => "a number",
        Rule::string | Rule::string_inner => "a string",
        Rule::color => "a colour like #ff8800",
        Rule::item | Rule::single_item => "a declaration (param, texture, pass, output, use)",
        Rule::EOI => "end of file",
        Rule::type_expr | Rule::enum_type | Rule::texture_type => "a type",
        Rule::param_default | Rule::range_value => "a default value",
        Rule::range_clause => "`in lo..hi`",
        Rule::animate_clause => "`animate { ... }`",
        Rule::pass_kind => "a pass kind such as render(scene) or image(a)",
        Rule::kind_arg => "a name or a pass's target (`ids.id`)",
        Rule::pass_body | Rule::pass_stmt => "`out`, `let`, `state`, `reduce`, `vertex` or a setting",
        Rule::out_stmt => "`out name: format = value [{ blend: over }]`",
        Rule::state_stmt => "`state name: type = value`",
        Rule::reduce_stmt => "`reduce name: type = sum(value)`",
        Rule::update_stmt => "`name = value`",
        Rule::let_stmt => "`let name = value`",
        Rule::setting => "`key: value`",
        Rule::settings_block => "`{ key: value }`",
        Rule::call => "a call",
        Rule::arg => "an argument",
        Rule::unit => "a unit (px, %, m, mm, s, Hz, deg)",
        Rule::add_op | Rule::mul_op | Rule::cmp_op | Rule::or_op | Rule::and_op => "an operator",
        Rule::field => "a field name",
        Rule::style_header => "`style \"Name\"`",
        Rule::doc_comment | Rule::doc_text => "a doc comment",
        Rule::scale_clause => "`scale`",
        Rule::pass_modifier => "a pass modifier",
        Rule::object_kw | Rule::object_name => "`object`",
        Rule::if_expr | Rule::else_if => "`if`",
        other => return format!("{other:?}"),
    }
    .to_string()
}
