//! Rendering a test's frames as `npr render` renders them, and the
//! non-finite texels found in them: what a declared test and a sweep
//! both do with a compiled style.

use super::checks;
use super::outcome::Failure;
use npr_runner::schedule::ScheduledFrame;
use npr_runner::{FrameSpec, Gpu, Renderer, RunError, StyleProgram, TargetImage};

/// A target found holding NaN or ±Inf in one frame.
pub(crate) struct FoundNonFinite {
    pub frame: u32,
    pub target: usize,
    pub found: checks::NonFinite,
}

/// The frames of one render of a test.
pub(crate) struct Rendered {
    /// Per written frame, its number and its output.
    pub outputs: Vec<(u32, TargetImage)>,
    /// Per target, the first frame it was non-finite in.
    pub non_finite: Vec<FoundNonFinite>,
}

/// What to render: the size, the eye, the frames.
pub(crate) struct Frames<'a> {
    pub size: (u32, u32),
    pub eye: u32,
    pub frames: &'a [ScheduledFrame],
}

impl Frames<'_> {
    /// Render the frames with a new renderer, as `npr render` does; with
    /// `read_targets`, read every target of each written frame back as
    /// floats (a target a later pass reuses by a partial re-render).
    pub(crate) fn render(
        &self,
        gpu: &Gpu,
        program: &StyleProgram,
        scene: &npr_runner::scene::Scene,
        read_targets: bool,
    ) -> Result<Rendered, RunError> {
        let mut r = Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
        self.render_with(&mut r, scene, read_targets)
    }

    /// [`Frames::render`] with a renderer made before (a sweep's, whose
    /// uniform parameters it sets between renders).
    pub(crate) fn render_with(
        &self,
        r: &mut Renderer,
        scene: &npr_runner::scene::Scene,
        read_targets: bool,
    ) -> Result<Rendered, RunError> {
        let (width, height) = self.size;
        let mut rendered = Rendered {
            outputs: Vec::new(),
            non_finite: Vec::new(),
        };
        for f in self.frames {
            let spec = FrameSpec {
                width,
                height,
                time_s: f.time_s,
                frame: f.frame,
                eye: self.eye,
            };
            r.render(scene, &spec)?;
            if !f.write {
                continue;
            }
            // Before the partial re-renders of `read_all_targets`, which
            // overwrite what shares the output's texture.
            rendered.outputs.push((f.frame, r.read_output()?));
            if read_targets {
                let targets = r.read_all_targets(scene, &spec)?;
                for (index, image) in targets.iter().enumerate() {
                    let seen = rendered.non_finite.iter().any(|n| n.target == index);
                    if let Some(found) = checks::non_finite(image).filter(|_| !seen) {
                        rendered.non_finite.push(FoundNonFinite {
                            frame: f.frame,
                            target: index,
                            found,
                        });
                    }
                }
            }
        }
        Ok(rendered)
    }

    /// Every target of each written frame, read back (a probe style's
    /// outputs), rendered with a new renderer.
    pub(crate) fn render_targets(
        &self,
        gpu: &Gpu,
        program: &StyleProgram,
        scene: &npr_runner::scene::Scene,
    ) -> Result<Vec<(u32, Vec<TargetImage>)>, RunError> {
        let mut r = Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
        let (width, height) = self.size;
        let mut out = Vec::new();
        for f in self.frames {
            let spec = FrameSpec {
                width,
                height,
                time_s: f.time_s,
                frame: f.frame,
                eye: self.eye,
            };
            r.render(scene, &spec)?;
            if f.write {
                out.push((f.frame, r.read_all_targets(scene, &spec)?));
            }
        }
        Ok(out)
    }
}

pub(crate) fn non_finite_failures(program: &StyleProgram, found: &[FoundNonFinite]) -> Vec<Failure> {
    found
        .iter()
        .map(|n| {
            let target = &program.manifest.targets[n.target];
            let writer = program
                .manifest
                .passes
                .iter()
                .find(|p| p.outputs.contains(&n.target))
                .map_or("no pass", |p| p.name.as_str());
            let (x, y) = n.found.first;
            Failure {
                check: "finite",
                message: format!(
                    "target `{}` ({}, written by pass `{writer}`) has {} non-finite texel(s) in frame {}; the first at ({x}, {y}) is {:?}",
                    target.name,
                    format!("{:?}", target.format).to_lowercase(),
                    n.found.count,
                    n.frame,
                    n.found.first_value
                ),
                files: Vec::new(),
                reproduce: None,
            }
        })
        .collect()
}
