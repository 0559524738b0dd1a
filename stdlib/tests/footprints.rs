//! Every declared neighbourhood footprint (`npr_stdlib::Footprint::Around`) is
//! measured on the GPU: the operator runs over an image, then again with one
//! texel of the texture argument changed; every output pixel whose result
//! changed must lie within the declared radius of that texel (the texel under
//! the pixel's `uv`, in the texture's own texels). A tiled schedule loads
//! exactly this apron (issue 14), so a radius that is too small would give a
//! wrong image there.
//!
//! Soundness (no change outside the radius) and tightness (a change at the
//! radius itself, so no apron is larger than it must be) are asserted for
//! every case; the inputs are chosen so that the farthest tap shows (flat
//! fields where an operator thresholds, a ramp where it takes a maximum).

mod harness;

use harness::*;
use npr_stdlib::reference::ImageF64;
use npr_stdlib::{Footprint, Radius};

const SIZE: u32 = 33;

fn noise(seed: u64) -> ImageF64 {
    pattern(2, SIZE, SIZE, seed)
}

/// A sphere's front as a G-buffer (positions 3 m ahead, alpha 1; unit normals).
fn sphere_gbuffer() -> (ImageF64, ImageF64) {
    let at = |x: u32, y: u32| {
        let u = (f64::from(x) - 16.0) / 16.0 * 0.8;
        let v = (f64::from(y) - 16.0) / 16.0 * 0.8;
        let w = (1.0 - u * u - v * v).sqrt();
        ([u, v, w - 3.0, 1.0], [u, v, w, 1.0])
    };
    (
        ImageF64::new(SIZE, SIZE, |x, y| at(x, y).0),
        ImageF64::new(SIZE, SIZE, |x, y| at(x, y).1),
    )
}

/// A per-pixel position in the other eye, `shift` px to the right, covered.
fn reprojection(shift: f64) -> ImageF64 {
    ImageF64::new(SIZE, SIZE, |x, y| {
        [f64::from(x) + 0.5 + shift, f64::from(y) + 0.5, 0.0, 1.0]
    })
}

fn texture(image: ImageF64) -> TexIn {
    TexIn {
        image,
        format: wgpu::TextureFormat::Rgba32Float,
    }
}

struct Case {
    op: &'static str,
    /// The texture parameter perturbed, and its index among t0, t1, t2.
    param: &'static str,
    index: usize,
    /// WGSL statements setting `result` (see `harness::run`).
    body: &'static str,
    /// The constant a scaled radius depends on, as `body` passes it.
    scaled_by: Option<f64>,
    /// The output image size (textures are SIZE × SIZE unless a case says;
    /// the changed texel is the middle one).
    out: (u32, u32),
    textures: fn() -> Vec<ImageF64>,
}

fn cases() -> Vec<Case> {
    let lsa = || {
        let (p, n) = sphere_gbuffer();
        vec![p, n]
    };
    let mut v = vec![
        Case {
            op: "gaussian",
            param: "src",
            index: 0,
            body: "result = npr_gaussian(t0, uv, 1.2, 0) + npr_gaussian(t0, uv, 1.2, 1);",
            scaled_by: Some(1.2),
            out: (SIZE, SIZE),
            textures: || vec![noise(1)],
        },
        Case {
            op: "downsample",
            param: "src",
            index: 0,
            body: "result = npr_downsample(t0, uv);",
            scaled_by: None,
            out: (16, 16),
            textures: || vec![pattern(2, 32, 32, 2)],
        },
        Case {
            op: "sobel",
            param: "src",
            index: 0,
            body: "result = vec4<f32>(npr_sobel(t0, uv));",
            scaled_by: None,
            out: (SIZE, SIZE),
            textures: || vec![noise(3)],
        },
        Case {
            op: "lsa_density",
            param: "src",
            index: 0,
            body: "result = npr_lsa_density(t0, uv, 1.0);",
            scaled_by: None,
            out: (SIZE, SIZE),
            textures: || vec![noise(4)],
        },
        Case {
            op: "id_share",
            param: "ids",
            index: 0,
            body: "result = vec4<f32>(npr_id_share(t0, uv, 1.0, 2.0));",
            scaled_by: Some(2.0),
            out: (SIZE, SIZE),
            textures: || vec![ImageF64::new(SIZE, SIZE, |_, _| [1.0, 0.0, 0.0, 1.0])],
        },
        Case {
            op: "reprojection_mask",
            param: "reproj",
            index: 0,
            body: "result = vec4<f32>(npr_reprojection_mask(t0, t1, uv, 0.5, 2.0, 0.5, 2.0));",
            scaled_by: None,
            out: (SIZE, SIZE),
            textures: || vec![reprojection(2.0), reprojection(-2.0)],
        },
        Case {
            op: "stereo_consistency",
            param: "e",
            index: 0,
            body: "result = vec4<f32>(npr_stereo_consistency(t0, t1, t2, 1.0, uv));",
            scaled_by: None,
            out: (SIZE, SIZE),
            textures: || vec![noise(5), noise(6), reprojection(2.0)],
        },
        Case {
            op: "stereo_consistency",
            param: "reproj",
            index: 2,
            body: "result = vec4<f32>(npr_stereo_consistency(t0, t1, t2, 0.0, uv));",
            scaled_by: None,
            out: (SIZE, SIZE),
            // E = 1 everywhere and the other eye's E rising along x: the
            // result is the other eye's E at the reprojected window's right edge.
            textures: || {
                vec![
                    ImageF64::new(SIZE, SIZE, |_, _| [1.0; 4]),
                    pattern(0, SIZE, SIZE, 0),
                    reprojection(2.0),
                ]
            },
        },
    ];
    for (param, index) in [("normals", 0), ("depth", 1)] {
        v.push(Case {
            op: "normal_depth_edges",
            param,
            index,
            body: "result = vec4<f32>(npr_normal_depth_edges(t0, t1, uv, 0.05, 0.4));",
            scaled_by: None,
            out: (SIZE, SIZE),
            // Flat: no edge anywhere until the changed texel makes one.
            textures: || {
                vec![
                    ImageF64::new(SIZE, SIZE, |_, _| [0.5, 0.5, 1.0, 1.0]),
                    ImageF64::new(SIZE, SIZE, |_, _| [2.0, 0.0, 0.0, 1.0]),
                ]
            },
        });
    }
    for (op, body) in [
        ("lsa", "result = npr_lsa(t0, t1, uv, true, true, 0.0, 0.001, 0);"),
        ("lsa_sum", "result = npr_lsa_sum(t0, t1, uv, true, 0.0, 0.001, 0);"),
        (
            "lsa_curv_aa",
            "result = npr_lsa_curv_aa(t0, t1, uv, true, 0.0, 0.001, 0);",
        ),
        ("lsa_curv", "result = npr_lsa_curv(t0, t1, uv, 0.0, 0.001, 0);"),
    ] {
        for (param, index) in [("pos", 0), ("normals", 1)] {
            v.push(Case {
                op,
                param,
                index,
                body,
                scaled_by: None,
                out: (SIZE, SIZE),
                textures: lsa,
            });
        }
    }
    v
}

