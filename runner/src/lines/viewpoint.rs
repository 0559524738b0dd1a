//! Where a mesh's faces are seen from, for the silhouette test: a point for
//! a perspective eye, a direction for an orthographic one (decision 0062).
//! Both are one homogeneous point e: (position, 1), or the point at
//! infinity (towards the eye, 0) behind an orthographic camera, whose view
//! direction is the same at every point. A face with normal n through p
//! faces the eye where n · (e.xyz − p·e.w) > 0, and e moves into an
//! object's space by the inverse model matrix as any point does.

use glam::{DMat4, DVec3, DVec4};

/// A homogeneous eye point (see the module header).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewpoint(pub DVec4);

impl Viewpoint {
    /// An orthographic eye: every point sees it along `towards_eye`
    /// (−the camera's forward).
    pub fn direction(towards_eye: DVec3) -> Viewpoint {
        Viewpoint(towards_eye.extend(0.0))
    }

    /// The direction from `point` towards this eye (not normalised).
    pub fn towards_from(self, point: DVec3) -> DVec3 {
        self.0.truncate() - point * self.0.w
    }

    /// This eye in the space `to_space` maps into (the inverse of an
    /// object's model matrix gives its own space).
    pub fn transformed(self, to_space: DMat4) -> Viewpoint {
        Viewpoint(to_space * self.0)
    }

    pub fn is_finite(self) -> bool {
        self.0.is_finite()
    }
}

impl From<DVec3> for Viewpoint {
    /// A perspective eye at a point.
    fn from(position: DVec3) -> Viewpoint {
        Viewpoint(position.extend(1.0))
    }
}
