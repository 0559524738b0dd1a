//! Operators on the GPU where no reference can follow: MetaTexture at
//! extreme close-ups far from the uv origin (f32 cannot resolve k·uv there)
//! stays finite and bounded. The comparisons with the f64 references are
//! data cases in `stdlib/src/ops/` (run by `gpu_cases.rs`).

mod harness;

use harness::*;
use npr_stdlib::reference::ImageF64;

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
