//! npr ABI: the one definition of the contract between the compiler, which
//! writes a compiled style, and the runner, which executes it.
//!
//! - [`manifest`]: the serde types of `manifest.json` (passes, targets,
//!   physical textures, bindings, parameters, uniform layouts).
//! - [`formats`]: the target texture formats.
//! - [`frame`]: the per-frame uniform block, one `#[repr(C)]` struct
//!   ([`FrameBlock`]) from which the WGSL `struct Frame` ([`FRAME_WGSL`]) is
//!   generated, so the two cannot drift apart.
//! - [`object`]: the fixed head of the per-object uniform block
//!   ([`ObjectHead`]) and its WGSL members ([`OBJECT_HEAD_WGSL`]), the same way.
//! - [`gradient`]: the slots of a `gradient` parameter kept live.
//! - [`lines`]: a `lines` pass's edges, shape settings and strip vertex.
//! - [`input`]: the images a style takes from its host ([`InputKind`]),
//!   and the one convention each kind has inside the language.
//! - [`noise`]: the parameters of a generated noise texture ([`NoiseSpec`]).
//! - [`scene`]: what the compiler may know about the scene ([`SceneSummary`]).
//! - [`param_literal`], [`param_value`]: a parameter's value as written
//!   (`--set` text), and the one rule typing it against a parameter
//!   (type, unit, range), which `--set` and a host's `set_param` share;
//!   [`Unit`], the dimensions of quantities.
//! - [`program`]: a compiled style as the runner takes it ([`StyleProgram`]),
//!   with [`StyleProgram::load_dir`], which validates every index of a
//!   manifest read from disk.
//! - [`bundle`]: a compiled style in one `.nprb` file (manifest, WGSL,
//!   image files), for programs that ship styles without the compiler.
//!
//! Neither the compiler nor the runner depends on the other; both depend on
//! this crate, which depends on neither.

pub mod artmap;
mod block;
pub mod bundle;
pub mod formats;
pub mod frame;
pub mod gradient;
pub mod halftone;
pub mod host_param;
pub mod input;
pub mod lines;
pub mod manifest;
pub mod noise;
pub mod object;
pub mod param_literal;
pub mod param_value;
pub mod program;
pub mod scene;
mod unit;
pub mod validate;

pub use artmap::{ArtmapSpec, FilterProgram, RipmapAtlas};
pub use formats::Format;
pub use frame::{FrameBlock, FRAME_WGSL};
pub use halftone::HalftoneTableSpec;
pub use input::{InputKind, InputSpec, NormalSpace};
pub use manifest::{Attribute, Manifest, ParamOverride, FRAME_UNIFORM_SIZE, MANIFEST_VERSION};
pub use noise::NoiseSpec;
pub use object::{ObjectHead, OBJECT_HEAD_WGSL};
pub use program::{LoadError, StyleProgram};
pub use scene::SceneSummary;
pub use unit::Unit;
