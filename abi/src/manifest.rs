//! `manifest.json`: everything the runner needs to execute a compiled style.
//!
//! The manifest is the contract between compiler and runner. It lists the
//! passes in execution order, the logical targets and the physical textures
//! they alias onto, the bindings of every pass, the uniform layouts, the
//! parameters (with defaults, ranges, and what the compiler did with them),
//! and the scene attributes the style requires.
//!
//! Uniform layout invariant: every parameter slot in the style and object
//! uniform blocks is one `vec4<f32>` (16 bytes), whatever its type; ints and
//! bools are stored as floats. This keeps WGSL's alignment rules out of the
//! runner.

use crate::formats::Format;
use crate::frame::FrameBlock;
use crate::noise::NoiseSpec;
use serde::{Deserialize, Serialize};

mod compute;
mod device;
pub mod layout;
pub use compute::*;
pub use device::*;

/// Bumped whenever the layout of the manifest or of the fixed uniform blocks
/// changes, or what a field means (8: a `gradient` param kept live fills 21
/// slots; 9: a texture may be a host input, `TextureSourceManifest::Input`;
/// 10: a pass may test against a host's depth, `DepthMode::TestInput`
/// (decision 0057), and `Frame::ortho_height` says whether the camera is
/// orthographic (decision 0062), which shaders of version 9 ignore). The
/// loader reads `version` before the rest, so a manifest of another version
/// is refused by its number (`crate::program::parse_manifest`), not as
/// JSON of an unknown shape.
pub const MANIFEST_VERSION: u32 = 10;

/// The side of a [`PassKindManifest::TiledImage`] workgroup, in pixels.
pub const TILE_SIZE: u32 = 16;

/// Byte size of the fixed per-frame uniform block (`struct Frame` in every shader that reads it).
pub const FRAME_UNIFORM_SIZE: u64 = core::mem::size_of::<FrameBlock>() as u64;
/// Byte offset of the first parameter slot in the per-object block (after [`crate::ObjectHead`]).
pub const OBJECT_PARAMS_OFFSET: u64 = core::mem::size_of::<crate::object::ObjectHead>() as u64;
/// Alignment of per-object dynamic offsets.
pub const OBJECT_STRIDE_ALIGN: u64 = 256;

/// Bytes between two objects' blocks in the object buffer: the block size
/// rounded up to [`OBJECT_STRIDE_ALIGN`] (render passes bind one block at a
/// dynamic offset; compute passes read the buffer as an array of slots of
/// this size).
pub const fn object_stride(object_uniform_size: u64) -> u64 {
    let blocks = object_uniform_size.div_ceil(OBJECT_STRIDE_ALIGN);
    (if blocks == 0 { 1 } else { blocks }) * OBJECT_STRIDE_ALIGN
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    pub version: u32,
    pub style: String,
    pub source: String,
    /// Passes in execution order (a topological order of the pass DAG).
    pub passes: Vec<PassManifest>,
    /// Logical render targets, by index.
    pub targets: Vec<TargetManifest>,
    /// Physical textures; several targets with disjoint lifetimes may share one.
    pub physical: Vec<PhysicalTexture>,
    pub textures: Vec<TextureManifest>,
    pub params: Vec<ParamManifest>,
    /// Size in bytes of the style uniform block (0 = none).
    pub style_uniform_size: u64,
    /// Size in bytes of one object's uniform block, before alignment (0 = no render pass).
    pub object_uniform_size: u64,
    /// Vertex attributes the scene must provide.
    pub scene_attributes: Vec<Attribute>,
    /// The target that is the final image.
    pub output: usize,
    /// What the style needs of the device beyond WebGPU's defaults: an
    /// optional feature, or a limit above its default, each with the pass
    /// that needs it (empty for most styles). A host requests exactly
    /// these; the runner refuses a device without one (E0510).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub device_needs: Vec<DeviceNeed>,
}

