//! The pattern examples blending their patches (Breslav et al. 2007 §3.6):
//! hatching, halftone, stipple and painterly, each drawing every patch over
//! its faces and the n-ring outside them with its ink (or paint) at strength
//! weight^patch_power, `blend: over`, tested against the ID pass's kept
//! depth. On the two-patch strip of `tests/common/patch_strip.rs`, each
//! style is drawn unblended (`blend_rings = 0`, the hard seam) and blended
//! over 2 rings, and measured:
//! - the ID image is unchanged by blending (tracking sees each patch's own
//!   faces);
//! - outside the n-ring the pixels equal the unblended drawing's, inside it
//!   they differ;
//! - inside the ring, on each side of the seam, some pixels are darker than
//!   the unblended drawing (the other patch's ink or paint, which nothing
//!   else can add: a patch alone at strength < 1 over the paper or the
//!   lightest paint only lightens) and, for the ink styles, some are lighter
//!   (this side's pattern weakened): both patches contribute there.
//!
//! Not measured here: a seam step across the boundary. On this still strip
//! every patch starts from the same pattern frame (o = 0, the same u and v),
//! so the halftone's and stipple's patterns agree across the boundary and
//! there is no seam to hide (hatching and painterly turn theirs per
//! `object.id`); a correlation measure of the step between the two columns
//! either side did not tell the hard seam from the blend for hatching
//! (0.95 against 1.06 × the median step) either.

use runner::{FrameSpec, Renderer, StyleProgram, TargetImage};

mod common;
use common::patch_strip::{half_pixel, scratch, strip_scene, surface_point, CELL, CELLS_Y, H, W};
use common::{gpu, root};

/// Rings of the blended drawing.
const RINGS: u32 = 2;

fn example(style: &str) -> StyleProgram {
    let mut sources = dsl::SourceMap::new();
    compiler::compile_file(
        &root().join(format!("examples/{style}.npr")),
        &mut sources,
        &Default::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"))
    .program()
}

fn target(program: &StyleProgram, name: &str) -> usize {
    program
        .manifest
        .targets
        .iter()
        .position(|t| t.name == name)
        .unwrap_or_else(|| panic!("no target `{name}`"))
}

/// Frames 0..3 of `program` on `scene` (the tracker needs a previous
/// frame): the output and the ID image of the last.
fn frames(program: &StyleProgram, scene: &runner::scene::Scene) -> (TargetImage, TargetImage) {
    let ids = target(program, "ids.id");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, program, scene).expect("renderer");
    for frame in 0..3 {
        let spec = FrameSpec {
            frame,
            time_s: frame as f64 / 24.0,
            ..FrameSpec::still(W, H, 0)
        };
        r.render(scene, &spec).expect("frame");
    }
    (r.read_output().expect("read"), r.read_target(ids).expect("ids"))
}

/// Whether row `py` is on the strip, away from its top and bottom edges.
fn on_strip_row(py: u32) -> bool {
    let (_, y) = surface_point(0, py);
    y.abs() <= CELLS_Y as f64 / 2.0 * CELL - 2.0 * half_pixel()
}

/// r + g + b at a pixel, in 0..=3.
fn value(img: &TargetImage, px: u32, py: u32) -> f64 {
    let t = img.texel(px, py);
    f64::from(t[0] + t[1] + t[2])
}

/// Drawn over `RINGS` rings against the hard seam: what changes where.
fn blends_over_the_n_ring(style: &str) {
    let dir = scratch(&format!("style-{style}"));
    let program = example(style);
    let (hard, hard_ids) = frames(&program, &strip_scene(&dir, Some(0)));
    let (blended, blended_ids) = frames(&program, &strip_scene(&dir, Some(RINGS)));
    // Blending changes what is drawn, not what is tracked: the ID image the
    // samples' visibility comes from holds each patch's own faces only.
    assert_eq!(
        hard_ids.bytes, blended_ids.bytes,
        "{style}: the ID image does not change with blending"
    );
    let reach = RINGS as f64 * CELL + 2.0 * half_pixel();
    let inner = RINGS as f64 * CELL - 2.0 * half_pixel();
    let (mut outside, mut inside, mut changed) = (0, 0, 0);
    // Per side of the seam (0: patch 0's faces, 1: patch 1's): ring pixels
    // darker and lighter than the unblended drawing by more than 8/255 in a
    // channel sum.
    let (mut darker, mut lighter, mut ring) = ([0usize; 2], [0usize; 2], [0usize; 2]);
    for py in (0..H).filter(|py| on_strip_row(*py)) {
        for px in 0..W {
            let (x, _) = surface_point(px, py);
            let (a, b) = (hard.texel(px, py), blended.texel(px, py));
            if x.abs() > reach {
                outside += 1;
                assert_eq!(
                    a, b,
                    "{style}: pixel ({px}, {py}) at x = {x:.3} is outside the {RINGS}-ring"
                );
            } else if x.abs() < inner {
                inside += 1;
                changed += usize::from(a != b);
                let side = usize::from(x > 0.0);
                let d = value(&blended, px, py) - value(&hard, px, py);
                ring[side] += 1;
                darker[side] += usize::from(d < -8.0 / 255.0);
                lighter[side] += usize::from(d > 8.0 / 255.0);
            }
        }
    }
    println!(
        "{style}: {outside} px outside the {RINGS}-ring equal; {changed} of {inside} px inside it changed; \
         darker {darker:?}, lighter {lighter:?} of {ring:?} px per side"
    );
    assert!(outside > 5_000 && inside > 1_000, "{style}: {outside}, {inside}");
    assert!(changed * 4 > inside, "{style}: {changed} of {inside}");
    for side in 0..2 {
        assert!(
            darker[side] * 20 > ring[side],
            "{style}: side {side}: the other patch's pattern shows in {} of {} ring px",
            darker[side],
            ring[side]
        );
    }
    if style != "painterly" {
        for side in 0..2 {
            assert!(
                lighter[side] * 20 > ring[side],
                "{style}: side {side}: this patch's pattern weakened in {} of {} ring px",
                lighter[side],
                ring[side]
            );
        }
    }
}

#[test]
fn hatching_blends_its_patches_over_the_n_ring() {
    blends_over_the_n_ring("hatching");
}

#[test]
fn halftone_blends_its_patches_over_the_n_ring() {
    blends_over_the_n_ring("halftone");
}

#[test]
fn stipple_blends_its_patches_over_the_n_ring() {
    blends_over_the_n_ring("stipple");
}

#[test]
fn painterly_blends_its_patches_over_the_n_ring() {
    blends_over_the_n_ring("painterly");
}
