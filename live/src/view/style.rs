//! The style `npr view` shows, driven through the runner's embedding API
//! (`npr_runner::embed`): a `StyleRuntime` on the window's device, the scene's
//! meshes registered once (`StyleRuntime::add_scene`, with the ocean's
//! animated vertices and blended patches), and each frame the scene's
//! objects as `Instance`s (posed at the frame's time: `spin`), the view's
//! camera, the scene's lights and the time, rendered into the surface's
//! image.
//!
//! A build comes from `live::build`, the same one `npr watch` and `npr
//! studio` make, compiled with `keep_params` so that the parameter keys
//! change uniforms without a recompile.

use crate::build::Built;
use npr_diag::{Diagnostic, SourceMap};
use npr_runner::embed::{EmbedError, Frame, Instance, Lights, StyleRuntime, Target};
use npr_runner::scene::{Camera, Scene};

pub struct Loaded {
    pub runtime: StyleRuntime,
    pub scene: Scene,
    /// Per scene object, its instance (`add_scene`); each frame turns the
    /// spinning ones to the frame's time.
    instances: Vec<Instance>,
    lights: Lights,
    pub stereo: bool,
    pub sources: SourceMap,
    /// The build's texture spans, where render-time texture errors point.
    texture_spans: Vec<npr_diag::Span>,
}

impl Loaded {
    /// A runtime for `built` on `device`, with the scene's meshes registered.
    pub fn new(built: Built, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Loaded, Failure> {
        let Built {
            compiled,
            scene,
            sources,
            ..
        } = built;
        let program = compiled.program();
        let stereo = program.manifest.is_stereo();
        let mut runtime = match StyleRuntime::new(device, queue, program) {
            Ok(r) => r,
            Err(e) => return Err(Failure::new(e, &compiled.texture_spans, sources)),
        };
        // The ocean's vertices, blended patches and per-object images come
        // with the meshes and instances `add_scene` registers.
        let instances = runtime.add_scene(&scene);
        let lights = Lights {
            key: scene.light,
            more: scene.more_lights,
        };
        Ok(Loaded {
            runtime,
            scene,
            instances,
            lights,
            stereo,
            sources,
            texture_spans: compiled.texture_spans,
        })
    }

    /// Pose the instances at `time_s` (spinning objects turned).
    fn pose(&mut self, time_s: f64) {
        for (instance, object) in self.instances.iter_mut().zip(&self.scene.objects) {
            instance.transform = object.model_at(time_s);
        }
    }

    /// Record a frame with `camera` at `time_s` into `view` (both eyes side
    /// by side for a stereo style).
    pub fn render(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        camera: &Camera,
        time_s: f64,
        frame_index: u32,
    ) -> Result<(), Failure> {
        self.pose(time_s);
        let frame = Frame {
            camera,
            objects: &self.instances,
            lights: &self.lights,
            time_s,
            frame_index,
            eye: 0,
        };
        let target = if self.stereo {
            Target::SideBySide(view)
        } else {
            Target::View(view)
        };
        self.runtime
            .render(encoder, &frame, target)
            .map_err(|e| Failure::new(e, &self.texture_spans, self.sources.clone()))
    }

    /// Set a style parameter by name, as `--set` writes its value.
    pub fn set_param(&mut self, name: &str, literal: &str) -> Result<(), Failure> {
        self.runtime
            .set_param(name, literal)
            .map_err(|e| Failure::new(e, &self.texture_spans, self.sources.clone()))
    }
}

/// Why a build could not be shown: diagnostics and the files they point into.
pub struct Failure {
    pub diagnostics: Vec<Diagnostic>,
    pub sources: SourceMap,
}

impl Failure {
    fn new(e: EmbedError, texture_spans: &[npr_diag::Span], sources: SourceMap) -> Failure {
        let diagnostics = match e {
            EmbedError::Run(run) => run.at_texture_spans(texture_spans).diagnostics(),
            other => other.diagnostics(),
        };
        Failure { diagnostics, sources }
    }
}
