//! A test's frame budget (`budget = 40`): the style's frame cost as a
//! ratio to a passthrough measured in the same run, never an absolute
//! time, so the bound holds on any machine as well as the ratio does.
//!
//! The passthrough is the least frame that draws the same scene: one
//! render pass writing each fragment's normal, at the same size and eye.
//! Each cost is the fastest of [`FRAMES`] frames (submit, then wait for
//! the device), the two renderers alternating frame by frame so machine
//! load falls on both alike (as `npr_lab::bench_contours` times its variants).
//! Wall clock and not GPU timestamps: lavapipe's timestamps do not bracket
//! compute work (docs/PERFORMANCE.md, "Compute passes"), and on a GPU the
//! wall clock of a submitted and awaited frame still bounds its GPU time.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Gpu, Renderer, RunError, StyleProgram};
use std::time::Instant;

/// Frames timed per renderer; the fastest counts.
pub const FRAMES: usize = 9;

/// The passthrough a budget is a ratio to.
const PASSTHROUGH: &str =
    "style \"passthrough\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(normal * 0.5 + 0.5, 1.0)\n}\noutput p.c\n";

/// The style's frame and the passthrough's, in milliseconds.
#[derive(Debug, Clone, Copy)]
pub struct FrameCost {
    pub style_ms: f64,
    pub passthrough_ms: f64,
}

impl FrameCost {
    pub fn ratio(&self) -> f64 {
        self.style_ms / self.passthrough_ms.max(1e-6)
    }
}

/// The passthrough compiled for `scene`.
pub fn passthrough(scene: &Scene) -> Result<StyleProgram, RunError> {
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        scene: Some(scene.summary("scene")),
        ..Default::default()
    };
    npr_compiler::compile_source(
        "passthrough.npr",
        PASSTHROUGH,
        std::path::Path::new("."),
        &mut sources,
        &opts,
    )
    .map(|c| c.program())
    .map_err(|e| RunError::Internal(format!("the passthrough style does not compile: {e:?}")))
}

/// Time `program` against the passthrough on `scene` at `spec`.
pub fn measure(gpu: &Gpu, program: &StyleProgram, scene: &Scene, spec: &FrameSpec) -> Result<FrameCost, RunError> {
    let base = passthrough(scene)?;
    let mut style = Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    let mut pass = Renderer::new(&gpu.device, &gpu.queue, &base, scene)?;
    let time = |r: &mut Renderer| -> Result<f64, RunError> {
        let started = Instant::now();
        r.render(scene, spec)?;
        npr_runner::readback::wait_idle(&gpu.device)?;
        Ok(started.elapsed().as_secs_f64() * 1e3)
    };
    // One frame each first: pipelines and first-use allocations are not the frame's cost.
    time(&mut style)?;
    time(&mut pass)?;
    let (mut style_ms, mut passthrough_ms) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..FRAMES {
        style_ms = style_ms.min(time(&mut style)?);
        passthrough_ms = passthrough_ms.min(time(&mut pass)?);
    }
    Ok(FrameCost {
        style_ms,
        passthrough_ms,
    })
}
