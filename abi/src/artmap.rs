//! `artmap(image("…"), filter: "filter.npr", levels: auto)`: the manifest's
//! description of an art-map (Klein et al. 2000 §4.2): "we simply filter the
//! photorealistic images as in normal mip-mapping, but then apply an NPR
//! filter to each level independently". The runner builds it at load:
//! the box-filtered mip chain of the source image, then the filter style's
//! image passes run once per level, each level's result one mip level of
//! the art-map.
//!
//! The filter is a style of its own, compiled with the host style and
//! carried inline (its manifest and WGSL), so a compiled directory is still
//! one manifest. It reads the level it filters through its one
//! `filter_input()` texture; `resolution` is that level's size in texels
//! and `frame` its index (0 = the full-size level).

use crate::manifest::Manifest;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A filter style, compiled: what `Renderer::new_filter` runs per level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FilterProgram {
    /// The filter file as the art-map names it (for messages).
    pub path: String,
    pub manifest: Box<Manifest>,
    /// WGSL by shader file name, as in [`crate::StyleProgram`].
    pub shaders: BTreeMap<String, String>,
}

impl FilterProgram {
    pub fn program(&self) -> crate::StyleProgram {
        crate::StyleProgram {
            manifest: (*self.manifest).clone(),
            shaders: self.shaders.clone(),
            files: BTreeMap::new(),
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArtmapSpec {
    /// The image that is mip-mapped, then filtered level by level.
    pub path: String,
    pub resolved: String,
    pub srgb: bool,
    pub filter: FilterProgram,
    /// How many mip levels are built (and filtered), from the full size
    /// down; `None` (`levels: auto`) is the whole chain to 1×1. For a
    /// rip-map, the levels along each axis.
    pub levels: Option<u32>,
    /// `ripmap(...)` (§4.2, Fig. 7–8): every 2^-i × 2^-j level, filtered,
    /// packed into one atlas ([`RipmapAtlas`]) read by `sample_ripmap`;
    /// otherwise the levels are the texture's mip chain.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub rip: bool,
}

/// Where the rip-map level (i, j) — the source's width halved i times and
/// its height j times — lies in its atlas of 2W × 2H texels: x from
/// W·(2 − 2^(1−i)), y from H·(2 − 2^(1−j)) (each axis's levels side by
/// side, as the mips of one axis would be). `sample_ripmap.wgsl` computes
/// the same offsets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RipmapAtlas {
    pub width: u32,
    pub height: u32,
}

impl RipmapAtlas {
    /// Levels along an axis of `size` texels (to 1).
    pub fn levels(size: u32) -> u32 {
        32 - size.max(1).leading_zeros()
    }

    /// Every level (i, j) the atlas holds: levels along x times along y.
    pub fn level_count(&self) -> u32 {
        Self::levels(self.width) * Self::levels(self.height)
    }

    pub fn atlas_size(&self) -> (u32, u32) {
        (2 * self.width, 2 * self.height)
    }

    /// Size of level (i, j).
    pub fn level_size(&self, i: u32, j: u32) -> (u32, u32) {
        ((self.width >> i).max(1), (self.height >> j).max(1))
    }

    /// Top-left texel of level (i, j) in the atlas.
    pub fn offset(&self, i: u32, j: u32) -> (u32, u32) {
        let along = |size: u32, k: u32| (0..k).map(|l| (size >> l).max(1)).sum::<u32>();
        (along(self.width, i), along(self.height, j))
    }
}

impl ArtmapSpec {
    /// The most levels a chain can have (a 16384² image has 15).
    pub const MAX_LEVELS: u32 = 15;

    /// The levels of a `width × height` source that are built (for a
    /// rip-map: along the longer axis; the other stops at 1 texel).
    pub fn level_count(&self, width: u32, height: u32) -> u32 {
        let full = RipmapAtlas::levels(width.max(height));
        self.levels.map_or(full, |n| n.clamp(1, full))
    }
}

impl Manifest {
    /// What makes a manifest a filter: exactly one `filter_input()`
    /// texture, and image passes only (a filter runs on no scene).
    pub fn validate_filter(&self) -> Result<(), String> {
        use crate::manifest::TextureSourceManifest;
        let inputs = self
            .textures
            .iter()
            .filter(|t| t.source == TextureSourceManifest::FilterInput)
            .count();
        if inputs != 1 {
            return Err(format!("a filter reads one `filter_input()` texture, not {inputs}"));
        }
        if let Some(p) = self.passes.iter().find(|p| !p.kind.is_image()) {
            return Err(format!("pass `{}` of a filter is not an image pass", p.name));
        }
        Ok(())
    }
}
