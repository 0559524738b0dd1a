//! GPU versus CPU reference: every stdlib operator runs on wgpu (lavapipe here)
//! inside a compute shader, over a grid of inputs that includes the hard cases,
//! and is compared with its f64 reference in `stdlib::reference`.
//!
//! Tolerances (absolute): arithmetic operators 1e-5 (f32 rounding of a few
//! operations on values ≤ 1); blurs 1e-5 (sums of ≤ 97 weights, renormalized);
//! edge detectors compare exactly except within 1e-4 of a threshold;
//! `sample` 4e-3 on 8-bit data (bilinear weights are quantized by the
//! rasterizer, 8 sub-texel bits on lavapipe).

mod harness;

use harness::*;
use stdlib::reference::ImageF64;

#[test]
fn metatexture_hard_cases_stay_finite_and_bounded_on_the_gpu() {
    // Extreme close-up far from the uv origin (2^E·u beyond f32 precision),
    // |∇u| → 0 and → ∞, ∇u ∥ ∇v, zero gradients; every MetaTexture parameter
    // at both ends of its range. No reference (f32 cannot resolve k·uv here):
    // finite, and within the texture's range widened by the largest contrast gain.
    let img = ImageF64::new(16, 16, |x, y| {
        q([(x as f64 / 15.0), (y as f64 / 15.0), ((x + y) % 2) as f64, 1.0])
    });
    let tex = [TexIn {
        image: img,
        format: wgpu::TextureFormat::Rgba8Unorm,
    }];
    let mut cases: Vec<[[f64; 4]; 3]> = Vec::new();
    let grads = [
        ([1e-30, 0.0], [0.0, 1e-30]),
        ([1e-7, 0.0], [0.0, 3e-7]),
        ([1e30, 0.0], [0.0, 1e30]),
        ([0.01, 0.01], [0.02, 0.02]),
        ([0.0, 0.0], [0.0, 0.0]),
    ];
    for uv in [[12345.678, -9876.5], [0.5, 0.5], [-3.0e6, 7.0e6]] {
        for (du, dv) in grads {
            for (width, base) in [(1.0, 1.01), (4096.0, 16.0), (256.0, 2.0)] {
                for (skew, band) in [(0.0, 0.01), (8.0, 8.0), (1.0, 1.0)] {
                    for contrast in [0.0, 1.0, 2.0] {
                        cases.push([
                            q([uv[0], uv[1], du[0], du[1]]),
                            q([dv[0], dv[1], base, width]),
                            [skew, band, contrast, 0.0],
                        ]);
                    }
                }
            }
        }
    }
    let inputs: Vec<[f32; 4]> = cases.iter().flat_map(|c| c.map(f32v)).collect();
    let body = "result = npr_metatexture_contour_grad(t0, samp_repeat, a.xy, a.zw, b.xy, b.w, 1, b.z, i32(c.x), i32(c.z), vec4<f32>(0.5), 1, c.y);";
    let out = run(
        &op_wgsl(&["metatexture_grad", "metatexture_contour_grad"]),
        body,
        &inputs,
        (cases.len() as u32, 1),
        &tex,
    );
    for (i, o) in out.iter().enumerate() {
        // Deviation from 0.5 is ≤ 0.5, times ≤ 1/√(k(½)³·k(½)) = 4 for variance-preserving contrast.
        assert!(
            o.iter().all(|v| v.is_finite() && (-1.5..=2.5).contains(v)),
            "case {i} {:?}: {o:?}",
            cases[i]
        );
    }
    println!("metatexture hard cases: {} cases finite and bounded", out.len());
}

