//! Embedding a style in a host application: a [`StyleRuntime`] the host
//! drives frame by frame, on the host's own wgpu device, inside the host's
//! own command encoder, into the host's own texture views.
//!
//! The host
//! 1. makes a runtime from a compiled style ([`StyleProgram`]: from
//!    `npr_compiler::compile_file(..)?.program()`, or [`StyleProgram::load_dir`]
//!    of a directory `npr compile -o DIR` wrote) on its device and queue;
//!    a device lacking a feature or limit the style needs is refused here
//!    (E0510), before any frame;
//! 2. registers its meshes once ([`StyleRuntime::add_mesh`] gives a
//!    [`MeshHandle`]; [`StyleRuntime::add_primitive`] a primitive's, whose
//!    vertices follow the frame's time when it is animated, as the ocean's
//!    are; [`StyleRuntime::add_patches`] one per patch of a mesh divided
//!    into blended patches; [`StyleRuntime::add_scene`] a TOML scene's),
//!    and deforms its own meshes when it likes ([`StyleRuntime::update_mesh`]:
//!    new vertices, same triangles); a skinned or morphing mesh is
//!    registered with its joints, weights and morph targets
//!    ([`StyleRuntime::add_skinned_mesh`]), and each of its instances
//!    carries its pose ([`Instance::pose`]: joint matrices, morph
//!    weights), which the GPU deforms it by every frame, as it deforms a
//!    scene file's clips;
//! 3. every frame, gives a [`Frame`] (the camera, or a stereo pair; the
//!    objects as [`Instance`]s: mesh handle, transform, tags, per-object
//!    params; the [`Lights`]; the time) and a [`Target`] (its texture view,
//!    e.g. the swapchain image's) to [`StyleRuntime::render`], which records
//!    the style's passes and one present pass into the host's encoder. The
//!    host submits the encoder (and presents) itself. A host that keeps
//!    linear light in its textures (an sRGB view, Bevy's view targets)
//!    gives [`Target::LinearView`] with the view's format: the present pass
//!    decodes the output, so the host's encoding shows what `npr render`
//!    writes.
//!
//! Style parameters are set by name at run time with
//! [`StyleRuntime::set_param`], typed and range-checked by the rule
//! `npr render --set` uses (`npr_abi::param_value`), from the manifest's
//! parameter metadata. A style compiled without `keep_params` has its
//! parameters folded into its shaders; only those in the manifest can
//! change ([`StyleRuntime::params`]).
//!
//! **What a frame costs.** The first frame builds the GPU resources: the
//! style's (shader modules, pipelines, the style's textures and art-maps),
//! the size's (targets, their views and bind groups) and the scene's (mesh
//! and object buffers, per-object bind groups, compute passes' buffers).
//! A frame after the set of objects' meshes, tags, images or shadow flags
//! changed (an object spawned or despawned) makes the scene's again,
//! never the style's or the size's: no shader module, pipeline, style
//! texture or target ([`Renderer::set_scene`]). The history goes on: a
//! style's `previous(...)` reads the last frame (trails stay), and objects
//! that stay keep their compute state and previous transform (an
//! [`Instance::id`] says which they are). A frame at a new size makes the
//! size's, and starts the history over. Every other frame writes
//! uniform buffers (and, in place, an animated primitive's vertex buffers
//! and those of a mesh the host deformed since the last frame, with the
//! copies compute passes over vertices read) and records commands, and
//! creates no buffer, texture, bind group or pipeline
//! (`runner/tests/embed_allocations.rs` and `embed_deform.rs` count them),
//! except a staging buffer for the uniforms while none of the earlier
//! frames' is back from the GPU: the runtime keeps one per frame in
//! flight and reuses them (decision 0047), so several frames may be
//! recorded before a submit, each with its own uniforms
//! (`embed_frames_in_flight.rs`).
//! A deformed mesh also costs the CPU what is made from its vertices: a
//! `lines` pass's edges and strips, the light camera's bounds.
//!
//! **Mistakes are values.** A removed mesh handle (E0601), an unknown
//! parameter (E0101) or a bad value (E0201, E0202, E0203), a texture view
//! of the wrong format or size (E0602), deformed vertices that do not fit
//! their mesh (E0603), a host input the style does not declare, cannot
//! read, of another size than the target or not given (E0604-E0607), a
//! pose whose joint matrices (E0612) or morph weights (E0614) do not fit
//! its mesh, or are not finite (E0613), a skin that does not fit its mesh
//! (E0615): every call returns an
//! [`EmbedError`] with a code, and leaves the runtime as it was.
//!
//! - `meshes.rs`: the generational mesh table (with what a mesh draws
//!   beyond its vertices: an animated primitive, a blended patch);
//! - `frame.rs`: [`Frame`], [`Instance`], [`Lights`], [`Target`];
//! - `objects.rs`: the host's instances as the renderer's scene;
//! - `params.rs`: setting style parameters by name;
//! - `patched.rs`: a host's mesh divided into blended patches;
//! - `deform.rs`: a host's deformed vertices ([`Deformed`]), checked;
//! - `skin.rs`: a host's skinned meshes ([`Skinning`]) and their
//!   instances' poses ([`SkinPose`]), checked;
//! - `inputs.rs`: the host's own images as the style's inputs
//!   ([`StyleRuntime::set_input`]), converted on the GPU every frame;
//! - `present.rs`: target checks and the present pass;
//! - `error.rs`: [`EmbedError`].
//!
//! # Example
//!
//! A 32×32 frame of a lit sphere, rendered into an offscreen texture and
//! read back (a window's surface view works the same way; see
//! `examples/embed.rs`):
//!
//! ```
//! use npr_runner::embed::{Frame, Instance, Lights, StyleRuntime, Target};
//! use npr_runner::scene::{primitives, Camera};
//!
//! // A compiled style: `npr_compiler::compile_file`, or `StyleProgram::load_dir`
//! // of what `npr compile -o DIR` wrote. `keep_params` keeps `tint` settable.
//! let style = "style \"Lit\"\nparam tint: color = #ffffff\n\
//!              pass p: render(scene) {\n  out c: rgba8unorm = vec4(tint.rgb * lambert(normal, light.dir), 1.0)\n}\n\
//!              output p.c\n";
//! let options = npr_compiler::CompileOptions { keep_params: true, ..Default::default() };
//! let mut sources = npr_diag::SourceMap::new();
//! let compiled = npr_compiler::compile_source("lit.npr", style, std::path::Path::new("."), &mut sources, &options)
//!     .map_err(|e| format!("{e:?}"))?;
//!
//! let gpu = npr_runner::Gpu::headless()?;
//! let mut runtime = StyleRuntime::new(&gpu.device, &gpu.queue, compiled.program())?;
//! runtime.set_param("tint", "#ff0000")?;
//! // Mistakes are values with a code, as `--set` reports them:
//! assert_eq!(runtime.set_param("tnit", "#ff0000").unwrap_err().code(), "E0101");
//! assert_eq!(runtime.set_param("tint", "0.5").unwrap_err().code(), "E0201");
//!
//! let sphere = runtime.add_mesh(primitives::sphere(1.0, 32, 16));
//! let objects = [Instance::new(sphere, glam::Mat4::IDENTITY)];
//! let camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 4.0), glam::Vec3::ZERO);
//! let lights = Lights::default();
//! let frame = Frame { camera: &camera, objects: &objects, lights: &lights, time_s: 0.0, frame_index: 0, eye: 0 };
//!
//! let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
//!     label: None,
//!     size: wgpu::Extent3d { width: 32, height: 32, depth_or_array_layers: 1 },
//!     mip_level_count: 1,
//!     sample_count: 1,
//!     dimension: wgpu::TextureDimension::D2,
//!     format: wgpu::TextureFormat::Rgba8Unorm,
//!     usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
//!     view_formats: &[],
//! });
//! let view = texture.create_view(&Default::default());
//! let mut encoder = gpu.device.create_command_encoder(&Default::default());
//! runtime.render(&mut encoder, &frame, Target::View(&view))?;
//! gpu.queue.submit([encoder.finish()]);
//!
//! let image = npr_runner::readback::read_texture(&gpu.device, &gpu.queue, &texture, 32, 32, npr_abi::Format::Rgba8unorm, "out")?;
//! assert_eq!(image.texel(0, 0), [0.0, 0.0, 0.0, 0.0]); // the corner: the pass's clear, no object
//! let centre = image.texel(16, 16); // the sphere, lit from the default light, in red
//! assert!(centre[0] > 0.3 && centre[1] == 0.0 && centre[2] == 0.0, "{centre:?}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod camera_check;
mod deform;
mod error;
mod frame;
mod inputs;
mod meshes;
mod objects;
mod params;
mod patched;
pub(crate) mod present;
mod skin;

