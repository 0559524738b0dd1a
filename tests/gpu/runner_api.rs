//! The runner as a library: bring your own device and encoder, textures from
//! files and from the generator, `use` of another style, stereo eyes.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Renderer, StyleProgram};
use std::path::{Path, PathBuf};

use crate::common;
use common::{gpu, root};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("runner-api").join(name);
    std::fs::create_dir_all(&dir).expect("scratch");
    dir
}

fn compile_text(text: &str, dir: &Path) -> StyleProgram {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source("test.npr", text, dir, &mut sources, &CompileOptions::default()) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}"),
    }
}

fn scene(path: &str) -> npr_runner::scene::Scene {
    let mut sources = SourceMap::new();
    npr_runner::scene::load_scene(&root().join(path), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn spec(width: u32, height: u32) -> FrameSpec {
    FrameSpec::still(width, height, 0)
}

#[test]
fn bring_your_own_device_and_encoder() {
    // A device created by "the host application", not by npr.
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::VULKAN | wgpu::Backends::GL;
    let instance = wgpu::Instance::new(desc);
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
        .expect("adapter (install mesa-vulkan-drivers)");
    let (device, queue) =
        pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor::default())).expect("device");

    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_file(
        &root().join("examples/toon.npr"),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"));
    let program = compiled.program();
    let scene = scene("examples/scenes/spot.toml");
    let mut r = Renderer::new(&device, &queue, &program, &scene).unwrap_or_else(|e| panic!("{e}"));
    r.prepare(&scene, &spec(64, 48)).expect("prepare");
    let mut encoder = device.create_command_encoder(&Default::default());
    r.encode(&mut encoder);
    queue.submit([encoder.finish()]);
    let ours = r.read_output().expect("read");

    let reference = npr_runner::render_frame(gpu(), &program, &scene, &spec(64, 48)).expect("render");
    assert_eq!((ours.width, ours.height), (64, 48));
    assert_eq!(ours.bytes, reference.bytes, "same frame whoever owns the device");
    // Something was drawn: not every pixel is the clear colour.
    let clear = ours.texel(0, 0);
    assert!((0..48)
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .any(|(x, y)| ours.texel(x, y) != clear));
}

#[test]
fn image_texture_is_read_texel_for_texel() {
    let dir = scratch("image");
    let img = image::RgbaImage::from_fn(16, 8, |x, y| image::Rgba([(x * 16) as u8, (y * 32) as u8, 200, 255]));
    img.save(dir.join("grad.png")).expect("png");
    let program = compile_text(
        "style \"T\"\ntexture grad = image(\"grad.png\", linear) { filter: nearest, wrap: clamp }\npass p: image() {\n  out c: rgba8unorm = grad\n}\noutput p.c\n",
        &dir,
    );
    let out =
        npr_runner::render_frame(gpu(), &program, &scene("examples/scenes/spot.toml"), &spec(16, 8)).expect("render");
    assert_eq!(
        out.to_rgba8(),
        img,
        "a linear texture at its own size comes back unchanged"
    );
}

#[test]
fn srgb_texture_is_decoded_to_linear() {
    let dir = scratch("srgb");
    let img = image::RgbaImage::from_pixel(4, 4, image::Rgba([188, 188, 188, 255]));
    img.save(dir.join("grey.png")).expect("png");
    let program = compile_text(
        "style \"T\"\ntexture grey = image(\"grey.png\", srgb)\npass p: image() {\n  out c: rgba16float = grey\n}\noutput p.c\n",
        &dir,
    );
    let out =
        npr_runner::render_frame(gpu(), &program, &scene("examples/scenes/spot.toml"), &spec(4, 4)).expect("render");
    // sRGB 188/255 is linear 0.5029 (IEC 61966-2-1).
    let expected = ((188.0f64 / 255.0 + 0.055) / 1.055).powf(2.4);
    let got = out.texel(1, 1)[0] as f64;
    assert!((got - expected).abs() < 2e-3, "{got} vs {expected}");
}

#[test]
fn generated_noise_matches_the_cpu_generator() {
    let dir = scratch("noise");
    let program = compile_text(
        "style \"N\"\ntexture n = noise(size: 32, octaves: 3, seed: 5, channels: 2, kind: gradient) { filter: nearest }\npass p: image() {\n  out c: rgba16float = n\n}\noutput p.c\n",
        &dir,
    );
    let out =
        npr_runner::render_frame(gpu(), &program, &scene("examples/scenes/spot.toml"), &spec(32, 32)).expect("render");
    let cpu = npr_runner::texgen::generate(&npr_runner::texgen::NoiseSpec {
        size: 32,
        octaves: 3,
        seed: 5,
        gradient: true,
        channels: 2,
        frequency: 4,
    });
    let mut max: f32 = 0.0;
    for y in 0..32 {
        for x in 0..32 {
            let g = out.texel(x, y);
            let c = cpu.pixels[(y * 32 + x) as usize];
            for ch in 0..2 {
                max = max.max((g[ch] - c[ch]).abs());
            }
        }
    }
    // Stored as rgba16float: half precision, 2^-11 relative.
    assert!(max < 1e-3, "max difference {max}");
}

#[test]
fn use_pulls_in_another_style() {
    let dir = scratch("use");
    std::fs::write(
        dir.join("common.npr"),
        "style \"Common\"\nparam ink: color = #102030\npass base: render(scene) {\n  out color: rgba8unorm = ink\n}\n",
    )
    .expect("write");
    let program = compile_text(
        "style \"Uses\"\nuse \"common.npr\"\npass post: image(base) {\n  out c: rgba8unorm = base.color\n}\noutput post.c\n",
        &dir,
    );
    let names: Vec<&str> = program.manifest.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["base", "post"]);
    let out = npr_runner::render_frame(gpu(), &program, &scene("examples/scenes/spheres.toml"), &spec(32, 32))
        .expect("render");
    let center = out.to_rgba8().get_pixel(16, 28).0;
    assert_eq!(
        center,
        [0x10, 0x20, 0x30, 0xff],
        "the ground plane is drawn in the used style's ink"
    );
}