#[test]
fn shadow_matches_reference_including_hard_cases() {
    // A 24×16 depth map: depths on a 1/8 grid, and light-space depths of the
    // query points on odd multiples of 1/32, so no comparison is a tie.
    let map = ImageF64::new(24, 16, |x, y| [((x * 3 + y * 5) % 9) as f64 / 8.0, 0.0, 0.0, 1.0]);
    let tex = [TexIn {
        image: map.clone(),
        format: wgpu::TextureFormat::Rgba32Float,
    }];
    let mut g = Lcg(4242);
    let mut points: Vec<[f64; 4]> = (0..400)
        .map(|_| {
            q([
                g.next() * 2.4 - 1.2,
                g.next() * 2.4 - 1.2,
                (2.0 * (g.next() * 18.0).floor() + 1.0) / 32.0,
                0.0,
            ])
        })
        .collect();
    // Hard cases: the frustum's edges and corners, beyond the far plane, NaN.
    points.extend([
        [1.0, 1.0, 0.5 / 32.0, 0.0],
        [-1.0, -1.0, 31.0 / 32.0, 0.0],
        [0.0, 0.0, 1.5, 0.0],
        [f64::NAN, 0.0, 0.5, 0.0],
        [0.0, 0.0, f64::NAN, 0.0],
    ]);
    let inputs: Vec<[f32; 4]> = points.iter().flat_map(|p| [f32v(*p), [0.0; 4], [0.0; 4]]).collect();
    for (warp, radius) in [(0.0, 0), (0.0, 1), (2.5, 1), (16.0, 3)] {
        let body = format!("result = vec4<f32>(npr_shadow(t0, a.xyz, 0.0, {warp:?}, {radius}), 0.0, 0.0, 0.0);");
        let out = run(&op_wgsl(&["shadow"]), &body, &inputs, (points.len() as u32, 1), &tex);
        // Exact, except for points within 1e-4 (in NDC) of a texel boundary, where
        // f32 and f64 may pick neighbouring texels.
        let mut keep = Vec::new();
        let mut reference = Vec::new();
        for (i, p) in points.iter().enumerate() {
            let at = |dx: f64, dy: f64| {
                stdlib::reference_pipeline::shadow(&map, [p[0] + dx, p[1] + dy, p[2]], 0.0, warp, radius)
            };
            let v = at(0.0, 0.0);
            if [(-1e-4, 0.0), (1e-4, 0.0), (0.0, -1e-4), (0.0, 1e-4)]
                .iter()
                .all(|(dx, dy)| at(*dx, *dy) == v)
            {
                keep.push(i);
                reference.push([v, 0.0, 0.0, 0.0]);
            }
        }
        assert!(
            keep.len() * 10 >= points.len() * 8,
            "too many boundary cases: {}",
            keep.len()
        );
        let gpu: Vec<[f32; 4]> = keep.iter().map(|i| out[*i]).collect();
        compare(
            &format!("shadow warp {warp} radius {radius}"),
            &gpu,
            &reference,
            1,
            1e-6,
        );
    }
}

