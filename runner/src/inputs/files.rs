//! Input files to the raw images `convert` takes: a PNG or EXR per input
//! (`npr render --input NAME=FILE`), or one multi-layer EXR for all of
//! them (`--inputs FILE.exr`), its layers found by name: Blender's
//! `<ViewLayer>.Combined`, `.Depth`, `.Normal`, `.IndexOB`, `.Vector` out
//! of the box, any other through `--map NAME=LAYER`.
//!
//! Every error is E0420 naming the input and the file; nothing is read
//! past the first.

use super::convert::{bad_input, ColorEncoding, DepthConvention, NormalConvention, SourceConvention};
use crate::image_level::Level;
use npr_abi::InputKind;
use npr_diag::Diagnostic;
use std::collections::BTreeMap;
use std::path::Path;

/// An EXR's channels by full name (`ViewLayer.Depth.Z`, or `R` in a
/// single-layer file), each row by row from the top, all of one size.
pub struct ExrChannels {
    pub width: u32,
    pub height: u32,
    pub channels: BTreeMap<String, Vec<f32>>,
}

/// The layer Blender writes each kind to (the part after the view layer's
/// name): what `--inputs` looks for when `--map` names none.
pub fn blender_layer(kind: InputKind) -> Option<&'static str> {
    match kind {
        InputKind::Color { .. } => Some("Combined"),
        InputKind::Depth => Some("Depth"),
        InputKind::Normal { .. } => Some("Normal"),
        InputKind::Id => Some("IndexOB"),
        InputKind::Motion => Some("Vector"),
        InputKind::Image { .. } => None,
    }
}

/// Channel letters in the order they fill r, g, b, a.
const ORDER: [&str; 9] = ["R", "G", "B", "A", "X", "Y", "Z", "W", "V"];

/// Every channel of `path`, an OpenEXR file (one part or several; a part's
/// name prefixes its channels).
pub fn read_exr(name: &str, path: &Path) -> Result<ExrChannels, Diagnostic> {
    let file = path.display().to_string();
    let image = exr::prelude::read_all_flat_layers_from_file(path).map_err(|e| {
        bad_input(
            name,
            &file,
            format!("not a readable OpenEXR file: {e}"),
            "give a PNG or EXR image (a multi-layer EXR with --inputs)",
        )
    })?;
    let mut out = ExrChannels {
        width: 0,
        height: 0,
        channels: BTreeMap::new(),
    };
    for layer in &image.layer_data {
        let (w, h) = (layer.size.x() as u32, layer.size.y() as u32);
        if out.channels.is_empty() {
            (out.width, out.height) = (w, h);
        } else if (w, h) != (out.width, out.height) {
            return Err(bad_input(
                name,
                &file,
                format!("its parts differ in size ({}x{} and {w}x{h})", out.width, out.height),
                "give layers of one size",
            ));
        }
        let part = layer.attributes.layer_name.as_ref().map(|t| t.to_string());
        for c in &layer.channel_data.list {
            let key = match &part {
                Some(p) => format!("{p}.{}", c.name),
                None => c.name.to_string(),
            };
            out.channels.insert(key, c.sample_data.values_as_f32().collect());
        }
    }
    Ok(out)
}

/// The layers of `exr` (channel names without their last component).
fn layer_names(exr: &ExrChannels) -> Vec<String> {
    let mut v: Vec<String> = exr
        .channels
        .keys()
        .map(|k| k.rsplit_once('.').map_or(String::new(), |(l, _)| l.to_string()))
        .collect();
    v.dedup();
    v
}

/// The channels of layer `layer` in `exr`: those named `layer.C`, or
/// `<view layer>.layer.C`; `""` is the un-prefixed channels. In `ORDER`.
fn layer_channels<'a>(exr: &'a ExrChannels, layer: &str) -> Vec<(&'a str, &'a [f32])> {
    let mut found: Vec<(&str, &[f32])> = exr
        .channels
        .iter()
        .filter_map(|(k, v)| {
            let (l, c) = k.rsplit_once('.').unwrap_or(("", k.as_str()));
            let matches = l == layer || (!layer.is_empty() && l.ends_with(&format!(".{layer}")));
            matches.then_some((c, v.as_slice()))
        })
        .collect();
    found.sort_by_key(|(c, _)| ORDER.iter().position(|o| o == c).unwrap_or(ORDER.len()));
    found
}

