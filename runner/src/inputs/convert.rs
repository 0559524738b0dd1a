//! A source's convention to the language's (`npr_abi::input`): each kind
//! has one meaning inside a style, and a host or file says which of the
//! conventions renderers use it wrote. Here a source's convention is
//! resolved into a [`Conversion`], the parameters of the one draw that
//! converts (`gpu.rs`), for files and a host's textures alike; and a
//! file's values are checked before they are drawn ([`check_values`]).

use crate::image_level::Level;
use crate::scene::CameraPose;
use npr_abi::{InputKind, NormalSpace};
use npr_diag::{codes, Diagnostic};

/// How a source encodes colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorEncoding {
    /// Linear light (an EXR, a float render target, an sRGB texture as
    /// the GPU reads it).
    Linear,
    /// sRGB-encoded, display-referred (an 8-bit PNG, a unorm texture
    /// holding display values).
    Srgb,
}

/// How a source encodes depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DepthConvention {
    /// The distance from the camera along its view axis in metres
    /// (Cycles' `Depth.Z`, a linear-depth target). `background` and
    /// beyond mean nothing was hit (Cycles writes 1e10 there; a target
    /// cleared to 0 needs none: 0 already means nothing was hit).
    ViewDistance { background: f32 },
    /// Infinite reverse-Z NDC depth with near plane `near` (as Bevy
    /// writes it): `ndc = near / distance`, 0 where nothing was hit.
    ReverseZ { near: f32 },
}

impl DepthConvention {
    /// What Cycles writes: distance along the view axis, 1e10 for the
    /// background (anything from 1e9 on is taken as background).
    pub const CYCLES: DepthConvention = DepthConvention::ViewDistance { background: 1e9 };
    /// Linear metres along the view axis with no background sentinel
    /// (0, the cleared value, is nothing hit).
    pub const METRES: DepthConvention = DepthConvention::ViewDistance {
        background: f32::INFINITY,
    };
}

/// The space a source's normals are in. Normals in a normalized-integer
/// image (a PNG, an `Rgba8Unorm` or `Rgb10a2Unorm` texture) are stored as
/// n·0.5 + 0.5 and decoded; in a float image they are taken as they are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NormalConvention {
    /// npr's world space (y up).
    World,
    /// A Z-up world, as Blender's: (x, y, z) is npr's (x, z, −y), the
    /// rotation that maps Blender's axes onto npr's (scene files written
    /// for both use it).
    WorldZUp,
    /// View space (x right, y up, z towards the viewer), as `normal.view`.
    View,
}

/// How a source measures motion vectors (both: from the previous frame
/// to this one, +x right, +y down).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionConvention {
    /// In pixels: the language's convention, taken as it is.
    Pixels,
    /// In fractions of the image's width and height, as Bevy's
    /// `MotionVectorPrepass` writes them (the change of the UV, current
    /// minus previous): scaled by the image's size.
    ScreenFraction,
}

/// What a source says of one input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SourceConvention {
    Color(ColorEncoding),
    Depth(DepthConvention),
    Normal(NormalConvention),
    Motion(MotionConvention),
    /// Ids, motion in pixels and free-form images: taken as they are.
    AsIs,
}

/// An E0420 for input `name` read from `file`.
pub fn bad_input(name: &str, file: &str, message: String, help: &str) -> Diagnostic {
    Diagnostic::error(codes::BAD_INPUT, format!("input `{name}` ({file}): {message}")).with_help(help.to_string())
}

/// Why a source cannot be converted to an input: the caller names the
/// input and its file or view, and gives the code.
#[derive(Debug, Clone, PartialEq)]
pub struct Mismatch {
    pub message: String,
    pub help: &'static str,
}

/// What the conversion draw does for one input (`gpu.rs`'s shader reads
/// these fields as its uniform block).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conversion {
    /// 0 as it is, 1 colour, 2 depth as a view distance, 3 reverse-Z
    /// depth, 4 normals, 5 motion in fractions of the image.
    pub(crate) mode: u32,
    /// Colour: 0 kept, 1 decoded from sRGB, 2 encoded to sRGB.
    pub(crate) colour: u32,
    /// Depth: the background sentinel (mode 2) or the near plane (mode 3).
    pub(crate) param: f32,
    /// Normals: from the source's space to the style's.
    pub(crate) normal_matrix: glam::Mat3,
    /// Normals stored as n·0.5 + 0.5.
    pub(crate) encoded_normals: bool,
}