#[test]
fn stereo_operators_match_reference() {
    use stdlib::reference_stereo as rs;
    // Contour fade: points around a sphere at 2 m, eyes 6.4 cm apart, and degenerate normals.
    let (left, right, forward) = ([-0.032, 0.01, 0.0], [0.032, 0.01, 0.0], [0.0, 0.0, -1.0]);
    let mut g = Lcg(99);
    let mut cases: Vec<([f64; 4], [f64; 4])> = (0..300)
        .map(|_| {
            let theta = g.next() * std::f64::consts::PI;
            let azimuth = g.next() * std::f64::consts::TAU;
            let n = [theta.sin() * azimuth.cos(), theta.sin() * azimuth.sin(), theta.cos()];
            let p = [0.5 * n[0], 0.5 * n[1], -2.0 + 0.5 * n[2]];
            (q([p[0], p[1], p[2], 0.0]), q([n[0], n[1], n[2], 0.0]))
        })
        .collect();
    cases.push(([0.0, 0.0, -2.0, 0.0], [0.0; 4]));
    cases.push(([-0.032, 0.01, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]));
    let inputs: Vec<[f32; 4]> = cases.iter().flat_map(|(p, n)| [f32v(*p), f32v(*n), [0.0; 4]]).collect();
    let body = format!(
        "result = vec4<f32>(npr_contour_fade(a.xyz, b.xyz, vec3<f32>({:?}, {:?}, {:?}), vec3<f32>({:?}, {:?}, {:?}), vec3<f32>({:?}, {:?}, {:?}), 1.75, 0.4375), 0.0, 0.0, 0.0);",
        left[0], left[1], left[2], right[0], right[1], right[2], forward[0], forward[1], forward[2]
    );
    let out = run(
        &op_wgsl(&["contour_fade"]),
        &body,
        &inputs,
        (cases.len() as u32, 1),
        &[],
    );
    let reference: Vec<[f64; 4]> = cases
        .iter()
        .map(|(p, n)| {
            let v = rs::contour_fade(
                [p[0], p[1], p[2]],
                [n[0], n[1], n[2]],
                left,
                right,
                forward,
                1.75,
                0.4375,
            );
            [v, 0.0, 0.0, 0.0]
        })
        .collect();
    // acos near ±1 and the ramp's small width (≈ 1.3·ᾱ ≈ 0.04 rad) amplify f32
    // rounding: 2e-3 of the fade's range.
    compare("contour_fade", &out, &reference, 1, 2e-3);

    // Reprojection mask and consistency on synthetic reprojections: a smooth
    // fronto-parallel shift of 3.3 px, a depth jump of 9 px in the right
    // third, background in a corner, and the other eye's inverse map.
    let (w, h) = (30u32, 12u32);
    let reproj = ImageF64::new(w, h, |x, y| {
        if x < 3 && y < 3 {
            return [0.0; 4];
        }
        let shift = if x >= 20 { 12.3 } else { 3.3 } + 0.05 * y as f64;
        q([x as f64 + 0.5 + shift, y as f64 + 0.5, 0.0, 1.0])
    });
    let reproj_other = ImageF64::new(w, h, |x, y| {
        let back = if x % 7 == 3 { 2.9 } else { 3.3 };
        q([
            x as f64 + 0.5 - back - 0.05 * y as f64,
            y as f64 + 0.5,
            0.0,
            if y == 9 { 0.0 } else { 1.0 },
        ])
    });
    let tex = [
        TexIn {
            image: reproj.clone(),
            format: wgpu::TextureFormat::Rgba32Float,
        },
        TexIn {
            image: reproj_other.clone(),
            format: wgpu::TextureFormat::Rgba32Float,
        },
    ];
    let out = run(
        &op_wgsl(&["reprojection_mask"]),
        "result = vec4<f32>(npr_reprojection_mask(t0, t1, uv, 2.0, 4.0, 3.0, 6.0), 0.0, 0.0, 0.0);",
        &[],
        (w, h),
        &tex,
    );
    let reference = pixels_ref((w, h), |uv| {
        let p = reproj.pixel_of(uv);
        [
            rs::reprojection_mask(&reproj, &reproj_other, p, (2.0, 4.0), (3.0, 6.0)),
            0.0,
            0.0,
            0.0,
        ]
    });
    compare("reprojection_mask", &out, &reference, 1, 1e-5);
    let masked = reference.iter().filter(|v| v[0] == 1.0).count();
    let clear = reference.iter().filter(|v| v[0] == 0.0).count();
    assert!(
        masked > 20 && clear > 100,
        "cases cover both outcomes: {masked} masked, {clear} clear"
    );

    let e = ImageF64::new(w, h, |x, y| {
        [if (x + y) % 5 == 0 { 1.0 } else { 0.1 * (x % 3) as f64 }, 0.0, 0.0, 1.0]
    });
    let e_other = ImageF64::new(w, h, |x, y| {
        [if (x + 2 * y) % 9 == 0 { 0.8 } else { 0.0 }, 0.0, 0.0, 1.0]
    });
    let tex = [
        TexIn {
            image: e.clone(),
            format: wgpu::TextureFormat::Rgba32Float,
        },
        TexIn {
            image: e_other.clone(),
            format: wgpu::TextureFormat::Rgba32Float,
        },
        TexIn {
            image: reproj.clone(),
            format: wgpu::TextureFormat::Rgba32Float,
        },
    ];
    for mask in [0.0, 0.3, 1.0] {
        let body = format!("result = vec4<f32>(npr_stereo_consistency(t0, t1, t2, {mask:?}, uv), 0.0, 0.0, 0.0);");
        let out = run(&op_wgsl(&["stereo_consistency"]), &body, &[], (w, h), &tex);
        let reference = pixels_ref((w, h), |uv| {
            [
                rs::stereo_consistency(&e, &e_other, &reproj, mask, e.pixel_of(uv)),
                0.0,
                0.0,
                0.0,
            ]
        });
        compare(&format!("stereo_consistency mask {mask}"), &out, &reference, 1, 1e-6);
    }
}
