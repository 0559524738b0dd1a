//! The `--report`: what the compiler removed or folded, and why.

use serde::Serialize;

#[derive(Debug, Clone, Default, Serialize)]
pub struct Report {
    pub entries: Vec<ReportEntry>,
}

#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ReportEntry {
    /// `removed`, `folded`, `kept`, `aliased`, `requires`, and the
    /// schedule's (`schedule`, `fused`, `tiled`, `recomputed`, and their
    /// `not …`): at most 14 characters, the width of the first column.
    pub action: &'static str,
    pub what: String,
    pub why: String,
}

impl Report {
    pub fn removed(&mut self, what: String, why: &str) {
        self.push("removed", what, why.to_string());
    }

    pub fn push(&mut self, action: &'static str, what: String, why: String) {
        self.entries.push(ReportEntry { action, what, why });
    }

    /// Human-readable, one line per entry.
    pub fn render(&self) -> String {
        let mut s = String::new();
        for e in &self.entries {
            s.push_str(&format!("{:<14} {:<36} {}\n", e.action, e.what, e.why));
        }
        s
    }
}
