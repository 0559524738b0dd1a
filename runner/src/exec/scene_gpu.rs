//! A renderer's scene-level GPU resources, made apart from the style's so a
//! new set of objects keeps the pipelines: the mesh buffers, the object
//! buffer and its shared group 1, the objects' images and per-object
//! groups, compute passes' buffers and groups, the light bounds and the
//! frame's upload. [`Renderer::set_scene`] gives a built renderer other
//! objects; `Renderer::build` makes its first scene the same way.

use super::bind::{self, ObjectResources};
use super::pass::{PassExec, PassScene};
use super::{continuity, deform, light_bounds, meshes, objects, upload, values, Renderer};
use crate::gpu_count::Create;
use crate::scene::Scene;
use crate::textures::{self, GpuTexture, ObjectImageKey};
use crate::RunError;
use npr_abi::manifest::*;
use std::collections::HashMap;

/// Everything a renderer holds for one scene's objects.
pub(super) struct SceneGpu {
    /// Every object's block, `object_stride` apart; written every frame.
    pub object_buffer: wgpu::Buffer,
    /// Group 1 of passes that read no per-object texture.
    pub object_group: wgpu::BindGroup,
    pub meshes: Vec<meshes::GpuMesh>,
    /// The GPU deformation of the objects playing a clip (decision 0053).
    pub deform: deform::DeformStage,
    /// Per manifest pass: a compute pass's buffers.
    pub values: Vec<Option<values::PassBuffers>>,
    pub light_bounds: light_bounds::LightBounds,
    /// The frame's uniforms (frame, style and object blocks), copied into
    /// their buffers from a reused staging buffer.
    pub upload: upload::Upload,
    /// Per object, its name: which object of the next scene continues it
    /// (`continuity.rs`).
    pub object_names: Vec<String>,
    /// Per object, its mesh's vertex count (the block's `ids.z`).
    pub vertex_counts: Vec<usize>,
    /// The per-object images this scene binds, kept for the next one.
    pub object_images: HashMap<ObjectImageKey, GpuTexture>,
}

/// What of the style a scene is bound with.
pub(super) struct StyleParts<'a> {
    pub manifest: &'a Manifest,
    pub textures: &'a [GpuTexture],
    /// The shared group 1 layout the pipelines were made with.
    pub object_layout: &'a wgpu::BindGroupLayout,
    pub object_stride: u64,
    /// The params each object block writes and their defaults.
    pub object_params: &'a objects::ObjectParams,
    pub passes: &'a [PassExec],
    pub eyes: usize,
    /// The per-object images the previous scene bound (none at a build).
    pub object_images: &'a HashMap<ObjectImageKey, GpuTexture>,
    /// The deformation stage's pipeline (made at the first scene needing it).
    pub deform_pipeline: &'a std::sync::OnceLock<deform::DeformPipeline>,
}

