//! Arithmetic on colours keeps their coverage (docs/decisions/0039-colours-keep-their-coverage.md):
//! each rule evaluated on the GPU with the colours kept live
//! (`--keep-params`, nothing folded), against the rule written out in f64.

use super::common::{artmaps, gpu};
use npr_compiler::CompileOptions;
use npr_runner::{FrameSpec, Renderer};

/// `#c0804080` and `#204060`, as the runner gives them (byte / 255).
const A: [f64; 4] = [192.0 / 255.0, 128.0 / 255.0, 64.0 / 255.0, 128.0 / 255.0];
const B: [f64; 4] = [32.0 / 255.0, 64.0 / 255.0, 96.0 / 255.0, 1.0];
const K: f64 = 0.25;

fn rgb_then(f: impl Fn(f64) -> f64, alpha: f64, c: [f64; 4]) -> [f64; 4] {
    [f(c[0]), f(c[1]), f(c[2]), alpha]
}

#[test]
fn colour_arithmetic_scales_light_and_keeps_coverage_on_the_gpu() {
    let cases: [(&str, [f64; 4]); 8] = [
        ("a * k", rgb_then(|x| x * K, A[3], A)),
        ("k * a", rgb_then(|x| K * x, A[3], A)),
        ("a / k", rgb_then(|x| x / K, A[3], A)),
        ("a + k", rgb_then(|x| x + K, A[3], A)),
        ("k - a", rgb_then(|x| K - x, A[3], A)),
        ("a + b", [A[0] + B[0], A[1] + B[1], A[2] + B[2], A[3].max(B[3])]),
        ("a - b", [A[0] - B[0], A[1] - B[1], A[2] - B[2], A[3].max(B[3])]),
        ("a * b", [A[0] * B[0], A[1] * B[1], A[2] * B[2], A[3] * B[3]]),
    ];
    let dir = artmaps::scratch("colour-alpha");
    let scene = artmaps::scene("[camera]\nposition = [0.0, 0.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\n");
    let options = CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    for (expr, want) in cases {
        let text = format!(
            "style \"Case\"\nparam a: color = #c0804080\nparam b: color = #204060\nparam k: float = 0.25\n\
             pass p: image() {{\n  out c: rgba32float = {expr}\n}}\noutput p.c\n"
        );
        let mut sources = npr_diag::SourceMap::new();
        let compiled = npr_compiler::compile_source("case.npr", &text, &dir, &mut sources, &options)
            .unwrap_or_else(|e| panic!("{expr}: {e:?}"));
        assert!(compiled.warnings.is_empty(), "{expr}: {:?}", compiled.warnings);
        let g = gpu();
        let mut r = Renderer::new(&g.device, &g.queue, &compiled.program(), &scene).expect("renderer");
        r.render(&scene, &FrameSpec::still(4, 4, 0)).expect("render");
        let got = r.read_output().expect("read").texel(1, 2);
        for c in 0..4 {
            // f32 arithmetic on values near 1: a few ulps.
            assert!(
                (got[c] as f64 - want[c]).abs() < 1e-6,
                "`{expr}` channel {c}: GPU {} vs rule {} (all: {got:?} vs {want:?})",
                got[c],
                want[c]
            );
        }
    }
}