impl Manifest {
    /// Whether a frame depends on earlier frames (a `previous(...)` read, or
    /// a compute pass with `state`):
    /// rendering frame `n` alone must then replay frames 0..n.
    pub fn is_path_dependent(&self) -> bool {
        self.physical.iter().any(|p| p.history)
            || self
                .passes
                .iter()
                .any(|p| matches!(p.kind, PassKindManifest::Compute { history: true, .. }))
    }

    /// Whether a pass reads a target of the other eye (`other_eye(...)`): the
    /// runner then renders both eyes of a stereo frame, pass by pass.
    pub fn is_stereo(&self) -> bool {
        self.passes.iter().flat_map(|p| &p.bindings).any(|b| {
            matches!(
                b.resource,
                Resource::Target {
                    copy: TargetCopy::OtherEye,
                    ..
                }
            )
        })
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Attribute {
    Position,
    Normal,
    Uv,
    Tangent,
    /// One `f32` per vertex: the blending weight of the patch being drawn
    /// (Breslav et al. 2007 §3.6), the `patch.weight` builtin. Every mesh
    /// has it: 1 at every vertex of an object without patches. A render pass
    /// that reads it draws each patch over its own faces and the n-ring of
    /// faces outside it (where its weight is above 0), so that the patches'
    /// weights sum to 1 at every pixel; every other pass draws a patch's own
    /// faces only. Render passes only: compute passes never read it.
    PatchWeight,
    /// Three `f32`s per vertex: its object-space position in the previous
    /// frame, which `position.previous` of compute passes over vertices
    /// and samples reads (through the previous `model`). An object playing
    /// a clip has its previous pose's (the GPU deformation stage keeps it,
    /// docs/decisions/0053); every other mesh's is its position buffer
    /// itself. Compute passes only, and without a binding of its own
    /// ([`Attribute::has_compute_binding`]).
    PreviousPosition,
}

impl Attribute {
    /// Whether a compute pass binds this attribute's pooled vertices as a
    /// storage buffer of its own (`a_<name>`, group 1, in list order after
    /// the objects and the members). The previous position has none: it is
    /// pooled in the position's buffer after every member's current
    /// positions (so `arrayLength(&a_position) / 6` vertices in), which
    /// keeps the pattern tracker's passes over samples within WebGPU's
    /// default of 8 storage buffers a stage.
    pub fn has_compute_binding(self) -> bool {
        self != Attribute::PreviousPosition
    }

    pub fn name(self) -> &'static str {
        match self {
            Attribute::Position => "position",
            Attribute::Normal => "normal",
            Attribute::Uv => "uv",
            Attribute::Tangent => "tangent",
            Attribute::PatchWeight => "patch_weight",
            Attribute::PreviousPosition => "previous_position",
        }
    }

    /// Its f32 components per vertex (WebGPU vertex format `float32`,
    /// `float32x2`, ...), tightly packed in its own vertex buffer.
    pub fn components(self) -> u32 {
        match self {
            Attribute::Position | Attribute::Normal | Attribute::PreviousPosition => 3,
            Attribute::Uv => 2,
            Attribute::Tangent => 4,
            Attribute::PatchWeight => 1,
        }
    }

    /// How the attribute is named in messages ("UVs", "tangents").
    pub fn plural_name(self) -> &'static str {
        match self {
            Attribute::Position => "positions",
            Attribute::Normal => "normals",
            Attribute::Uv => "UVs",
            Attribute::Tangent => "tangents",
            Attribute::PatchWeight => "patch weights",
            Attribute::PreviousPosition => "previous positions",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum PassKindManifest {
    Render {
        /// Draw only objects with this tag; `None` draws every object.
        tag: Option<String>,
        /// `view(light)`: projected with `Frame::light_view_proj`, whose
        /// x, y extent the runner fits to the objects such passes draw.
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        light_view: bool,
        /// Vertex attributes in location order (location = index).
        attributes: Vec<Attribute>,
        /// What the pass does with its depth buffer: `depth: keep` or
        /// `depth: test(...)`; absent for the default (its own, discarded).
        #[serde(default, skip_serializing_if = "DepthMode::is_own")]
        depth: DepthMode,
        /// The entry points of the pass's shader.
        vertex_entry: String,
        fragment_entry: String,
    },
    /// A fullscreen triangle; its vertex entry makes `screen_uv`.
    Image {
        vertex_entry: String,
        fragment_entry: String,
    },
    /// An `image` pass the compiler scheduled as a compute shader over
    /// workgroup tiles (issue 14): the same pixels, each computed by one
    /// invocation of a `TILE_SIZE` × `TILE_SIZE` workgroup that first loads
    /// the texels its operators read around the pixel into workgroup
    /// memory. Group 0 as an image pass; group 1: the outputs as write-only
    /// storage textures, binding i = output i (every output's format is
    /// [`Format::storage_capable`], no output blends).
    TiledImage { entry: String },
    /// Per-object values computed on the GPU. Group 0 as every kind; group
    /// 1: every object's block as a read-only storage array of
    /// [`object_stride`]-byte slots (binding 0), the pass's member table
    /// (binding 1: per object it runs over, `vec4<u32>`(object index, first
    /// vertex, vertex count, first element workgroup)), then one read-only
    /// `array<f32>` per attribute with every member's vertices one after the
    /// other (bindings 2..); group 2: the pass's own buffers (`values.rs`,
    /// `compute_pass.rs`). Each stage is one dispatch over all members.
    Compute {
        domain: ComputeDomain,
        /// Run only over objects with this tag; `None` runs over all. Other
        /// objects' slots stay zero.
        tag: Option<String>,
        /// Vertex attributes read by the element stage, in binding order.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        attributes: Vec<Attribute>,
        /// The per-object value slots, in slot order.
        values: Vec<ValueSlot>,
        /// The pass keeps state: its value buffer has two copies, written
        /// by frame parity, and one more slot per object (after `values`)
        /// whose `x` is 1 once the object's state has been written.
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        history: bool,
        /// The element stage (`vertices` and `pixels`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        elements_entry: Option<String>,
        /// The ID target whose pixels a `pixels` pass runs over (an index
        /// into [`Manifest::targets`]); its value at each pixel is the
        /// `object.id` (object index + 1) the pixel belongs to, 0 for none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pixels_of: Option<usize>,
        /// How a `samples` pass samples each object's surface.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        samples: Option<SampleSpec>,
        /// The object stage.
        objects_entry: String,
    },
    /// Wavy strips along the silhouette and crease edges of scene objects
    /// (Klein et al. 2000, §5), built on the CPU per eye when the view, an
    /// object or the shape changes, drawn as one indexed triangle list of
    /// [`crate::lines::LineVertex`] (vertex buffer 0, no object group)
    /// into the pass's targets, blended per output.
    Lines {
        /// Only objects with this tag; `None` takes every object.
        tag: Option<String>,
        edges: crate::lines::LineEdges,
        shape: crate::lines::LineShape,
        /// The pass's line sets, highest priority first (decision 0056);
        /// with any, they replace `edges` and `shape`.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        sets: Vec<crate::lines::LineSet>,
        /// `Own`: no depth test (every edge drawn, hidden ones too). `Test`:
        /// against the depth an earlier pass kept; for lines `bias_px`
        /// moves every strip vertex towards the eye, along its view ray, by
        /// the world distance N px span at its depth (a view-space bias:
        /// the same slack on screen at every distance). A bias in window
        /// depth is in the WGSL, as for render passes.
        #[serde(default, skip_serializing_if = "DepthMode::is_own")]
        depth: DepthMode,
        vertex_entry: String,
        fragment_entry: String,
    },
}

impl PassKindManifest {
    /// Every entry point of the pass's shader, with its field name.
    pub fn entries(&self) -> Vec<(&'static str, &str)> {
        match self {
            PassKindManifest::Render {
                vertex_entry,
                fragment_entry,
                ..
            }
            | PassKindManifest::Image {
                vertex_entry,
                fragment_entry,
            }
            | PassKindManifest::Lines {
                vertex_entry,
                fragment_entry,
                ..
            } => vec![("vertex_entry", vertex_entry), ("fragment_entry", fragment_entry)],
            PassKindManifest::Compute {
                elements_entry,
                objects_entry,
                ..
            } => elements_entry
                .iter()
                .map(|e| ("elements_entry", e.as_str()))
                .chain([("objects_entry", objects_entry.as_str())])
                .collect(),
            PassKindManifest::TiledImage { entry } => vec![("entry", entry)],
        }
    }

    /// An image pass, run by a render pipeline or as workgroup tiles.
    pub fn is_image(&self) -> bool {
        matches!(
            self,
            PassKindManifest::Image { .. } | PassKindManifest::TiledImage { .. }
        )
    }

    /// The (vertex, fragment) entry points of a kind drawn by a render
    /// pipeline; `None` for kinds with other entry points.
    pub fn raster_entries(&self) -> Option<(&str, &str)> {
        match self {
            PassKindManifest::Render {
                vertex_entry,
                fragment_entry,
                ..
            }
            | PassKindManifest::Image {
                vertex_entry,
                fragment_entry,
            }
            | PassKindManifest::Lines {
                vertex_entry,
                fragment_entry,
                ..
            } => Some((vertex_entry, fragment_entry)),
            PassKindManifest::Compute { .. } | PassKindManifest::TiledImage { .. } => None,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PassManifest {
    pub name: String,
    pub kind: PassKindManifest,
    /// Resolution relative to the output size.
    pub scale: f64,
    /// The WGSL file (relative to the manifest) holding this pass's shader.
    pub shader: String,
    /// Targets written, in `@location` order.
    pub outputs: Vec<usize>,
    /// How each output combines with its target, in `@location` order;
    /// empty when every output replaces (the default, and every manifest
    /// written before blending existed).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub blend: Vec<Blend>,
    pub clear: [f64; 4],
    /// Group 0 bindings, by binding number.
    pub bindings: Vec<Binding>,
    /// Group 1 bindings after the `Object` uniform block (binding 0), by
    /// binding number: the per-object textures (`object param t: texture`)
    /// this render pass reads. The runner builds one group 1 per object.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub object_bindings: Vec<Binding>,
    /// `.npr` line of the pass declaration (for messages).
    pub line: usize,
    /// The shader repeats 16-bit float stores (a pass fused into it) and
    /// declares `formats::HALF_ROUNDING_OVERRIDE`: the runner sets it to the
    /// device's measured rounding (`formats::HalfRounding`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub device_half_rounding: bool,
}

/// How a pass output combines with what its target holds already: the
/// pass's clear colour, then the fragments this pass drew there before. `s`
/// is the fragment's value (straight alpha, as every colour of a style), `d`
/// the target's. Each is one fixed-function `wgpu::BlendState` (the runner's
/// `blend_state`), exact up to the target format's rounding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Blend {
    /// `s`: the fragment overwrites the target.
    #[default]
    Replace,
    /// Porter-Duff over, straight alpha: rgb = s.rgb·s.a + d.rgb·(1 − s.a),
    /// a = s.a + d.a·(1 − s.a) (`wgpu::BlendState::ALPHA_BLENDING`). This is
    /// the stdlib's `over(s, d)` wherever `d` is opaque (an opaque clear, or
    /// an opaque fragment drawn before); over a transparent `d` the stored
    /// rgb is premultiplied by the coverage drawn (rgb·a), because straight
    /// over divides by the result's alpha, which blending cannot.
    Over,
    /// s + d, every channel, alpha included (clamped by unorm formats).
    Add,
    /// s × d, every channel, alpha included.
    Multiply,
}

impl Blend {
    /// Every mode as a style writes it.
    pub const ALL: &'static [(&'static str, Blend)] = &[
        ("replace", Blend::Replace),
        ("over", Blend::Over),
        ("add", Blend::Add),
        ("multiply", Blend::Multiply),
    ];

    pub fn parse(name: &str) -> Option<Blend> {
        Self::ALL.iter().find(|(n, _)| *n == name).map(|(_, b)| *b)
    }

    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, b)| *b == self)
            .map(|(n, _)| *n)
            .unwrap_or("?")
    }
}

