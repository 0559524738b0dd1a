//! Target texture formats a pass output may declare, and what values fit them.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    R8unorm,
    Rg8unorm,
    Rgba8unorm,
    Rgba8unormSrgb,
    R16float,
    Rg16float,
    Rgba16float,
    R32float,
    Rg32float,
    Rgba32float,
}

impl Format {
    pub const ALL: &'static [(&'static str, Format)] = &[
        ("r8unorm", Format::R8unorm),
        ("rg8unorm", Format::Rg8unorm),
        ("rgba8unorm", Format::Rgba8unorm),
        ("rgba8unorm_srgb", Format::Rgba8unormSrgb),
        ("r16float", Format::R16float),
        ("rg16float", Format::Rg16float),
        ("rgba16float", Format::Rgba16float),
        ("r32float", Format::R32float),
        ("rg32float", Format::Rg32float),
        ("rgba32float", Format::Rgba32float),
    ];

    pub fn parse(name: &str) -> Option<Format> {
        Self::ALL.iter().find(|(n, _)| *n == name).map(|(_, f)| *f)
    }

    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, f)| *f == self)
            .map(|(n, _)| *n)
            .unwrap_or("?")
    }

    /// Number of channels, which must equal the components of the value written.
    pub fn channels(self) -> u32 {
        use Format::*;
        match self {
            R8unorm | R16float | R32float => 1,
            Rg8unorm | Rg16float | Rg32float => 2,
            Rgba8unorm | Rgba8unormSrgb | Rgba16float | Rgba32float => 4,
        }
    }

    /// unorm targets clamp to [0, 1]; float targets keep any value.
    pub fn is_unorm(self) -> bool {
        matches!(
            self,
            Format::R8unorm | Format::Rg8unorm | Format::Rgba8unorm | Format::Rgba8unormSrgb
        )
    }

    /// 32-bit float formats are not filterable without an optional feature.
    pub fn is_filterable(self) -> bool {
        !matches!(self, Format::R32float | Format::Rg32float | Format::Rgba32float)
    }

    /// Whether a pass may blend into a target of this format: wgpu blends
    /// 32-bit float formats only with `Features::FLOAT32_BLENDABLE`, which
    /// the runner does not request (lavapipe and many GPUs lack it).
    pub fn is_blendable(self) -> bool {
        !matches!(self, Format::R32float | Format::Rg32float | Format::Rgba32float)
    }

    pub fn bytes_per_pixel(self) -> u32 {
        use Format::*;
        match self {
            R8unorm => 1,
            Rg8unorm | R16float => 2,
            Rgba8unorm | Rgba8unormSrgb | Rg16float | R32float => 4,
            Rgba16float | Rg32float => 8,
            Rgba32float => 16,
        }
    }

    /// What storing a value in a target of this format and loading it back
    /// does to each channel: the rounding a fused pass must repeat so that it
    /// computes what the separate passes did (`compiler::schedule`).
    pub fn storage(self) -> Storage {
        use Format::*;
        match self {
            R32float | Rg32float | Rgba32float => Storage::Exact,
            R16float | Rg16float | Rgba16float => Storage::Half,
            R8unorm | Rg8unorm | Rgba8unorm => Storage::Unorm8,
            Rgba8unormSrgb => Storage::Srgb8,
        }
    }
}

/// How a format stores a channel (see [`Format::storage`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Storage {
    /// f32 in, the same f32 out.
    Exact,
    /// Rounded to the nearest binary16 (WGSL `pack2x16float`).
    Half,
    /// Clamped to [0, 1] and rounded to k/255 (WGSL `pack4x8unorm`:
    /// ⌊255·x + 0.5⌋).
    Unorm8,
    /// sRGB-encoded before the 8-bit rounding; no fused pass repeats it.
    Srgb8,
}

impl Storage {
    /// The stored value of one channel, in f64 (the constant evaluator's
    /// and the tests' definition; `None` for sRGB, which is never emulated).
    pub fn stored(self, x: f64) -> Option<f64> {
        match self {
            Storage::Exact => Some(x as f32 as f64),
            Storage::Half => Some(half::f16::from_f64(x).to_f64()),
            Storage::Unorm8 => Some((x.clamp(0.0, 1.0) * 255.0 + 0.5).floor() / 255.0),
            Storage::Srgb8 => None,
        }
    }
}
