//! A source's convention to the language's (`npr_abi::input`): each kind
//! has one meaning inside a style, and a host or file says which of the
//! conventions renderers use it wrote.

use crate::artmap::Level;
use crate::scene::CameraPose;
use npr_abi::{InputKind, NormalSpace};
use npr_diag::{codes, Diagnostic};

/// How a source encodes colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorEncoding {
    /// Linear light (an EXR, a float render target).
    Linear,
    /// sRGB-encoded, display-referred (an 8-bit PNG).
    Srgb,
}

/// How a source encodes depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DepthConvention {
    /// The distance from the camera along its view axis in metres
    /// (Cycles' `Depth.Z`, a linear-depth target). `background` and
    /// beyond mean nothing was hit (Cycles writes 1e10 there).
    ViewDistance { background: f32 },
    /// Infinite reverse-Z NDC depth with near plane `near` (as Bevy
    /// writes it): `ndc = near / distance`, 0 where nothing was hit.
    ReverseZ { near: f32 },
}

impl DepthConvention {
    /// What Cycles writes: distance along the view axis, 1e10 for the
    /// background (anything from 1e9 on is taken as background).
    pub const CYCLES: DepthConvention = DepthConvention::ViewDistance { background: 1e9 };
}

/// The space a source's normals are in.
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

/// What a source says of one input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SourceConvention {
    Color(ColorEncoding),
    Depth(DepthConvention),
    Normal(NormalConvention),
    /// Ids, motion and free-form images: taken as they are.
    AsIs,
}

/// An E0420 for input `name` read from `file`.
pub fn bad_input(name: &str, file: &str, message: String, help: &str) -> Diagnostic {
    Diagnostic::error(codes::BAD_INPUT, format!("input `{name}` ({file}): {message}")).with_help(help.to_string())
}

