//! What the embedding tests (`embed_*.rs`) share: one headless device per
//! test binary, the offscreen texture a host would render into, the
//! examples compiled as a host would, and the images a mismatch leaves.

// Each test binary compiles this module and uses a part of it.
#![allow(dead_code)]

use npr_runner::embed::{EmbedError, Frame, StyleRuntime, Target};
use npr_runner::{Gpu, TargetImage};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The device, made once per test binary; a machine without an adapter
/// fails with how to install one.
pub fn gpu() -> &'static Gpu {
    static GPU: OnceLock<Gpu> = OnceLock::new();
    GPU.get_or_init(|| {
        Gpu::headless().unwrap_or_else(|e| {
            panic!("runner tests need a GPU adapter (Mesa's lavapipe: `./setup.sh --tests`, or apt-get install mesa-vulkan-drivers): {e}")
        })
    })
}

/// A host's texture of `format` that the runtime presents into and the test
/// reads back.
pub fn host_target(
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    gpu().device.create_texture(&wgpu::TextureDescriptor {
        label: Some("host target"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats,
    })
}

/// The host's Rgba8Unorm `texture`, read back at its size (waits for the GPU).
pub fn read_host(texture: &wgpu::Texture) -> TargetImage {
    npr_runner::readback::read_texture(
        &gpu().device,
        &gpu().queue,
        texture,
        texture.width(),
        texture.height(),
        npr_abi::Format::Rgba8unorm,
        "host",
    )
    .unwrap_or_else(|e| panic!("read back the host's texture: {e}"))
}

/// `runtime` renders `frame` into `target` in an encoder of its own, which
/// is submitted whatever the answer (as a host's loop submits its frame);
/// the runtime's answer comes back. The GPU work is not waited for.
pub fn render_frame(runtime: &mut StyleRuntime, frame: &Frame, target: Target) -> Result<(), EmbedError> {
    let mut encoder = gpu().device.create_command_encoder(&Default::default());
    let result = runtime.render(&mut encoder, frame, target);
    gpu().queue.submit([encoder.finish()]);
    result
}

/// The repository's `examples/` folder.
pub fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples")
}

/// Compiles `examples/{example}` with its params kept as uniforms (a host
/// sets them at run time); a compile error fails the test with the
/// rendered diagnostic.
pub fn compile(example: &str) -> npr_runner::StyleProgram {
    let mut sources = npr_diag::SourceMap::new();
    let options = npr_compiler::CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    match npr_compiler::compile_file(&examples().join(example), &mut sources, &options) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    }
}

/// Writes `actual`, `expected` and their difference (×8, alpha folded into
/// blue) as `{name}_actual.png`, `{name}_expected.png`, `{name}_diff.png`
/// under the test's temporary `folder`; returns the folder.
pub fn write_mismatch(folder: &str, name: &str, actual: &TargetImage, expected: &TargetImage) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(folder);
    std::fs::create_dir_all(&dir).expect("output folder");
    let diff = TargetImage {
        name: "diff".into(),
        width: actual.width,
        height: actual.height,
        format: npr_abi::Format::Rgba8unorm,
        bytes: actual
            .bytes
            .chunks(4)
            .zip(expected.bytes.chunks(4))
            .flat_map(|(a, b)| {
                let d = |c: usize| a[c].abs_diff(b[c]).saturating_mul(8);
                [d(0), d(1), d(2).max(d(3)), 255]
            })
            .collect(),
    };
    for (suffix, image) in [("actual", actual), ("expected", expected), ("diff", &diff)] {
        npr_runner::output::write_target(image, &dir.join(format!("{name}_{suffix}.png"))).expect("write image");
    }
    dir
}
