//! The nesting check that runs on the raw text before pest does.
//!
//! pest is a recursive-descent parser: every `(`, `{`, call and `if` costs it
//! a dozen nested rule calls, so a thousand nested parentheses used to
//! overflow the stack before any diagnostic could be made. This scan counts
//! the same levels with an explicit stack, skipping comments and strings,
//! and refuses the file at the first level past [`MAX_NESTING`], pointing at
//! the bracket or `if` that opens it. After it, pest never recurses deeper
//! than `MAX_NESTING` levels.
//!
//! An `if` opens a level that its final `else { ... }` block closes; an
//! `else if` continues the same level (the grammar parses an `else if`
//! chain as a repetition, not by recursion). An `if` whose `else` never
//! comes is closed by the bracket around it. Where the text is malformed the
//! count can only be too high, never too low.

use npr_diag::limits::MAX_NESTING;
use npr_diag::{codes, Diagnostic, FileId, Span};

#[derive(Clone, Copy, PartialEq, Eq)]
enum Level {
    Paren,
    /// A `{`; `closes_if` when it is the final `else` block of an `if`.
    Brace {
        closes_if: bool,
    },
    If,
}

/// The first place where nesting goes past [`MAX_NESTING`], as an E0005
/// diagnostic; `None` when the text stays within it.
pub fn check(file: FileId, text: &str) -> Option<Diagnostic> {
    let bytes = text.as_bytes();
    let mut stack: Vec<Level> = Vec::new();
    // An `else` was just seen (not followed by `if`): its `{` ends an `if`.
    let mut else_block = false;
    // The last byte before this one that is not whitespace, to tell a field
    // `.if` from the keyword.
    let mut last = b' ';
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        // (level opened, its length in bytes, where the scan goes on)
        let (opened, next) = match c {
            b'/' if bytes.get(i + 1) == Some(&b'/') => (None, skip_line(bytes, i)),
            b'/' if bytes.get(i + 1) == Some(&b'*') => (None, skip_block_comment(bytes, i)),
            b'"' => (None, skip_string(bytes, i)),
            b'(' => (Some((Level::Paren, 1)), i + 1),
            b'{' => {
                let closes_if = std::mem::take(&mut else_block);
                (Some((Level::Brace { closes_if }, 1)), i + 1)
            }
            b')' | b'}' => {
                close(&mut stack);
                (None, i + 1)
            }
            c if is_word_start(c) && !(i > 0 && is_word_byte(bytes[i - 1])) => {
                let end = word_end(bytes, i);
                match &text[i..end] {
                    "if" if last != b'.' => (Some((Level::If, 2)), end),
                    "else" => {
                        let after = skip_trivia(bytes, end);
                        if is_word_at(text, after, "if") {
                            // `else if`: the same level goes on.
                            (None, after + 2)
                        } else {
                            else_block = true;
                            (None, end)
                        }
                    }
                    _ => (None, end),
                }
            }
            _ => (None, i + 1),
        };
        if let Some((level, len)) = opened {
            stack.push(level);
            if stack.len() > MAX_NESTING {
                return Some(too_deep(file, i, len));
            }
        }
        if c == b'/' && next > i + 1 {
            // A comment separates words like a space.
            last = b' ';
        } else if let Some(&b) = bytes[i..next].iter().rev().find(|b| !b.is_ascii_whitespace()) {
            last = b;
        }
        i = next;
    }
    None
}

/// Whether the word `word` (not a longer name) starts at `at`.
fn is_word_at(text: &str, at: usize, word: &str) -> bool {
    text[at..].starts_with(word) && !text.as_bytes().get(at + word.len()).copied().is_some_and(is_word_byte)
}

/// A `)` or `}`: close the innermost bracket, and every `if` left open inside
/// it; the final `else` block of an `if` closes that `if` too.
fn close(stack: &mut Vec<Level>) {
    while let Some(top) = stack.pop() {
        match top {
            Level::If => continue,
            Level::Paren | Level::Brace { closes_if: false } => return,
            Level::Brace { closes_if: true } => {
                if stack.last() == Some(&Level::If) {
                    stack.pop();
                }
                return;
            }
        }
    }
}

