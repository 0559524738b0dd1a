//! Scenes: the objects, camera and light a style is rendered with, read
//! from a TOML file.
//!
//! # Scene file format
//!
//! ```toml
//! background = "#202020"          # optional: "#rrggbb", "#rrggbbaa" or [r, g, b(, a)]; default black
//!
//! [camera]                        # required
//! position = [0.0, 0.5, 3.0]      # the eye (required unless every key has one)
//! target = [0.0, 0.0, 0.0]        # the point looked at (likewise)
//! up = [0.0, 1.0, 0.0]            # optional, default +Y; must not be parallel to the view
//! fov = 40.0                      # optional: vertical field of view in degrees, in (0, 180); default 40
//! near = 0.1                      # optional: > 0; default 0.1
//! far = 100.0                     # optional: > near; default 100
//! ipd = 0.064                     # optional: eye separation in metres; makes the camera stereo
//!
//! [[camera.keys]]                 # optional keyframes: linear in position and target,
//! time = 0.0                      # held before the first and after the last key;
//! position = [0.0, 0.5, 3.0]      # position/target default to [camera]'s own
//! [[camera.keys]]
//! time = 4.0
//! position = [2.0, 0.5, 2.0]
//!
//! [light]                         # optional; the key directional light (`light.dir` …)
//! direction = [0.5, 1.0, 0.8]     # towards the light; normalized on load
//! color = [1.0, 1.0, 1.0]         # or "#rrggbb"; default white
//! intensity = 1.0                 # >= 0; default 1
//!
//! [light2]                        # optional, and [light3], [light4]: more directional
//! direction = [-1.0, 0.3, 0.2]    # lights (`light2.dir` …), with [light]'s fields and
//! color = "#ffb070"               # defaults; an absent one has direction 0 and
//!                                 # intensity 0
//!
//! [[object]]
//! name = "spot"                   # optional: default the file stem or primitive kind (made unique)
//! mesh = "../models/spot.obj"     # relative to the scene file: .obj, .gltf or .glb
//! translate = [0.0, 0.0, 0.0]     # optional
//! rotate = [0.0, 30.0, 0.0]       # optional, degrees: about Y first, then X, then Z
//! scale = 1.0                     # optional: > 0, a number or [x, y, z]
//! tags = ["caster"]               # optional: for `render(scene, tag: ...)` passes
//! casts_shadows = true            # optional, default true
//! crease_angle = 30.0             # optional, degrees in (0, 180]: split normals where faces meet at
//!                                 # a sharper angle (CAD parts); default: smooth normals throughout
//! params = { tint = "#ff8080", breakup = 0.5 }   # optional per-object parameter bindings
//! spin = [0.0, 30.0, 0.0]         # optional, degrees per second about the object's own Y, X, Z
//! patches = 4                     # optional (Breslav et al. §3.6): split into 2..=64 patches, each
//!                                 # an object of its own named `<name>.<k>`; or "parts": the
//!                                 # file's OBJ `o`/`g` groups or glTF primitives
//! blend_rings = 1                 # optional, with `patches`, 0..=16, default 1: render passes that
//!                                 # read `patch.weight` draw each patch over the n rings of faces
//!                                 # around it, where patterns cross-fade (0: hard seams)
//! animation = { clip = "bend" }  # optional, a glTF mesh with animations: play this clip; also
//!                                 # `speed` (default 1, clip seconds per second, may be negative),
//!                                 # `loop` (default true; false holds the first and last pose) and
//!                                 # `offset` (default 0, the clip's time at scene time 0)
//! # an `object param albedo: texture` takes an image, relative to this file:
//! # `albedo = "../textures/spot.png"` or `albedo = { image = "spot.png", srgb = false }`
//!
//! [[object]]
//! primitive = { kind = "sphere", radius = 1.0, segments = 64, rings = 32 }
//! translate = [1.5, 0.0, 0.0]
//! ```
//!
//! Each object has exactly one of `mesh` and `primitive`. Primitive kinds and
//! their fields, with defaults:
//!
//! | kind       | fields (default)                                               |
//! |------------|----------------------------------------------------------------|
//! | `sphere`   | `radius` (1), `segments` (64), `rings` (32)                    |
//! | `cube`     | `size` (1)                                                     |
//! | `torus`    | `major` (1), `minor` (0.25), `segments` (64), `sides` (32)     |
//! | `plane`    | `size` (1), `subdivisions` (1)                                 |
//! | `cylinder` | `radius` (0.5), `height` (1), `segments` (64)                  |
//! | `ocean`    | see below                                                      |
//!
//! See [`primitives`] for their geometry.
//!
//! The `ocean` primitive (Age of Sail §6.1; the model is in [`ocean`]) is
//! animated: the renderer rebuilds its vertices at every frame's time. Its
//! fields, with defaults and valid ranges:
//!
//! | field            | default    | meaning                                                         |
//! |------------------|------------|-----------------------------------------------------------------|
//! | `size`           | 60         | tile width L in metres, the spatial period; (0, 10000]          |
//! | `cells`          | 80         | quads along a tile's side; 1..=256                              |
//! | `tiles`          | 5          | tiles along a side of the grid, odd; 1..=15                     |
//! | `period`         | 20         | loop length T in seconds, the temporal period; (0, 3600]        |
//! | `modes`          | 12         | wave vectors 2π(m, n)/L with \|m\|, \|n\| ≤ modes; 1..=32, ≤ cells/2 |
//! | `wave_height`    | 1.2        | significant wave height in metres; [0, 100]                     |
//! | `wind_speed`     | 5          | m/s, sets the Phillips spectrum's peak; (0, 100]                |
//! | `wind_direction` | [0, 1]     | [x, z] the wind blows towards; not zero                         |
//! | `choppiness`     | 0.7        | λ of the horizontal displacement; [0, 4]                        |
//! | `seed`           | 1          | the random sea state; 0..=4294967295                            |
//! | `drift`          | [0, 0]     | whole tiles the water moves per period along x and z; \|·\| ≤ 100 |
//! | `horizon`        | 120        | false-horizon radius in metres; (0, 100000]                     |
//! | `horizon_drop`   | 0.05       | drop past the horizon, metres per square metre; [0, 10]         |
//! | `ring`           | 0          | outer radius of the flat ring past the horizon, metres; 0 = none; [0, 100000] |
//!
//! The model matrix is `translate · rotate · scale`, with the rotation
//! `Rz · Rx · Ry` (a vertex turns about Y first).
//!
//! Parameter bindings: a number is one component, a boolean is 1 or 0, an
//! array is 1 to 4 components, a colour string `"#rrggbb"` is 4 components
//! (alpha 1) holding the bytes / 255, the same convention as colour literals
//! in `.npr` styles (no sRGB decoding).
//!
//! # Limits and errors
//!
//! Every problem is a [`npr_diag::Diagnostic`] pointing into the scene file, and
//! as many are collected as the file allows: malformed TOML, unknown or
//! mistyped fields and bad values are E0405 (`BAD_SCENE`); a missing,
//! unreadable or unsupported mesh file E0402 (`UNREADABLE_MESH`); a mesh or
//! primitive over [`MAX_TRIANGLES`] triangles, or a count over
//! [`MAX_SEGMENTS`], E0404 (`LIMIT_EXCEEDED`). A style that reads an
//! attribute some mesh lacks is E0403, from [`Scene::check_attributes`].
//!
//! # Meshes
//!
//! OBJ files are read with `tobj` (triangulated, single index; all models
//! merged). glTF files are read with the `gltf` crate: every triangle
//! primitive of the default scene, node transforms baked in. Coordinates
//! are kept as in the file. See [`Mesh`] for the attribute conventions.
//!
//! A glTF file with skins, morph targets or animations is read into a
//! [`rig::Rig`] as well ([`gltf_rig`]); its mesh is then the rest pose
//! (skinned by the nodes' rest transforms, the default morph weights
//! applied). An object with `animation` plays one of its clips: a renderer
//! deforms it on the GPU each frame into the object's own vertex buffers
//! (`exec/deform.rs`, docs/decisions/0053), and [`Scene::posed`] gives
//! the CPU stages that read vertices (lines, light bounds) the same pose
//! deformed on the CPU (`rig::Rig::deform`). Objects of one file share its rig.
//! A host's skinned mesh (the embedding API, Bevy) is deformed the same
//! way, from the pose its host gives each frame ([`Object::pose`]).

