//! Art-maps and rip-maps (Klein et al. 2000 §4.2) on the hard cases of
//! issue 10: a one-texel source, non-power-of-two sources, and a source at
//! the 16384-texel limit. Each is built through the renderer (the hatching
//! filter on every level), sampled on a plane seen face-on and at a grazing
//! angle into a float target, and every texel read back must be finite and
//! in 0..1; a rip-map whose atlas (twice the source) would pass the limit is
//! refused with E0404, not a crash.

use npr_runner::{FrameSpec, Renderer, RunError};
use std::path::{Path, PathBuf};

use crate::common;
use common::{gpu, root};

fn scratch(name: &str) -> PathBuf {
    let d = root().join("target/npr-test-output/artmap-hard-cases").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("filters")).unwrap();
    std::fs::copy(
        root().join("examples/filters/hatching.npr"),
        d.join("filters/hatching.npr"),
    )
    .unwrap();
    d
}

/// A `w`×`h` source with structure at every scale (a hash of the texel).
fn source_png(path: &Path, w: u32, h: u32) {
    image::RgbaImage::from_fn(w, h, |x, y| {
        let v = ((x.wrapping_mul(2_654_435_761) ^ y.wrapping_mul(40_503)) >> 7) as u8;
        image::Rgba([v, v / 2 + 64, 255 - v, 255])
    })
    .save(path)
    .unwrap();
}

fn style(source: &str, rip: bool) -> String {
    let (decl, read) = if rip {
        (
            format!("texture t = ripmap(image(\"{source}\", srgb), filter: \"filters/hatching.npr\")"),
            "sample_ripmap(t, uv * 3.0)",
        )
    } else {
        (
            format!("texture t = artmap(image(\"{source}\", srgb), filter: \"filters/hatching.npr\", levels: auto) {{ wrap: repeat }}"),
            "sample(t, uv * 3.0)",
        )
    };
    format!("style \"Hard case\"\n{decl}\npass p: render(scene) {{\n  out c: rgba32float = {read}\n}}\noutput p.c\n")
}

/// A plane seen face-on (tilt 0) or at a grazing angle (tilt 80°).
fn plane(tilt_deg: f64) -> npr_runner::scene::Scene {
    let text = format!(
        "[camera]\nposition = [0.0, 0.0, 2.5]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = {{ kind = \"plane\", size = 2.0 }}\nrotate = [{}, 0.0, 0.0]\n",
        90.0 - tilt_deg
    );
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("scene.toml", text.clone());
    npr_runner::scene::parse_scene(&text, file, root()).unwrap_or_else(|d| panic!("{d:?}"))
}

fn build_and_sample(dir: &Path, rip: bool) -> Result<(), RunError> {
    let mut sources = npr_diag::SourceMap::new();
    let compiled = match npr_compiler::compile_source(
        "case.npr",
        &style("src.png", rip),
        dir,
        &mut sources,
        &Default::default(),
    ) {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    };
    let program = compiled.program();
    for tilt in [0.0, 80.0] {
        let scene = plane(tilt);
        let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene)?;
        r.render(&scene, &FrameSpec::still(48, 48, 0))?;
        let img = r.read_output()?;
        for y in 0..img.height {
            for x in 0..img.width {
                let t = img.texel(x, y);
                assert!(
                    t.iter().all(|c| c.is_finite() && (-1e-6..=1.0 + 1e-6).contains(c)),
                    "texel ({x}, {y}) is {t:?} (tilt {tilt}°, rip-map: {rip})"
                );
            }
        }
    }
    Ok(())
}

#[test]
fn a_one_texel_source() {
    let dir = scratch("one-texel");
    source_png(&dir.join("src.png"), 1, 1);
    build_and_sample(&dir, false).expect("art-map of one texel");
    build_and_sample(&dir, true).expect("rip-map of one texel");
}

#[test]
fn non_power_of_two_sources() {
    for (w, h) in [(37, 23), (3, 64), (100, 1)] {
        let dir = scratch(&format!("npot-{w}x{h}"));
        source_png(&dir.join("src.png"), w, h);
        build_and_sample(&dir, false).unwrap_or_else(|e| panic!("art-map {w}x{h}: {e}"));
        build_and_sample(&dir, true).unwrap_or_else(|e| panic!("rip-map {w}x{h}: {e}"));
    }
}

#[test]
fn a_source_at_the_texture_limit() {
    // 16384 × 1: fifteen levels, each filtered; its rip-map's atlas would be
    // 32768 wide, over the limit.
    let dir = scratch("limit");
    source_png(&dir.join("src.png"), 16384, 1);
    build_and_sample(&dir, false).expect("art-map of 16384 x 1");
    match build_and_sample(&dir, true) {
        Err(e) => {
            let diags = e.diagnostics();
            assert!(
                diags.iter().any(|d| d.code == npr_diag::codes::LIMIT_EXCEEDED),
                "a limit error, got {e}: {diags:?}"
            );
        }
        Ok(()) => panic!("a 32768-wide atlas was accepted"),
    }
}
