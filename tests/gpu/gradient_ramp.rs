//! `ramp(g, t)` of a `gradient` param on the GPU against the ramp written
//! out in f64 (compiler/src/front/resolve/gradient.rs): linear stops, two
//! stops at one position (a hard edge), and `mode: constant`.

use super::common::{artmaps, gpu};
use runner::{FrameSpec, Renderer};

/// (position, colour bytes): the stops of the test's gradients.
const STOPS: [(f64, [u8; 4]); 5] = [
    (0.1, [0x10, 0x20, 0x30, 0xff]),
    (0.4, [0xe0, 0x7a, 0x3a, 0xff]),
    (0.6, [0x40, 0xc0, 0x80, 0x80]),
    (0.6, [0xff, 0xff, 0xff, 0xff]),
    (0.9, [0x00, 0x00, 0xff, 0xff]),
];

fn colour(bytes: [u8; 4]) -> [f64; 4] {
    bytes.map(|b| b as f64 / 255.0)
}

/// The colour at `t`: the first stop's below it, the last's past it, in
/// between the mix of the two stops around `t` (linear), or the colour of
/// the last stop at or before `t` (constant).
fn reference(t: f64, constant: bool) -> [f64; 4] {
    let last_at_or_before = STOPS.iter().rposition(|(p, _)| *p <= t);
    let Some(i) = last_at_or_before else {
        return colour(STOPS[0].1);
    };
    if constant || i + 1 == STOPS.len() {
        return colour(STOPS[i].1);
    }
    let ((p0, c0), (p1, c1)) = (STOPS[i], STOPS[i + 1]);
    let f = (t - p0) / (p1 - p0);
    let (a, b) = (colour(c0), colour(c1));
    [0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * f)
}

#[test]
fn ramp_matches_the_f64_rule_on_the_gpu() {
    let dir = artmaps::scratch("gradient-ramp");
    let scene = artmaps::scene("[camera]\nposition = [0.0, 0.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\n");
    let stops: Vec<String> = STOPS
        .iter()
        .map(|(p, c)| format!("stop({p}, #{:02x}{:02x}{:02x}{:02x})", c[0], c[1], c[2], c[3]))
        .collect();
    let width = 200u32;
    for constant in [false, true] {
        let mode = if constant { ", mode: constant" } else { "" };
        let text = format!(
            "style \"Ramp\"\nparam g: gradient = gradient({}{mode})\npass p: image() {{\n  out c: rgba32float = ramp(g, screen_uv.x)\n}}\noutput p.c\n",
            stops.join(", ")
        );
        let program = artmaps::compile(&text, &dir);
        let g = gpu();
        let mut r = Renderer::new(&g.device, &g.queue, &program, &scene).expect("renderer");
        r.render(&scene, &FrameSpec::still(width, 1, 0)).expect("render");
        let img = r.read_output().expect("read");
        for x in 0..width {
            let t = (x as f64 + 0.5) / width as f64;
            let (got, want) = (img.texel(x, 0), reference(t, constant));
            for k in 0..4 {
                // f32 arithmetic of a few operations on values in 0..1.
                assert!(
                    (got[k] as f64 - want[k]).abs() < 1e-5,
                    "constant: {constant}, t = {t}, channel {k}: GPU {got:?} vs f64 {want:?}"
                );
            }
        }
    }
}