pub mod anim_sampler;
mod attributes;
mod camera;
mod edge_marks;
pub(crate) mod geometry;
mod gltf_file;
pub mod gltf_material;
pub mod gltf_rig;
mod light;
mod mesh;
mod mesh_error;
mod mesh_file;
mod obj_file;
pub mod ocean;
mod parse;
mod parse_camera;
mod parse_object;
mod parse_patches;
mod parse_primitive;
pub mod patch_blend;
pub mod patch_weights;
pub mod patches;
pub mod primitives;
pub mod rig;
pub mod samples;
#[cfg(test)]
mod test_grid;
pub mod toml_fields;

pub use camera::{Camera, CameraKey, CameraPose};
pub use light::{light_view_proj, Light};
pub use mesh::{Attribute, Mesh, MAX_TRIANGLES};
pub use mesh_file::{load_mesh_and_rig, load_mesh_file, load_mesh_file_parts, LoadedMesh, MeshLoadError};
pub use primitives::{Primitive, MAX_SEGMENTS};

use npr_diag::limits::MAX_SCENE_BYTES;
use npr_diag::{codes, Diagnostic, FileId, SourceMap, Span};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// Everything a style is rendered with.
#[derive(Debug, Clone)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub camera: Camera,
    pub light: Light,
    /// `[light2]`, `[light3]`, `[light4]`, where the scene has them.
    pub more_lights: [Option<Light>; 3],
    /// RGBA, as written (see the module docs on colours).
    pub background: [f32; 4],
}

