//! What each builtin value is, for the reference and hover: one sentence
//! per `npr_compiler::ir::Builtin` (an exhaustive match, so a new builtin does
//! not build until it is described), with its type and unit from the IR.

use crate::ir::Builtin;

/// One sentence saying what the builtin holds.
pub fn doc(b: Builtin) -> &'static str {
    use Builtin::*;
    match b {
        SampleSpacing => "In a pass over samples: the distance between neighbouring samples on the surface (Breslav et al. 2007 §3.1).",
        Uv => "The surface's texture coordinates (the mesh's UVs).",
        NormalWorld => "The unit surface normal in world space.",
        NormalView => "The unit surface normal in view space.",
        PositionWorld => "The surface point in world space.",
        PositionView => "The surface point in view space.",
        PositionLight => "Light-space NDC of the surface point: x, y in [−1, 1] (unwarped), z in [0, 1].",
        Tangent => "The unit world tangent: the direction of increasing u.",
        ViewDir => "The unit direction from the surface point towards the camera.",
        Depth => "The distance of the surface point along the view direction.",
        FragCoord => "This pixel's position in pixels (x right, y down), at its centre.",
        ScreenUv => "This pixel's position in [0, 1]² of the pass's image.",
        Resolution => "The pass's image size in pixels.",
        Time => "The frame's time in seconds.",
        Frame => "The frame's number (0, 1, ...).",
        Eye => "The eye being rendered: 0 (left or mono) or 1 (right).",
        LightDir => "The unit direction towards the scene's `[light]`.",
        LightColor => "The colour of the scene's `[light]`.",
        LightIntensity => "The intensity of the scene's `[light]`.",
        MoreLightDir(_) => "The unit direction towards one of the scene's extra lights (`[light2]`..`[light4]`).",
        MoreLightColor(_) => "The colour of one of the scene's extra lights.",
        MoreLightIntensity(_) => "The intensity of one of the scene's extra lights.",
        CameraPosition => "The camera's position in world space (the centre of a stereo camera).",
        CameraNear => "The camera's near plane distance.",
        CameraFar => "The camera's far plane distance.",
        CameraFocal => "(P₀₀, P₁₁) of the projection: the focal lengths in NDC units (Age of Sail eq. 12). For an orthographic camera, 2 / the view's width and 2 / its height in NDC per metre: a length s at any depth spans s · P₁₁ · H / 2 px, without the perspective's division by depth.",
        CameraLeftEye => "The left eye's position of a stereo camera (the camera position in mono).",
        CameraRightEye => "The right eye's position of a stereo camera (the camera position in mono).",
        CameraForward => "The camera's unit view direction.",
        CameraOrthographic => "1 for an orthographic camera, 0 for a perspective one: a view-space point at depth d projects with clip w = d (perspective) or 1 (orthographic), and `view_dir` is −`camera.forward` everywhere for an orthographic camera.",
        CameraRight => "The camera's unit right direction in world space (x of its view).",
        CameraUp => "The camera's unit up direction in world space (y of its view).",
        TangentScreen => "T_s: the world tangent projected to the screen, px per metre, from the projection's Jacobian (Age of Sail §3.2).",
        BitangentScreen => "B_s: the bitangent projected to the screen, px per metre (Age of Sail §3.2).",
        TangentScreenCenter => "T_s projected with the stereo camera's centre (equal to `tangent.screen` in mono).",
        BitangentScreenCenter => "B_s projected with the stereo camera's centre (equal to `bitangent.screen` in mono).",
        ObjectIndex => "The object's position in the scene's object list (0, 1, ...).",
        ObjectId => "The object's id for ID images: its index + 1, so 0 (a cleared target) is no object.",
        PositionPrevious => "The surface point in world space in the previous frame (equal to `position` on the first frame).",
        LineArc => "In a lines pass: the arc length along the line on screen, in px (the s of Klein et al. 2000 §5's wave).",
        LineAcross => "In a lines pass: -1 on one edge of the strip, +1 on the other, interpolated across it.",
        LineSet => "In a lines pass with line sets: the index of the set drawing the strip, highest priority first (0, 1, ...). `line.color` is that set's `color:`.",
        PatchWeight => "The blending weight of the patch being drawn (Breslav et al. 2007 §3.6), interpolated from its vertices: 1 inside a patch, falling to 0 over the scene's `blend_rings` rings outside it; the patches' weights sum to 1 at every point. 1 on objects without patches. A pass that reads it draws each patch over that n-ring too.",
    }
}

/// Where the builtin exists, in words.
pub fn availability(b: Builtin) -> &'static str {
    if b == Builtin::PatchWeight {
        "render passes only"
    } else if matches!(b, Builtin::Depth | Builtin::PositionView) {
        "render passes, compute passes over geometry, and image passes of a style with `input(depth)`"
    } else if b == Builtin::NormalView {
        "render passes, compute passes over geometry, and image passes of a style with `input(normal, view)`"
    } else if b == Builtin::NormalWorld {
        "render passes, compute passes over geometry, and image passes of a style with `input(normal, world)`"
    } else if b.needs_geometry() {
        "render passes and compute passes over geometry"
    } else if b.is_per_fragment() {
        "render and image passes (per pixel)"
    } else if b.needs_object() {
        "render and compute passes (per object)"
    } else {
        "every pass"
    }
}

/// `name: type [unit]` of a builtin spelling.
pub fn signature(spelling: &str, b: Builtin) -> String {
    let (ty, unit) = b.ty_unit();
    let ty = match ty {
        crate::ir::Ty::Float => "float",
        crate::ir::Ty::Int => "int",
        crate::ir::Ty::Bool => "bool",
        crate::ir::Ty::Vec2 => "vec2",
        crate::ir::Ty::Vec3 => "vec3",
        crate::ir::Ty::Vec4 => "vec4",
        _ => "value",
    };
    let mut s = format!("{spelling}: {ty}");
    let sym = super::unit_symbol(unit);
    if !sym.is_empty() {
        s.push_str(&format!(" [{sym}]"));
    }
    s
}

/// A builtin's hover / reference text in Markdown.
pub fn markdown(spelling: &str, b: Builtin) -> String {
    format!(
        "```npr\n{}\n```\n\n{}\n\nAvailable in {}.",
        signature(spelling, b),
        doc(b),
        availability(b)
    )
}
