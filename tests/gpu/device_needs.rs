//! Device needs past WebGPU's defaults (`Manifest::device_needs`, issue 32)
//! on real devices: a style that needs more than the defaults is refused
//! with E0510, naming the need and the pass, by a device made with exactly
//! the defaults, before its first frame; the device `Gpu::for_style` makes
//! for it renders it, to the same image under both schedules that need
//! different limits.

use crate::common;

use npr_abi::manifest::{DeviceNeed, Feature, Limit};
use npr_runner::{FrameSpec, Gpu, Renderer, RunError};

/// A tiled pass with five live outputs (five storage textures, one past
/// the default of four) that its reader sums; naive, the same pass has
/// five colour attachments of 8 + 8 + 8 + 4 + 16 = 44 bytes per sample
/// (the default is 32).
const FIVE_OUTPUTS: &str = "style \"Five outputs\"
pass g: render(scene) {
  out c: rgba16float = vec4(normal * 0.5 + 0.5, 1.0)
}
pass b: image(g) {
  schedule: tiled
  let v = gaussian(g.c, sigma: 1px, axis: x)
  out o1: rgba8unorm = v
  out o2: rgba8unorm = v * 0.5
  out o3: rgba16float = v
  out o4: r32float = v.r
  out o5: rgba32float = v
}
pass f: image(b) {
  out c: rgba8unorm = (b.o1 + b.o2 + b.o3 + vec4(b.o4) + b.o5) * 0.2
}
output f.c
";

/// A style with nothing past the defaults: `Gpu::for_style` of it is a
/// device with exactly WebGPU's default limits and no feature.
const PLAIN: &str =
    "style \"Plain\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(normal, 1.0)\n}\noutput p.c\n";

fn scene() -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&common::root().join("examples/scenes/spot.toml"), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

/// The E0510 messages of building `program` on `gpu`.
fn refusal(gpu: &Gpu, program: &npr_runner::StyleProgram) -> Vec<String> {
    match Renderer::new(&gpu.device, &gpu.queue, program, &scene()) {
        Ok(_) => panic!("a device without what the style needs built its renderer"),
        Err(RunError::User(d)) => d
            .iter()
            .map(|d| {
                assert_eq!(d.code, npr_diag::codes::DEVICE_LACKS_NEED, "{}", d.message);
                d.message.clone()
            })
            .collect(),
        Err(e) => panic!("E0510 expected, got {e}"),
    }
}

fn render(gpu: &Gpu, program: &npr_runner::StyleProgram) -> Vec<f32> {
    let scene = scene();
    let mut r = Renderer::new(&gpu.device, &gpu.queue, program, &scene).unwrap_or_else(|e| {
        panic!(
            "{}",
            npr_diag::diagnostic::render(&e.diagnostics(), &npr_diag::SourceMap::new(), false)
        )
    });
    r.render(&scene, &FrameSpec::still(48, 48, 0)).expect("render");
    let out = r.read_output().expect("read back");
    (0..out.height)
        .flat_map(|y| (0..out.width).map(move |x| (x, y)))
        .flat_map(|(x, y)| out.texel(x, y))
        .collect()
}

fn need(pass: &str, limit: Limit, value: u64) -> DeviceNeed {
    DeviceNeed::Limit {
        pass: pass.into(),
        limit,
        value,
    }
}

#[test]
fn a_style_past_the_defaults_is_refused_by_a_default_device_and_renders_on_its_own() {
    let default_device = Gpu::for_style(&common::compile_text(PLAIN).manifest).expect("a default device");
    assert_eq!(
        default_device.device.limits().max_storage_textures_per_shader_stage,
        4,
        "for_style of a style without needs asks for WebGPU's defaults"
    );
    let tiled = common::compile_text(FIVE_OUTPUTS);
    assert_eq!(
        tiled.manifest.device_needs,
        [need("b", Limit::MaxStorageTexturesPerShaderStage, 5)]
    );
    let naive = common::compile_text(&FIVE_OUTPUTS.replace("  schedule: tiled\n", "  schedule: naive\n"));
    assert_eq!(
        naive.manifest.device_needs,
        [need("b", Limit::MaxColorAttachmentBytesPerSample, 44)]
    );

    // Refused before any pipeline is built, with the need and the pass.
    let messages = refusal(&default_device, &tiled);
    assert_eq!(messages.len(), 1, "{messages:?}");
    assert!(
        messages[0].contains("pass `b`")
            && messages[0].contains("`maxStorageTexturesPerShaderStage` of at least 5")
            && messages[0].contains("this device allows 4"),
        "{}",
        messages[0]
    );
    let messages = refusal(&default_device, &naive);
    assert!(
        messages[0].contains("pass `b`") && messages[0].contains("`maxColorAttachmentBytesPerSample` of at least 44"),
        "{}",
        messages[0]
    );

    // On the device made for each: rendered, and the same image.
    let tiled_gpu = Gpu::for_style(&tiled.manifest).expect("lavapipe allows 5 storage textures");
    assert_eq!(tiled_gpu.device.limits().max_storage_textures_per_shader_stage, 5);
    let naive_gpu = Gpu::for_style(&naive.manifest).expect("lavapipe allows 44 bytes per sample");
    let (a, b) = (render(&tiled_gpu, &tiled), render(&naive_gpu, &naive));
    assert_eq!(a, b, "the tiled and naive schedules give the same image");
    let lit = a.chunks(4).filter(|t| t[0] > 0.05 && t[0] < 0.95).count();
    assert!(lit > 48 * 48 / 10, "the mesh shows ({lit} mid-grey pixels)");
}

#[test]
fn a_feature_the_device_lacks_is_refused_naming_it_and_its_pass() {
    // No style needs an optional feature today (32-bit float targets are
    // read unfiltered and never blended), so the need is written into a
    // compiled manifest: what a manifest from a later compiler may hold.
    let mut program = common::compile_text(PLAIN);
    program.manifest.device_needs.push(DeviceNeed::Feature {
        pass: "p".into(),
        feature: Feature::Float32Filterable,
    });
    let gpu = Gpu::for_style(&common::compile_text(PLAIN).manifest).expect("a default device");
    let messages = refusal(&gpu, &program);
    assert_eq!(messages.len(), 1, "{messages:?}");
    assert!(
        messages[0].contains("pass `p` needs the WebGPU feature `float32-filterable`"),
        "{}",
        messages[0]
    );
}