/// `raw` (as the source wrote it) in the language's convention for `kind`.
/// `camera` turns normals between world and view space; it is needed only
/// when their spaces differ.
pub fn convert(
    name: &str,
    file: &str,
    kind: InputKind,
    source: SourceConvention,
    raw: &Level,
    camera: Option<&CameraPose>,
) -> Result<Level, Diagnostic> {
    let mut pixels = raw.pixels.clone();
    let channels = kind.channels() as usize;
    for (i, p) in pixels.iter().enumerate() {
        if let Some(c) = p[..channels].iter().find(|c| !c.is_finite()) {
            let (x, y) = (i as u32 % raw.width, i as u32 / raw.width);
            return Err(bad_input(
                name,
                file,
                format!("pixel ({x}, {y}) holds {c}, not a finite number"),
                "a renderer's background is a finite sentinel (Cycles writes 1e10 for depth); re-render or fix the pass",
            ));
        }
    }
    match (kind, source) {
        (InputKind::Color { display }, SourceConvention::Color(enc)) => {
            let to = if display {
                ColorEncoding::Srgb
            } else {
                ColorEncoding::Linear
            };
            if to != enc {
                let f = match to {
                    ColorEncoding::Linear => crate::srgb::srgb_to_linear,
                    ColorEncoding::Srgb => crate::srgb::linear_to_srgb,
                };
                for p in &mut pixels {
                    for c in &mut p[..3] {
                        *c = f(*c);
                    }
                }
            }
        }
        (InputKind::Depth, SourceConvention::Depth(conv)) => {
            for (i, p) in pixels.iter_mut().enumerate() {
                let d = match conv {
                    DepthConvention::ViewDistance { background } if p[0] >= background => 0.0,
                    DepthConvention::ViewDistance { .. } => p[0],
                    DepthConvention::ReverseZ { .. } if p[0] == 0.0 => 0.0,
                    DepthConvention::ReverseZ { near } => near / p[0],
                };
                if d < 0.0 {
                    let (x, y) = (i as u32 % raw.width, i as u32 / raw.width);
                    return Err(bad_input(
                        name,
                        file,
                        format!("pixel ({x}, {y}) has depth {d}: behind the camera"),
                        "depth is a distance in front of the camera; check the file's depth convention",
                    ));
                }
                *p = [d, 0.0, 0.0, 1.0];
            }
        }
        (InputKind::Normal { space }, SourceConvention::Normal(conv)) => {
            let view_of = |what: &str| {
                camera.map(|c| glam::Mat3::from_mat4(c.center_view())).ok_or_else(|| {
                    bad_input(
                        name,
                        file,
                        format!("normals in {what} need the camera"),
                        "give the scene whose camera rendered the inputs (`--scene`)",
                    )
                })
            };
            // Every source's normals to npr's world space, then to the space
            // the style reads.
            let to_world: Option<glam::Mat3> = match conv {
                NormalConvention::World => None,
                NormalConvention::WorldZUp => Some(glam::Mat3::from_cols(
                    glam::Vec3::new(1.0, 0.0, 0.0),
                    glam::Vec3::new(0.0, 0.0, -1.0),
                    glam::Vec3::new(0.0, 1.0, 0.0),
                )),
                NormalConvention::View => Some(view_of("view space")?.transpose()),
            };
            let to_style = match space {
                NormalSpace::World => None,
                NormalSpace::View => Some(view_of("world space, read in view space,")?),
            };
            for p in &mut pixels {
                let mut n = glam::Vec3::new(p[0], p[1], p[2]);
                if let Some(m) = to_world {
                    n = m * n;
                }
                if let Some(m) = to_style {
                    n = m * n;
                }
                *p = [n.x, n.y, n.z, 1.0];
            }
        }
        (_, SourceConvention::AsIs) => {}
        (kind, source) => {
            return Err(bad_input(
                name,
                file,
                format!(
                    "the source is described as {source:?}, but the style reads it as {}",
                    kind.name()
                ),
                "map the input to a layer of its kind (`--map NAME=LAYER`)",
            ))
        }
    }
    Ok(Level {
        width: raw.width,
        height: raw.height,
        pixels,
    })
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
    fn cycles_depth_keeps_distances_and_zeroes_the_background() {
        let l = Level {
            width: 2,
            height: 1,
            pixels: vec![[3.25, 0.0, 0.0, 1.0], [1e10, 0.0, 0.0, 1.0]],
        };
        let c = convert(
            "d",
            "f",
            InputKind::Depth,
            SourceConvention::Depth(DepthConvention::CYCLES),
            &l,
            None,
        )
        .unwrap();
        assert_eq!(c.pixels[0][0], 3.25);
        assert_eq!(c.pixels[1][0], 0.0);
    }

    #[test]
    fn reverse_z_is_near_over_ndc() {
        let src = SourceConvention::Depth(DepthConvention::ReverseZ { near: 0.1 });
        let c = convert("d", "f", InputKind::Depth, src, &one([0.025, 0.0, 0.0, 1.0]), None).unwrap();
        assert!((c.pixels[0][0] - 4.0).abs() < 1e-6, "{}", c.pixels[0][0]);
    }

    #[test]
    fn a_non_finite_depth_is_e0420_naming_input_file_and_pixel() {
        let src = SourceConvention::Depth(DepthConvention::CYCLES);
        let e = convert(
            "depth",
            "shot.exr",
            InputKind::Depth,
            src,
            &one([f32::NAN, 0.0, 0.0, 1.0]),
            None,
        )
        .unwrap_err();
        assert_eq!(e.code, codes::BAD_INPUT);
        assert!(
            e.message.contains("`depth`") && e.message.contains("shot.exr") && e.message.contains("(0, 0)"),
            "{}",
            e.message
        );
    }

    #[test]
    fn z_up_normals_become_y_up() {
        let kind = InputKind::Normal {
            space: NormalSpace::World,
        };
        let src = SourceConvention::Normal(NormalConvention::WorldZUp);
        // Blender's up (+z) is npr's up (+y); Blender's +y (away from a
        // front view) is npr's −z.
        let up = convert("n", "f", kind, src, &one([0.0, 0.0, 1.0, 0.0]), None).unwrap();
        assert_eq!(&up.pixels[0][..3], &[0.0, 1.0, 0.0]);
        let back = convert("n", "f", kind, src, &one([0.0, 1.0, 0.0, 0.0]), None).unwrap();
        assert_eq!(&back.pixels[0][..3], &[0.0, 0.0, -1.0]);
    }

    #[test]
    fn display_colour_from_linear_is_srgb_encoded() {
        let kind = InputKind::Color { display: true };
        let c = convert(
            "c",
            "f",
            kind,
            SourceConvention::Color(ColorEncoding::Linear),
            &one([0.5, 0.0, 1.0, 1.0]),
            None,
        )
        .unwrap();
        assert!((c.pixels[0][0] - crate::srgb::linear_to_srgb(0.5)).abs() < 1e-7);
        assert_eq!(c.pixels[0][3], 1.0);
    }
}
