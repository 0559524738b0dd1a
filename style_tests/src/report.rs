//! How a run of `npr test` is reported: a line per test as it ends, and the
//! whole run as a human summary (counts, the slowest tests, each failure
//! with the images it wrote), one JSON document, or JUnit XML for CI.

use super::outcome::{Outcome, Status};
use std::fmt::Write;
use std::path::PathBuf;

/// How many of the slowest tests the summary names.
const SLOWEST: usize = 3;

/// `--format` (with the `clap` feature, a `clap::ValueEnum`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum ReportFormat {
    Human,
    Json,
    Junit,
}

/// The run as a whole.
pub struct RunReport<'a> {
    pub outcomes: &'a [Outcome],
    pub seconds: f64,
    /// Styles found without a test file.
    pub untested: &'a [PathBuf],
    /// Tests declared but left out by `--filter` or `--shard`.
    pub not_selected: usize,
}

fn status_word(s: Status) -> &'static str {
    match s {
        Status::Passed => "passed",
        Status::Failed => "failed",
        Status::Invalid => "invalid",
        Status::Internal => "internal error",
    }
}

/// One test's line, printed as it ends (`ok`, `FAIL`, ...), then one
/// indented line per failure.
pub fn line(o: &Outcome) -> String {
    let tag = match o.status {
        Status::Passed => "ok     ",
        Status::Failed => "FAIL   ",
        Status::Invalid => "INVALID",
        Status::Internal => "ERROR  ",
    };
    let mut s = format!("{tag} {} ({:.2} s)", o.id, o.seconds);
    if let Some(golden) = &o.blessed {
        let _ = write!(s, ", blessed {}", golden.display());
    }
    if let Some(note) = &o.note {
        let _ = write!(s, ", {note}");
    }
    for f in &o.failures {
        let _ = write!(s, "\n        {}: {}", f.check, f.message);
        for file in &f.files {
            let _ = write!(s, "\n          wrote {}", file.display());
        }
        if let Some(line) = &f.reproduce {
            let _ = write!(s, "\n          reproduce: {line}");
        }
    }
    s
}

fn count(outcomes: &[Outcome], status: Status) -> usize {
    outcomes.iter().filter(|o| o.status == status).count()
}

/// The human summary: counts, time, the slowest tests, what failed.
pub fn human(r: &RunReport) -> String {
    let mut s = String::new();
    let o = r.outcomes;
    let _ = write!(
        s,
        "{} test(s): {} passed, {} failed, {} invalid, {} internal error(s) in {:.1} s",
        o.len(),
        count(o, Status::Passed),
        count(o, Status::Failed),
        count(o, Status::Invalid),
        count(o, Status::Internal),
        r.seconds
    );
    if r.not_selected > 0 {
        let _ = write!(s, "; {} not selected by --filter/--shard", r.not_selected);
    }
    s.push('\n');
    let mut slowest: Vec<&Outcome> = o.iter().collect();
    slowest.sort_by(|a, b| b.seconds.total_cmp(&a.seconds));
    if o.len() > 1 {
        let named: Vec<String> = slowest
            .iter()
            .take(SLOWEST)
            .map(|t| format!("{} {:.2} s", t.id, t.seconds))
            .collect();
        let _ = writeln!(s, "slowest: {}", named.join(", "));
    }
    // The diagnostics were printed in full as each test ended: the recap
    // names each by its first line only, so none is read twice.
    for t in o.iter().filter(|t| t.status != Status::Passed) {
        let _ = writeln!(s, "{}", line(t));
        for m in &t.messages {
            if let Some(headline) = m.lines().find(|l| !l.trim().is_empty()) {
                let _ = writeln!(s, "        {}", headline.trim());
            }
        }
    }
    if !r.untested.is_empty() {
        let _ = writeln!(
            s,
            "note: {} style file(s) have no tests (a `<style>.tests.toml` beside them declares some)",
            r.untested.len()
        );
    }
    s
}