/// Whether a source of convention `source` can be read as `kind`.
pub fn fits(kind: InputKind, source: SourceConvention) -> Result<(), Mismatch> {
    match (kind, source) {
        (InputKind::Color { .. }, SourceConvention::Color(_))
        | (InputKind::Depth, SourceConvention::Depth(_))
        | (InputKind::Normal { .. }, SourceConvention::Normal(_))
        | (InputKind::Motion, SourceConvention::Motion(_))
        | (_, SourceConvention::AsIs) => Ok(()),
        (kind, source) => Err(Mismatch {
            message: format!(
                "the source is described as {source:?}, but the style reads it as {}",
                kind.name()
            ),
            help: "give the input an image of its kind, described by that kind's convention",
        }),
    }
}

impl Conversion {
    /// Texels as they are.
    pub const AS_IS: Conversion = Conversion {
        mode: 0,
        colour: 0,
        param: 0.0,
        normal_matrix: glam::Mat3::IDENTITY,
        encoded_normals: false,
    };

    /// How `source` becomes the language's convention for `kind`. `camera`
    /// turns normals between world and view space (needed only when their
    /// spaces differ); `unorm`: the source is a normalized-integer image.
    pub fn resolve(
        kind: InputKind,
        source: SourceConvention,
        camera: Option<&CameraPose>,
        unorm: bool,
    ) -> Result<Conversion, Mismatch> {
        fits(kind, source)?;
        Ok(match (kind, source) {
            (InputKind::Color { display }, SourceConvention::Color(enc)) => {
                let to = if display {
                    ColorEncoding::Srgb
                } else {
                    ColorEncoding::Linear
                };
                Conversion {
                    mode: 1,
                    colour: match (enc, to) {
                        (ColorEncoding::Srgb, ColorEncoding::Linear) => 1,
                        (ColorEncoding::Linear, ColorEncoding::Srgb) => 2,
                        _ => 0,
                    },
                    ..Self::AS_IS
                }
            }
            (InputKind::Depth, SourceConvention::Depth(DepthConvention::ViewDistance { background })) => Conversion {
                mode: 2,
                param: background,
                ..Self::AS_IS
            },
            (InputKind::Depth, SourceConvention::Depth(DepthConvention::ReverseZ { near })) => Conversion {
                mode: 3,
                param: near,
                ..Self::AS_IS
            },
            (InputKind::Normal { space }, SourceConvention::Normal(conv)) => {
                let view_of = |what: &str| {
                    camera
                        .map(|c| glam::Mat3::from_mat4(c.center_view()))
                        .ok_or_else(|| Mismatch {
                            message: format!("normals in {what} need the camera"),
                            help: "give the camera that rendered the inputs (`--scene`; a host's frame camera)",
                        })
                };
                // Every source's normals to npr's world space, then to the
                // space the style reads.
                let to_world = match conv {
                    NormalConvention::World => glam::Mat3::IDENTITY,
                    NormalConvention::WorldZUp => glam::Mat3::from_cols(
                        glam::Vec3::new(1.0, 0.0, 0.0),
                        glam::Vec3::new(0.0, 0.0, -1.0),
                        glam::Vec3::new(0.0, 1.0, 0.0),
                    ),
                    NormalConvention::View => view_of("view space")?.transpose(),
                };
                let to_style = match space {
                    NormalSpace::World => glam::Mat3::IDENTITY,
                    NormalSpace::View => view_of("world space, read in view space,")?,
                };
                Conversion {
                    mode: 4,
                    normal_matrix: to_style * to_world,
                    encoded_normals: unorm,
                    ..Self::AS_IS
                }
            }
            (InputKind::Motion, SourceConvention::Motion(MotionConvention::ScreenFraction)) => {
                Conversion { mode: 5, ..Self::AS_IS }
            }
            _ => Self::AS_IS,
        })
    }
}

/// A file's values that its kind's convention does not allow: a
/// non-finite number in a channel the kind reads, a depth behind the
/// camera. (A host's textures are the GPU's, not read back to check.)
pub fn check_values(
    name: &str,
    file: &str,
    kind: InputKind,
    source: SourceConvention,
    raw: &Level,
) -> Result<(), Diagnostic> {
    let channels = kind.channels() as usize;
    let at = |i: usize| (i as u32 % raw.width, i as u32 / raw.width);
    for (i, p) in raw.pixels.iter().enumerate() {
        if let Some(c) = p[..channels].iter().find(|c| !c.is_finite()) {
            let (x, y) = at(i);
            return Err(bad_input(
                name,
                file,
                format!("pixel ({x}, {y}) holds {c}, not a finite number"),
                "a renderer's background is a finite sentinel (Cycles writes 1e10 for depth); re-render or fix the pass",
            ));
        }
        // Negative in both depth conventions: a distance, or near / distance.
        if matches!(source, SourceConvention::Depth(_)) && p[0] < 0.0 {
            let (x, y) = at(i);
            return Err(bad_input(
                name,
                file,
                format!("pixel ({x}, {y}) has depth {}: behind the camera", p[0]),
                "depth is a distance in front of the camera; check the file's depth convention",
            ));
        }
    }
    Ok(())
}