pub use deform::Deformed;
pub use error::EmbedError;
pub use frame::{Frame, Instance, Lights, Target};
pub use meshes::MeshHandle;
pub use params::ParamInfo;
pub use skin::{SkinPose, Skinning};

use crate::scene::patches::PatchSpec;
use crate::scene::{Mesh, Primitive, Scene};
use crate::{FrameSpec, Renderer, StyleProgram};
use meshes::MeshExtras;
use std::sync::Arc;

/// A compiled style running on a host's device: owned (it holds clones of
/// the device and queue, which wgpu reference-counts), so it can live as
/// long as the host wants, in a `'static` resource or across threads.
///
/// Style-level resources (shader modules, pipelines and their layouts, the
/// style's textures and art-maps, the sampler, the frame and style uniform
/// buffers) are built at the first frame and kept for the runtime's life;
/// size-level ones (targets, their bind groups) when the target's size
/// changes; scene-level ones (mesh buffers, the object buffer, per-object
/// bind groups, compute passes' buffers, line caches, light bounds) when
/// the set of objects' meshes, tags, images, shadow flags or ids changes.
/// The history goes on across such a change (trails stay; objects that
/// stay keep their compute state) and starts over at a new size.
pub struct StyleRuntime {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// The style, with the parameter values [`StyleRuntime::set_param`] gave.
    program: StyleProgram,
    meshes: meshes::MeshTable,
    /// The host's objects as the renderer's scene.
    scene: objects::HostScene,
    renderer: Option<Renderer>,
    presenter: present::Presenter,
    /// Times the renderer was built (the style's resources made): what a
    /// host or test can watch.
    builds: u64,
    /// Times a built renderer was given other objects
    /// ([`Renderer::set_scene`]: the scene-level resources made anew).
    scene_changes: u64,
    /// 2 for a stereo style, else 1 (`Manifest::is_stereo` scans every
    /// binding of every pass: asked once, not every frame).
    eye_slots: usize,
    /// Meshes divided by [`StyleRuntime::add_patches`] so far: names each
    /// division, whose patches `lines` passes join into one surface.
    patch_sets: u64,
    /// The host's images for the style's `input(...)` textures.
    inputs: inputs::HostViews,
}

