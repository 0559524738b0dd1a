//! What the schedule decided, as data the IR carries to the back end:
//! which image passes run over workgroup tiles ([`Tiling`]) and which
//! targets are computed in their reader's tiles instead of stored
//! ([`Recomputed`]), and the [`Schedule`] names the style and the command
//! line choose from. The decisions themselves are `crate::schedule`'s; this
//! module only holds their outcome, so the IR depends on no stage.

use super::{PassId, TargetRef};
use npr_abi::manifest::TILE_SIZE;
use serde::Serialize;

/// `--schedule naive|auto|tiled|recompute`, and the `schedule:` setting of
/// an image pass (what each does: `crate::schedule`).
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

/// Bytes of one channel of a tile texel (an `f32`: what `textureLoad`
/// returns, whatever the target's format).
const CHANNEL_BYTES: u32 = 4;

/// Where a tile's texels come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum TileSource {
    /// `textureLoad` of the stored target.
    Load,
    /// The producer's expression, evaluated at each texel: the target is
    /// not stored (`schedule/recompute.rs`).
    Recompute,
}

/// One target a tiled pass keeps in workgroup memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct TileRead {
    pub target: TargetRef,
    /// The apron, in texels on each side of the `TILE_SIZE`² block.
    pub radius: u32,
    pub source: TileSource,
    /// The target's channels (1, 2 or 4): a tile texel keeps those alone,
    /// so a depth tile is a quarter of an `rgba32float` one.
    pub channels: u32,
}

impl TileRead {
    /// Texels per row (and rows) of the tile with its apron.
    pub fn side(&self) -> u32 {
        TILE_SIZE + 2 * self.radius
    }

    pub fn bytes(&self) -> u32 {
        self.side() * self.side() * self.channels * CHANNEL_BYTES
    }
}

/// How one image pass is tiled (`schedule/tile.rs`): the targets kept in
/// workgroup memory.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Tiling {
    pub reads: Vec<TileRead>,
}

impl Tiling {
    /// Workgroup memory all its tiles take.
    pub fn bytes(&self) -> u32 {
        self.reads.iter().map(TileRead::bytes).sum()
    }
}

/// A target that is not stored: its reader computes it in its tiles
/// (`schedule/recompute.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Recomputed {
    /// The pass that reads it (tiled), the producer's only reader.
    pub reader: PassId,
    /// How far around its pixel the reader reads it: the tile's apron.
    pub radius: u32,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tile_is_its_block_and_apron_of_its_channels() {
        let t = TileRead {
            target: TargetRef {
                pass: PassId(0),
                output: 0,
            },
            radius: 2,
            source: TileSource::Load,
            channels: 4,
        };
        assert_eq!(t.side(), 20);
        assert_eq!(t.bytes(), 20 * 20 * 16);
        let depth = TileRead { channels: 1, ..t };
        assert_eq!(depth.bytes(), 20 * 20 * 4);
    }
}