/// What a render pass does with its depth buffer.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "mode", rename_all = "snake_case")]
pub enum DepthMode {
    /// Cleared to 1, tested (`Less`) and written, discarded after the pass;
    /// passes of one size share one such buffer.
    #[default]
    Own,
    /// `depth: keep`: as `Own`, but in a depth texture of its own per eye
    /// slot, stored, so that later passes can test against it.
    Keep,
    /// `depth: test(pass)`: loads the depth `pass` kept and tests against it
    /// (`LessEqual`) without writing it. A bias in depth units is applied by
    /// the pass's vertex shader (clip.z −= bias·clip.w), so it is in the WGSL,
    /// not here.
    Test {
        /// Index into [`Manifest::passes`] of an earlier render pass with
        /// `depth: keep`, the same scale and the same view.
        pass: usize,
        /// `bias: N px`: a slope-scaled bias (`wgpu::DepthBiasState` with
        /// `slope_scale = −N`): the fragment's depth is lowered by N·m, m =
        /// max(|∂z/∂x|, |∂z/∂y|) of its triangle in depth per px, i.e. by
        /// the depth its own surface spans over N px.
        #[serde(default, skip_serializing_if = "is_zero")]
        bias_px: f64,
    },
    /// `depth: test(input)`: as `Test`, against the host's depth instead
    /// of an earlier pass's: each frame the runner draws the
    /// `input(depth)` texture (the language's convention, a view distance
    /// in metres, 0 for nothing hit) through the frame camera's
    /// projection into a depth buffer of the output's size, which the
    /// pass loads and tests against without writing it.
    TestInput {
        /// Index into [`Manifest::textures`] of an `input(depth)` texture;
        /// the pass renders at scale 1 through the camera's view.
        input: usize,
        /// As [`DepthMode::Test`]'s.
        #[serde(default, skip_serializing_if = "is_zero")]
        bias_px: f64,
    },
}

