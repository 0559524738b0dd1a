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

    /// Whether a compute shader can write this format as a storage texture
    /// in core WebGPU (no adapter feature): what a tiled image pass needs
    /// of its outputs.
    pub fn storage_capable(self) -> bool {
        matches!(
            self,
            Format::Rgba8unorm | Format::Rgba16float | Format::R32float | Format::Rg32float | Format::Rgba32float
        )
    }

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

    /// WebGPU's render-target pixel byte cost and component alignment of
    /// the format (the spec's table of colour formats): what a colour
    /// attachment adds to `maxColorAttachmentBytesPerSample`. 8-bit RGBA
    /// costs 8, not 4: the table's value.
    pub fn render_target_cost_and_alignment(self) -> (u64, u64) {
        use Format::*;
        match self {
            R8unorm => (1, 1),
            Rg8unorm => (2, 1),
            Rgba8unorm | Rgba8unormSrgb => (8, 1),
            R16float => (2, 2),
            Rg16float => (4, 2),
            Rgba16float => (8, 2),
            R32float => (4, 4),
            Rg32float => (8, 4),
            Rgba32float => (16, 4),
        }
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
    /// computes what the separate passes did (`npr_compiler::schedule`).
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
    /// Rounded to binary16 as the device rounds a store into a 16-bit float
    /// target ([`HalfRounding`]: Vulkan allows to nearest or toward zero).
    Half,
    /// Clamped to [0, 1] and rounded to k/255 (WGSL `pack4x8unorm`:
    /// ⌊255·x + 0.5⌋).
    Unorm8,
    /// sRGB-encoded before the 8-bit rounding; no fused pass repeats it.
    Srgb8,
}

impl Storage {
    /// The stored value of one channel, in f64 (the constant evaluator's
    /// definition, which runs before any pass is fused, so it never decides
    /// a fused pass's value; 16-bit floats round to nearest here, a device
    /// may truncate: [`HalfRounding`]). `None` for sRGB, never emulated.
    pub fn stored(self, x: f64) -> Option<f64> {
        match self {
            Storage::Exact => Some(x as f32 as f64),
            Storage::Half => Some(half::f16::from_f64(x).to_f64()),
            Storage::Unorm8 => Some((x.clamp(0.0, 1.0) * 255.0 + 0.5).floor() / 255.0),
            Storage::Srgb8 => None,
        }
    }
}

/// How a device rounds an f32 stored into a 16-bit float target. The Vulkan
/// specification leaves it to the implementation (round to nearest even, or
/// toward zero); Mesa's lavapipe truncates, so a fused pass that rounded to
/// nearest would differ from the stored target by one binary16 step. The
/// runner measures it once per renderer (`npr_runner::half_rounding`) and gives
/// it to every shader that repeats the rounding as the pipeline-overridable
/// constant [`HALF_ROUNDING_OVERRIDE`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HalfRounding {
    /// To the nearest binary16, ties to even.
    NearestEven,
    /// Toward zero: the dropped mantissa bits are cut off (past 65504, the
    /// largest finite binary16 is kept, not infinity).
    TowardZero,
}

/// The WGSL `override` a shader that repeats 16-bit float stores declares
/// (a `bool`, true when the device truncates; no default, so a runner that
/// does not set it fails to build the pipeline instead of guessing).
pub const HALF_ROUNDING_OVERRIDE: &str = "npr_f16_stores_truncate";

impl HalfRounding {
    /// The value of [`HALF_ROUNDING_OVERRIDE`] for this rounding.
    pub fn override_value(self) -> f64 {
        match self {
            HalfRounding::NearestEven => 0.0,
            HalfRounding::TowardZero => 1.0,
        }
    }

    /// `x` stored as binary16 with this rounding, back as f32: the bit-level
    /// definition the WGSL helper `npr_round_f16` implements and the
    /// runner's measurement compares with. Finite inputs only.
    pub fn round(self, x: f32) -> f32 {
        let a = x.abs();
        if a < 6.103_515_6e-5 {
            // binary16 subnormals are multiples of 2^-24 (exact scalings).
            let steps = f64::from(a) * 16_777_216.0;
            let steps = match self {
                HalfRounding::NearestEven => steps.round_ties_even(),
                HalfRounding::TowardZero => steps.trunc(),
            };
            return (steps / 16_777_216.0).copysign(f64::from(x)) as f32;
        }
        let bits = x.to_bits();
        let carry = match self {
            HalfRounding::NearestEven => 0xfff + ((bits >> 13) & 1),
            HalfRounding::TowardZero => 0,
        };
        let rounded = f32::from_bits(bits.wrapping_add(carry) & 0xffff_e000);
        if rounded.abs() > 65504.0 {
            return match self {
                HalfRounding::NearestEven => f32::INFINITY.copysign(x),
                HalfRounding::TowardZero => 65504.0f32.copysign(x),
            };
        }
        rounded
    }
}
