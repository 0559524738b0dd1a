//! The strips' GPU vertices (Klein et al. 2000, §5: "the lines are drawn as
//! a 2D triangle strip"): px to NDC, and the depth of each vertex's edge
//! point pulled towards the eye by the pass's bias ([`DepthBias`]). The
//! `lines` pass executor (`exec/lines_pass.rs`) uploads them; its compiled
//! shader tests visibility at the edge point against the kept depth
//! (`compiler/src/back/emit/lines.rs`).
//!
//! Why the test is at the edge point and not per fragment with a
//! fixed-function `LessEqual`: a strip lies across the edge it outlines,
//! and inside a silhouette the surface under the strip bulges towards the
//! eye, so per fragment the inner half of the line (and every inward wave)
//! loses the test. Measured on lavapipe with that earlier design (256², a
//! unit sphere at 4 m and a cube at 5.7 m, bias in NDC depth): 3e-4 kept 52
//! inner-half pixels of the sphere's rim (of ~700) and leaked no hidden
//! crease; 1e-3 kept 400 and leaked 7 of 512 hidden-edge samples; 3e-3
//! kept 460 and leaked 91. The edge-point test keeps 752 inside against
//! 668 outside and leaks none (`tests/gpu/lines_pass.rs`).
//!
//! The bias: `bias: N px` is a view-space pull (every vertex moves towards
//! the eye along its own ray by the world distance N px span at its depth,
//! so the slack is the same on screen at every distance); `bias: b` lowers
//! the NDC depth by b in the shader, as render passes do.

use super::strip::Strips;

pub use npr_abi::lines::LineVertex;

/// How strip vertices are pulled towards the eye before the depth test
/// (`bias: N px`; a bias in NDC depth, `bias: 0.001`, is the shader's).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DepthBias {
    /// A view-space pull (`bias: N px`): every vertex moves towards the eye
    /// along its own view ray by the share `pull` of its distance, which
    /// leaves its NDC x, y unchanged. With `eye_clip_z` the clip z of the eye
    /// (view_proj · eye; its w is 0 for a perspective camera), clip space is
    /// linear, c' = (1 − r)·c + r·E, so z'/w' = z/w + r/(1 − r)·E.z/w.
    pub pull: f64,
    pub eye_clip_z: f64,
}

impl DepthBias {
    /// The pull for `px` pixels at the vertex's own depth: one pixel spans
    /// 2/(P₁₁·H) of the view depth, so r = px·2/(P₁₁·H) (exact on the
    /// view axis, up to 1/cos of the ray's angle off it towards the edges).
    pub fn view_space_px(px: f64, focal_y: f64, height_px: f64, eye_clip_z: f64) -> DepthBias {
        DepthBias {
            pull: (px * 2.0 / (focal_y * height_px)).clamp(0.0, 0.5),
            eye_clip_z,
        }
    }

    fn apply(&self, depth: f64, inv_w: f64) -> f64 {
        depth + self.pull / (1.0 - self.pull) * self.eye_clip_z * inv_w
    }
}

/// The GPU vertices of `strips` on a `size` px viewport, depth lowered by
/// `bias` (clamped to the 0..1 range, so a line at the near plane stays).
pub fn vertices(strips: &Strips, size: [f64; 2], bias: DepthBias) -> Vec<LineVertex> {
    strips
        .vertices
        .iter()
        .map(|v| LineVertex {
            position: [
                (v.px.x / size[0] * 2.0 - 1.0) as f32,
                (1.0 - v.px.y / size[1] * 2.0) as f32,
                bias.apply(v.depth, v.inv_w).clamp(0.0, 1.0) as f32,
                v.s as f32,
            ],
            line: [v.base.x as f32, v.base.y as f32, v.across as f32, v.set as f32],
        })
        .collect()
}