#[test]
fn stereo_eyes_differ_and_mono_eyes_agree() {
    let dir = scratch("stereo");
    let base = std::fs::read_to_string(root().join("examples/scenes/spot.toml")).expect("scene");
    let stereo = base.replace("far = 50.0", "far = 50.0\nipd = 0.3");
    std::fs::write(dir.join("stereo.toml"), &stereo).expect("write");
    std::fs::create_dir_all(dir.join("../models")).expect("dir");
    std::fs::copy(root().join("examples/models/spot.obj"), dir.join("../models/spot.obj")).expect("copy");
    let mut sources = SourceMap::new();
    let stereo_scene = npr_runner::scene::load_scene(&dir.join("stereo.toml"), &mut sources).expect("scene");
    let mono_scene = scene("examples/scenes/spot.toml");
    let mut compile_sources = SourceMap::new();
    let program = npr_compiler::compile_file(
        &root().join("examples/toon.npr"),
        &mut compile_sources,
        &CompileOptions::default(),
    )
    .expect("compile")
    .program();
    let eye = |s: &npr_runner::scene::Scene, e: u32| {
        npr_runner::render_frame(gpu(), &program, s, &FrameSpec { eye: e, ..spec(48, 48) })
            .expect("render")
            .bytes
    };
    assert_ne!(eye(&stereo_scene, 0), eye(&stereo_scene, 1));
    assert_eq!(eye(&mono_scene, 0), eye(&mono_scene, 1));
}

#[test]
fn time_varying_geometry_is_rebuilt_for_each_frame() {
    // A style that does not read `time`: any change between frames comes
    // from the ocean's vertices, which `Renderer::prepare` rewrites at each
    // frame's time (Age of Sail §6.1 waves).
    let program = compile_text(
        "style \"Height\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(saturate(0.5 + position.y / 4m), saturate(normal.y), 0.0, 1.0)\n  clear: #000000\n}\noutput p.c\n",
        root(),
    );
    let ocean = scene("examples/scenes/ocean.toml");
    let (device, queue) = (&gpu().device, &gpu().queue);
    let mut r = Renderer::new(device, queue, &program, &ocean).expect("renderer");
    let mut at = |time_s: f64| {
        r.render(&ocean, &FrameSpec { time_s, ..spec(64, 64) }).expect("render");
        r.read_output().expect("read").bytes
    };
    let start = at(0.0);
    let later = at(5.0);
    let back = at(0.0);
    let looped = at(20.0);
    let changed = start.chunks(4).zip(later.chunks(4)).filter(|(a, b)| a != b).count();
    assert!(changed > 64 * 64 / 4, "only {changed} pixels changed in 5 s");
    // Rewriting the buffers is exact: back at t = 0, and at t = T, the frame
    // is the first one again, byte for byte.
    assert!(back == start, "t = 0 after t = 5 differs from the first frame");
    assert!(looped == start, "t = 20 s (one period) differs from t = 0");
}
