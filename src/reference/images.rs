//! The demo images of the reference: each operator's `npr_stdlib::Demo` style
//! compiled for its scene and rendered headless by the runner, as
//! `npr render` does (the same `npr_compiler::compile_source`, the auto
//! schedule, `npr_runner::Renderer`, path-dependent styles replayed from frame
//! 0), into an 8-bit PNG of `npr_stdlib::ops::DEMO_SIZE`. No GPU is npr doc's
//! failure with the runner's install hint; a demo that does not compile or
//! render is npr's own (internal) error.

use crate::printer::{headless_gpu, load_scene};
use npr_compiler::{CompileError, CompileOptions};
use npr_diag::exit::{EXIT_INTERNAL, EXIT_USER};
use npr_diag::printer::Printer;
use npr_diag::SourceMap;
use npr_runner::schedule::FrameRequest;
use npr_runner::{FrameSpec, Gpu, Renderer};
use npr_stdlib::ops::{Demo, DemoRender, DEMO_SIZE};
use std::path::Path;

/// The frame rate path-dependent demos are replayed at (`npr render`'s default).
const FPS: f64 = 24.0;

/// The path of an operator's image, relative to the reference's directory.
pub fn image_path(op: &str) -> String {
    format!("img/{op}.png")
}

/// Every demo image: (path relative to the reference, PNG bytes), or the
/// exit code with the diagnostics printed. `examples` is the directory the
/// demos' scenes and relative paths are in.
pub fn render_all(examples: &Path, printer: &Printer) -> Result<Vec<(String, Vec<u8>)>, i32> {
    let gpu = headless_gpu(printer)?;
    let mut out = Vec::new();
    for def in npr_stdlib::ops::ALL {
        if let Demo::Render(demo) = def.demo {
            out.push((
                image_path(def.op.name),
                render_one(&gpu, def.op.name, &demo, examples, printer)?,
            ));
        }
    }
    Ok(out)
}

fn render_one(gpu: &Gpu, name: &str, demo: &DemoRender, examples: &Path, printer: &Printer) -> Result<Vec<u8>, i32> {
    let mut sources = SourceMap::new();
    let scene_path = examples.join(demo.scene);
    let scene = load_scene(&scene_path, &mut sources, printer)?;
    let opts = CompileOptions {
        scene: Some(scene.summary(&scene_path.display().to_string())),
        ..Default::default()
    };
    let style_name = format!("demo of {name}");
    let program = match npr_compiler::compile_source(&style_name, demo.style, examples, &mut sources, &opts) {
        Ok(c) => c.program(),
        Err(CompileError::User(d)) => {
            printer.diagnostics(&d, &sources);
            return Err(EXIT_INTERNAL);
        }
        Err(CompileError::Internal(e)) => {
            printer.diagnostics(&[e.to_diagnostic()], &sources);
            return Err(EXIT_INTERNAL);
        }
    };
    let rendered = (|| {
        let mut r = Renderer::new(&gpu.device, &gpu.queue, &program, &scene)?;
        let path_dependent = program.manifest.is_path_dependent();
        let schedule = npr_runner::schedule::schedule(FrameRequest::At { time_s: demo.time_s }, FPS, path_dependent);
        for f in &schedule {
            r.render(
                &scene,
                &FrameSpec {
                    width: DEMO_SIZE.0,
                    height: DEMO_SIZE.1,
                    time_s: f.time_s,
                    frame: f.frame,
                    eye: 0,
                },
            )?;
        }
        r.read_output()
    })();
    let img = match gpu.watch.check(rendered) {
        Ok(img) => img.to_rgba8(),
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            return Err(if e.is_user_error() { EXIT_USER } else { EXIT_INTERNAL });
        }
    };
    encode_png8(&img).map_err(|e| {
        printer.fail(npr_diag::Diagnostic::error(
            npr_diag::codes::INTERNAL,
            format!("cannot encode the demo image of {name}: {e}"),
        ))
    })
}

/// An 8-bit RGBA PNG in memory.
fn encode_png8(img: &image::RgbaImage) -> Result<Vec<u8>, image::ImageError> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out).write_image(
        img.as_raw(),
        img.width(),
        img.height(),
        image::ExtendedColorType::Rgba8,
    )?;
    Ok(out)
}