/// One placed mesh.
#[derive(Debug, Clone)]
pub struct Object {
    /// Unique within the scene.
    pub name: String,
    /// Shared between objects naming the same file or primitive.
    pub mesh: Arc<Mesh>,
    /// Object-to-world.
    pub model: glam::Mat4,
    pub tags: Vec<String>,
    /// Per-object parameter bindings: 1 component for a number or boolean,
    /// N for an array, 4 for a colour.
    pub params: BTreeMap<String, Vec<f64>>,
    /// Where each binding's value was written.
    pub param_spans: BTreeMap<String, Span>,
    /// Per-object image bindings of `object param t: texture` params.
    pub textures: BTreeMap<String, TextureBinding>,
    /// Where the mesh or primitive was declared (for E0403).
    pub mesh_span: Span,
    /// A primitive whose geometry depends on time (the ocean): `mesh` is its
    /// geometry at t = 0, and a renderer rebuilds the vertices from this at
    /// each frame's time ([`Primitive::build_at`]).
    pub time_varying: Option<Primitive>,
    pub casts_shadows: bool,
    /// `spin = [x, y, z]`: turning about the object's own origin, in degrees
    /// per second about Y, then X, then Z (as `rotate`); zero when still.
    pub spin: glam::Vec3,
    /// A patch of a patched object (Breslav et al. 2007 §3.6) blended over
    /// `blend_rings` rings: what a render pass reading `patch.weight` draws
    /// instead of `mesh` (its faces and n-ring, with its weights). `None`:
    /// `mesh` with weight 1 at every vertex (no patches, or `blend_rings = 0`).
    pub blend: Option<Arc<patch_blend::PatchBlend>>,
    /// A patch of a patched object: which, and the object's whole mesh.
    /// `None` for an object that is not divided.
    pub patch: Option<patches::PatchOf>,
    /// `animation = { clip = ... }`: a clip of the object's glTF file
    /// playing; `mesh` is the file's rest pose, and [`Scene::posed`] gives
    /// the object its mesh deformed at each frame's time. `None`: still.
    pub animation: Option<ObjectAnimation>,
    /// A pose its host gives every frame (the embedding API's skinned
    /// meshes, Bevy's `SkinnedMesh`): `mesh` is the rig's bind mesh,
    /// deformed as a clip's is (the GPU stage for the passes, the CPU for
    /// [`Scene::posed`]). `None`: not posed by a host.
    pub pose: Option<rig::HostPose>,
    /// The material of its glTF file (`gltf_material`): per-object values
    /// and the base colour texture under fixed names, each used where the
    /// style declares the name and the scene binds none. `None`: an OBJ
    /// file, a primitive, or a glTF file without materials.
    pub material: Option<Arc<gltf_material::MeshMaterial>>,
}

