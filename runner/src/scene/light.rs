//! The scene's single directional light.

use glam::Vec3;

/// A directional light (like the sun): parallel rays, no falloff.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Unit vector pointing TOWARDS the light, in world space.
    pub direction: Vec3,
    /// RGB multiplier, as written: `"#rrggbb"` is its bytes / 255, the same
    /// convention as colour literals in `.npr` styles.
    pub color: [f32; 3],
    pub intensity: f32,
}

impl Light {
    /// The direction used when a scene has no `[light]` table: from above,
    /// to the right and in front, so that lit and shadowed sides both show.
    pub fn default_direction() -> Vec3 {
        Vec3::new(0.5, 1.0, 0.8).normalize()
    }
}

impl Default for Light {
    fn default() -> Self {
        Light {
            direction: Light::default_direction(),
            color: [1.0, 1.0, 1.0],
            intensity: 1.0,
        }
    }
}