/// The declared radius of `case`'s texture parameter.
fn declared(case: &Case) -> u32 {
    let op = npr_stdlib::find(case.op).expect("an operator");
    match op.footprint(case.param) {
        Some(Footprint::Around { radius, .. }) => {
            if matches!(radius, Radius::Scaled { .. }) {
                assert!(
                    case.scaled_by.is_some(),
                    "{}.{}: give the scaling constant",
                    case.op,
                    case.param
                );
            }
            radius.texels(case.scaled_by)
        }
        other => panic!("{}.{}: {other:?} is not a neighbourhood footprint", case.op, case.param),
    }
}

/// Changes one texel by 0.75 in each colour channel (alpha kept, so a G-buffer
/// texel stays geometry; an ID becomes another object's).
fn perturb(image: &mut ImageF64, (x, y): (i64, i64)) {
    let i = (y as u32 * image.width + x as u32) as usize;
    let p = &mut image.pixels[i];
    for c in &mut p[..3] {
        *c += 0.75;
    }
}

#[test]
fn every_neighbourhood_footprint_bounds_what_the_operator_reads() {
    let cases = cases();
    let mut report = Vec::new();
    for case in &cases {
        let radius = declared(case);
        let wgsl = op_wgsl(&[case.op]);
        let inputs = (case.textures)();
        let base = run(
            &wgsl,
            case.body,
            &[],
            case.out,
            &inputs.clone().into_iter().map(texture).collect::<Vec<_>>(),
        );
        let (tw, th) = (inputs[case.index].width, inputs[case.index].height);
        let centre = (i64::from(tw / 2), i64::from(th / 2));
        let mut changed_inputs = inputs;
        perturb(&mut changed_inputs[case.index], centre);
        let changed = run(
            &wgsl,
            case.body,
            &[],
            case.out,
            &changed_inputs.into_iter().map(texture).collect::<Vec<_>>(),
        );
        let (w, h) = case.out;
        let mut farthest: Option<i64> = None;
        for (i, (a, b)) in base.iter().zip(&changed).enumerate() {
            if a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()) {
                continue;
            }
            // The texel under this pixel's uv, in the texture's texels.
            let (px, py) = ((i as u32 % w) as f64, (i as u32 / w) as f64);
            let tx = (((px + 0.5) / f64::from(w)) * f64::from(tw)).floor() as i64;
            let ty = (((py + 0.5) / f64::from(h)) * f64::from(th)).floor() as i64;
            let d = (tx - centre.0).abs().max((ty - centre.1).abs());
            assert!(
                d <= i64::from(radius),
                "{}.{}: the pixel at ({px}, {py}) changed, {d} texels from the changed texel, past the declared radius {radius}",
                case.op,
                case.param
            );
            farthest = Some(farthest.map_or(d, |f| f.max(d)));
        }
        let farthest = farthest.unwrap_or_else(|| panic!("{}.{}: no pixel saw the changed texel", case.op, case.param));
        assert_eq!(
            farthest,
            i64::from(radius),
            "{}.{}: the declared radius is not tight",
            case.op,
            case.param
        );
        report.push(format!(
            "{}.{}: declared {radius}, farthest change {farthest}",
            case.op, case.param
        ));
    }
    eprintln!("{}", report.join("\n"));
}

#[test]
fn every_neighbourhood_footprint_has_a_case() {
    let cases = cases();
    for op in npr_stdlib::all() {
        for (param, f) in op.footprints {
            if matches!(f, Footprint::Around { .. }) {
                assert!(
                    cases.iter().any(|c| c.op == op.name && c.param == *param),
                    "{}.{param}: a neighbourhood footprint without a measured case",
                    op.name
                );
            }
        }
    }
}