/// An object's clip playing (`animation = { clip, speed, loop, offset }`).
#[derive(Debug, Clone)]
pub struct ObjectAnimation {
    /// The object's file's skins, morph targets and clips (shared by every
    /// object of the file).
    pub rig: Arc<rig::Rig>,
    /// Index into `rig.clips`.
    pub clip: usize,
    /// Clip seconds per scene second (negative plays backwards).
    pub speed: f64,
    /// Whether the clip repeats; else it holds its first and last pose.
    pub looping: bool,
    /// Clip time at scene time 0, in seconds.
    pub offset: f64,
}

/// Equal when they play the same clip of the same rig (one `Arc`: one
/// file's), at the same speed, looping and offset; the rig is not
/// compared deeply (a host's frame compares instances).
impl PartialEq for ObjectAnimation {
    fn eq(&self, other: &ObjectAnimation) -> bool {
        Arc::ptr_eq(&self.rig, &other.rig)
            && self.clip == other.clip
            && self.speed == other.speed
            && self.looping == other.looping
            && self.offset == other.offset
    }
}

impl ObjectAnimation {
    /// The clip's time at scene time `time_s`: `offset + speed · t`,
    /// wrapped into [0, duration) when looping.
    pub fn clip_time(&self, time_s: f64) -> f32 {
        let t = self.offset + self.speed * time_s;
        let duration = self.rig.clips.get(self.clip).map_or(0.0, |c| f64::from(c.duration));
        let t = if self.looping && duration > 0.0 {
            t.rem_euclid(duration)
        } else {
            t
        };
        t as f32
    }

    /// The object's mesh at scene time `time_s`.
    pub fn mesh_at(&self, time_s: f64) -> Mesh {
        self.rig
            .deform(&self.rig.pose(Some((self.clip, self.clip_time(time_s)))))
    }
}

/// `params = { lit = "textures/lit.png" }` or `{ image = "...", srgb = false }`:
/// an object's own image for a per-object texture param. The sampler
/// options (wrap, filter, mips) are the style's, from the param's declaration.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureBinding {
    /// As written in the scene.
    pub path: String,
    /// Joined to the scene file's directory.
    pub resolved: std::path::PathBuf,
    /// `srgb = true/false` in a table binding; `None` (a plain path): the
    /// colour space of the param's declared default image.
    pub srgb: Option<bool>,
    /// The binding's value in the scene TOML.
    pub span: Span,
}

#[cfg(test)]
impl Object {
    /// `mesh` at `model` with `tags`, casting shadows, nothing else bound:
    /// the object unit tests build.
    pub(crate) fn plain(name: &str, mesh: &Arc<Mesh>, model: glam::Mat4, tags: &[&str]) -> Object {
        Object {
            name: name.into(),
            mesh: mesh.clone(),
            model,
            tags: tags.iter().map(|t| t.to_string()).collect(),
            params: BTreeMap::new(),
            param_spans: BTreeMap::new(),
            textures: BTreeMap::new(),
            mesh_span: Span::default(),
            time_varying: None,
            casts_shadows: true,
            spin: glam::Vec3::ZERO,
            blend: None,
            patch: None,
            animation: None,
            pose: None,
            material: None,
        }
    }
}

impl Object {
    /// Whether its vertices are deformed every frame by a rig: it plays a
    /// clip, or its host poses it.
    pub fn deforms(&self) -> bool {
        self.animation.is_some() || self.pose.is_some()
    }

