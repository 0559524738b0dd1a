//! G-buffer packing operators: the octahedral encoding of unit normals
//! (Cigolle et al. 2014, "A Survey of Efficient Representations for
//! Independent Unit Vectors", §3.1, the signed variant in [−1, 1]²), so a
//! normal fits a 2-channel `rg16float` target. The LSA contour operators
//! read such a target with `normal_encoding: octahedral` (Zaidi et al.,
//! "Local Surface Approximation Contours for Virtual Reality Stylisation",
//! §6 asks for precise G-buffers; docs/PERFORMANCE.md measures this one).
//! The WGSL lives in the `oct` snippet, which the LSA operators share.

use crate::ops::p;
use crate::{Operator, Stage, Ty};

pub static ALL: &[Operator] = &[
    Operator {
        name: "oct_encode",
        doc: "Octahedral encoding of a unit vector, signed variant: the point of the octahedron |x|+|y|+|z| = 1 on n's ray, the lower hemisphere folded over the diagonals, in [−1, 1]². Store it in an `rg16float` target: decoded, the round trip is within 0.06° where 16-bit stores round to nearest and 0.12° where they truncate (lavapipe), measured over the sphere, the folds and both poles.",
        reference: "Cigolle et al. 2014, A Survey of Efficient Representations for Independent Unit Vectors, §3.1 (float32x3_to_oct)",
        params: &[p("n", Ty::Vec3, "a direction (any length but 0), e.g. `normal.view`")],
        returns: Ty::Vec2,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/oct_encode.wgsl"),
        depends: &[],
        snippets: &["oct"],
        specializations: &[],
        footprints: &[],
    },
    Operator {
        name: "oct_decode",
        doc: "The unit vector of an octahedral code from `oct_encode`: the outer triangles unfolded (z < 0), then normalized.",
        reference: "Cigolle et al. 2014, A Survey of Efficient Representations for Independent Unit Vectors, §3.1 (oct_to_float32x3)",
        params: &[p("e", Ty::Vec2, "an octahedral code in [−1, 1]² (e.g. an `rg16float` target's rg)")],
        returns: Ty::Vec3,
        stage: Stage::Any,
        wgsl: include_str!("../wgsl/oct_decode.wgsl"),
        depends: &[],
        snippets: &["oct"],
        specializations: &[],
        footprints: &[],
    },
];
