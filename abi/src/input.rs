//! Host inputs: the images a style takes from the renderer that runs it
//! (`texture c = input(color, linear)`), each with a semantic kind that
//! fixes what its texels mean inside the language (issue 47).
//!
//! **One convention inside the language.** Whatever the host or file wrote,
//! the runner converts at load so that a style reads:
//! - `color`: linear-light RGB and straight alpha (a display-referred
//!   source is decoded from sRGB at load; `display` only says which the
//!   host gives when it cannot say itself, e.g. a PNG);
//! - `depth`: in `r`, the positive distance from the camera along its view
//!   axis in metres, the value npr's own `depth` builtin gives
//!   (`-(view · position).z`); `0` where nothing was hit (a cleared target's
//!   value; Blender writes 1e10 there, reverse-Z writes 0 NDC);
//! - `normal`: in `rgb`, the unit surface normal in world space, the value
//!   of npr's `normal` builtin (not encoded as n·0.5 + 0.5); `0` where
//!   nothing was hit. `space` is the space the style wants it in: `view`
//!   turns it into view space, as `normal.view`;
//! - `id`: in `r`, an object or material id as a whole number, `0` for none
//!   (npr's `object.id` convention);
//! - `motion`: in `rg`, the screen-space motion from the previous frame to
//!   this one, in pixels, +x right and +y down;
//! - `image`: anything else, with the format it is read as.

use crate::formats::Format;
use serde::{Deserialize, Serialize};

/// The space a normal input is read in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalSpace {
    World,
    View,
}

/// What an input's texels mean (see the module documentation for each
/// kind's convention inside the language).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "input", rename_all = "snake_case")]
pub enum InputKind {
    /// Colour; `display`: the style reads display-referred (sRGB-encoded)
    /// values, else linear light.
    Color {
        display: bool,
    },
    Depth,
    Normal {
        space: NormalSpace,
    },
    Id,
    Motion,
    /// A free-form image read as `format` (its channel count and range).
    Image {
        format: Format,
    },
}

impl InputKind {
    /// The kinds as a style names them, for messages and "did you mean".
    pub const NAMES: [&'static str; 6] = ["color", "depth", "normal", "id", "motion", "image"];

    /// The name a style writes for this kind.
    pub fn name(&self) -> &'static str {
        match self {
            InputKind::Color { .. } => "color",
            InputKind::Depth => "depth",
            InputKind::Normal { .. } => "normal",
            InputKind::Id => "id",
            InputKind::Motion => "motion",
            InputKind::Image { .. } => "image",
        }
    }

    /// How many channels of the texture carry the input's value.
    pub fn channels(&self) -> u32 {
        match self {
            InputKind::Color { .. } => 4,
            InputKind::Depth | InputKind::Id => 1,
            InputKind::Normal { .. } => 3,
            InputKind::Motion => 2,
            InputKind::Image { format } => format.channels(),
        }
    }
}

/// One `input(...)` texture of a manifest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputSpec {
    #[serde(flatten)]
    pub kind: InputKind,
}
