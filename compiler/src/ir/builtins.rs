//! `Builtin`: the values the runtime provides (`position.view`, `light.dir`,
//! `frame`, ...), their `.npr` spellings, types and units, and which pass
//! kinds have them.

use super::*;

/// Values the runtime provides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum Builtin {
    /// In a pass over samples: the distance between neighbouring samples
    /// on the surface, in world units (the diameter of the tangent disc
    /// each sample stands for, Breslav et al. 2007 §3.1).
    SampleSpacing,
    Uv,
    NormalWorld,
    NormalView,
    PositionWorld,
    PositionView,
    /// Light-space NDC of the surface point: x, y in [−1, 1] (unwarped), z in [0, 1].
    PositionLight,
    Tangent,
    ViewDir,
    Depth,
    FragCoord,
    ScreenUv,
    Resolution,
    Time,
    Frame,
    Eye,
    LightDir,
    LightColor,
    LightIntensity,
    /// `light2.dir` … `light4.dir`: the scene's extra lights (index 0..3 is
    /// light2..light4, `Frame::more_light_dir`).
    MoreLightDir(u8),
    MoreLightColor(u8),
    MoreLightIntensity(u8),
    CameraPosition,
    CameraNear,
    CameraFar,
    /// (P₀₀, P₁₁) of the projection matrix: the focal lengths in NDC units
    /// that Age of Sail eq. 12 divides the screen position by.
    CameraFocal,
    /// The left and right eye positions of a stereo camera (both the camera
    /// position in mono), and the unit view direction.
    CameraLeftEye,
    CameraRightEye,
    CameraForward,
    /// The camera's unit right and up directions in world space (the view
    /// matrix's first two rows): with `camera.forward`, the frame that
    /// turns a view-space point into a world one.
    CameraRight,
    CameraUp,
    /// 1 for an orthographic camera, 0 for a perspective one (decision
    /// 0062): a view-space point at depth d has clip w = d through a
    /// perspective projection and 1 through an orthographic one.
    CameraOrthographic,
    /// Screen-space projection T_s of the unit world tangent (direction of
    /// increasing u), in px per metre, computed in the vertex shader from the
    /// analytic Jacobian of the projection and interpolated (Age of Sail §3.2).
    TangentScreen,
    /// B_s: the same for the unit bitangent (direction of increasing v).
    BitangentScreen,
    /// T_s projected with the stereo camera's centre (the same for both eyes;
    /// equal to `tangent.screen` in mono), against stereo "shimmer" (§3.2).
    TangentScreenCenter,
    /// B_s projected with the stereo camera's centre.
    BitangentScreenCenter,
    /// The object's position in the scene's object list (0, 1, ...).
    ObjectIndex,
    /// The object's id for ID images: its index + 1, so that 0 (a cleared
    /// target) means "no object".
    ObjectId,
    /// The world position of this surface point in the previous frame (the
    /// object's previous transform; equal to `position` on the first frame).
    PositionPrevious,
    /// In a `lines` pass: the screen-space arc length along the strip's
    /// chain, in px (the s of Klein et al. 2000 §5's sin(2π·s/λ + φ)).
    LineArc,
    /// In a `lines` pass: −1 on one edge of the strip, +1 on the other,
    /// interpolated across it (for soft edges or a brush profile).
    LineAcross,
    /// In a `lines` pass with line sets: the index of the set drawing the
    /// strip, highest priority first (decision 0056); `line.color` chooses
    /// on it.
    LineSet,
    /// In a render pass: the blending weight of the patch being drawn at
    /// this point (Breslav et al. 2007 §3.6), interpolated from its
    /// vertices; 1 on objects without patches. A pass that reads it draws
    /// each patch over its n-ring too (`npr_abi::Attribute::PatchWeight`).
    PatchWeight,
}

