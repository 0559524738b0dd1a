//! `shadow`: cast-shadow visibility from a light-view depth map with
//! percentage-closer filtering (Williams 1978), the depth pass's
//! coordinates sigmoid-warped as in Age of Sail §5. Exact, except near a
//! texel boundary or a depth tie (skipped).

pub mod reference;
pub use reference::*;

mod demos;

use super::{p, random, scalar, tex32, Arg, Case, OpDef, Tol, Value};
use crate::image_f64::ImageF64;
use crate::{Default, Footprint, Operator, Param, Ty, Unit};

/// A 24×16 depth map, depths on a 1/8 grid.
fn depth_map() -> ImageF64 {
    ImageF64::new(24, 16, |x, y| [f64::from((x * 3 + y * 5) % 9) / 8.0, 0.0, 0.0, 1.0])
}

const WARPS: Arg = each![0.0, 2.5, 16.0];
const RADII: Arg = each![0, 1, 3];
const HARD_POINTS: &[Value] = &[
    [1.0, 1.0, 0.5 / 32.0, 0.0],
    [-1.0, -1.0, 31.0 / 32.0, 0.0],
    [0.0, 0.0, 1.5, 0.0],
    [f64::NAN, 0.0, 0.5, 0.0],
    [0.0, 0.0, f64::NAN, 0.0],
];

pub const SHADOW: OpDef = OpDef::new(
    Operator {
        name: "shadow",
        doc: "Cast-shadow visibility (lit fraction in [0, 1]) of a surface point, from a light-view depth map written by a `view(light)` pass; outside the map is lit.",
        reference: "Williams 1978 shadow maps with percentage-closer filtering; Harvill et al., Age of Sail (journal 2019) §5, depth pass with sigmoid-warped coordinates",
        params: &[
            p("depth_map", Ty::Texture, "light-space depth (channel r) from a `view(light)` pass, cleared to 1"),
            Param {
                name: "p_light",
                ty: Ty::Vec3,
                unit: Unit::None,
                default: Default::Builtin("position.light"),
                range: None,
                doc: "the point in light NDC (default: this fragment's `position.light`)",
            },
            Param {
                name: "bias",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.005),
                range: Some((0.0, 0.5)),
                doc: "depth bias against self-shadowing, in light-NDC depth (1 = the light frustum's depth)",
            },
            Param {
                name: "warp",
                ty: Ty::Float,
                unit: Unit::None,
                default: Default::Number(0.0),
                range: Some((0.0, 16.0)),
                doc: "sigmoid strength k of the depth pass's `shadow_warp` (must match it)",
            },
            Param {
                name: "radius",
                ty: Ty::Int,
                unit: Unit::None,
                default: Default::Number(1.0),
                range: Some((0.0, 3.0)),
                doc: "percentage-closer filter radius in texels ((2r+1)² taps)",
            },
        ],
        returns: Ty::Float,
        wgsl: include_str!("shadow.wgsl"),
        depends: &[],
        snippets: &[],
        specializations: &[],
        footprints: &[("depth_map", Footprint::Anywhere)],
    },
    |a| {
        let (map, p, bias, warp, radius) = (a[0].tex(), a[1].v3(), a[2].f(), a[3].f(), a[4].i());
        // Undefined within 1e-4 (in NDC) of a texel boundary or a depth,
        // where f32 and f64 may pick neighbouring texels or differ on a tie.
        let at = |dx: f64, dy: f64, dz: f64| shadow(map, [p[0] + dx, p[1] + dy, p[2] + dz], bias, warp, radius);
        let v = at(0.0, 0.0, 0.0);
        let steps = [(-1e-4, 0.0, 0.0), (1e-4, 0.0, 0.0), (0.0, -1e-4, 0.0), (0.0, 1e-4, 0.0), (0.0, 0.0, -1e-4), (0.0, 0.0, 1e-4)];
        scalar(if steps.iter().all(|(x, y, z)| at(*x, *y, *z) == v) { v } else { f64::NAN })
    },
    &[
        Case::new(
            "random points around the light frustum",
            &[tex32(depth_map), random([-1.2, -1.2, 0.0, 0.0], [1.2, 1.2, 1.15, 0.0], 100), each![0.0, 0.005], WARPS, RADII],
            Tol::Abs(1e-6),
        )
        .skipping(0.2),
        Case::new(
            "the frustum's edges and corners, beyond the far plane, NaN",
            &[tex32(depth_map), Arg::Each(HARD_POINTS), each![0.0], WARPS, RADII],
            Tol::Abs(1e-6),
        )
        // The frustum's edges are texel boundaries (undefined); the far, NaN
        // and corner-depth points are compared.
        .skipping(0.3),
    ],
).with_demo(demos::SHADOW);
