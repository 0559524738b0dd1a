//! Every target of a frame as a named layer of one OpenEXR file (`npr render
//! --layers`), for compositors (Nuke, Blender's compositor, Natron read
//! multi-part EXR, OpenEXR 2).
//!
//! Each target is a part named after it, at its own size (a target at
//! `scale: 0.5` is a half-size layer), with the channels its format has:
//! `R`, `R G` or `R G B A`. Float targets keep their precision exactly: a
//! 16-bit float target is stored as EXR half, a 32-bit one as float, the
//! texture's bits unchanged. An 8-bit target is stored as float `v / 255`,
//! the value a shader read of it gives (for an sRGB target, its colour
//! decoded to linear light, as an EXR holds and as the single-image `.exr`
//! output writes it). Compression is
//! lossless (`Encoding::FAST_LOSSLESS`), and the file is written atomically.

use crate::readback::TargetImage;
use exr::prelude::*;
use npr_abi::Format;
use std::path::Path;

/// The channel names of a format with `channels` channels.
fn channel_names(channels: u32) -> &'static [&'static str] {
    match channels {
        1 => &["R"],
        2 => &["R", "G"],
        _ => &["R", "G", "B", "A"],
    }
}

/// Channel `c` of every pixel of `img`, row by row from the top, in the
/// sample type that keeps the target's values exactly.
fn channel_samples(img: &TargetImage, c: usize) -> FlatSamples {
    let channels = img.format.channels() as usize;
    let bpp = img.format.bytes_per_pixel() as usize;
    let size = bpp / channels;
    let samples = img.bytes.chunks_exact(bpp).map(move |px| &px[c * size..(c + 1) * size]);
    match img.format {
        Format::R16float | Format::Rg16float | Format::Rgba16float => FlatSamples::F16(
            samples
                .map(|b| f16::from_bits(u16::from_le_bytes([b[0], b[1]])))
                .collect(),
        ),
        Format::R32float | Format::Rg32float | Format::Rgba32float => {
            FlatSamples::F32(samples.map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect())
        }
        Format::R8unorm | Format::Rg8unorm | Format::Rgba8unorm | Format::Rgba8unormSrgb => {
            // As a shader reads it: an sRGB target's colour decoded to
            // linear, since an EXR holds linear light.
            let srgb = img.format == Format::Rgba8unormSrgb;
            FlatSamples::F32(samples.map(|b| crate::srgb::unorm8_as_read(b[0], c, srgb)).collect())
        }
    }
}

/// One EXR layer of a target.
fn layer(img: &TargetImage) -> Layer<AnyChannels<FlatSamples>> {
    let names = channel_names(img.format.channels());
    let channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = names
        .iter()
        .enumerate()
        .map(|(c, name)| AnyChannel::new(*name, channel_samples(img, c)))
        .collect();
    Layer::new(
        (img.width as usize, img.height as usize),
        LayerAttributes::named(img.name.as_str()),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels),
    )
}

/// The bytes of one EXR holding every image of `images` as a layer named
/// after it; the display window is the largest layer's size.
pub fn encode_layers(images: &[TargetImage]) -> std::io::Result<Vec<u8>> {
    if images.is_empty() {
        return Err(std::io::Error::other("no targets to write as layers"));
    }
    let (w, h) = images
        .iter()
        .fold((0, 0), |(w, h), i| (w.max(i.width), h.max(i.height)));
    let layers: Layers<AnyChannels<FlatSamples>> = images.iter().map(layer).collect();
    let image = Image::from_layers(
        ImageAttributes::new(IntegerBounds::from_dimensions((w as usize, h as usize))),
        layers,
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| std::io::Error::other(format!("encoding the EXR layers: {e}")))?;
    Ok(bytes.into_inner())
}

/// Write [`encode_layers`] of `images` to `path` atomically.
pub fn write_layers(images: &[TargetImage], path: &Path) -> std::io::Result<()> {
    crate::output::write_atomic(path, &encode_layers(images)?)
}
