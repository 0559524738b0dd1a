//! A sequence Blender rendered (issue 47): four 64×48 frames of a sphere
//! moving over a ground plane, Cycles on the CPU, one multi-layer EXR each
//! (`tests/data/blender/sequence/0000.exr` …, made by
//! `tests/data/blender/render_sequence.py` and committed: 5 KB each). A
//! path-dependent style runs over them through `npr render --inputs
//! 'sequence/{frame:04}.exr' --frames 0-3`, its layers written as EXRs, and
//! every frame is checked against the recurrence it computes, in f64 from
//! the files Blender wrote: out_k = (v_k + out_{k−1}) / 2 with v_k =
//! (Combined.R, Combined.G, Depth.Z / 10, 1) and out_{−1} = 0 (`previous`
//! reads zero before the first frame). Depth is Cycles' distance along the
//! view axis; the background (Cycles writes 1e10) is 0.

use crate::common::cli::{npr, scratch, stderr};
use npr_runner::inputs::files::read_exr;
use std::path::Path;

const TRAIL: &str = "style \"Trail over Blender\"\n\
texture c = input(color, linear)\n\
texture z = input(depth)\n\
pass final: image() {\n  out color: rgba32float = mix(vec4(c.r, c.g, z.r / 10.0, 1.0), previous(final.color), 0.5)\n}\n\
output final.color\n";

fn channel(exr: &npr_runner::inputs::files::ExrChannels, name: &str) -> Vec<f64> {
    exr.channels
        .get(name)
        .unwrap_or_else(|| panic!("no channel {name}: {:?}", exr.channels.keys().collect::<Vec<_>>()))
        .iter()
        .map(|&v| f64::from(v))
        .collect()
}

#[test]
fn a_blender_sequence_through_a_path_dependent_style_equals_its_recurrence() {
    let dir = scratch("blender_sequence", "trail");
    let style = dir.join("trail.npr");
    std::fs::write(&style, TRAIL).expect("write style");
    let frames = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/blender/sequence");
    let shots = frames.join("{frame:04}.exr").display().to_string();
    let out = dir.join("{frame:04}.exr").display().to_string();
    let o = npr(&[
        "render",
        style.to_str().expect("utf-8"),
        "--inputs",
        &shots,
        "--frames",
        "0-3",
        "--layers",
        "-o",
        &out,
    ]);
    assert!(o.status.success(), "npr render:\n{}", stderr(&o));
    let mut previous: Option<[Vec<f64>; 3]> = None;
    let mut moved = 0usize;
    for k in 0..4u32 {
        let shot = read_exr("blender", &frames.join(format!("{k:04}.exr"))).expect("Blender's frame");
        let (r, g, z) = (
            channel(&shot, "ViewLayer.Combined.R"),
            channel(&shot, "ViewLayer.Combined.G"),
            channel(&shot, "ViewLayer.Depth.Z"),
        );
        assert_eq!(r.len(), 64 * 48, "frame {k}: Blender's size");
        let hit: Vec<f64> = z.iter().map(|&d| if d >= 1e9 { 0.0 } else { d }).collect();
        let v = [r, g, hit.iter().map(|d| d / 10.0).collect::<Vec<f64>>()];
        let want: [Vec<f64>; 3] = std::array::from_fn(|c| {
            (0..v[c].len())
                .map(|i| 0.5 * (v[c][i] + previous.as_ref().map_or(0.0, |p| p[c][i])))
                .collect()
        });
        let got = read_exr("npr", &dir.join(format!("{k:04}.exr"))).expect("npr's frame");
        let got = ["R", "G", "B"].map(|c| channel(&got, &format!("final.color.{c}")));
        let mut worst = [0.0f64; 3];
        for c in 0..3 {
            for i in 0..want[c].len() {
                // Relative to the value, with a floor for dark pixels.
                let error = (got[c][i] - want[c][i]).abs() / want[c][i].abs().max(0.05);
                worst[c] = worst[c].max(error);
            }
        }
        // Blender's colour is half floats (its 16-bit EXR), which npr keeps
        // as they are (inputs are half-float textures): exact; the style
        // computes in f32 and stores rgba32float, a few ulps per frame.
        assert!(
            worst[0] < 1e-5 && worst[1] < 1e-5,
            "frame {k}: colour differs from the recurrence by {:e} (r), {:e} (g) of the value",
            worst[0],
            worst[1]
        );
        // A depth Blender keeps as a 32-bit float is rounded to half on
        // load: under one step, 2⁻¹⁰ of the value (as tests/gpu/host_builtins.rs).
        assert!(
            worst[2] < 9.8e-4,
            "frame {k}: depth differs from the recurrence by {:e} of the value",
            worst[2]
        );
        if let Some(p) = &previous {
            moved += (0..v[2].len()).filter(|&i| (want[2][i] - p[2][i]).abs() > 0.01).count();
        }
        previous = Some(want);
    }
    // The sphere moves: the depth's trail changes from frame to frame.
    assert!(moved > 100, "only {moved} pixels changed over the sequence");
    assert!(!dir.join("0004.exr").exists());
}