/// The run as one JSON document (one line).
pub fn json(r: &RunReport) -> String {
    let tests: Vec<serde_json::Value> = r
        .outcomes
        .iter()
        .map(|o| {
            serde_json::json!({
                "id": o.id,
                "style": o.style.display().to_string(),
                "name": o.name,
                "status": status_word(o.status),
                "seconds": o.seconds,
                "failures": o.failures.iter().map(|f| serde_json::json!({
                    "check": f.check,
                    "message": f.message,
                    "files": f.files.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
                    "reproduce": f.reproduce,
                })).collect::<Vec<_>>(),
                "note": o.note,
                "diagnostics": o.messages,
                "blessed": o.blessed.as_ref().map(|p| p.display().to_string()),
            })
        })
        .collect();
    let o = r.outcomes;
    let doc = serde_json::json!({
        "tests": tests,
        "summary": {
            "total": o.len(),
            "passed": count(o, Status::Passed),
            "failed": count(o, Status::Failed),
            "invalid": count(o, Status::Invalid),
            "internal": count(o, Status::Internal),
            "not_selected": r.not_selected,
            "seconds": r.seconds,
            "untested_styles": r.untested.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
        }
    });
    format!("{doc}\n")
}

fn xml_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // Characters XML 1.0 cannot hold at all (terminal colour codes).
            c if (c as u32) < 0x20 && !matches!(c, '\n' | '\r' | '\t') => out.push('?'),
            c => out.push(c),
        }
    }
    out
}

/// JUnit XML: one `<testsuite>` per style, one `<testcase>` per test; a
/// failed check is a `<failure>`, bad input or an internal error an `<error>`.
pub fn junit(r: &RunReport) -> String {
    let o = r.outcomes;
    let errors = count(o, Status::Invalid) + count(o, Status::Internal);
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<testsuites name=\"npr test\" tests=\"{}\" failures=\"{}\" errors=\"{errors}\" time=\"{:.3}\">",
        o.len(),
        count(o, Status::Failed),
        r.seconds
    );
    let mut styles: Vec<&PathBuf> = o.iter().map(|t| &t.style).collect();
    styles.dedup();
    for style in styles {
        let suite: Vec<&Outcome> = o.iter().filter(|t| &t.style == style).collect();
        let name = xml_escape(&style.display().to_string());
        let _ = writeln!(
            s,
            "  <testsuite name=\"{name}\" tests=\"{}\" failures=\"{}\" errors=\"{}\" time=\"{:.3}\">",
            suite.len(),
            suite.iter().filter(|t| t.status == Status::Failed).count(),
            suite
                .iter()
                .filter(|t| matches!(t.status, Status::Invalid | Status::Internal))
                .count(),
            suite.iter().map(|t| t.seconds).sum::<f64>()
        );
        for t in suite {
            let _ = write!(
                s,
                "    <testcase name=\"{}\" classname=\"{name}\" time=\"{:.3}\"",
                xml_escape(&t.name),
                t.seconds
            );
            match t.status {
                Status::Passed => s.push_str("/>\n"),
                Status::Failed => {
                    s.push_str(">\n");
                    for f in &t.failures {
                        let mut body = f.message.clone();
                        for file in &f.files {
                            let _ = write!(body, "\nwrote {}", file.display());
                        }
                        if let Some(line) = &f.reproduce {
                            let _ = write!(body, "\nreproduce: {line}");
                        }
                        let _ = writeln!(
                            s,
                            "      <failure type=\"{}\" message=\"{}\">{}</failure>",
                            f.check,
                            xml_escape(&f.message),
                            xml_escape(&body)
                        );
                    }
                    s.push_str("    </testcase>\n");
                }
                Status::Invalid | Status::Internal => {
                    let body = t.messages.join("\n");
                    let first = t.messages.first().and_then(|m| m.lines().next()).unwrap_or("");
                    let _ = writeln!(
                        s,
                        ">\n      <error type=\"{}\" message=\"{}\">{}</error>\n    </testcase>",
                        status_word(t.status),
                        xml_escape(first),
                        xml_escape(&body)
                    );
                }
            }
        }
        s.push_str("  </testsuite>\n");
    }
    s.push_str("</testsuites>\n");
    s
}
