//! Reading every target of a frame (`--dump-passes`, the studio's pass
//! thumbnails), including targets whose texture a later pass reuses.

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
    read_all_targets(r, scene, &spec)
}

/// Read every target of the frame `spec` that `r` has just rendered;
/// aliased targets are captured by partial re-renders of that same frame
/// (which neither begin a new frame nor change any history texture).
pub(crate) fn read_all_targets(
    r: &mut Renderer,
    scene: &npr_runner::scene::Scene,
    spec: &FrameSpec,
) -> Result<Vec<npr_runner::TargetImage>, RunError> {
    let count = r.manifest().targets.len();
    // Read every survivor of the full frame first: a partial re-render
    // overwrites the textures that aliased targets share with them.
    let mut images: Vec<Option<npr_runner::TargetImage>> = Vec::with_capacity(count);
    for t in 0..count {
        images.push(if r.target_survives_frame(t) {
            Some(r.read_target(t)?)
        } else {
            None
        });
    }
    for (t, image) in images.iter_mut().enumerate() {
        if image.is_none() {
            *image = Some(r.render_until_target(scene, spec, t)?);
        }
    }
    Ok(images.into_iter().flatten().collect())
}
