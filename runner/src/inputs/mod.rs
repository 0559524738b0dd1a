//! Host inputs (issue 47): the images a style declares with `input(...)`,
//! given by the host or read from files, converted at load from the
//! source's convention to the language's one (`npr_abi::input`), so that
//! one style runs unchanged on npr's own G-buffer and on any renderer's.
//!
//! - `convert.rs`: a source's convention (depth as view distance or
//!   reverse-Z, normals in which space, colour encoding) to the language's.
//! - `files.rs`: PNG/EXR files and multi-layer EXRs (Blender's layer names
//!   understood) to the raw images `convert` takes.

pub mod convert;
pub mod files;

pub use convert::{convert, ColorEncoding, DepthConvention, NormalConvention, SourceConvention};

use crate::artmap::Level;
use std::collections::BTreeMap;

/// Every input of a style by its declared name, already in the language's
/// convention for its kind, all of one size.
pub type HostInputs = BTreeMap<String, Level>;

/// The size all of `inputs` share; `None` when there are none.
pub fn size(inputs: &HostInputs) -> Option<(u32, u32)> {
    inputs.values().next().map(|l| (l.width, l.height))
}
