//! What the LSA contour tests share (`lsa_contours.rs`,
//! `lsa_packed_gbuffer.rs`): an example style with text replaced, an
//! analytic scene loaded, targets read back after their passes, and the
//! packed G-buffer layout as replacements of `examples/lsa_contours.npr`.

use super::{gpu, root};
use npr_lab::contours::AnalyticScene;
use npr_runner::{FrameSpec, Renderer, StyleProgram, TargetImage};
use npr_stdlib::reference::ImageF64;

/// An example style with some of its text replaced (parameter defaults,
/// formats), compiled `--schedule naive`: the tests read intermediate
/// targets (`thin.e`, which `auto` computes inside the ink pass, so it is
/// no target there); the output is the same bit for bit under either
/// schedule (`tests/gpu/schedule_equivalence.rs`).
pub fn style(name: &str, replacements: &[(&str, &str)]) -> StyleProgram {
    let path = root().join("examples").join(name);
    let mut text = std::fs::read_to_string(&path).expect("read style");
    for (from, to) in replacements {
        assert!(text.contains(from), "`{from}` not in {name}");
        text = text.replace(from, to);
    }
    let mut sources = npr_diag::SourceMap::new();
    let opts = npr_compiler::CompileOptions {
        schedule: npr_compiler::schedule::Schedule::Naive,
        ..Default::default()
    };
    match npr_compiler::compile_source(name, &text, &root().join("examples"), &mut sources, &opts) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

/// The packed LSA G-buffer in `lsa_contours.npr`: view positions in
/// rgba16float (the precision study, `lsa_gbuffer_precision.rs`, holds them
/// to 1 km), octahedral view normals in rg16float (`oct_encode`), and the
/// operator told so. View space for both, since LSA compares positions with
/// normals (κ's sign, eq. 3) and they must share a frame.
pub const PACKED: &[(&str, &str)] = &[
    (
        "out pos: rgba32float = vec4(position.world, 1.0)",
        "out pos: rgba16float = vec4(position.view, 1.0)",
    ),
    (
        "out nrm: rgba32float = vec4(normal.world, 1.0)",
        "out nrm: rg16float = oct_encode(normal.view)",
    ),
    (
        "eta_min: eta_min, eta_max: eta_max)",
        "eta_min: eta_min, eta_max: eta_max, normal_encoding: octahedral)",
    ),
];

pub fn scene_of(s: &AnalyticScene) -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    s.scene(&mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

pub fn spec(width: u32, height: u32) -> FrameSpec {
    FrameSpec::still(width, height, 0)
}

/// Targets `names` (e.g. "gbuffer.pos") after rendering up to each one's pass.
pub fn targets(
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    size: (u32, u32),
    names: &[&str],
) -> Vec<TargetImage> {
    let mut r = Renderer::new(&gpu().device, &gpu().queue, program, scene).unwrap_or_else(|e| panic!("{e}"));
    names
        .iter()
        .map(|name| {
            let index = program
                .manifest
                .targets
                .iter()
                .position(|t| t.name == *name)
                .unwrap_or_else(|| panic!("no target {name}"));
            r.render_until_target(scene, &spec(size.0, size.1), index)
                .unwrap_or_else(|e| panic!("{name}: {e}"))
        })
        .collect()
}

pub fn output(program: &StyleProgram, scene: &npr_runner::scene::Scene, size: u32) -> TargetImage {
    npr_runner::render_frame(gpu(), program, scene, &spec(size, size)).unwrap_or_else(|e| panic!("render: {e}"))
}

pub fn to_f64(t: &TargetImage) -> ImageF64 {
    ImageF64::new(t.width, t.height, |x, y| t.texel(x, y).map(f64::from))
}

/// The uv of pixel (x, y)'s centre in a w × h image.
pub fn uv(x: u32, y: u32, w: u32, h: u32) -> [f64; 2] {
    [(x as f64 + 0.5) / w as f64, (y as f64 + 0.5) / h as f64]
}
