//! `npr explain CODE`: a long explanation of every code in
//! [`npr_diag::codes::ALL`] (what it means, a wrong example, the fixed one), as
//! rustc's `--explain` gives, and the nearest codes for one that does not
//! exist.
//!
//! The explanations are data, one file per code range (`syntax.rs` E00xx,
//! `names.rs` E01xx, `types.rs` E02xx, `ranges.rs` W0203–W0210, `passes.rs` E03xx (E0319–E0321 too) and W03xx, `line_sets.rs` E0313–E0318 and E0323,
//! `files.rs` E04xx and W04xx, `command_line.rs` E05xx,
//! `host.rs` E06xx). Each example is a
//! set of files and `npr` command lines, so `tests/general/explain.rs` runs every
//! pair through the `npr` binary: the wrong one must give exactly its code,
//! the fixed one none.

mod command_line;
mod files;
mod host;
mod line_sets;
mod names;
mod passes;
mod ranges;
mod syntax;
mod types;

/// The style file every example writes; its commands name it.
pub const STYLE_FILE: &str = "case.npr";

/// The explanation of one code.
#[derive(Debug)]
pub struct Explanation {
    pub code: &'static str,
    /// What the code means, in paragraphs separated by blank lines.
    pub meaning: &'static str,
    pub wrong: Example,
    pub fixed: Example,
}

/// How an example's files are written to disk.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    Utf8,
    /// Every character as one byte (Latin-1): what an old editor saves.
    Latin1,
}

/// One example: the style file, other files beside it, and the commands
/// that show the code (the last one) after the ones before it succeeded.
#[derive(Debug)]
pub struct Example {
    /// The text of [`STYLE_FILE`]; each `…` in it is replaced by the next
    /// entry of `repeat` (a piece written that many times), so an example
    /// past a limit can be shown short.
    pub style: &'static str,
    pub repeat: &'static [(&'static str, usize)],
    pub encoding: Encoding,
    /// Other files, by name relative to the style, and their text.
    pub files: &'static [(&'static str, &'static str)],
    /// `npr` argument lists run in the directory of the files; empty means
    /// `npr check case.npr`.
    pub commands: &'static [&'static [&'static str]],
    /// The last command is a server: it is fixed when it starts serving
    /// (prints its address), and the test stops it then.
    pub serves: bool,
    /// Why this example cannot be run on a machine where it is tested;
    /// `tests/general/explain.rs` lists these and runs everything else.
    pub not_runnable: Option<&'static str>,
    /// A host application's Rust code, shown instead of the style and the
    /// commands: the mistake is in a call of `npr_runner::embed`, not in a
    /// file `npr` reads (the host codes, E06xx).
    pub host_rust: Option<&'static str>,
}

/// The default of every field but `style`.
pub const EXAMPLE: Example = Example {
    style: "",
    repeat: &[],
    encoding: Encoding::Utf8,
    files: &[],
    commands: &[],
    serves: false,
    not_runnable: None,
    host_rust: None,
};

/// The command list of an example with no commands.
const CHECK: &[&[&str]] = &[&["check", STYLE_FILE]];

impl Example {
    /// The style file's text with every `…` expanded.
    pub fn style_text(&self) -> String {
        let mut out = String::new();
        let mut pieces = self.repeat.iter();
        for (i, part) in self.style.split('…').enumerate() {
            if i > 0 {
                if let Some((piece, n)) = pieces.next() {
                    out.push_str(&piece.repeat(*n));
                }
            }
            out.push_str(part);
        }
        out
    }

    /// The style file's bytes, in its encoding.
    pub fn style_bytes(&self) -> Vec<u8> {
        let text = self.style_text();
        match self.encoding {
            Encoding::Utf8 => text.into_bytes(),
            Encoding::Latin1 => text
                .chars()
                .map(|c| u8::try_from(u32::from(c)).unwrap_or(b'?'))
                .collect(),
        }
    }

    /// The commands to run (`npr check case.npr` when none are given).
    pub fn command_lines(&self) -> &'static [&'static [&'static str]] {
        if self.commands.is_empty() {
            CHECK
        } else {
            self.commands
        }
    }

    fn write_text(&self, out: &mut String) {
        if let Some(code) = self.host_rust {
            out.push_str("    // the host application (Rust)\n");
            for line in code.lines() {
                out.push_str(&format!("    {line}\n"));
            }
            if let Some(why) = self.not_runnable {
                out.push_str(&format!("    (not run by `npr explain`'s tests: {why})\n"));
            }
            return;
        }
        if !self.style.is_empty() {
            out.push_str(&format!("    // {STYLE_FILE}"));
            if self.encoding == Encoding::Latin1 {
                out.push_str(" (saved as Latin-1)");
            }
            out.push('\n');
            for line in self.style.lines() {
                out.push_str(&format!("    {line}\n"));
            }
            for (piece, n) in self.repeat {
                out.push_str(&format!("    // (each `…` is `{piece}` written {n} times)\n"));
            }
        }
        for (name, text) in self.files {
            out.push_str(&format!("\n    // {name}\n"));
            for line in text.lines() {
                out.push_str(&format!("    {line}\n"));
            }
        }
        out.push('\n');
        for args in self.command_lines() {
            out.push_str(&format!("    $ npr {}\n", args.join(" ")));
        }
        if let Some(why) = self.not_runnable {
            out.push_str(&format!("    (not run by the tests: {why})\n"));
        }
    }
}