fn too_deep(file: FileId, at: usize, len: usize) -> Diagnostic {
    Diagnostic::error(
        codes::NESTED_TOO_DEEP,
        format!("nested more than {MAX_NESTING} levels deep"),
    )
    .with_primary(
        Span::new(file, at, at + len),
        format!("level {} opens here", MAX_NESTING + 1),
    )
    .with_help(format!(
        "brackets, blocks, calls and `if`s may nest {MAX_NESTING} levels; give an inner part a name with `let`"
    ))
}

fn is_word_start(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_'
}

fn is_word_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

fn word_end(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && is_word_byte(bytes[i]) {
        i += 1;
    }
    i
}

fn skip_line(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && bytes[i] != b'\n' {
        i += 1;
    }
    i
}

/// Past the `*/` (or to the end: an unclosed comment is pest's error to report).
fn skip_block_comment(bytes: &[u8], i: usize) -> usize {
    let mut j = i + 2;
    while j + 1 < bytes.len() {
        if bytes[j] == b'*' && bytes[j + 1] == b'/' {
            return j + 2;
        }
        j += 1;
    }
    bytes.len()
}

/// Past the closing quote; a string ends at a newline too (the grammar's
/// strings cannot hold one), so an unclosed quote hides one line at most.
fn skip_string(bytes: &[u8], i: usize) -> usize {
    let mut j = i + 1;
    while j < bytes.len() {
        match bytes[j] {
            b'\\' => j += 2,
            b'"' => return j + 1,
            b'\n' => return j,
            _ => j += 1,
        }
    }
    bytes.len()
}

/// Past whitespace and comments.
fn skip_trivia(bytes: &[u8], mut i: usize) -> usize {
    loop {
        while i < bytes.len() && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        match (bytes.get(i), bytes.get(i + 1)) {
            (Some(b'/'), Some(b'/')) => i = skip_line(bytes, i),
            (Some(b'/'), Some(b'*')) => i = skip_block_comment(bytes, i),
            _ => return i,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn depth_error(text: &str) -> Option<usize> {
        check(FileId(0), text)
            .and_then(|d| d.primary_span())
            .map(|s| s.start as usize)
    }

    #[test]
    fn counts_brackets_and_points_at_the_first_level_past_the_limit() {
        let ok = format!("{}x{}", "(".repeat(MAX_NESTING), ")".repeat(MAX_NESTING));
        assert_eq!(depth_error(&ok), None);
        let deep = format!("{}x{}", "(".repeat(MAX_NESTING + 1), ")".repeat(MAX_NESTING + 1));
        assert_eq!(depth_error(&deep), Some(MAX_NESTING));
        let braces = "{".repeat(MAX_NESTING + 5);
        assert_eq!(depth_error(&braces), Some(MAX_NESTING));
    }

    #[test]
    fn comments_and_strings_do_not_count() {
        let hidden = format!("// {0}\n/* {0} */ \"{0}\" x", "(".repeat(MAX_NESTING * 2));
        assert_eq!(depth_error(&hidden), None);
    }

    #[test]
    fn siblings_do_not_add_up() {
        let many = "f(a) { b } ".repeat(MAX_NESTING * 10);
        assert_eq!(depth_error(&many), None);
        let ifs = "let x = if a { 1 } else { 2 }\n".repeat(MAX_NESTING * 10);
        assert_eq!(depth_error(&ifs), None);
    }

    #[test]
    fn else_if_chains_are_one_level_but_ifs_in_conditions_nest() {
        let chain = format!(
            "x = if a {{ 1 }}{} else {{ 3 }}",
            " else if b { 2 }".repeat(MAX_NESTING * 4)
        );
        assert_eq!(depth_error(&chain), None);
        let conds = format!(
            "{}c{}",
            "if ".repeat(MAX_NESTING + 1),
            " { 1 } else { 2 }".repeat(MAX_NESTING + 1)
        );
        assert_eq!(depth_error(&conds), Some(3 * MAX_NESTING));
    }

    #[test]
    fn a_field_named_if_is_not_a_keyword() {
        let fields = "a.if ".repeat(MAX_NESTING * 2);
        assert_eq!(depth_error(&fields), None);
    }

    #[test]
    fn an_if_after_a_comment_counts() {
        let text = "// note\nif ".repeat(MAX_NESTING + 1);
        assert!(depth_error(&text).is_some());
    }
}
