//! `--dump-passes` at one time: the frame rendered, then every target read
//! (`npr_runner::Renderer::read_all_targets`, which re-renders aliased ones).

use npr_runner::{FrameSpec, Renderer, RunError};

/// Read every target. Targets aliased onto a texture that a later pass
/// reuses are captured by re-running the frame up to the pass that wrote
/// them (by rendering with aliasing-aware reads: render, read the survivors,
/// and for the others render again and read right after their pass).
pub(crate) fn dump_all_targets(
    r: &mut Renderer,
    scene: &npr_runner::scene::Scene,
    width: u32,
    height: u32,
    time: f64,
    eye: u32,
) -> Result<Vec<npr_runner::TargetImage>, RunError> {
    let spec = FrameSpec {
        width,
        height,
        time_s: time,
        frame: 0,
        eye,
    };
    r.render(scene, &spec)?;
    r.read_all_targets(scene, &spec)
}
