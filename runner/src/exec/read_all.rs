//! Reading every target of a frame (`npr render --dump-passes`, the
//! studio's pass thumbnails, `npr test`'s images), including targets whose
//! texture a later pass reuses (the compiler aliases targets whose lives do
//! not overlap onto one physical texture).

use super::Renderer;
use crate::{FrameSpec, RunError, TargetImage};

impl Renderer {
    /// Every target of the frame `spec` that this renderer has just
    /// rendered, in the manifest's order. Aliased targets are captured by
    /// partial re-renders of that same frame, which neither begin a new
    /// frame nor change any history texture.
    pub fn read_all_targets(
        &mut self,
        scene: &crate::scene::Scene,
        spec: &FrameSpec,
    ) -> Result<Vec<TargetImage>, RunError> {
        let count = self.manifest().targets.len();
        // Read every survivor of the full frame first: a partial re-render
        // overwrites the textures that aliased targets share with them.
        let mut images: Vec<Option<TargetImage>> = Vec::with_capacity(count);
        for t in 0..count {
            images.push(if self.target_survives_frame(t) {
                Some(self.read_target(t)?)
            } else {
                None
            });
        }
        for (t, image) in images.iter_mut().enumerate() {
            if image.is_none() {
                *image = Some(self.render_until_target(scene, spec, t)?);
            }
        }
        Ok(images.into_iter().flatten().collect())
    }
}
