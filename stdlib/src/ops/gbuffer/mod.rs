//! G-buffer packing operators: the octahedral encoding of unit normals
//! (Cigolle et al. 2014, "A Survey of Efficient Representations for
//! Independent Unit Vectors", §3.1, the signed variant in [−1, 1]²), so a
//! normal fits a 2-channel `rg16float` target. The LSA contour operators
//! read such a target with `normal_encoding: octahedral` (Zaidi et al.,
//! "Local Surface Approximation Contours for Virtual Reality Stylisation",
//! §6 asks for precise G-buffers; docs/PERFORMANCE.md measures this one).
//! The WGSL lives in the `oct` snippet (`oct.wgsl`), which the LSA
//! operators share; `tests/gpu_gbuffer.rs` bounds the rg16float round trip.

pub mod reference;
pub use reference::*;

mod demos;

use super::{p, pair, random, triple, Arg, Case, OpDef, Tol, Value};
use crate::{Operator, Ty};

const S: f64 = std::f64::consts::FRAC_1_SQRT_2;
const T: f64 = 0.577_350_269_189_625_8;
const HARD_DIRECTIONS: &[Value] = &[
    [1.0, 0.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, -1.0, 0.0],
    [S, S, 0.0, 0.0],
    [S, -S, -0.0, 0.0],
    [-S, S, -0.0, 0.0],
    [S, 0.0, -S, 0.0],
    [0.0, -S, -S, 0.0],
    [T, T, T, 0.0],
    [-T, T, -T, 0.0],
    [T, -T, -T, 0.0],
    [1e-4, -1e-4, 1.0, 0.0],
    [-1e-4, 1e-4, -1.0, 0.0],
    [1.0, 1e-4, -1e-6, 0.0],
];
const HARD_CODES: &[Value] = &[
    [0.0; 4],
    [1.0, 0.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0, 0.0],
    [-1.0, 1.0, 0.0, 0.0],
    [1.0, -1.0, 0.0, 0.0],
    [-1.0, -1.0, 0.0, 0.0],
    [0.5, 0.5, 0.0, 0.0],
    [0.75, -0.5, 0.0, 0.0],
];

pub const OCT_ENCODE: OpDef = OpDef::new(
    Operator {
        name: "oct_encode",
        doc: "Octahedral encoding of a unit vector, signed variant: the point of the octahedron |x|+|y|+|z| = 1 on n's ray, the lower hemisphere folded over the diagonals, in [−1, 1]². Store it in an `rg16float` target: decoded, the round trip is within 0.06° where 16-bit stores round to nearest and 0.12° where they truncate (lavapipe), measured over the sphere, the folds and both poles.",
        reference: "Cigolle et al. 2014, A Survey of Efficient Representations for Independent Unit Vectors, §3.1 (float32x3_to_oct)",
        params: &[p("n", Ty::Vec3, "a direction (any length but 0), e.g. `normal.view`")],
        returns: Ty::Vec2,
        wgsl: include_str!("oct_encode.wgsl"),
        depends: &[],
        snippets: &["oct"],
        specializations: &[],
        footprints: &[],
    },
    |a| pair(oct_encode(a[0].v3())),
    &[
        // f32 arithmetic on |e| ≤ 1: a few ulps.
        Case::new("random directions of any length", &[random([-1.0; 4], [1.0; 4], 400)], Tol::Abs(1e-6)),
        Case::new("axes, the equator (±0), octant diagonals, near the poles", &[Arg::Each(HARD_DIRECTIONS)], Tol::Abs(1e-6)),
    ],
).with_demo(demos::OCT_ENCODE);

pub const OCT_DECODE: OpDef = OpDef::new(
    Operator {
        name: "oct_decode",
        doc: "The unit vector of an octahedral code from `oct_encode`: the outer triangles unfolded (z < 0), then normalized.",
        reference: "Cigolle et al. 2014, A Survey of Efficient Representations for Independent Unit Vectors, §3.1 (oct_to_float32x3)",
        params: &[p("e", Ty::Vec2, "an octahedral code in [−1, 1]² (e.g. an `rg16float` target's rg)")],
        returns: Ty::Vec3,
        wgsl: include_str!("oct_decode.wgsl"),
        depends: &[],
        snippets: &["oct"],
        specializations: &[],
        footprints: &[],
    },
    |a| triple(oct_decode(a[0].v2())),
    &[
        Case::new("random codes", &[random([-1.0; 4], [1.0; 4], 400)], Tol::Abs(2e-6)),
        Case::new("the square's edges, corners and centre", &[Arg::Each(HARD_CODES)], Tol::Abs(2e-6)),
    ],
).with_demo(demos::OCT_DECODE);
