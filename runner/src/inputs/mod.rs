//! Host inputs (issue 47): the images a style declares with `input(...)`,
//! given by the host or read from files, converted from the source's
//! convention to the language's one (`npr_abi::input`), so that one style
//! runs unchanged on npr's own G-buffer and on any renderer's.
//!
//! - `convert.rs`: a source's convention (depth as view distance or
//!   reverse-Z, normals in which space and encoding, colour encoding)
//!   resolved into a [`Conversion`]; a file's values checked.
//! - `gpu.rs`: the conversion itself, one GPU draw for files and for a
//!   host's texture views alike (the one definition of each convention).
//! - `files.rs`: PNG/EXR files and multi-layer EXRs (Blender's layer names
//!   understood) to the raw images `convert` takes.

pub mod convert;
pub mod files;
pub mod gpu;

pub use convert::{
    prepare, ColorEncoding, Conversion, DepthConvention, Mismatch, MotionConvention, NormalConvention, SourceConvention,
};

use crate::image_level::Level;
use std::collections::BTreeMap;

/// One input read from a file: its image as the file holds it, and how it
/// becomes the language's convention (drawn on the GPU when it is bound).
#[derive(Debug, Clone)]
pub struct HostImage {
    pub raw: Level,
    pub conversion: Conversion,
}

/// Every input of a style by its declared name, all of one size.
pub type HostInputs = BTreeMap<String, HostImage>;

/// The size all of `inputs` share; `None` when there are none.
pub fn size(inputs: &HostInputs) -> Option<(u32, u32)> {
    inputs.values().next().map(|i| (i.raw.width, i.raw.height))
}

/// `image` converted on the GPU and read back, as the style reads it (in
/// half floats): for tests and tools that look at an input's values.
pub fn converted(device: &wgpu::Device, queue: &wgpu::Queue, image: &HostImage) -> Result<Level, crate::RunError> {
    let (width, height) = (image.raw.width, image.raw.height);
    let texture = gpu::input_texture(device, "npr input", width, height);
    gpu::convert_level(
        device,
        queue,
        &gpu::Converter::new(device),
        &image.raw,
        &image.conversion,
        &texture,
    );
    let read = crate::readback::read_texture(
        device,
        queue,
        &texture,
        width,
        height,
        npr_abi::Format::Rgba16float,
        "input",
    )?;
    let pixels = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| read.texel(x, y))
        .collect();
    Ok(Level { width, height, pixels })
}
