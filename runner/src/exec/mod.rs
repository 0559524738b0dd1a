//! Execute a compiled style on wgpu: the [`Renderer`], which orchestrates
//! the pieces in this folder.
//!
//! A [`Renderer`] borrows a device and queue, so it works in someone else's
//! wgpu application as well as headless. It builds one executor per pass
//! (`pass::PassExec`, pipelines built once and cached for the renderer's
//! life: they depend on the style and the device, never on the scene),
//! uploads the scene's meshes once (again only when
//! [`Renderer::set_scene`] gives it other objects), allocates the physical textures
//! of the manifest (aliased targets share one) and re-allocates only when
//! the output size changes. Each frame writes only uniforms (camera, style
//! params, object transforms and params, all read from the `Scene` given)
//! and records the passes.
//!
//! - `frame.rs`: [`FrameSpec`] and the per-frame uniform writing;
//! - `objects.rs`: object uniform blocks;
//! - `light_bounds.rs`: the world bounds the light camera is fitted to;
//! - `upload.rs`: the frame's uniforms through a reused staging buffer, copied into their buffers;
//! - `sized.rs`: the types of the size-dependent resources (a leaf the
//!   executors share); `resources.rs` builds them per size;
//! - `bind.rs`: bind group layouts and bind groups;
//! - `meshes.rs`: GPU meshes and time-varying vertex updates;
//! - `deform.rs`: the GPU stage that morphs and skins objects playing a
//!   glTF clip, at the start of each frame (decision 0053);
//! - `scene_check.rs`: scene-against-style checks (E0403, E0405);
//! - `scene_gpu.rs`: the scene-level resources, made apart from the
//!   style's ([`Renderer::set_scene`]);
//! - `continuity.rs`: what a scene change carries over (continuing
//!   objects, their compute state and transforms; [`Renderer::restart_history`]);
//! - `values.rs`: compute passes' buffers (per-object values, partials);
//! - `pass.rs`: `pass::PassExec`, one variant per pass kind, dispatching
//!   to the executors `render_pass.rs`, `image_pass.rs`, `tiled_pass.rs`,
//!   `compute_pass.rs` and `lines_pass.rs`;
//! - `common.rs`: what the executors share (they import it, never `pass.rs`);
//! - `prepare_lines.rs`: each frame's strips of the `lines` passes;
//! - `host_depth.rs`: the host's `input(depth)` drawn into a depth buffer
//!   each frame, for passes with `depth: test(input)`;
//! - `state.rs`: what outlives a frame, saved and restored (checkpoints).

use crate::gpu_count::Create;
mod bind;
mod common;
mod compute_pass;
mod continuity;
pub mod deform;
mod frame;
mod host_depth;
mod image_pass;
mod light_bounds;
mod lines_pass;
mod meshes;
mod objects;
mod pass;
mod prepare_lines;
mod read_all;
mod render_pass;
mod resources;
mod scene_check;
mod scene_gpu;
mod scene_warnings;
mod sized;
mod state;
mod tiled_pass;
mod upload;
mod values;

pub use frame::FrameSpec;
pub(crate) use host_depth::host_depth_wgsl;
pub use scene_check::{check_scene, check_texture_bindings};
pub use scene_warnings::scene_warnings;
pub use sized::{scaled_size, wgpu_format};
pub use state::{FrameTransforms, RendererState, StateBlock, StateKind};

use crate::scene::Scene;
use crate::textures::{self, GpuTexture};
use crate::{readback, RunError};
use common::{EncodeContext, Timestamps};
use npr_abi::manifest::*;
use pass::PassExec;

/// The largest image (`--size`): `npr_diag::limits`, where every limit is listed.
pub use npr_diag::limits::MAX_OUTPUT_SIZE;

