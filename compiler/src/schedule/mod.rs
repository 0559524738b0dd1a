//! Schedules: how the passes a style declares are run. The style fixes the
//! algorithm (what each pass computes, at which precision); the schedule is
//! the compiler's, and every schedule gives the naive one's image.
//!
//! - `naive`: one GPU pass per declared pass, each target stored and read
//!   back, exactly as written.
//! - `auto`: image passes whose only reader reads them at its own pixel are
//!   fused into that reader ([`fuse`]); the rounding of the skipped target's
//!   format is repeated, so the image does not change. Each remaining
//!   image pass that a tile would serve is reported with its apron.
//! - `tiled`: `auto`, then image passes whose operators read targets
//!   around the pixel run as compute over workgroup tiles ([`tile`]). Not
//!   `auto`'s choice, by measurement: on lavapipe, the one device measured,
//!   a tiled pass costs 1.0–2.2× its fragment pass (docs/PERFORMANCE.md,
//!   "Tiled compute"); a device where tiles pay would make it the choice.
//! - `recompute`: `tiled`, then a neighbourhood pass whose one reader reads
//!   it around the pixel is not stored: the reader's workgroups compute it
//!   on their tile and apron ([`recompute`], Halide's `compute_at`). Not
//!   `auto`'s choice either, by the same measurement (docs/PERFORMANCE.md,
//!   "Recomputed tiles").
//!
//! `--schedule` sets the run's schedule; an image pass's `schedule:`
//! setting overrides it for that pass ([`Plan`]). `schedule: recompute`
//! asks that the pass be computed in its reader's tiles, under every
//! `--schedule`; where that cannot be, it is E0312 at the setting. `schedule: naive` runs
//! the pass as written: it is never fused into its reader, nothing is
//! fused into it, and it is not tiled. `schedule: tiled` runs it as its own
//! pass over tiles, also never fused either way, so whether it can be tiled
//! is a question about the pass as written, answered the same under every
//! `--schedule`; where the tiler refuses it, that is E0311 at the setting,
//! with the tiler's reason, never a silent fragment pass. `schedule: auto`
//! (the same as no setting) leaves the pass to `--schedule`; it does not
//! override `--schedule naive`, which `--dump-passes` and the studio use to
//! show every declared target.
//!
//! What each pass got, and why, goes in the `--report` (`schedule`,
//! `fused`, `tiled`, `not tiled` entries; a forced pass's say "forced by
//! `schedule: …` at line L"), with the apron a tiled schedule of it would
//! need ([`footprint`]).

pub mod footprint;
mod fuse;
pub mod recompute;
pub mod tile;
mod unstored;

use crate::ir::{Ir, PassId, PassKind};
use crate::mid::prune::Live;
use crate::report::Report;
use diag::{Diagnostic, FileId, SourceMap, Span};
use serde::Serialize;
use std::collections::BTreeMap;

/// `--schedule naive|auto|tiled`, and the `schedule:` setting of an image
/// pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum Schedule {
    /// Every declared pass runs as written: every target exists, so
    /// `--dump-passes` and the studio's thumbnails use it.
    Naive,
    /// The compiler's choice: fusion where it saves a target and a pass.
    /// The default: `tests/gpu/schedule_equivalence.rs` shows it gives the naive
    /// image, bit for bit, on every example.
    #[default]
    Auto,
    /// `auto` plus workgroup tiles for neighbourhood passes: the same image
    /// (`tests/gpu/schedule_equivalence.rs`), slower on lavapipe.
    Tiled,
    /// `tiled`, and each neighbourhood pass whose one reader reads it
    /// around the pixel is computed in that reader's tiles instead of
    /// stored: the same image, slower on lavapipe.
    Recompute,
}

impl Schedule {
    pub const ALL: [Schedule; 4] = [Schedule::Naive, Schedule::Auto, Schedule::Tiled, Schedule::Recompute];

    /// As written in a style and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Schedule::Naive => "naive",
            Schedule::Auto => "auto",
            Schedule::Tiled => "tiled",
            Schedule::Recompute => "recompute",
        }
    }

    pub fn parse(name: &str) -> Option<Schedule> {
        Schedule::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Whether neighbourhood passes run over workgroup tiles.
    pub fn tiles(self) -> bool {
        matches!(self, Schedule::Tiled | Schedule::Recompute)
    }
}

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
    fn new(ir: &Ir, run: Schedule, apron_deficit: u32, sources: &SourceMap, root: FileId) -> Plan {
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

/// Applies `schedule` (`--schedule`) and the passes' `schedule:` settings
/// to the live passes: rewrites `ir` and `live` (fused passes leave
/// `live.passes`, their targets `live.targets`) and reports each image
/// pass's schedule. A pass forced `tiled` that cannot be tiled is E0311,
/// one forced `recompute` that cannot be recomputed E0312, returned.
pub fn apply(
    ir: &mut Ir,
    live: &mut Live,
    schedule: Schedule,
    apron_deficit: u32,
    sources: &SourceMap,
    root: FileId,
    report: &mut Report,
) -> Vec<Diagnostic> {
    let plan = Plan::new(ir, schedule, apron_deficit, sources, root);
    fuse::fuse_pointwise(ir, live, &plan, report);
    let mut errors = recompute::recompute_neighbourhoods(ir, live, &plan, report);
    errors.extend(tile::tile_neighbourhoods(ir, live, &plan, report));
    errors
}
