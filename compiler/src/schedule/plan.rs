//! Which schedule decides each image pass: the run's (`--schedule`), or the
//! pass's own `schedule:` setting, with where that setting is written (the
//! report and E0311/E0312 name it). Read by every scheduling stage
//! (`fuse.rs`, `tile.rs`, `recompute.rs`).

use crate::ir::{Ir, PassId, PassKind, Schedule};
use npr_diag::{FileId, SourceMap, Span};
use std::collections::BTreeMap;

/// A pass whose `schedule:` setting overrides the run's schedule.
#[derive(Debug, Clone)]
pub(crate) struct Forced {
    /// `Naive`, `Tiled` or `Recompute`: `schedule: auto` forces nothing.
    pub schedule: Schedule,
    pub span: Span,
    /// "line 12", or "line 12 of lib/x.npr" for a pass from a `use`d file.
    pub at: String,
}

impl Forced {
    /// The report's reason: "forced by `schedule: naive` at line 12".
    pub fn why(&self) -> String {
        format!("forced by `schedule: {}` at {}", self.schedule.name(), self.at)
    }
}

/// Which schedule decides each image pass: the run's (`--schedule`), or
/// the pass's own `schedule: naive | tiled`.
#[derive(Debug, Clone)]
pub(crate) struct Plan {
    pub run: Schedule,
    pub forced: BTreeMap<PassId, Forced>,
    /// `CompileOptions::tile_apron_deficit` (tests only).
    pub apron_deficit: u32,
}

impl Plan {
    pub fn new(ir: &Ir, run: Schedule, apron_deficit: u32, sources: &SourceMap, root: FileId) -> Plan {
        let mut forced = BTreeMap::new();
        for (i, p) in ir.passes.iter().enumerate() {
            let PassKind::Image { schedule: Some(s), .. } = &p.kind else {
                continue;
            };
            if s.schedule == Schedule::Auto {
                continue;
            }
            let (line, _) = sources.line_col(s.span.file, s.span.start);
            let at = match sources.get(s.span.file) {
                Some(f) if s.span.file != root => format!("line {line} of {}", f.name),
                _ => format!("line {line}"),
            };
            forced.insert(
                PassId(i as u32),
                Forced {
                    schedule: s.schedule,
                    span: s.span,
                    at,
                },
            );
        }
        Plan {
            run,
            forced,
            apron_deficit,
        }
    }

    pub fn forced(&self, pass: PassId) -> Option<&Forced> {
        self.forced.get(&pass)
    }
}
