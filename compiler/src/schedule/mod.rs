//! Schedules: how the passes a style declares are run. The style fixes the
//! algorithm (what each pass computes, at which precision); the schedule is
//! the compiler's, and every schedule gives the naive one's image.
//!
//! - `naive`: one GPU pass per declared pass, each target stored and read
//!   back, exactly as written.
//! - `auto`: image passes whose only reader reads them at its own pixel are
//!   fused into that reader (`fuse`); the rounding of the skipped target's
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
//! setting overrides it for that pass (`Plan`). `schedule: recompute`
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
mod plan;
pub mod recompute;
pub mod tile;
mod unstored;

/// The schedules' names are IR data (a pass's `schedule:` setting holds
/// one); they are offered here too, where the schedules are described.
pub use crate::ir::Schedule;

use crate::ir::Ir;
use crate::mid::prune::Live;
use crate::report::Report;
use npr_diag::{Diagnostic, FileId, SourceMap};
use plan::Plan;

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