    pub fn has_tag(&self, tag: &str) -> bool {
        self.tags.iter().any(|t| t == tag)
    }

    /// Object-to-world at `time_s`: `model` turned by `spin × time`.
    pub fn model_at(&self, time_s: f64) -> glam::Mat4 {
        if self.spin == glam::Vec3::ZERO {
            return self.model;
        }
        let a = self.spin * (time_s as f32).to_radians();
        self.model
            * glam::Mat4::from_quat(
                glam::Quat::from_rotation_z(a.z) * glam::Quat::from_rotation_x(a.x) * glam::Quat::from_rotation_y(a.y),
            )
    }
}

/// The box of nothing: (+∞, −∞), which [`union_bounds`] leaves unchanged.
pub const EMPTY_BOUNDS: (glam::Vec3, glam::Vec3) = (glam::Vec3::INFINITY, glam::Vec3::NEG_INFINITY);

/// The smallest box holding boxes `a` and `b` (each (min, max)).
pub fn union_bounds(a: (glam::Vec3, glam::Vec3), b: (glam::Vec3, glam::Vec3)) -> (glam::Vec3, glam::Vec3) {
    (a.0.min(b.0), a.1.max(b.1))
}

impl Object {
    /// World-space bounding box (min, max) of this object's vertices under
    /// `model`; vertices that land on a non-finite point are left out;
    /// [`EMPTY_BOUNDS`] when none is left.
    ///
    /// Every vertex is transformed (an exact box needs them all: a turned
    /// sphere's extreme vertices are any of them), four lanes at a time:
    /// the same products and sums as [`glam::Mat4::transform_point3`], so
    /// the same points, and this is a light camera's cost per moved object
    /// each frame (docs/PERFORMANCE.md, "host path").
    pub fn world_bounds(&self) -> (glam::Vec3, glam::Vec3) {
        let m = &self.model;
        let (mut lo, mut hi) = (glam::Vec4::INFINITY, glam::Vec4::NEG_INFINITY);
        for p in &self.mesh.positions {
            let w = m.w_axis + (m.z_axis * p[2] + (m.y_axis * p[1] + m.x_axis * p[0]));
            // x, y and z finite (the fourth lane is not a coordinate).
            if w.is_finite_mask().bitmask() & 0b111 == 0b111 {
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
        (lo.truncate(), hi.truncate())
    }
}

impl Scene {
    /// No objects, a still camera and the default light: what an art-map's
    /// filter runs on (its passes are image passes only).
    pub fn empty() -> Scene {
        Scene {
            objects: Vec::new(),
            camera: Camera::looking_at(glam::Vec3::Z, glam::Vec3::ZERO),
            light: Light::default(),
            more_lights: [None, None, None],
            background: [0.0, 0.0, 0.0, 0.0],
        }
    }

    /// The scene as it stands at `time_s`: every spinning object's model
    /// turned to that time, every animated object's mesh deformed to it on
    /// the CPU (borrowed unchanged when nothing spins or plays a clip).
    pub fn posed(&self, time_s: f64) -> std::borrow::Cow<'_, Scene> {
        self.posed_with(time_s, true)
    }

    /// [`Scene::posed`]; with `deform_meshes` false, animated objects keep
    /// their rest mesh (a renderer whose passes draw the GPU stage's
    /// deformation and which has no CPU stage reading vertices: decision 0053).
    pub fn posed_with(&self, time_s: f64, deform_meshes: bool) -> std::borrow::Cow<'_, Scene> {
        let moves = |o: &Object| o.spin != glam::Vec3::ZERO || (deform_meshes && o.deforms());
        if !self.objects.iter().any(moves) {
            return std::borrow::Cow::Borrowed(self);
        }
        let mut posed = self.clone();
        for o in &mut posed.objects {
            o.model = o.model_at(time_s);
            if let (Some(animation), true) = (&o.animation, deform_meshes) {
                o.mesh = Arc::new(animation.mesh_at(time_s));
            } else if let (Some(host), true) = (&o.pose, deform_meshes) {
                o.mesh = Arc::new(host.rig.deform(&host.pose));
            }
        }
        std::borrow::Cow::Owned(posed)
    }
}

