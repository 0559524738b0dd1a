//! npr tests its own examples the way a user tests a style: `npr test
//! examples/` runs the golden-image tests declared beside each example in
//! `examples/*.tests.toml` (each rendered as `npr render` renders it, every
//! target checked finite, the output not blank and the same twice, and
//! compared with `examples/golden/` within its declared tolerance).

use crate::common::cli::npr;

/// The tests the examples declare: golden images (were `tests/gpu/golden_images.rs`,
/// and the multi-frame goldens of `pattern_styles.rs`, `compute.rs` and `history.rs`),
/// and each style's temporal coherence bounds (`::coherence`).
const EXPECTED: &[&str] = &[
    "afterimage.npr::coherence",
    "afterimage.npr::orbit",
    "age_of_sail.npr::coherence",
    "age_of_sail.npr::spot",
    "artmap_gallery.npr::coherence",
    "artmap_gallery.npr::gallery",
    "edge_breakup.npr::coherence",
    "edge_breakup.npr::spot",
    "halftone.npr::coherence",
    "halftone.npr::cows_00",
    "halftone.npr::cows_12",
    "halftone.npr::cows_24",
    "halftone.npr::patched_cow_00",
    "halftone.npr::patched_cow_12",
    "halftone.npr::patched_cow_24",
    "hatching.npr::coherence",
    "hatching.npr::cows_00",
    "hatching.npr::cows_12",
    "hatching.npr::cows_24",
    "hatching.npr::patched_cow_00",
    "hatching.npr::patched_cow_12",
    "hatching.npr::patched_cow_24",
    "hidden_lines.npr::boxes",
    "live_contour.npr::coherence",
    "live_contour.npr::spheres",
    "lsa_base.npr::coherence",
    "lsa_base.npr::fandisk",
    "lsa_base.npr::spheres",
    "lsa_base.npr::spot",
    "lsa_contours.npr::coherence",
    "lsa_contours.npr::fandisk",
    "lsa_contours.npr::spheres",
    "lsa_contours.npr::spot",
    "lsa_stereo.npr::sphere_on_plane",
    "lsa_stereo.npr::sphere_on_plane_right_eye",
    "metatexture.npr::coherence",
    "metatexture.npr::spot",
    "object_centroids.npr::coherence",
    "object_centroids.npr::orbit_00",
    "object_centroids.npr::orbit_12",
    "object_centroids.npr::orbit_24",
    "ocean.npr::coherence",
    "ocean.npr::ocean",
    "outline.npr::coherence",
    "outline.npr::spot",
    "overlay_lines.npr::coherence",
    "overlay_lines.npr::spheres",
    "painterly.npr::coherence",
    "painterly.npr::cows_00",
    "painterly.npr::cows_12",
    "painterly.npr::cows_24",
    "rounded_shadows.npr::coherence",
    "rounded_shadows.npr::spot",
    "sobel_outline.npr::coherence",
    "sobel_outline.npr::fandisk",
    "sobel_outline.npr::spheres",
    "sobel_outline.npr::spot",
    "stipple.npr::coherence",
    "stipple.npr::cows_00",
    "stipple.npr::cows_12",
    "stipple.npr::cows_24",
    "stipple.npr::patched_cow_00",
    "stipple.npr::patched_cow_12",
    "stipple.npr::patched_cow_24",
    "technical_lines.npr::technical",
    "toon.npr::coherence",
    "toon.npr::spheres",
    "toon.npr::spot",
    "toon_ramp.npr::coherence",
    "toon_ramp.npr::spheres",
    "toon_ramp.npr::spot",
    "wavy_lines.npr::coherence",
    "wavy_lines.npr::cube",
    "wavy_lines.npr::fandisk",
    "wavy_lines.npr::teapot",
];

#[test]
fn every_example_test_passes_under_npr_test() {
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("npr-test-examples");
    let out = out.to_str().expect("a UTF-8 path");
    let o = npr(&["test", "examples/", "--format", "json", "--out", out]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    let report: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{e}: {stdout}"));
    let mut ids: Vec<String> = report["tests"]
        .as_array()
        .expect("tests")
        .iter()
        .map(|t| {
            t["id"]
                .as_str()
                .expect("id")
                .trim_start_matches("examples/")
                .to_string()
        })
        .collect();
    ids.sort();
    assert_eq!(ids, EXPECTED, "the examples' declared tests");
    let not_passed: Vec<&serde_json::Value> = report["tests"]
        .as_array()
        .expect("tests")
        .iter()
        .filter(|t| t["status"] != "passed")
        .collect();
    assert!(
        not_passed.is_empty(),
        "{not_passed:#?}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(o.status.code(), Some(0));
}
