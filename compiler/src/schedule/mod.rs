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
//!
//! What each pass got, and why, goes in the `--report` (`schedule` entries),
//! with the apron a tiled schedule of it would need ([`footprint`]).

pub mod footprint;
mod fuse;
pub mod tile;

use crate::ir::Ir;
use crate::prune::Live;
use crate::report::Report;

/// `--schedule naive|auto`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Schedule {
    /// Every declared pass runs as written: every target exists, so
    /// `--dump-passes` and the studio's thumbnails use it.
    Naive,
    /// The compiler's choice: fusion where it saves a target and a pass.
    /// The default: `tests/schedule_equivalence.rs` shows it gives the naive
    /// image, bit for bit, on every example.
    #[default]
    Auto,
    /// `auto` plus workgroup tiles for neighbourhood passes: the same image
    /// (`tests/schedule_equivalence.rs`), slower on lavapipe.
    Tiled,
}

/// Applies `schedule` to the live passes: rewrites `ir` and `live` (fused
/// passes leave `live.passes`, their targets `live.targets`) and reports
/// each image pass's schedule.
pub fn apply(ir: &mut Ir, live: &mut Live, schedule: Schedule, report: &mut Report) {
    match schedule {
        Schedule::Naive => {}
        Schedule::Auto => {
            fuse::fuse_pointwise(ir, live, report);
            tile::tile_neighbourhoods(ir, live, report, false);
        }
        Schedule::Tiled => {
            fuse::fuse_pointwise(ir, live, report);
            tile::tile_neighbourhoods(ir, live, report, true);
        }
    }
}
