//! The parameters of a generated tileable noise texture (`noise(...)` in a
//! style): resolved by the compiler, written into the manifest, and handed
//! to the runner's generator unchanged.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct NoiseSpec {
    /// Width and height in texels.
    pub size: u32,
    pub octaves: u32,
    pub seed: u32,
    /// Gradient (Perlin) noise; value noise otherwise.
    pub gradient: bool,
    /// Channels with independent noise (1..=4).
    pub channels: u32,
    /// Lattice cells across the texture at the first octave.
    pub frequency: u32,
}

impl NoiseSpec {
    /// The largest `size` (the compiler's `noise(size: ...)` range).
    pub const MAX_SIZE: u32 = 4096;
    /// The most octaves.
    pub const MAX_OCTAVES: u32 = 12;
    /// The most lattice cells at the first octave.
    pub const MAX_FREQUENCY: u32 = 256;
}