/// Every explanation, in the order of [`npr_diag::codes::ALL`].
pub fn all() -> impl Iterator<Item = &'static Explanation> {
    syntax::ALL
        .iter()
        .chain(names::ALL)
        .chain(types::ALL)
        .chain(ranges::ALL)
        .chain(passes::ALL)
        .chain(line_sets::ALL)
        .chain(files::ALL)
        .chain(command_line::ALL)
        .chain(host::ALL)
}

/// The explanation of `code` (any letter case).
pub fn lookup(code: &str) -> Option<&'static Explanation> {
    all().find(|e| e.code.eq_ignore_ascii_case(code.trim()))
}

/// The one-line meaning of `code` from [`npr_diag::codes::ALL`].
pub fn summary(code: &str) -> Option<&'static str> {
    npr_diag::codes::ALL.iter().find(|(c, _)| *c == code).map(|(_, s)| *s)
}

/// The codes nearest to one that does not exist: the same letter and the
/// closest numbers first, then spelling (`E0z02` is near `E0202`).
pub fn nearest(code: &str, n: usize) -> Vec<&'static str> {
    let wanted = code.trim().to_ascii_uppercase();
    let number = |c: &str| c.get(1..).and_then(|d| d.parse::<i64>().ok());
    let letter = wanted.chars().next();
    let mut scored: Vec<(bool, i64, f64, &'static str)> = npr_diag::codes::ALL
        .iter()
        .map(|(c, _)| {
            let same_letter = c.chars().next() == letter;
            let distance = match (number(&wanted), number(c)) {
                (Some(a), Some(b)) => (a - b).abs(),
                _ => i64::MAX,
            };
            (!same_letter, distance, -strsim::jaro_winkler(&wanted, c), *c)
        })
        .collect();
    scored.sort_by(|a, b| (a.0, a.1).cmp(&(b.0, b.1)).then(a.2.total_cmp(&b.2)));
    scored.into_iter().take(n).map(|s| s.3).collect()
}

/// Codes whose one-line title shares words with `query` (`unit`,
/// `cannot write`, `misspelt` near `misspelled`), most shared words first;
/// a word matches a title word it equals or nearly spells (Jaro-Winkler
/// 0.88 or more, so `colour` finds `color` and `units` finds `unit`).
pub fn by_words(query: &str, n: usize) -> Vec<&'static str> {
    let words: Vec<String> = query
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| w.chars().count() >= 3 && !w.chars().any(|c| c.is_ascii_digit()))
        .map(str::to_lowercase)
        .collect();
    if words.is_empty() {
        return Vec::new();
    }
    let mut scored: Vec<(usize, f64, &'static str)> = npr_diag::codes::ALL
        .iter()
        .filter_map(|(code, title)| {
            let title_words: Vec<String> = title
                .split(|c: char| !c.is_alphanumeric())
                .filter(|w| !w.is_empty())
                .map(str::to_lowercase)
                .collect();
            let best: Vec<f64> = words
                .iter()
                .map(|w| {
                    title_words
                        .iter()
                        .map(|t| strsim::jaro_winkler(w, t))
                        .fold(0.0, f64::max)
                })
                .collect();
            let hits = best.iter().filter(|s| **s >= 0.88).count();
            (hits > 0).then(|| (hits, best.iter().sum::<f64>(), *code))
        })
        .collect();
    scored.sort_by(|a, b| b.0.cmp(&a.0).then(b.1.total_cmp(&a.1)));
    scored.into_iter().take(n).map(|s| s.2).collect()
}

/// A code written as its number alone (`202`, `0401`): the codes of that
/// number, E before W.
pub fn by_number(query: &str) -> Vec<&'static str> {
    let q = query.trim();
    if q.is_empty() || !q.chars().all(|c| c.is_ascii_digit()) {
        return Vec::new();
    }
    let Ok(n) = q.parse::<u32>() else {
        return Vec::new();
    };
    ["E", "W"]
        .iter()
        .filter_map(|l| {
            let code = format!("{l}{n:04}");
            npr_diag::codes::ALL.iter().find(|(c, _)| *c == code).map(|(c, _)| *c)
        })
        .collect()
}

/// The explanation as text for a terminal.
pub fn render(e: &Explanation) -> String {
    let mut out = format!("{}: {}\n\n", e.code, summary(e.code).unwrap_or(""));
    for paragraph in e.meaning.trim().split("\n\n") {
        out.push_str(&fill(paragraph, 76));
        out.push_str("\n\n");
    }
    out.push_str("Wrong:\n\n");
    e.wrong.write_text(&mut out);
    out.push_str("\nFixed:\n\n");
    e.fixed.write_text(&mut out);
    out
}

/// `text` with its whitespace re-flowed into lines of at most `width`.
fn fill(text: &str, width: usize) -> String {
    let mut out = String::new();
    let mut line_len = 0;
    for word in text.split_whitespace() {
        if line_len > 0 && line_len + 1 + word.chars().count() > width {
            out.push('\n');
            line_len = 0;
        } else if line_len > 0 {
            out.push(' ');
            line_len += 1;
        }
        out.push_str(word);
        line_len += word.chars().count();
    }
    out
}
