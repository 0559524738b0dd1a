//! The sliding ("shower-door") measure of dynamic 2D patterns (Breslav et
//! al. 2007 §4, Fig. 4), `npr_lab::sliding`, on the real runner: a tracked
//! pattern slides far less than one fixed to the screen under a pan, a
//! dolly and a roll; the elongated strip of Fig. 4, whose ends move
//! differently, is where a single similarity slides most, and patches
//! (§3.6, one similarity each) reduce it, as they reduce the orbit's. The full table
//! (every motion and tracker variant) is `npr bench patterns`'s.

use crate::common;
use common::{gpu, root};

/// The tracker the examples `use`.
fn tracker() -> String {
    std::fs::read_to_string(root().join("examples/lib/dynamic_pattern.npr")).expect("examples/lib/dynamic_pattern.npr")
}

fn measure(motion: &str, samples: u32, weighting: &str) -> npr_lab::sliding::Sliding {
    let (_, text) = npr_lab::sliding::motions()
        .into_iter()
        .find(|(name, _)| *name == motion)
        .expect("a motion");
    let scene = npr_lab::sliding::scene(&text, &root().join("examples/scenes")).expect("scene");
    let program = common::compile_text(&npr_lab::sliding::style(&tracker(), samples, weighting));
    let s = npr_lab::sliding::measure(gpu(), &program, &scene).expect("measure");
    println!(
        "{motion}, {samples} samples, {weighting}: {:.3e} px/frame, screen-fixed {:.4}",
        s.tracked, s.screen_fixed
    );
    assert!(s.tracked.is_finite() && s.screen_fixed.is_finite());
    s
}

#[test]
fn a_tracked_pattern_slides_a_fraction_of_a_screen_fixed_one() {
    // Under motions a similarity describes well (pan, dolly, roll), the
    // pattern moves with the cow: it slides by a small part of its motion.
    for motion in ["pan", "zoom", "roll"] {
        let s = measure(motion, 400, "area");
        assert!(
            s.screen_fixed > 0.5,
            "{motion}: the cow moves {} px/frame",
            s.screen_fixed
        );
        assert!(
            s.tracked < 0.2 * s.screen_fixed,
            "{motion}: tracked {} px/frame against screen-fixed {}",
            s.tracked,
            s.screen_fixed
        );
    }
}

#[test]
fn the_elongated_strip_is_the_worst_case_and_patches_reduce_it() {
    // Fig. 4: the strip's near end sweeps across the image while its far
    // end hardly moves, which no single similarity follows.
    let bar = measure("elongated", 400, "area");
    let pan = measure("pan", 400, "area");
    let share = |s: &npr_lab::sliding::Sliding| s.tracked / s.screen_fixed;
    assert!(
        share(&bar) > 2.0 * share(&pan),
        "bar slides {:.3} of its motion, the panned cow {:.3}",
        share(&bar),
        share(&pan)
    );
    assert!(
        bar.tracked < bar.screen_fixed,
        "tracking still beats a screen-fixed pattern on the bar"
    );
    // §3.6: four patches, each with its own similarity, follow it better.
    let patched = measure("elongated, 4 patches", 400, "area");
    assert!(
        patched.tracked < 0.8 * bar.tracked,
        "4 patches slide {:.3} px/frame, one pattern {:.3}",
        patched.tracked,
        bar.tracked
    );
}

#[test]
fn patches_reduce_the_sliding_of_the_orbit() {
    // The orbit turns the cow out of the image plane, which one similarity
    // follows worst among the cow's motions; six patches, each with its
    // own (§3.6), follow the parts of the turning body.
    let one = measure("orbit", 400, "area");
    let six = measure("orbit, 6 patches", 400, "area");
    println!(
        "orbit: one pattern {:.3} px/frame, 6 patches {:.3} ({:.0}% of one)",
        one.tracked,
        six.tracked,
        100.0 * six.tracked / one.tracked
    );
    assert!((six.screen_fixed - one.screen_fixed).abs() < 1e-3 * one.screen_fixed);
    assert!(
        six.tracked < 0.9 * one.tracked,
        "{} against {}",
        six.tracked,
        one.tracked
    );
}