/// Input `name` of `kind` from layer `layer` of `exr` (read from `file`),
/// as the raw image `convert` takes.
pub fn exr_layer(name: &str, file: &str, kind: InputKind, exr: &ExrChannels, layer: &str) -> Result<Level, Diagnostic> {
    let found = layer_channels(exr, layer);
    let want = kind.channels() as usize;
    // A colour without alpha is opaque.
    let least = if matches!(kind, InputKind::Color { .. }) {
        3
    } else {
        want
    };
    if found.len() < least {
        let what = if found.is_empty() {
            format!("no layer `{layer}`")
        } else {
            format!(
                "layer `{layer}` has {} channel(s), and {} needs {least}",
                found.len(),
                kind.name()
            )
        };
        return Err(bad_input(
            name,
            file,
            format!(
                "{what}; its layers are: {}",
                layer_names(exr)
                    .iter()
                    .map(|l| if l.is_empty() { "(unnamed)" } else { l.as_str() })
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            "name the layer that holds it: `--map NAME=LAYER`",
        ));
    }
    let pixels = (0..(exr.width * exr.height) as usize)
        .map(|i| {
            let mut p = [0.0, 0.0, 0.0, 1.0];
            for (c, (_, v)) in found.iter().take(want).enumerate() {
                p[c] = v[i];
            }
            p
        })
        .collect();
    Ok(Level {
        width: exr.width,
        height: exr.height,
        pixels,
    })
}

/// The convention a file of this type states for `kind`, unless the user
/// says otherwise: an EXR holds linear colour, an 8-bit image sRGB; depth
/// is Cycles' (distance along the view axis, 1e10 for the background);
/// normals found under Blender's layer name are in Blender's Z-up world,
/// others in npr's.
pub fn file_convention(kind: InputKind, exr: bool, blender_normals: bool) -> SourceConvention {
    match kind {
        InputKind::Color { .. } if exr => SourceConvention::Color(ColorEncoding::Linear),
        InputKind::Color { .. } => SourceConvention::Color(ColorEncoding::Srgb),
        InputKind::Depth => SourceConvention::Depth(DepthConvention::CYCLES),
        InputKind::Normal { .. } if blender_normals => SourceConvention::Normal(NormalConvention::WorldZUp),
        InputKind::Normal { .. } => SourceConvention::Normal(NormalConvention::World),
        InputKind::Id | InputKind::Motion | InputKind::Image { .. } => SourceConvention::AsIs,
    }
}

/// One input from its own file: an EXR's un-prefixed channels (or its one
/// layer), or any image npr reads as a texture (PNG).
/// Also says whether the file holds normalized integers (a PNG: normals in
/// it are stored as n·0.5 + 0.5).
pub fn single_file(name: &str, kind: InputKind, path: &Path) -> Result<(Level, SourceConvention, bool), Diagnostic> {
    let file = path.display().to_string();
    let is_exr = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    if is_exr {
        let exr = read_exr(name, path)?;
        let layers = layer_names(&exr);
        let layer = if layers.len() == 1 {
            layers[0].clone()
        } else {
            String::new()
        };
        let blender = blender_layer(kind).is_some_and(|b| layer == b || layer.ends_with(&format!(".{b}")));
        let level = exr_layer(name, &file, kind, &exr, &layer)?;
        return Ok((level, file_convention(kind, true, blender), false));
    }
    let img = crate::texture_file::read(path)
        .map_err(|e| bad_input(name, &file, texture_error(e), "give a PNG or EXR image"))?;
    let rgba = img.to_rgba32f();
    let (width, height) = rgba.dimensions();
    let pixels = rgba.pixels().map(|p| p.0).collect();
    // 16- and 32-bit float images are linear; 8- and 16-bit integer ones sRGB.
    let float = matches!(img.color(), image::ColorType::Rgb32F | image::ColorType::Rgba32F);
    Ok((
        Level { width, height, pixels },
        file_convention(kind, float, false),
        !float,
    ))
}

/// The size of input `name`'s file `path` from its header alone: a
/// sequence's frames are checked before any is read.
pub fn header_size(name: &str, path: &Path) -> Result<(u32, u32), Diagnostic> {
    let file = path.display().to_string();
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
        let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| {
            bad_input(
                name,
                &file,
                format!("not a readable OpenEXR file: {e}"),
                "give a PNG or EXR image (a multi-layer EXR with --inputs)",
            )
        })?;
        return meta
            .headers
            .first()
            .map(|h| (h.layer_size.x() as u32, h.layer_size.y() as u32))
            .ok_or_else(|| {
                bad_input(
                    name,
                    &file,
                    "an OpenEXR file without a part".into(),
                    "re-render the file",
                )
            });
    }
    crate::texture_file::probe(path).map_err(|e| bad_input(name, &file, texture_error(e), "give a PNG or EXR image"))
}

/// What is wrong with an image file npr reads as a texture.
fn texture_error(e: crate::texture_file::TextureFileError) -> String {
    use crate::texture_file::TextureFileError as E;
    match e {
        E::Unreadable(e) => format!("cannot be read: {e}"),
        E::NotAnImage(e) => format!("not an image npr can read: {e}"),
        E::TooLarge { width, height } => format!(
            "{width}x{height}, past the largest image npr loads ({} px a side)",
            npr_diag::limits::MAX_TEXTURE_SIZE
        ),
    }
}