impl Scene {
    /// What the compiler may know of this scene (its objects' tags);
    /// `name` names it in the compile report.
    pub fn summary(&self, name: &str) -> npr_abi::SceneSummary {
        npr_abi::SceneSummary {
            tags: self.objects.iter().flat_map(|o| o.tags.iter().cloned()).collect(),
            name: name.to_string(),
        }
    }

    /// World-space bounding box (min, max) of every object's vertices;
    /// (+∞, −∞) for an empty scene.
    pub fn bounds(&self) -> (glam::Vec3, glam::Vec3) {
        self.bounds_of(|_| true)
    }

    /// World-space bounding box of the objects `keep` accepts: the union
    /// of their [`Object::world_bounds`], in object order (a renderer that
    /// keeps each object's box between frames folds them the same way, so
    /// its union equals this one).
    pub fn bounds_of(&self, keep: impl Fn(&Object) -> bool) -> (glam::Vec3, glam::Vec3) {
        self.objects
            .iter()
            .filter(|o| keep(o))
            .map(Object::world_bounds)
            .fold(EMPTY_BOUNDS, union_bounds)
    }

    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(|o| o.mesh.triangle_count()).sum()
    }
}

/// Reads a scene file, adds it to `sources` (so diagnostics can be rendered
/// against it) and parses it with [`parse_scene`]. Mesh paths are relative
/// to the file's folder.
pub fn load_scene(path: &Path, sources: &mut SourceMap) -> Result<Scene, Vec<Diagnostic>> {
    load_scene_in(path, sources, None)
}

/// [`load_scene`] under a paths policy: the meshes and images the scene
/// names must be files it admits (E0406 at the path otherwise).
pub fn load_scene_in(
    path: &Path,
    sources: &mut SourceMap,
    paths: Option<&npr_diag::paths::PathPolicy>,
) -> Result<Scene, Vec<Diagnostic>> {
    let bytes = read_bounded(path).map_err(|err| {
        vec![Diagnostic::error(
            codes::BAD_SCENE,
            format!("cannot read scene file `{}`: {err}", path.display()),
        )
        .with_help("check the path to the scene file (a UTF-8 TOML file)")]
    })?;
    if bytes.len() > MAX_SCENE_BYTES {
        return Err(vec![too_large(sources, path, &bytes)]);
    }
    let (file, text) = npr_diag::text::add_utf8(sources, &path.display().to_string(), bytes).map_err(|d| vec![d])?;
    let base_dir = path.parent().unwrap_or(Path::new("."));
    parse::parse_scene(&text, file, base_dir, paths)
}

/// A scene file's bytes, never more than one past [`MAX_SCENE_BYTES`]
/// (so `/dev/zero` is not read for ever).
fn read_bounded(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(MAX_SCENE_BYTES as u64 + 1)
        .read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// E0404 for a scene file past [`MAX_SCENE_BYTES`], at the byte where the
/// limit is reached (the file's first [`MAX_SCENE_BYTES`] bytes are added,
/// lossily, so the label has a line and column).
fn too_large(sources: &mut SourceMap, path: &Path, bytes: &[u8]) -> Diagnostic {
    let text = String::from_utf8_lossy(&bytes[..MAX_SCENE_BYTES]).into_owned();
    let at = text.len();
    let file = sources.add(path.display().to_string(), text);
    Diagnostic::error(
        codes::LIMIT_EXCEEDED,
        format!("the scene file is over the {MAX_SCENE_BYTES}-byte limit"),
    )
    .with_primary(Span::new(file, at, at), "the limit is reached here")
    .with_help("put large geometry in mesh files (OBJ, glTF) that the scene names with `mesh = \"...\"`")
}

/// Parses scene TOML `text`, whose spans refer to `file`, loading meshes
/// relative to `base_dir`. Returns every diagnostic found, in file order.
pub fn parse_scene(text: &str, file: FileId, base_dir: &Path) -> Result<Scene, Vec<Diagnostic>> {
    parse::parse_scene(text, file, base_dir, None)
}
