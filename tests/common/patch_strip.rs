//! The two-patch strip the §3.6 tests draw on (Breslav et al. 2007): a flat
//! grid facing the camera, two OBJ groups meeting at x = 0 (patch 0 on the
//! left, patch 1 on the right), the scene around it, and the surface point
//! under each pixel (a plane parallel to the image maps to it affinely).
//! Shared by `tests/gpu/patch_blend.rs` and `tests/gpu/patch_blend_styles.rs`.

use super::root;
use std::path::{Path, PathBuf};

pub const W: u32 = 256;
pub const H: u32 = 96;
/// Cells of the strip along x and y, and their side in metres.
pub const CELLS_X: i32 = 16;
pub const CELLS_Y: i32 = 4;
pub const CELL: f64 = 0.25;
/// The camera, 3 m in front of the strip, 40° vertical field of view.
pub const DISTANCE: f64 = 3.0;
pub const FOV_DEG: f64 = 40.0;

/// `target/npr-test-output/patch-blend/<name>`, created.
pub fn scratch(name: &str) -> PathBuf {
    let dir = root().join("target/npr-test-output/patch-blend").join(name);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// The strip as an OBJ: a grid of CELLS_X × CELLS_Y squares centred on the
/// origin in the xy plane, two triangles each (diagonal from lower left to
/// upper right), in two groups split at x = 0.
pub fn strip_obj() -> String {
    let mut text = String::new();
    for j in 0..=CELLS_Y {
        for i in 0..=CELLS_X {
            let x = (i - CELLS_X / 2) as f64 * CELL;
            let y = (j - CELLS_Y / 2) as f64 * CELL;
            text.push_str(&format!("v {x} {y} 0\n"));
        }
    }
    let at = |i: i32, j: i32| j * (CELLS_X + 1) + i + 1;
    for (group, range) in [("left", 0..CELLS_X / 2), ("right", CELLS_X / 2..CELLS_X)] {
        text.push_str(&format!("o {group}\n"));
        for j in 0..CELLS_Y {
            for i in range.clone() {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                text.push_str(&format!("f {a} {b} {c}\nf {a} {c} {d}\n"));
            }
        }
    }
    text
}

/// The scene file: the strip split into its two parts, blended over
/// `rings` rings (`None`: the default).
pub fn strip_scene(dir: &Path, rings: Option<u32>) -> npr_runner::scene::Scene {
    std::fs::write(dir.join("strip.obj"), strip_obj()).expect("obj");
    let rings = rings.map_or(String::new(), |n| format!("blend_rings = {n}\n"));
    let text = format!(
        "background = \"#ffffff\"\n[camera]\nposition = [0.0, 0.0, {DISTANCE}]\ntarget = [0.0, 0.0, 0.0]\nfov = {FOV_DEG}\nnear = 0.5\nfar = 20.0\n\n[light]\ndirection = [0.3, 0.5, 1.0]\n\n[[object]]\nname = \"strip\"\nmesh = \"strip.obj\"\npatches = \"parts\"\n{rings}"
    );
    let path = dir.join(format!("strip_{}.toml", rings.trim().replace([' ', '='], "")));
    std::fs::write(&path, text).expect("scene");
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// The surface point under pixel (x, y)'s centre: a pinhole camera at
/// distance `DISTANCE` looking straight at the strip.
pub fn surface_point(px: u32, py: u32) -> (f64, f64) {
    let k = 2.0 * DISTANCE * (FOV_DEG.to_radians() / 2.0).tan() / H as f64;
    (
        (px as f64 + 0.5 - W as f64 / 2.0) * k,
        (H as f64 / 2.0 - py as f64 - 0.5) * k,
    )
}

/// Half a pixel on the strip, in metres: pixels this close to its border are skipped.
pub fn half_pixel() -> f64 {
    DISTANCE * (FOV_DEG.to_radians() / 2.0).tan() / H as f64
}