impl StyleRuntime {
    /// A runtime of `program` on `device`. Refuses (E0510) a device that
    /// lacks a feature or limit the style needs, naming it and its pass,
    /// and a program whose manifest and shaders disagree (E9001).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, program: StyleProgram) -> Result<StyleRuntime, EmbedError> {
        program
            .validate()
            .map_err(|e| crate::RunError::Internal(format!("the compiled style is inconsistent: {e}")))?;
        let lacking = crate::device_needs::unmet(&program.manifest, device.features(), &device.limits(), "this device");
        if !lacking.is_empty() {
            return Err(crate::RunError::User(lacking).into());
        }
        if program.manifest.validate_filter().is_ok() {
            return Err(crate::RunError::User(vec![npr_diag::Diagnostic::error(
                npr_diag::codes::BAD_FILTER,
                format!(
                    "style \"{}\" is an art-map filter: it runs on a texture level, not on a scene",
                    program.manifest.style
                ),
            )])
            .into());
        }
        static RUNTIMES: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
        let id = RUNTIMES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(StyleRuntime {
            eye_slots: if program.manifest.is_stereo() { 2 } else { 1 },
            inputs: inputs::HostViews::new(&program.manifest),
            presenter: present::Presenter::new(device),
            device: device.clone(),
            queue: queue.clone(),
            program,
            meshes: meshes::MeshTable::new(id),
            scene: objects::HostScene::default(),
            renderer: None,
            builds: 0,
            scene_changes: 0,
            patch_sets: 0,
        })
    }

    /// What a host's device must have for `program`: the WebGPU features
    /// and `base` with the limits raised that its passes need (the
    /// manifest's `device_needs`). Ask the adapter for these in
    /// `wgpu::DeviceDescriptor`; [`StyleRuntime::new`] refuses a device
    /// without them (E0510).
    pub fn device_needs(program: &StyleProgram, base: wgpu::Limits) -> (wgpu::Features, wgpu::Limits) {
        let features = program
            .manifest
            .required_features()
            .into_iter()
            .fold(wgpu::Features::empty(), |f, need| {
                f | crate::device_needs::wgpu_feature(need)
            });
        (features, crate::device_needs::requested_limits(&program.manifest, base))
    }

    /// The style's manifest (passes, targets, parameters, device needs).
    pub fn manifest(&self) -> &npr_abi::manifest::Manifest {
        &self.program.manifest
    }

    /// Register a mesh; instances name it by the handle. Its GPU buffers
    /// are made once, at the first frame that draws it.
    pub fn add_mesh(&mut self, mesh: Mesh) -> MeshHandle {
        self.meshes.add(Arc::new(mesh), MeshExtras::default())
    }

    /// [`StyleRuntime::add_mesh`] of a mesh the host shares (no copy).
    pub fn add_shared_mesh(&mut self, mesh: Arc<Mesh>) -> MeshHandle {
        self.meshes.add(mesh, MeshExtras::default())
    }

    /// Register a skinned or morphing mesh: `mesh` in its bind pose, with
    /// its joints, weights and morph targets. Each [`Instance`] of the
    /// handle then gives its pose every frame ([`Instance::pose`]: one
    /// matrix per joint, in skin space, and one weight per morph target),
    /// and the GPU morphs and skins its vertices by it before the style's
    /// passes, with the stage that plays a scene file's glTF clips (glTF
    /// 2.0's linear blend skinning of 4 joints and morph targets,
    /// docs/decisions/0053 and 0055): every pass sees the deformed surface,
    /// `position.previous` the previous frame's pose, and the CPU stages
    /// (a `lines` pass, a light view's bounds) the same pose deformed on
    /// the CPU. Instances of one handle share the mesh and have poses of
    /// their own (a crowd); an instance without a pose draws the bind
    /// pose. A frame whose poses changed and nothing else allocates
    /// nothing.
    ///
    /// Refused (E0615), registering nothing: joint indices or weights that
    /// are not one set per vertex, weights that are negative, not finite
    /// or do not sum to 1 (within
    /// [`WEIGHT_SUM_TOLERANCE`](crate::scene::gltf_rig::WEIGHT_SUM_TOLERANCE);
    /// they are renormalised), a weighted joint index past `joint_count`,
    /// more than [`MAX_JOINTS`](crate::scene::gltf_rig::MAX_JOINTS) joints,
    /// morph deltas that are not one per vertex or not finite, neither
    /// joints nor morph targets.
    ///
    /// ```
    /// use npr_runner::embed::{Instance, SkinPose, Skinning, StyleRuntime};
    /// use npr_runner::scene::primitives;
    ///
    /// let style = "style \"Flat\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n";
    /// let mut sources = npr_diag::SourceMap::new();
    /// let compiled = npr_compiler::compile_source("flat.npr", style, std::path::Path::new("."), &mut sources, &Default::default())
    ///     .map_err(|e| format!("{e:?}"))?;
    /// let gpu = npr_runner::Gpu::headless()?;
    /// let mut runtime = StyleRuntime::new(&gpu.device, &gpu.queue, compiled.program())?;
    ///
    /// // A box bound to two joints: its lower half to joint 0, its upper to joint 1.
    /// let cube = primitives::cube(1.0);
    /// let joints = cube.positions.iter().map(|p| if p[1] > 0.0 { [1, 0, 0, 0] } else { [0; 4] }).collect();
    /// let weights = vec![[1.0, 0.0, 0.0, 0.0]; cube.vertex_count()];
    /// let skinning = Skinning { joint_count: 2, joints, weights, morph_targets: Vec::new() };
    /// let boxed = runtime.add_skinned_mesh(cube, skinning)?;
    ///
    /// // Each frame: the instance's pose, here the upper joint lifted.
    /// let mut pose = SkinPose::bind(2, 0);
    /// pose.joints[1] = glam::Mat4::from_translation(glam::Vec3::Y * 0.5);
    /// let objects = [Instance::new(boxed, glam::Mat4::IDENTITY).with_pose(pose)];
    /// // `objects` go in each `Frame`; a pose of 3 matrices would be E0612.
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_skinned_mesh(&mut self, mesh: Mesh, skinning: Skinning) -> Result<MeshHandle, EmbedError> {
        let rig = Arc::new(skin::rig_of(mesh, skinning)?);
        // The drawn mesh is the bind mesh, which the GPU stage deforms.
        let bind = Arc::new(rig.bind.clone());
        let extras = MeshExtras {
            rig: Some(rig),
            ..MeshExtras::default()
        };
        Ok(self.meshes.add(bind, extras))
    }

    /// The joint count and morph target count of a mesh registered with
    /// [`StyleRuntime::add_skinned_mesh`] (what its instances' poses give);
    /// `None` for another mesh or a removed handle.
    pub fn skin(&self, handle: MeshHandle) -> Option<(usize, usize)> {
        let rig = self.meshes.entry(handle).ok()?.extras.rig.as_ref()?;
        Some(skin::sizes(rig))
    }

    /// Register a primitive's geometry ([`Primitive::build`]). A
    /// time-varying one (the ocean of Age of Sail §6.1,
    /// [`Primitive::is_time_varying`]) is animated: every instance of the
    /// handle has its vertices at the frame's `time_s`, rebuilt on the CPU
    /// and written over its GPU buffers in place (its vertex count and
    /// indices never change, so a frame allocates nothing on the GPU), as
    /// `npr render` draws a scene's ocean. [`StyleRuntime::mesh`] gives its
    /// geometry at t = 0.
    ///
    /// ```
    /// use npr_runner::embed::{Instance, StyleRuntime};
    /// use npr_runner::scene::{ocean::Ocean, patches::PatchSpec, primitives, Primitive};
    ///
    /// let style = "style \"Flat\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n";
    /// let mut sources = npr_diag::SourceMap::new();
    /// let compiled = npr_compiler::compile_source("flat.npr", style, std::path::Path::new("."), &mut sources, &Default::default())
    ///     .map_err(|e| format!("{e:?}"))?;
    /// let gpu = npr_runner::Gpu::headless()?;
    /// let mut runtime = StyleRuntime::new(&gpu.device, &gpu.queue, compiled.program())?;
    ///
    /// // A small sea: every frame draws its waves at the frame's `time_s`.
    /// let sea = runtime.add_primitive(Primitive::Ocean(Ocean { cells: 16, tiles: 3, modes: 8, ..Ocean::default() }));
    /// // A sphere in 4 patches blended over 1 ring: one instance per patch, one transform.
    /// let ball = std::sync::Arc::new(primitives::sphere(1.0, 32, 16));
    /// let patches = runtime.add_patches(ball, PatchSpec::Split(4), 1)?;
    /// let lifted = glam::Mat4::from_translation(glam::Vec3::Y * 2.0);
    /// let mut objects = vec![Instance::new(sea, glam::Mat4::IDENTITY)];
    /// objects.extend(patches.iter().map(|&p| Instance::new(p, lifted)));
    /// assert_eq!(objects.len(), 5);
    /// // `objects` go in each `Frame` as any instances do.
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_primitive(&mut self, primitive: Primitive) -> MeshHandle {
        let extras = MeshExtras {
            time_varying: primitive.is_time_varying().then_some(primitive),
            ..MeshExtras::default()
        };
        self.meshes.add(Arc::new(primitive.build()), extras)
    }

    /// Register `mesh` divided into patches (Breslav et al. 2007 §3.6), as
    /// a scene's `patches = ...` and `blend_rings = n` divide an object:
    /// one handle per patch, in order. Draw the patched surface as one
    /// instance of each handle, all with the same transform (and, as a
    /// scene's patches have, the same tags and params): each patch then
    /// gets its own samples and 2D similarity in the style's per-object
    /// passes; render passes that read `patch.weight` draw each patch over
    /// the `blend_rings` rings of faces around it with its blending weights,
    /// where the patches' patterns cross-fade (0: hard seams); and `lines`
    /// passes find feature edges on the whole mesh, so a seam is no edge.
    ///
    /// A mesh that cannot be divided so (`PatchSpec::Parts` of a mesh with
    /// one part; more patches than triangles), a count outside
    /// 2..=[`MAX_PATCHES`](crate::scene::patches::MAX_PATCHES) or rings over
    /// [`MAX_BLEND_RINGS`](crate::scene::patch_blend::MAX_BLEND_RINGS) is
    /// refused (E0405), registering nothing.
    pub fn add_patches(
        &mut self,
        mesh: Arc<Mesh>,
        spec: PatchSpec,
        blend_rings: u32,
    ) -> Result<Vec<MeshHandle>, EmbedError> {
        let pieces = patched::divide(&mesh, spec, blend_rings, self.patch_sets + 1)?;
        self.patch_sets += 1;
        Ok(pieces
            .into_iter()
            .map(|(piece, extras)| self.meshes.add(piece, extras))
            .collect())
    }

    /// Forget a mesh: its handle is refused from now on (E0601), and its
    /// GPU buffers are freed once no frame draws it.
    pub fn remove_mesh(&mut self, handle: MeshHandle) -> Result<(), EmbedError> {
        self.meshes.remove(handle).map(|_| ())
    }

    /// Deform a registered mesh: its vertices are `vertices` from the next
    /// frame on, for every instance of `handle` (skinning on the CPU, cloth,
    /// a morph, a sculpting tool). Its triangles and UVs stay, so this is
    /// not a change of the scene: the next frame writes the new vertices
    /// over the mesh's GPU buffers in place (no buffer, bind group or
    /// pipeline is made) and the history goes on (`previous(...)`, compute
    /// passes' state), as an animated primitive's vertices do. Everything
    /// made from the vertices follows: every pass's vertex buffers, the
    /// copies compute passes over vertices read (a `samples` pass's samples
    /// stay on their triangles, so they ride on the surface), the edges and strips of
    /// `lines` passes, and the bounds the light camera of shadow passes is
    /// fitted to.
    ///
    /// Normals and tangents left out ([`Deformed::positions`]) are made from
    /// the new positions (smooth normals; tangents from the UVs), as for a
    /// mesh read without them; given ones are written as given. The CPU
    /// keeps a copy of the deformed mesh (the lines and the light bounds
    /// read it), made anew at each call. Several calls before a frame: the
    /// last one is drawn. Handles of one shared mesh
    /// ([`StyleRuntime::add_shared_mesh`] of one `Arc` twice) are one mesh,
    /// drawn from the same GPU buffers: deforming one deforms them all.
    ///
    /// Refused, leaving the mesh as it was: a removed handle (E0601);
    /// another number of positions, normals or tangents than the mesh has
    /// vertices, a number that is not finite, tangents for a mesh without
    /// them, or an animated primitive's or a patch's handle, whose vertices
    /// the runtime makes itself (E0603). A mesh of other vertices or
    /// triangles is another mesh: [`StyleRuntime::add_mesh`] it and draw its
    /// handle (a scene change, which restarts the history).
    ///
    /// ```
    /// use npr_runner::embed::{Deformed, StyleRuntime};
    /// use npr_runner::scene::primitives;
    ///
    /// let style = "style \"Flat\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n";
    /// let mut sources = npr_diag::SourceMap::new();
    /// let compiled = npr_compiler::compile_source("flat.npr", style, std::path::Path::new("."), &mut sources, &Default::default())
    ///     .map_err(|e| format!("{e:?}"))?;
    /// let gpu = npr_runner::Gpu::headless()?;
    /// let mut runtime = StyleRuntime::new(&gpu.device, &gpu.queue, compiled.program())?;
    /// let ball = runtime.add_mesh(primitives::sphere(1.0, 16, 8));
    ///
    /// // Each frame: the host's own deformation (here a squash), then render.
    /// let rest = runtime.mesh(ball)?.positions.clone();
    /// let squashed: Vec<[f32; 3]> = rest.iter().map(|p| [p[0] * 1.2, p[1] * 0.7, p[2] * 1.2]).collect();
    /// runtime.update_mesh(ball, Deformed::positions(&squashed))?;
    /// assert_eq!(runtime.mesh(ball)?.positions, squashed);
    ///
    /// // Another vertex count is another mesh, not a deformation:
    /// let e = runtime.update_mesh(ball, Deformed::positions(&squashed[1..])).unwrap_err();
    /// assert_eq!(e.code(), "E0603");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn update_mesh(&mut self, handle: MeshHandle, vertices: Deformed) -> Result<(), EmbedError> {
        let entry = self.meshes.entry(handle)?;
        let deformed = Arc::new(deform::deformed_mesh(handle, entry, &vertices)?);
        let old = entry.mesh.clone();
        self.scene.replace_mesh(&old, &deformed);
        self.meshes.replace(&old, &deformed);
        Ok(())
    }

    /// How many meshes are registered now (added and not removed): a host
    /// checks that it removes the meshes it no longer draws.
    pub fn mesh_count(&self) -> usize {
        self.meshes.len()
    }

    /// The mesh a handle names (E0601 for a removed one).
    pub fn mesh(&self, handle: MeshHandle) -> Result<&Arc<Mesh>, EmbedError> {
        self.meshes.get(handle)
    }

    /// A scene read from TOML (`scene::load_scene`) as the host's
    /// objects: each distinct mesh registered once, one [`Instance`] per
    /// object (its model at load, tags, per-object params, images, shadow
    /// flag), in order, so `instances[i]` is `scene.objects[i]`. Meshes
    /// come with what the scene's objects draw beyond their vertices, as
    /// [`StyleRuntime::add_primitive`] and [`StyleRuntime::add_patches`]
    /// register them: the ocean's vertices follow the frame's time, and a
    /// patched object's patches blend over their n-rings and are one
    /// surface for `lines` passes. An object playing a clip
    /// (`animation = {...}`) plays it at each frame's time
    /// ([`Instance::animation`]). What else a TOML scene has beyond an
    /// instance is the host's to animate: a spinning object's transform is
    /// `scene.objects[i].model_at(t)`.
    pub fn add_scene(&mut self, scene: &Scene) -> Vec<Instance> {
        // Objects naming the same file or primitive share one mesh (and
        // then its extras: the same primitive; a patch is never shared).
        let mut registered: Vec<(*const Mesh, MeshHandle)> = Vec::new();
        scene
            .objects
            .iter()
            .map(|o| {
                let key = Arc::as_ptr(&o.mesh);
                let mesh = match registered.iter().find(|(k, _)| *k == key) {
                    Some((_, h)) => *h,
                    None => {
                        let extras = MeshExtras {
                            time_varying: o.time_varying,
                            blend: o.blend.clone(),
                            patch: o.patch.clone(),
                            rig: None,
                        };
                        let h = self.meshes.add(o.mesh.clone(), extras);
                        registered.push((key, h));
                        h
                    }
                };
                Instance {
                    mesh,
                    transform: o.model,
                    tags: o.tags.clone(),
                    params: o.params.clone(),
                    casts_shadows: o.casts_shadows,
                    images: o.textures.clone(),
                    id: None,
                    pose: None,
                    animation: o.animation.clone(),
                    material: o.material.clone(),
                }
            })
            .collect()
    }

    /// Times the renderer was built, with every GPU resource of the style
    /// (pipelines, textures, art-maps): once, at the first frame (again
    /// only after a refused scene).
    pub fn builds(&self) -> u64 {
        self.builds
    }

    /// Times the set of objects' meshes, tags, images or shadow flags
    /// changed after the first frame, each making only the scene-level
    /// resources anew ([`Renderer::set_scene`]).
    pub fn scene_changes(&self) -> u64 {
        self.scene_changes
    }

    /// Start the style's history over at the next frame, as a new runtime
    /// starts it (`previous(...)` reads zero, compute state its first
    /// values): for a cut to another shot. Objects coming and going keep
    /// the history; a new size starts it over too.
    pub fn restart_history(&mut self) {
        if let Some(renderer) = &mut self.renderer {
            renderer.restart_history();
        }
    }

    /// Give input `name` of the style (its `texture name = input(kind,
    /// ...)`) from the host's own `view`, written in `source`'s convention:
    /// colour linear or sRGB-encoded, depth reverse-Z NDC with its near
    /// plane or a distance along the view axis (metres), normals in world
    /// space (y or z up) or view space, stored as they are in a float
    /// format and as n·0.5 + 0.5 in a normalized one. Every frame from the
    /// next on reads the view, converted into the language's convention
    /// inside the frame's encoder by the draw `npr render --input` files
    /// go through (`npr_runner::inputs::gpu`): the same images give the
    /// same pixels either way. Normals turned between world and view space
    /// use the frame's camera.
    ///
    /// The view is kept (a clone) until another is given: a host whose
    /// G-buffer stays gives its views once, or again every frame; a frame
    /// makes the conversion's bind group only for a view it has not read
    /// before. Refused, changing nothing: a name the style does not
    /// declare (E0604); a texture that is not 2D with one layer, mip level
    /// and sample, lacks `TEXTURE_BINDING`, or has a format not read as
    /// floats, or a convention not of the input's kind (E0605). At
    /// [`StyleRuntime::render`]: an input not given (E0607), or not of the
    /// target's size (E0606).
    pub fn set_input(
        &mut self,
        name: &str,
        view: &wgpu::TextureView,
        source: crate::inputs::SourceConvention,
    ) -> Result<(), EmbedError> {
        self.inputs.set(name, view, source)
    }

    /// Record one frame into `encoder`: the style's passes, then the
    /// output drawn into `target`'s views at their size. Nothing is
    /// submitted; the host submits `encoder`. On an error nothing was
    /// recorded.
    pub fn render(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &Frame,
        target: Target,
    ) -> Result<(), EmbedError> {
        let checked = present::check_target(&target, self.eye_slots, frame.eye)?;
        camera_check::check_camera(frame.camera)?;
        let size = (checked.width, checked.height);
        if self.inputs.any() {
            self.inputs.check(size)?;
        }
        if self.scene.sync(frame, &self.meshes)? {
            // Other meshes, tags, images or shadow flags: only the
            // scene-level resources are made anew; the style's stay.
            if let Some(renderer) = &mut self.renderer {
                if let Err(e) = renderer.set_scene(self.scene.scene()) {
                    // The renderer still holds the old objects, which the
                    // next frame's sync no longer compares against: a
                    // refused scene builds afresh once it is fixed.
                    self.renderer = None;
                    return Err(e.into());
                }
                self.scene_changes += 1;
            }
        }
        let renderer = match &mut self.renderer {
            Some(r) => r,
            slot => {
                let blank = self.inputs.blank(size);
                let built =
                    Renderer::new_with_inputs(&self.device, &self.queue, &self.program, self.scene.scene(), &blank)?;
                self.inputs.made(size);
                self.builds += 1;
                slot.insert(built)
            }
        };
        if self.inputs.any() && !self.inputs.made_at(size) {
            // The host's size changed: input textures of the new one.
            renderer.set_inputs(&self.inputs.blank(size))?;
            self.inputs.made(size);
        }
        let spec = FrameSpec {
            width: checked.width,
            height: checked.height,
            time_s: frame.time_s,
            frame: frame.frame_index,
            eye: frame.eye,
        };
        renderer.prepare(self.scene.scene(), &spec)?;
        if self.inputs.any() {
            let camera = frame.camera.pose(frame.time_s);
            self.inputs
                .encode(&self.device, &self.queue, encoder, renderer, &camera)?;
        }
        renderer.encode(encoder);
        self.presenter.encode(&self.device, encoder, renderer, &checked)
    }

    /// Read back a target of the last frame (after the host submitted it):
    /// for tests and tools; blocks until the GPU is done.
    pub fn read_target(&self, name: &str) -> Result<crate::TargetImage, EmbedError> {
        let renderer = self
            .renderer
            .as_ref()
            .ok_or_else(|| crate::RunError::Internal("read before the first frame".into()))?;
        let index = self
            .program
            .manifest
            .targets
            .iter()
            .position(|t| t.name == name)
            .ok_or_else(|| crate::RunError::Internal(format!("the style has no target `{name}`")))?;
        Ok(renderer.read_target(index)?)
    }

    /// The scene as the renderer sees it (the host's instances, posed by
    /// the last frame).
    pub fn scene(&self) -> &Scene {
        self.scene.scene()
    }
}