pub struct Renderer {
    /// Clones of the caller's handles (wgpu's are reference-counted), so a
    /// renderer borrows nothing and can live in a `'static` host (a Bevy resource).
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// Read through [`Renderer::manifest`]; its parameters change only
    /// through [`Renderer::params_mut`], which has the style block made
    /// anew (`frame.rs` writes only the animated parameters otherwise).
    manifest: Manifest,
    /// One executor per manifest pass, in manifest order.
    passes: Vec<PassExec>,
    /// The scene-level resources (meshes, object blocks and groups,
    /// compute buffers, light bounds, the frame's upload), made anew by
    /// [`Renderer::set_scene`]; the rest of the renderer is the style's.
    scene_gpu: scene_gpu::SceneGpu,
    /// Its layout, which the pipelines were made with (style-level: kept
    /// across [`Renderer::set_scene`]).
    object_layout: wgpu::BindGroupLayout,
    textures: Vec<GpuTexture>,
    linear_clamp: wgpu::Sampler,
    /// One per eye rendered in a frame (two for stereo styles).
    frame_buffers: Vec<wgpu::Buffer>,
    style_buffer: wgpu::Buffer,
    /// How many parities frames alternate between ([`Renderer::parities`]),
    /// known at build: the host path asks every frame.
    parities: usize,
    object_stride: u64,
    /// The params each object block writes and their defaults, found at build.
    object_params: objects::ObjectParams,
    /// [`crate::animation::animated_style_param_indices`], found whenever
    /// the whole style block is written: the params a frame writes again.
    animated_style_params: Vec<usize>,
    /// Whether a pass draws lines (a frame without one skips their preparation).
    has_lines: bool,
    /// Whether a CPU stage reads the frame's deformed vertices: the lines
    /// passes, and the light bounds a light-view pass is fitted to. Only
    /// then does a frame also deform animated objects on the CPU
    /// (`Scene::posed`); the passes draw the GPU stage's (decision 0053).
    cpu_pose: bool,
    /// The GPU deformation stage's pipeline, made at the first scene with
    /// an object playing a clip and kept across scenes.
    deform_pipeline: std::sync::OnceLock<deform::DeformPipeline>,
    sized: Option<sized::SizedResources>,
    /// The host depth draw, made when a pass tests against an `input(depth)`.
    host_depth: Option<host_depth::HostDepthPipeline>,
    /// Frames begun (by [`Renderer::prepare`]) since the textures were
    /// made: the current frame's parity is `(frames_begun - 1) % 2` for
    /// styles with history textures.
    frames_begun: u64,
    /// Object transforms and view-projections per eye slot of the frame
    /// begun last and of the one before it: `previous_model` and
    /// `previous_view_proj` (the current ones on the first frame).
    motion: frame::Motion,
    /// The camera's matrices of the last frame, kept while its pose and the size stay.
    camera: frame::CameraMatrices,
    artmap_builds: Vec<crate::artmap::ArtmapBuild>,
    /// Value rows of continuing objects that a scene change carries into
    /// the new value buffers, recorded by the next encode (`continuity.rs`).
    carried_rows: std::sync::Mutex<Vec<continuity::RowCopy>>,
    /// Changes whenever the textures a frame writes are made anew (a new
    /// renderer, a new size): what holders of views into them compare.
    generation: u64,
}

/// A number no renderer's resources had before ([`Renderer::resources_generation`]).
fn next_generation() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