/// Input `name` read from `file` as `raw`, in `source`'s convention,
/// checked and ready to convert into the language's convention for `kind`
/// (`unorm`: a normalized-integer image, such as a PNG).
pub fn prepare(
    name: &str,
    file: &str,
    kind: InputKind,
    source: SourceConvention,
    raw: crate::image_level::Level,
    camera: Option<&CameraPose>,
    unorm: bool,
) -> Result<super::HostImage, Diagnostic> {
    check_values(name, file, kind, source, &raw)?;
    let conversion = Conversion::resolve(kind, source, camera, unorm).map_err(|m| {
        bad_input(
            name,
            file,
            m.message,
            if matches!(source, SourceConvention::Normal(_)) {
                m.help
            } else {
                "map the input to a layer of its kind (`--map NAME=LAYER`)"
            },
        )
    })?;
    Ok(super::HostImage { raw, conversion })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(p: [f32; 4]) -> Level {
        Level {
            width: 1,
            height: 1,
            pixels: vec![p],
        }
    }

    #[test]
    fn depth_conventions_resolve_to_their_draws() {
        let cycles = Conversion::resolve(
            InputKind::Depth,
            SourceConvention::Depth(DepthConvention::CYCLES),
            None,
            false,
        )
        .unwrap();
        assert_eq!((cycles.mode, cycles.param), (2, 1e9));
        let rz = SourceConvention::Depth(DepthConvention::ReverseZ { near: 0.1 });
        let rz = Conversion::resolve(InputKind::Depth, rz, None, false).unwrap();
        assert_eq!((rz.mode, rz.param), (3, 0.1));
    }

    #[test]
    fn a_non_finite_depth_is_e0420_naming_input_file_and_pixel() {
        let src = SourceConvention::Depth(DepthConvention::CYCLES);
        let e = check_values(
            "depth",
            "shot.exr",
            InputKind::Depth,
            src,
            &one([f32::NAN, 0.0, 0.0, 1.0]),
        )
        .unwrap_err();
        assert_eq!(e.code, codes::BAD_INPUT);
        assert!(
            e.message.contains("`depth`") && e.message.contains("shot.exr") && e.message.contains("(0, 0)"),
            "{}",
            e.message
        );
        let behind = check_values("depth", "f", InputKind::Depth, src, &one([-1.0, 0.0, 0.0, 1.0])).unwrap_err();
        assert!(behind.message.contains("behind the camera"), "{}", behind.message);
    }

    #[test]
    fn motion_in_fractions_of_the_image_is_scaled_and_motion_in_pixels_kept() {
        let fraction = SourceConvention::Motion(MotionConvention::ScreenFraction);
        assert_eq!(
            Conversion::resolve(InputKind::Motion, fraction, None, false).map(|c| c.mode),
            Ok(5)
        );
        let pixels = SourceConvention::Motion(MotionConvention::Pixels);
        assert_eq!(
            Conversion::resolve(InputKind::Motion, pixels, None, false),
            Ok(Conversion::AS_IS)
        );
        assert!(Conversion::resolve(InputKind::Depth, fraction, None, false).is_err());
    }

    #[test]
    fn z_up_normals_turn_to_y_up() {
        let kind = InputKind::Normal {
            space: NormalSpace::World,
        };
        let c = Conversion::resolve(kind, SourceConvention::Normal(NormalConvention::WorldZUp), None, false).unwrap();
        // Blender's up (+z) is npr's up (+y); Blender's +y (away from a
        // front view) is npr's −z.
        assert_eq!(c.normal_matrix * glam::Vec3::Z, glam::Vec3::Y);
        assert_eq!(c.normal_matrix * glam::Vec3::Y, glam::Vec3::NEG_Z);
    }

    #[test]
    fn view_normals_need_the_camera_and_kinds_must_match() {
        let kind = InputKind::Normal {
            space: NormalSpace::View,
        };
        let e = Conversion::resolve(kind, SourceConvention::Normal(NormalConvention::World), None, false).unwrap_err();
        assert!(e.message.contains("need the camera"), "{}", e.message);
        let e = Conversion::resolve(
            InputKind::Depth,
            SourceConvention::Color(ColorEncoding::Linear),
            None,
            false,
        )
        .unwrap_err();
        assert!(e.message.contains("reads it as depth"), "{}", e.message);
    }
}