impl SceneGpu {
    /// `scene`'s resources for a style's passes, and each pass's part
    /// ([`PassExec::bind_scene`], in manifest order). Bad per-object params and
    /// images are reported here (as `RunError::User`/`Textures`), before
    /// any frame; nothing of the renderer changes until the caller installs
    /// the result.
    pub fn make(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        style: &StyleParts,
        scene: &Scene,
    ) -> Result<(SceneGpu, Vec<PassScene>), RunError> {
        let manifest = style.manifest;
        let object_textures = textures::load_object_textures(device, queue, manifest, scene, style.object_images)?;
        let mut object_bytes = vec![0; (style.object_stride as usize) * scene.objects.len()];
        objects::write_object_blocks(
            (manifest, style.object_params),
            scene,
            style.object_stride,
            (&[], &[]),
            &mut object_bytes,
        )?;
        let object_count = scene.objects.len().max(1) as u64;
        let object_buffer = device.make_buffer(&wgpu::BufferDescriptor {
            label: Some("npr objects"),
            size: style.object_stride * object_count,
            // STORAGE: compute passes read every object's block at once.
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let object_group = bind::shared_object_group(
            device,
            style.object_layout,
            &object_buffer,
            manifest.object_uniform_size,
        );
        let object_resources = ObjectResources {
            scene,
            buffer: &object_buffer,
            uniform_size: manifest.object_uniform_size,
            textures: style.textures,
            object_textures: &object_textures,
        };
        let meshes = meshes::upload_scene(
            device,
            scene,
            manifest.passes.iter().any(|p| {
                matches!(&p.kind, PassKindManifest::Render { attributes, .. } if attributes.contains(&Attribute::PatchWeight))
            }),
        );
        let deform = deform::DeformStage::new(device, style.deform_pipeline, scene, &meshes)?;
        let values = values::create(device, manifest, scene, &meshes)?;
        values::reset(queue, &values);
        let pass_scenes = style
            .passes
            .iter()
            .zip(&manifest.passes)
            .zip(&values)
            .map(|((exec, pass), buffers)| exec.bind_scene(device, pass, &object_resources, buffers.as_ref()))
            .collect::<Result<Vec<_>, RunError>>()?;
        let upload = upload::Upload::new(
            device,
            FRAME_UNIFORM_SIZE as usize,
            style.eyes,
            manifest.style_uniform_size as usize,
            object_bytes.len(),
        );
        let made = SceneGpu {
            object_group,
            object_buffer,
            values,
            light_bounds: light_bounds::LightBounds::new(manifest, scene),
            upload,
            object_names: scene.objects.iter().map(|o| o.name.clone()).collect(),
            vertex_counts: meshes.iter().map(|m| m.vertex_count).collect(),
            meshes,
            deform,
            object_images: object_textures.keys.into_iter().zip(object_textures.images).collect(),
        };
        Ok((made, pass_scenes))
    }
}

impl Renderer {
    /// Render `scene`'s objects from now on: other meshes, tags, bound
    /// images or shadow flags than the renderer was built or last set
    /// with (a game spawning or despawning an object). Only the
    /// scene-level resources are made anew (`SceneGpu`; per-object images
    /// the previous objects bound too are kept); the shader
    /// modules, pipelines and their layouts, the style's textures and
    /// art-maps, the sampler, the frame and style buffers, and the targets
    /// stay.
    ///
    /// **The history goes on** (docs/decisions/0046): the history
    /// textures keep their contents and the frame parity its course, so
    /// `previous(...)` reads the last frame (a trail behind the other
    /// objects survives a spawn). An object of `scene` continues the
    /// previous scene's object of the same name (the k-th of a name the
    /// k-th): it keeps its compute state and its `previous_model`. An
    /// object with a name the previous scene did not have is new: its
    /// compute state starts from its first values and its
    /// `previous_model` is its model at its first frame. To start the
    /// history over instead, call [`Renderer::restart_history`] too.
    ///
    /// A scene the style refuses (E0403, E0405, a bad per-object param or
    /// image) is an error that leaves the renderer as it was.
    pub fn set_scene(&mut self, scene: &Scene) -> Result<(), RunError> {
        let diags = super::check_scene(&self.manifest, scene);
        if !diags.is_empty() {
            return Err(RunError::User(diags));
        }
        let device = self.device.clone();
        let (made, pass_scenes) = crate::gpu_error::scoped(
            &device,
            || "making the scene's GPU resources (meshes, objects, compute buffers)".to_string(),
            || {
                let style = StyleParts {
                    manifest: &self.manifest,
                    textures: &self.textures,
                    object_layout: &self.object_layout,
                    object_stride: self.object_stride,
                    object_params: &self.object_params,
                    passes: &self.passes,
                    eyes: self.frame_buffers.len(),
                    object_images: &self.scene_gpu.object_images,
                    deform_pipeline: &self.deform_pipeline,
                };
                SceneGpu::make(&self.device, &self.queue, &style, scene)
            },
        )?;
        for (exec, part) in self.passes.iter_mut().zip(pass_scenes) {
            exec.set_scene(part);
        }
        let continuing = continuity::continuing(&self.scene_gpu.object_names, scene);
        // A deformed object that continues one keeps its last pose as its previous.
        let mut made = made;
        made.deform.carry_previous(&self.scene_gpu.deform, &continuing);
        let rows = continuity::value_rows(&self.scene_gpu.values, &made.values, &continuing);
        self.carried_rows.lock().unwrap_or_else(|e| e.into_inner()).extend(rows);
        self.scene_gpu = made;
        self.motion.remap(&continuing);
        // Group 0 binds compute passes' values: the groups are made again
        // over the new buffers, the targets kept.
        self.rebind_scene_values();
        Ok(())
    }
}
