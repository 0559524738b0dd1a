//! The compute-pass part of the manifest contract: workgroup sizes and
//! the pixel-tile schedule the emitter and the runner share, the `samples`
//! domain's settings, the domains, reductions and per-object value slots.

use super::*;

/// Invocations per workgroup of a compute pass's element stage: each
/// workgroup reduces [`ELEMENTS_PER_WORKGROUP`] elements of one object to one
/// partial per value, with a tree reduction in workgroup memory.
pub const ELEMENT_WORKGROUP: u32 = 256;
/// Elements each invocation of the element stage accumulates before the tree.
pub const ELEMENTS_PER_INVOCATION: u32 = 4;
/// Elements one element-stage workgroup covers.
pub const ELEMENTS_PER_WORKGROUP: u32 = ELEMENT_WORKGROUP * ELEMENTS_PER_INVOCATION;
/// Invocations of the object stage's workgroup, which reduces one object's
/// partials (one workgroup per object).
pub const OBJECT_WORKGROUP: u32 = 64;
/// A `pixels` pass's element workgroup covers a tile of
/// `PIXEL_TILE × PIXEL_TILE` pixels at a time: its [`ELEMENT_WORKGROUP`]
/// invocations are a 16 × 16 grid, each with 2 × 2 pixels 16 apart (so
/// every round of the reduction spends its barriers on 4 pixels per
/// invocation, not 1).
pub const PIXEL_TILE: u32 = 32;
/// Most element workgroups of a `pixels` pass; each loops over every
/// `workgroups`-th tile, so the partials (one per workgroup per object per
/// value) do not grow with the image.
pub const MAX_PIXEL_WORKGROUPS: u32 = 256;
/// The partials of a `pixels` pass stay under this many bytes: with many
/// objects it runs fewer element workgroups.
pub const PIXEL_PARTIALS_BUDGET: u64 = 64 << 20;

/// The element workgroups of a `pixels` pass over an ID target of `size` (in tiles of [`PIXEL_TILE`]²)
/// with `objects` objects in the scene and `values` reduced values: one per
/// tile, at most [`MAX_PIXEL_WORKGROUPS`], and fewer when the partials
/// (`workgroups × objects × values` slots of 16 bytes) would pass
/// [`PIXEL_PARTIALS_BUDGET`]. At least 1.
pub fn pixel_workgroups(size: (u32, u32), objects: u64, values: u64) -> u32 {
    let tiles = u64::from(size.0.div_ceil(PIXEL_TILE)) * u64::from(size.1.div_ceil(PIXEL_TILE));
    let per_workgroup = objects.max(1) * values.max(1) * 16;
    let budget = (PIXEL_PARTIALS_BUDGET / per_workgroup).max(1);
    tiles.min(u64::from(MAX_PIXEL_WORKGROUPS)).min(budget).max(1) as u32
}

/// The stratified surface samples of a `samples` pass (Breslav et al.
/// 2007 §3.1): about `count` per object, drawn from `seed` (the object's
/// index is mixed in, so objects sharing a mesh get different samples).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct SampleSpec {
    pub count: u32,
    pub seed: u32,
}

/// Most samples per object a `samples` pass may ask for.
pub const MAX_SAMPLES_PER_OBJECT: u32 = 1 << 20;

/// Words (`u32`) per sample in a `samples` pass's sample buffer: the three
/// vertex indices of its triangle (into the pass's pooled vertices), its
/// barycentric b1 and b2 and the object's sample spacing (f32 bits).
pub const SAMPLE_WORDS: u32 = 6;

/// What a compute pass runs over.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ComputeDomain {
    /// One invocation per object (`objects_entry`, workgroups of
    /// [`OBJECT_WORKGROUP`]).
    Objects,
    /// Every vertex of every object: the element stage (`elements_entry`,
    /// ⌈vertices / ELEMENTS_PER_WORKGROUP⌉ workgroups per object, all in one
    /// dispatch, writing partials), then the object stage (`objects_entry`,
    /// one workgroup per object, reducing its partials).
    Vertices,
    /// Every pixel of an ID target (`pixels_of`), reduced per object by the
    /// ID at the pixel: the element stage (`elements_entry`, at most
    /// [`MAX_PIXEL_WORKGROUPS`] workgroups, each looping over tiles and, per
    /// tile, over the distinct IDs in it), then the object stage as for
    /// `Vertices`.
    Pixels,
    /// Stratified sample points on every object's surface (`samples`),
    /// each stored as a triangle and barycentric coordinates: the element
    /// and object stages as for `Vertices`.
    Samples,
}

impl ComputeDomain {
    /// Whether its elements are points on the objects' meshes (vertices or
    /// surface samples), read from the members' pooled vertex attributes.
    pub fn on_meshes(self) -> bool {
        matches!(self, ComputeDomain::Vertices | ComputeDomain::Samples)
    }

    /// As a style writes it: `compute(objects)`, `compute(vertices)`.
    pub fn name(self) -> &'static str {
        match self {
            ComputeDomain::Objects => "objects",
            ComputeDomain::Vertices => "vertices",
            ComputeDomain::Pixels => "pixels",
            ComputeDomain::Samples => "samples",
        }
    }

    /// Whether the pass reduces elements (an element stage, then the object
    /// stage), rather than running once per object.
    pub fn has_elements(self) -> bool {
        match self {
            ComputeDomain::Objects => false,
            ComputeDomain::Vertices | ComputeDomain::Pixels | ComputeDomain::Samples => true,
        }
    }
}

/// How a reduced value combines its elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReduceOp {
    Sum,
    Min,
    Max,
}

impl ReduceOp {
    pub const ALL: [(&'static str, ReduceOp); 3] =
        [("sum", ReduceOp::Sum), ("min", ReduceOp::Min), ("max", ReduceOp::Max)];

    pub fn name(self) -> &'static str {
        match self {
            ReduceOp::Sum => "sum",
            ReduceOp::Min => "min",
            ReduceOp::Max => "max",
        }
    }
}

/// How a per-object value slot of a compute pass is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ValueKind {
    /// `reduce`: over the elements of each object.
    Reduce(ReduceOp),
    /// `out`: once per object.
    Out,
    /// `state`: once per object, from its own previous value.
    State,
}

/// One per-object value of a compute pass: slot `i` of object `o` is the
/// `vec4<f32>` at index `o * slots + i` of the pass's value buffer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ValueSlot {
    pub name: String,
    /// `float`, `vec2`, `vec3` or `vec4` (the slot's leading components).
    pub ty: String,
    pub kind: ValueKind,
}