impl Builtin {
    /// (spelling, builtin) for every name a style can write.
    pub const SPELLINGS: &'static [(&'static str, Builtin)] = &[
        ("uv", Builtin::Uv),
        ("normal", Builtin::NormalWorld),
        ("normal.world", Builtin::NormalWorld),
        ("normal.view", Builtin::NormalView),
        ("position", Builtin::PositionWorld),
        ("position.world", Builtin::PositionWorld),
        ("position.view", Builtin::PositionView),
        ("position.light", Builtin::PositionLight),
        ("tangent", Builtin::Tangent),
        ("view_dir", Builtin::ViewDir),
        ("depth", Builtin::Depth),
        ("frag_coord", Builtin::FragCoord),
        ("screen_uv", Builtin::ScreenUv),
        ("resolution", Builtin::Resolution),
        ("time", Builtin::Time),
        ("frame", Builtin::Frame),
        ("eye", Builtin::Eye),
        ("light.dir", Builtin::LightDir),
        ("light.color", Builtin::LightColor),
        ("light.intensity", Builtin::LightIntensity),
        ("light2.dir", Builtin::MoreLightDir(0)),
        ("light2.color", Builtin::MoreLightColor(0)),
        ("light2.intensity", Builtin::MoreLightIntensity(0)),
        ("light3.dir", Builtin::MoreLightDir(1)),
        ("light3.color", Builtin::MoreLightColor(1)),
        ("light3.intensity", Builtin::MoreLightIntensity(1)),
        ("light4.dir", Builtin::MoreLightDir(2)),
        ("light4.color", Builtin::MoreLightColor(2)),
        ("light4.intensity", Builtin::MoreLightIntensity(2)),
        ("camera.position", Builtin::CameraPosition),
        ("camera.near", Builtin::CameraNear),
        ("camera.far", Builtin::CameraFar),
        ("camera.focal", Builtin::CameraFocal),
        ("camera.left_eye", Builtin::CameraLeftEye),
        ("camera.right_eye", Builtin::CameraRightEye),
        ("camera.forward", Builtin::CameraForward),
        ("camera.right", Builtin::CameraRight),
        ("camera.up", Builtin::CameraUp),
        ("camera.orthographic", Builtin::CameraOrthographic),
        ("tangent.screen", Builtin::TangentScreen),
        ("bitangent.screen", Builtin::BitangentScreen),
        ("tangent.screen_center", Builtin::TangentScreenCenter),
        ("bitangent.screen_center", Builtin::BitangentScreenCenter),
        ("object.index", Builtin::ObjectIndex),
        ("object.id", Builtin::ObjectId),
        ("position.previous", Builtin::PositionPrevious),
        ("sample.spacing", Builtin::SampleSpacing),
        ("line.s", Builtin::LineArc),
        ("line.across", Builtin::LineAcross),
        ("line.set", Builtin::LineSet),
        ("patch.weight", Builtin::PatchWeight),
    ];

    pub fn name(self) -> &'static str {
        Self::SPELLINGS
            .iter()
            .rev()
            .find(|(_, b)| *b == self)
            .map(|(s, _)| *s)
            .unwrap_or("?")
    }

    pub fn ty_unit(self) -> (Ty, Unit) {
        use Builtin::*;
        match self {
            Uv | ScreenUv => (Ty::Vec2, Unit::None),
            NormalWorld | NormalView | Tangent | ViewDir | LightDir | PositionLight => (Ty::Vec3, Unit::None),
            PositionWorld | PositionView | CameraPosition | PositionPrevious => (Ty::Vec3, Unit::Meters),
            ObjectIndex | ObjectId => (Ty::Int, Unit::None),
            Depth | CameraNear | CameraFar | SampleSpacing => (Ty::Float, Unit::Meters),
            CameraLeftEye | CameraRightEye => (Ty::Vec3, Unit::Meters),
            CameraForward | CameraRight | CameraUp => (Ty::Vec3, Unit::None),
            FragCoord | Resolution => (Ty::Vec2, Unit::Px),
            Time => (Ty::Float, Unit::Seconds),
            LineArc => (Ty::Float, Unit::Px),
            LineAcross | PatchWeight => (Ty::Float, Unit::None),
            Frame | Eye | LineSet => (Ty::Int, Unit::None),
            LightColor | MoreLightColor(_) | MoreLightDir(_) => (Ty::Vec3, Unit::None),
            LightIntensity | MoreLightIntensity(_) | CameraOrthographic => (Ty::Float, Unit::None),
            // px per metre has no unit of its own; NDC focal lengths are ratios.
            CameraFocal | TangentScreen | BitangentScreen | TangentScreenCenter | BitangentScreenCenter => {
                (Ty::Vec2, Unit::None)
            }
        }
    }

    /// Interpolated per fragment (the fragment shader's varyings or its pixel
    /// position), so a `vertex { ... }` modifier cannot read it.
    pub fn is_per_fragment(self) -> bool {
        use Builtin::*;
        self.needs_geometry()
            || self.is_line_value()
            || matches!(
                self,
                FragCoord | ScreenUv | TangentScreen | BitangentScreen | TangentScreenCenter | BitangentScreenCenter
            )
    }

    /// Exists only in the fragments of a `lines` pass's strips.
    pub fn is_line_value(self) -> bool {
        matches!(self, Builtin::LineArc | Builtin::LineAcross | Builtin::LineSet)
    }

    /// Only meaningful on scene geometry (needs vertex data).
    pub fn needs_geometry(self) -> bool {
        use Builtin::*;
        matches!(
            self,
            Uv | NormalWorld
                | NormalView
                | PositionWorld
                | PositionView
                | Tangent
                | ViewDir
                | PositionLight
                | Depth
                | TangentScreen
                | BitangentScreen
                | TangentScreenCenter
                | BitangentScreenCenter
                | PositionPrevious
                | SampleSpacing
                | PatchWeight
        )
    }

    /// Needs an object (the `Object` block): render and compute passes.
    pub fn needs_object(self) -> bool {
        matches!(self, Builtin::ObjectIndex | Builtin::ObjectId)
    }

    /// Whether a compute pass over the pixels of an ID target has it: the
    /// pixel's position (not the interpolated screen-space frames, which
    /// exist only for fragments of geometry).
    pub fn in_pixel_elements(self) -> bool {
        matches!(self, Builtin::FragCoord | Builtin::ScreenUv)
    }

    /// Whether a compute pass over the vertices of objects has it: the
    /// vertex's own attributes and what follows from them, not what exists
    /// only per fragment (the pixel, interpolated screen-space frames) or
    /// what needs the light camera.
    pub fn in_vertex_elements(self) -> bool {
        use Builtin::*;
        !self.is_per_fragment()
            || matches!(
                self,
                Uv | NormalWorld | NormalView | PositionWorld | PositionView | ViewDir | Depth | PositionPrevious
            )
    }
}