impl Renderer {
    /// Build pipelines and upload the scene. Diagnostics (E0403, E0401, E0404)
    /// come back as `RunError::User`. Other objects later:
    /// [`Renderer::set_scene`], which keeps the pipelines and textures.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        program: &crate::StyleProgram,
        scene: &Scene,
    ) -> Result<Renderer, RunError> {
        Self::new_with_inputs(device, queue, program, scene, &crate::inputs::HostInputs::new())
    }

    /// [`Renderer::new`] for a style that reads host inputs (`input(...)`
    /// textures), given by name in the language's conventions
    /// ([`crate::inputs`]); each is missing (E0420) unless given. Frames
    /// are rendered at the inputs' size. Later frames' inputs:
    /// [`Renderer::set_inputs`].
    pub fn new_with_inputs(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        program: &crate::StyleProgram,
        scene: &Scene,
        inputs: &crate::inputs::HostInputs,
    ) -> Result<Renderer, RunError> {
        if program.manifest.validate_filter().is_ok() {
            return Err(RunError::User(vec![npr_diag::Diagnostic::error(
                npr_diag::codes::BAD_FILTER,
                format!(
                    "style \"{}\" is an art-map filter: it runs on a texture level, not on a scene",
                    program.manifest.style
                ),
            )
            .with_help(
                "use it in another style: `texture t = artmap(image(\"brick.png\", srgb), filter: \"this.npr\")`",
            )]));
        }
        Self::build(device, queue, program, scene, None, inputs)
    }

    /// The next frame's host inputs (a sequence). Of the size of the
    /// last ones, they are written over the input textures in place: the
    /// history goes on (`previous(...)` reads the frame before). Of
    /// another size, the input textures are made anew, the pipelines stay,
    /// and the size-dependent resources are rebuilt at the next frame,
    /// since their bind groups hold the old textures.
    pub fn set_inputs(&mut self, inputs: &crate::inputs::HostInputs) -> Result<(), RunError> {
        if textures::write_host_inputs(&self.device, &self.queue, &self.manifest, inputs, &self.textures)? {
            return Ok(());
        }
        for (i, texture) in textures::host_inputs(&self.device, &self.queue, &self.manifest, inputs)? {
            self.textures[i] = texture;
        }
        self.sized = None;
        Ok(())
    }

    /// The texture a host input `name` is converted into (`input(...)`),
    /// of the inputs' size: what `embed` draws a host's views into.
    pub fn input_texture(&self, name: &str) -> Option<&wgpu::Texture> {
        self.manifest
            .textures
            .iter()
            .position(|t| t.name == name && matches!(t.source, TextureSourceManifest::Input(_)))
            .map(|i| &self.textures[i].texture)
    }

    /// A renderer of an art-map's filter style, whose `filter_input()` is
    /// `level`; it renders on [`Scene::empty`] at the level's size.
    pub fn new_filter(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        program: &crate::StyleProgram,
        level: &crate::image_level::Level,
    ) -> Result<Renderer, RunError> {
        program
            .manifest
            .validate_filter()
            .map_err(|e| RunError::Internal(format!("not a filter style: {e}")))?;
        Self::build(
            device,
            queue,
            program,
            &Scene::empty(),
            Some(level),
            &crate::inputs::HostInputs::new(),
        )
    }

    /// A filter renderer ([`Renderer::new_filter`]) moves on to the next
    /// level: its `filter_input()` texture is replaced by `level`; the
    /// pipelines stay (what building them costs is most of a level's
    /// filtering on lavapipe), the size-dependent resources are rebuilt at
    /// the next frame, since their bind groups hold the old texture.
    pub fn set_filter_input(&mut self, level: &crate::image_level::Level) -> Result<(), RunError> {
        for (i, texture) in textures::filter_inputs(&self.device, &self.queue, &self.manifest, level)? {
            self.textures[i] = texture;
        }
        self.sized = None;
        Ok(())
    }

    /// What building each art-map of the style did (filtered, or read from
    /// the cache), in declaration order.
    pub fn artmap_builds(&self) -> &[crate::artmap::ArtmapBuild] {
        &self.artmap_builds
    }

    fn build(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        program: &crate::StyleProgram,
        scene: &Scene,
        filter_input: Option<&crate::image_level::Level>,
        inputs: &crate::inputs::HostInputs,
    ) -> Result<Renderer, RunError> {
        // Every index the executors use is checked once here, whether the
        // program came from `load_dir` or was built in memory by an embedder.
        program
            .validate()
            .map_err(|e| RunError::Internal(format!("the compiled style is inconsistent: {e}")))?;
        // A feature or limit the style needs that this device lacks: E0510
        // naming it and its pass, before any pipeline fails on it.
        let lacking = crate::device_needs::unmet(&program.manifest, device.features(), &device.limits(), "this device");
        if !lacking.is_empty() {
            return Err(RunError::User(lacking));
        }
        let diags = check_scene(&program.manifest, scene);
        if !diags.is_empty() {
            return Err(RunError::User(diags));
        }
        let targets: Vec<(String, npr_abi::Format)> = program
            .manifest
            .targets
            .iter()
            .map(|t| (t.name.clone(), t.format))
            .collect();
        let diags = crate::gpu_error::check_target_formats(device, &targets, crate::gpu_error::TARGET_USAGE);
        if !diags.is_empty() {
            return Err(RunError::User(diags));
        }
        crate::gpu_error::scoped(
            device,
            || "building the renderer (pipelines, textures, meshes)".to_string(),
            || Self::build_in_scopes(device, queue, program, scene, filter_input, inputs),
        )
    }

    /// [`Renderer::build`] after its checks, inside its error scopes.
    fn build_in_scopes(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        program: &crate::StyleProgram,
        scene: &Scene,
        filter_input: Option<&crate::image_level::Level>,
        inputs: &crate::inputs::HostInputs,
    ) -> Result<Renderer, RunError> {
        let manifest = program.manifest.clone();
        let (textures, artmap_builds) =
            textures::load_all(device, queue, &manifest, filter_input, inputs, &program.files)?;
        let linear_clamp = device.make_sampler(&wgpu::SamplerDescriptor {
            label: Some("npr linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let object_stride = object_stride(manifest.object_uniform_size);
        let object_layout = bind::shared_object_layout(device, manifest.object_uniform_size);
        // Measured once, and only when a fused pass repeats a 16-bit store.
        let half_rounding = if manifest.passes.iter().any(|p| p.device_half_rounding) {
            Some(crate::half_rounding::measure(device, queue)?)
        } else {
            None
        };
        let mut passes = Vec::new();
        for pass in &manifest.passes {
            let wgsl = program
                .shaders
                .get(&pass.shader)
                .ok_or_else(|| RunError::Internal(format!("no shader `{}` for pass `{}`", pass.shader, pass.name)))?;
            passes.push(PassExec::build(
                device,
                &manifest,
                pass,
                wgsl,
                &object_layout,
                half_rounding,
            )?);
        }
        let eyes = if manifest.is_stereo() { 2 } else { 1 };
        let frame_buffers = (0..eyes)
            .map(|e| {
                device.make_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("npr frame, eye slot {e}")),
                    size: FRAME_UNIFORM_SIZE,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let style_buffer = device.make_buffer(&wgpu::BufferDescriptor {
            label: Some("npr style params"),
            size: manifest.style_uniform_size.max(16),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let object_params = objects::ObjectParams::new(&manifest, object_stride);
        let deform_pipeline = std::sync::OnceLock::new();
        // The scene's part, made as `set_scene` makes another's.
        let style = scene_gpu::StyleParts {
            manifest: &manifest,
            textures: &textures,
            object_layout: &object_layout,
            object_stride,
            object_params: &object_params,
            passes: &passes,
            eyes,
            object_images: &Default::default(),
            deform_pipeline: &deform_pipeline,
        };
        let (scene_gpu, pass_scenes) = scene_gpu::SceneGpu::make(device, queue, &style, scene)?;
        for (exec, part) in passes.iter_mut().zip(pass_scenes) {
            exec.set_scene(part);
        }
        let host_depth =
            (!host_depth::tested_inputs(&manifest).is_empty()).then(|| host_depth::HostDepthPipeline::new(device));
        let has_lines = passes.iter().any(|p| matches!(p, PassExec::Lines(_)));
        let light_view = manifest
            .passes
            .iter()
            .any(|p| matches!(p.kind, PassKindManifest::Render { light_view: true, .. }));
        Ok(Renderer {
            device: device.clone(),
            queue: queue.clone(),
            passes,
            scene_gpu,
            object_layout,
            textures,
            linear_clamp,
            frame_buffers,
            style_buffer,
            parities: if manifest.is_path_dependent() { 2 } else { 1 },
            object_stride,
            object_params,
            animated_style_params: Vec::new(),
            has_lines,
            cpu_pose: has_lines || light_view,
            deform_pipeline,
            manifest,
            sized: None,
            host_depth,
            frames_begun: 0,
            motion: frame::Motion::default(),
            camera: frame::CameraMatrices::default(),
            artmap_builds,
            carried_rows: Default::default(),
            generation: next_generation(),
        })
    }

    /// Render one frame; every target stays on the GPU for [`Renderer::read_target`].
    pub fn render(&mut self, scene: &Scene, spec: &FrameSpec) -> Result<(), RunError> {
        self.prepare(scene, spec)?;
        crate::gpu_error::scoped(
            &self.device,
            || format!("rendering a {}x{} frame", spec.width, spec.height),
            || {
                let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("npr frame"),
                });
                self.encode(&mut encoder);
                self.queue.submit([encoder.finish()]);
                Ok(())
            },
        )
    }

    /// Record every pass of the style into `encoder` (after [`Renderer::prepare`]).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) {
        self.encode_passes(encoder, self.manifest.passes.len(), None);
    }

    /// Like [`Renderer::encode`], writing GPU timestamps at the beginning and
    /// end of pass `i` into `queries` slots `2i` and `2i + 1` (for benchmarks;
    /// the query set needs `2 × passes` slots and the device `TIMESTAMP_QUERY`).
    pub fn encode_timed(&self, encoder: &mut wgpu::CommandEncoder, queries: &wgpu::QuerySet) {
        self.encode_passes(encoder, self.manifest.passes.len(), Some(queries));
    }

    /// Size the targets and write the uniforms for `spec`; then [`Renderer::encode`]
    /// records the passes into your own command encoder, after the copies
    /// that bring this frame's uniforms into their buffers (they go
    /// through a staging buffer, `upload.rs`): encode after every prepare.
    ///
    /// `scene` must have the objects the renderer was built (or last
    /// [`Renderer::set_scene`]) for (same meshes, tags and bound images,
    /// in the same order); their transforms and
    /// per-object params are read again here, so objects may move and
    /// change params between frames, and an object's mesh may be another
    /// of the same vertex count, indices and attributes (a deformed copy),
    /// whose vertices are written over the buffers in place.
    pub fn prepare(&mut self, scene: &Scene, spec: &FrameSpec) -> Result<(), RunError> {
        self.prepare_frame(scene, spec, true)
    }

    /// [`Renderer::prepare`]; `begin` starts a new frame, which for a style
    /// with history textures swaps their copies. A partial re-render of the
    /// same frame (`render_until_target`) does not begin one, so it reads
    /// the same previous frame and writes the same copies.
    fn prepare_frame(&mut self, scene: &Scene, spec: &FrameSpec, begin: bool) -> Result<(), RunError> {
        if spec.width == 0 || spec.height == 0 || spec.width > MAX_OUTPUT_SIZE || spec.height > MAX_OUTPUT_SIZE {
            return Err(RunError::Limit(format!(
                "image size {}x{} is outside 1..={MAX_OUTPUT_SIZE} (the 2D texture limit)",
                spec.width, spec.height
            )));
        }
        if self.frame_buffers.len() == 2 && spec.eye > 1 {
            return Err(RunError::Limit(format!(
                "eye {} does not exist: a stereo frame has eyes 0 and 1",
                spec.eye
            )));
        }
        if scene.objects.len() != self.scene_gpu.meshes.len() {
            return Err(RunError::User(vec![npr_diag::Diagnostic::error(
                npr_diag::codes::BAD_SCENE,
                format!(
                    "the scene has {} object(s), the renderer was built for {}",
                    scene.objects.len(),
                    self.scene_gpu.meshes.len()
                ),
            )
            .with_help(
                "only objects' transforms and params may change between frames; give other objects with Renderer::set_scene",
            )]));
        }
        // Spinning objects turn with the frame's time (`spin`). Objects
        // playing a clip are deformed by the GPU stage (`deform.rs`) for
        // every pass; their mesh is deformed on the CPU too (`scene::rig`)
        // only for the CPU stages that read it (lines, light bounds).
        let posed = scene.posed_with(spec.time_s, self.cpu_pose);
        // A host's deformed mesh (same topology) is written in place, or refused before anything changed.
        meshes::update_deformed(&self.queue, &mut self.scene_gpu.meshes, &posed)?;
        self.scene_gpu
            .deform
            .prepare(&self.queue, scene, spec.time_s, &mut self.scene_gpu.meshes);
        self.ensure_size(spec.width, spec.height)?;
        if begin || self.frames_begun == 0 {
            self.frames_begun += 1;
            self.motion.begin();
        }
        if let Some(sized) = self.sized.as_mut() {
            sized.output_slot = if sized.physical.slots.len() == 2 {
                spec.eye as usize
            } else {
                0
            };
        }
        self.record_render_draws();
        meshes::update_time_varying(&self.queue, &mut self.scene_gpu.meshes, scene, spec.time_s)?;
        self.write_uniforms(&posed, spec)?;
        self.prepare_lines(&posed, spec)
    }

    /// Record the draws of every render pass that has none for the current
    /// size and scene (after a resize or a scene change; a steady frame
    /// records nothing here).
    fn record_render_draws(&mut self) {
        let Some(sized) = self.sized.as_mut() else { return };
        for (parity, parity_passes) in sized.passes.iter_mut().enumerate() {
            let ctx = EncodeContext {
                meshes: &self.scene_gpu.meshes,
                object_group: &self.scene_gpu.object_group,
                object_stride: self.object_stride,
                parity,
            };
            for slot_passes in parity_passes.iter_mut() {
                for (exec, sized_pass) in self.passes.iter().zip(slot_passes.iter_mut()) {
                    if sized_pass.draws.is_none() {
                        sized_pass.draws = exec.record_draws(&self.device, sized_pass, &ctx);
                    }
                }
            }
        }
    }

    /// Run the frame only up to (and including) the pass that writes `target`,
    /// and read it back: for targets whose texture a later pass reuses.
    pub fn render_until_target(
        &mut self,
        scene: &Scene,
        spec: &FrameSpec,
        target: usize,
    ) -> Result<readback::TargetImage, RunError> {
        let writer = self
            .manifest
            .passes
            .iter()
            .position(|p| p.outputs.contains(&target))
            .ok_or_else(|| RunError::Internal(format!("no pass writes target #{target}")))?;
        self.prepare_frame(scene, spec, false)?;
        crate::gpu_error::scoped(
            &self.device,
            || format!("rendering a {}x{} partial frame", spec.width, spec.height),
            || {
                let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("npr partial frame"),
                });
                self.encode_passes(&mut encoder, writer + 1, None);
                self.queue.submit([encoder.finish()]);
                Ok(())
            },
        )?;
        self.read_target(target)
    }

    /// Record the first `count` passes, each by its kind's executor.
    fn encode_passes(&self, encoder: &mut wgpu::CommandEncoder, count: usize, queries: Option<&wgpu::QuerySet>) {
        let Some(sized) = self.sized.as_ref() else { return };
        // Continuing objects' state, into the buffers a scene change made.
        self.record_carried_rows(encoder);
        // The uniforms `prepare` wrote, into their buffers before any pass reads them.
        self.scene_gpu.upload.encode_copies(
            encoder,
            &self.frame_buffers,
            &self.style_buffer,
            &self.scene_gpu.object_buffer,
        );
        // Objects playing a clip, deformed into the vertex buffers every pass binds.
        self.scene_gpu.deform.encode(encoder, &self.deform_pipeline);
        // The host's depth, for the passes that test against it.
        if let Some(host_depth) = &self.host_depth {
            host_depth.encode(encoder, &sized.host_depths);
        }
        let ctx = EncodeContext {
            meshes: &self.scene_gpu.meshes,
            object_group: &self.scene_gpu.object_group,
            object_stride: self.object_stride,
            parity: self.parity(),
        };
        // Stereo styles run each pass for both eyes before the next pass, so
        // a pass that reads `other_eye(...)` finds the other eye's target done.
        let parity_passes = &sized.passes[self.parity() % sized.passes.len()];
        let slots = parity_passes.len();
        for (pi, pass) in self.passes.iter().enumerate().take(count) {
            // A compute pass runs once per frame, with eye slot 0's frame block.
            let eye_slots = if pass.per_eye() { slots } else { 1 };
            for (slot, slot_passes) in parity_passes.iter().enumerate().take(eye_slots) {
                let timestamps = queries.map(|query_set| Timestamps {
                    query_set,
                    beginning: (slot == 0).then_some(2 * pi as u32),
                    end: (slot + 1 == eye_slots).then_some(2 * pi as u32 + 1),
                });
                pass.encode(encoder, (&slot_passes[pi], slot), &ctx, timestamps.as_ref());
            }
        }
    }

    /// Read a logical target back to the CPU.
    pub fn read_target(&self, target: usize) -> Result<readback::TargetImage, RunError> {
        let sized = self
            .sized
            .as_ref()
            .ok_or_else(|| RunError::Internal("read before render".into()))?;
        let t = self
            .manifest
            .targets
            .get(target)
            .ok_or_else(|| RunError::Internal(format!("no target #{target}")))?;
        let (w, h) = scaled_size(sized.width, sized.height, t.scale);
        readback::read_texture(
            &self.device,
            &self.queue,
            sized
                .physical
                .texture(sized.output_slot, self.parity(), t.physical, false),
            w,
            h,
            t.format,
            &t.name,
        )
    }

    /// Object `object`'s vertex attribute `attribute` as its vertex buffer
    /// holds it after the last submitted frame (the GPU deformation
    /// stage's output for an object playing a clip): tightly packed f32s,
    /// `attribute.components()` per vertex. For tests and tools.
    pub fn read_vertices(&self, object: usize, attribute: Attribute) -> Result<Vec<f32>, RunError> {
        let mesh = self
            .scene_gpu
            .meshes
            .get(object)
            .ok_or_else(|| RunError::Internal(format!("no object #{object}")))?;
        let buffer = mesh
            .buffers
            .get(&attribute)
            .ok_or_else(|| RunError::Internal(format!("object #{object} has no {} buffer", attribute.name())))?;
        let bytes = readback::read_buffer(&self.device, &self.queue, buffer)?;
        Ok(bytes
            .chunks_exact(4)
            .take(mesh.vertex_count * attribute.components() as usize)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect())
    }

    /// The per-object values of compute pass `pass` (its name), as this
    /// frame left them: per object, its value slots in manifest order
    /// (`PassKindManifest::Compute::values`; a `vec2` in `.xy`).
    pub fn read_object_values(&self, pass: &str) -> Result<Vec<Vec<[f32; 4]>>, RunError> {
        let pi = self
            .manifest
            .passes
            .iter()
            .position(|p| p.name == pass)
            .ok_or_else(|| RunError::Internal(format!("no pass `{pass}`")))?;
        let buffers = self.scene_gpu.values[pi]
            .as_ref()
            .ok_or_else(|| RunError::Internal(format!("pass `{pass}` is not a compute pass")))?;
        self.submit_carried_rows();
        let bytes = readback::read_buffer(&self.device, &self.queue, buffers.copy(self.parity(), false))?;
        let vec4s: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
        Ok(vec4s
            .chunks(buffers.slots as usize)
            .take(self.scene_gpu.meshes.len())
            .map(|c| c.to_vec())
            .collect())
    }

    /// The parity of the current frame: which copy of each history texture
    /// it writes (0 before any frame).
    fn parity(&self) -> usize {
        (self.frames_begun.saturating_sub(1) % 2) as usize
    }

    /// The frame's parity as [`Renderer::output_texture`] reads it.
    pub fn parity_now(&self) -> usize {
        self.parity()
    }

    /// Changes whenever the renderer's textures are made anew (at a new
    /// size): views of [`Renderer::output_texture`] made before are stale.
    pub fn resources_generation(&self) -> u64 {
        self.generation
    }

    /// Eye slots a frame renders: 2 for a stereo style, else 1.
    pub fn eye_slots(&self) -> usize {
        self.frame_buffers.len()
    }

    /// The texture holding the output of eye slot `slot` in frames of
    /// `parity` (see [`Renderer::parity_now`]; a style with history
    /// textures alternates two); `None` before the first frame.
    pub fn output_texture(&self, slot: usize, parity: usize) -> Option<&wgpu::Texture> {
        let sized = self.sized.as_ref()?;
        let physical = self.manifest.targets.get(self.manifest.output)?.physical;
        (slot < sized.physical.slots.len() && parity < 2).then(|| sized.physical.texture(slot, parity, physical, false))
    }

    /// The style's manifest as the renderer runs it (parameters as last set).
    pub fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    /// The style's parameters, to change their values (`--set`, a sweep, a
    /// host's `set_param`): the next frame writes the whole style block
    /// again.
    pub fn params_mut(&mut self) -> &mut Vec<ParamManifest> {
        self.scene_gpu.upload.style_changed();
        &mut self.manifest.params
    }

    /// How many parities frames alternate between: 2 for a style with
    /// history textures, else 1.
    pub fn parities(&self) -> usize {
        self.parities
    }

    /// Frames begun since the renderer was built, its textures were
    /// resized or [`Renderer::restart_history`] (the history they hold is
    /// that long; a scene change keeps counting).
    pub fn frames_begun(&self) -> u64 {
        self.frames_begun
    }

    /// Read the style's final image.
    pub fn read_output(&self) -> Result<readback::TargetImage, RunError> {
        self.read_target(self.manifest.output)
    }

    /// Whether a target still holds its own contents at the end of the frame
    /// (false when a later target was aliased onto the same physical texture).
    pub fn target_survives_frame(&self, target: usize) -> bool {
        let phys = self.manifest.targets[target].physical;
        let last_writer = self
            .manifest
            .passes
            .iter()
            .flat_map(|p| p.outputs.iter())
            .rfind(|t| self.manifest.targets[**t].physical == phys);
        last_writer == Some(&target)
    }
}