impl DepthMode {
    pub fn is_own(&self) -> bool {
        *self == DepthMode::Own
    }

    /// Whether the pass loads a depth it does not write: a test against an
    /// earlier pass's kept depth or the host's depth.
    pub fn is_test(&self) -> bool {
        matches!(self, DepthMode::Test { .. } | DepthMode::TestInput { .. })
    }

    /// The slope-scaled bias of a test (`None` for a pass's own depth).
    pub fn test_bias_px(&self) -> Option<f64> {
        match self {
            DepthMode::Test { bias_px, .. } | DepthMode::TestInput { bias_px, .. } => Some(*bias_px),
            DepthMode::Own | DepthMode::Keep => None,
        }
    }
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Binding {
    pub binding: u32,
    pub resource: Resource,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Resource {
    /// The fixed `Frame` block ([`FRAME_UNIFORM_SIZE`] bytes).
    FrameUniforms,
    /// The style parameter block.
    StyleUniforms,
    /// A logical target read as `texture_2d<f32>` (unfilterable-safe: read with `textureLoad`
    /// or with the clamp sampler when the format is filterable).
    Target {
        target: usize,
        filterable: bool,
        /// Which copy to bind: this frame's (the default), the other eye's
        /// (`other_eye(...)`: the style is stereo) or the previous frame's
        /// (`previous(...)`: the target's physical texture is `history`).
        #[serde(default, skip_serializing_if = "TargetCopy::is_this")]
        copy: TargetCopy,
    },
    /// A declared texture.
    Texture { texture: usize },
    /// The sampler of a declared texture (its wrap and filter settings).
    TextureSampler { texture: usize },
    /// A bilinear clamp-to-edge sampler (for `sample()` on targets).
    LinearClampSampler,
    /// The per-object values of the compute pass at index `pass` of
    /// [`Manifest::passes`] (an earlier pass), read-only `array<vec4<f32>>`:
    /// this frame's copy.
    ObjectValues { pass: usize },
}

/// Which copy of a target a read sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetCopy {
    /// As this frame's pass wrote it, for this eye.
    #[default]
    This,
    /// `other_eye(pass.target)`: as the other eye of a stereo frame rendered
    /// it (the runner renders both eyes pass by pass).
    OtherEye,
    /// `previous(pass.target)`: as the previous frame left it (the pass's
    /// clear value on the first frame and after a reset). Not a dependency
    /// within the frame, so a pass may read its own previous output.
    Previous,
}

impl TargetCopy {
    pub fn is_this(&self) -> bool {
        *self == TargetCopy::This
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TargetManifest {
    /// `pass.output`
    pub name: String,
    pub format: Format,
    pub scale: f64,
    /// Index into [`Manifest::physical`].
    pub physical: usize,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PhysicalTexture {
    pub format: Format,
    pub scale: f64,
    /// Read with `previous(...)`: never shared with another target; the
    /// runner keeps two copies, writes one and binds the other to
    /// previous-frame reads, swaps them after each frame, and clears both
    /// to the writing pass's clear value when it (re)creates them.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub history: bool,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum TextureSourceManifest {
    /// A file, `path` as written and `resolved` against the style's directory.
    Image { path: String, resolved: String, srgb: bool },
    /// Generated tileable noise (its fields inline, beside `kind`).
    Noise(NoiseSpec),
    /// A halftone's tone-correction table, built at load (its fields inline).
    HalftoneTable(crate::HalftoneTableSpec),
    /// An art-map: a mip chain filtered level by level, built at load.
    Artmap(crate::ArtmapSpec),
    /// In a filter style only: the level the filter runs on, given by the
    /// runner (`Renderer::new_filter`).
    FilterInput,
    /// `input(kind, ...)`: an image the host gives each frame, converted
    /// to the language's convention for its kind (`crate::input`).
    Input(crate::input::InputSpec),
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TextureManifest {
    pub name: String,
    pub source: TextureSourceManifest,
    /// `object param name: texture`: `source` is the default; the scene may
    /// bind another image per object (`params = { name = "file.png" }`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub per_object: bool,
    pub wrap_repeat: bool,
    pub filter_linear: bool,
    pub mips: bool,
}

/// What the compiler did with a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ParamBinding {
    /// Folded into the shaders as a constant.
    Folded,
    /// A slot in the style uniform block (animated, or `--keep-params`).
    Uniform,
    /// A slot in the per-object uniform block, bound by the scene.
    PerObject,
    /// Not used by anything the output depends on.
    Removed,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParamManifest {
    pub name: String,
    pub doc: String,
    /// `float`, `int`, `bool`, `vec2`..`vec4`, `color`, `enum(a|b)`, `range`, or a unit type (`px`, ...).
    pub ty: String,
    pub unit: String,
    pub components: u32,
    /// Default value, in canonical units (px, m, s, Hz, radians). Enum: the variant index.
    pub default: Vec<f64>,
    /// When the default was written in `%` of the image height: the runner multiplies by height/100.
    pub default_percent_of_height: bool,
    pub range: Option<(f64, f64)>,
    pub enum_variants: Vec<String>,
    pub keyframes: Vec<(f64, Vec<f64>)>,
    pub interpolation: String,
    pub binding: ParamBinding,
    /// Byte offset of the slot in its uniform block (style or object), when bound.
    pub offset: Option<u64>,
}

impl ParamManifest {
    /// Make the parameter the constant `value` at run time (a host's
    /// `set_param`, a sweep's combination, the studio's controls): its
    /// default becomes the value, in `%` of the height when it was typed
    /// so, and its keyframes go, as `--set` makes a constant at compile
    /// time (`mid::overrides`). The one place these three fields change
    /// together.
    pub fn set_constant(&mut self, value: &ParamOverride) {
        self.default.clone_from(&value.value);
        self.default_percent_of_height = value.percent_of_height;
        self.keyframes.clear();
    }
}

/// One parameter's new default, in canonical units (px, m, s, Hz, radians;
/// an enum's variant index; a colour's four components).
#[derive(Debug, Clone, PartialEq)]
pub struct ParamOverride {
    pub name: String,
    pub value: Vec<f64>,
    /// The value is a `%` of the image height (`value[0]` in percent),
    /// resolved by the runner per frame like a `%` default.
    pub percent_of_height: bool,
}
