//! The proved ranges as text: one line per live target (its format, its
//! range, "finite for all declared params" or not) and, under a target
//! not proved finite, where the proof stops (`file:line:col`). One
//! implementation for its two callers, `npr check --ranges` and
//! `npr compile --report` (and the `report.txt` beside the WGSL).

use super::TargetRange;
use npr_diag::SourceMap;

/// The ranges of `targets`, with spans resolved through `sources`.
pub fn render(targets: &[TargetRange], sources: &SourceMap) -> String {
    let mut out = String::from("value ranges (each param over its declared range; `--set` values fixed):\n");
    for t in targets {
        let verdict = if t.value_finite {
            "finite for all declared params"
        } else {
            "not proved finite"
        };
        out.push_str(&format!(
            "  {} ({}): {} - {verdict}\n",
            t.name,
            t.format.name(),
            t.range
        ));
        for (span, what) in &t.stops {
            let (line, col) = sources.line_col(span.file, span.start);
            let file = sources.get(span.file).map_or("?", |f| f.name.as_str());
            out.push_str(&format!(
                "    stopped at {file}:{line}:{col}: `{}`: {what}\n",
                sources.snippet(*span)
            ));
        }
    }
    out
}
