//! What the art-map tests share (`tests/gpu/artmaps.rs`, `tests/gpu/artmap_cache.rs`):
//! a scratch directory, compiling a style text, a scene from text, a grey
//! source image, and one frame through the runner.

use super::{gpu, root};
use npr_runner::{FrameSpec, Renderer};
use std::path::{Path, PathBuf};

pub fn scratch(name: &str) -> PathBuf {
    let d = root().join("target/npr-test-output/artmaps").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

pub fn compile(text: &str, dir: &Path) -> npr_runner::StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    match npr_compiler::compile_source("case.npr", text, dir, &mut sources, &Default::default()) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    }
}

pub fn scene(text: &str) -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("scene.toml", text);
    npr_runner::scene::parse_scene(text, file, root())
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// A `size`² grey PNG (sRGB 0.5): the source of the art-maps below.
pub fn grey_png(path: &Path, size: u32, value: u8) {
    image::RgbaImage::from_pixel(size, size, image::Rgba([value, value, value, 255]))
        .save(path)
        .unwrap();
}

pub fn render(
    program: &npr_runner::StyleProgram,
    scene: &npr_runner::scene::Scene,
    size: u32,
) -> npr_runner::TargetImage {
    let g = gpu();
    let mut r = Renderer::new(&g.device, &g.queue, program, scene).unwrap_or_else(|e| panic!("{e:?}"));
    r.render(
        scene,
        &FrameSpec {
            width: size,
            height: size,
            time_s: 0.0,
            frame: 0,
            eye: 0,
        },
    )
    .unwrap();
    r.read_output().unwrap()
}
