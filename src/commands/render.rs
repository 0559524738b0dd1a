//! `npr render`: a style (compiled for the scene) or a compiled directory
//! rendered to an image, a frame sequence, or every target (`--dump-passes`).
//! A path-dependent style replays its earlier frames first.

use crate::cli::{RenderArgs, EXIT_INTERNAL, EXIT_OK, EXIT_USER};
use crate::commands::dump::{dump_all_targets, read_all_targets};
use crate::printer::{cannot_write, load_scene_in, style_gpu, Printer};
use compiler::CompileOptions;
use diag::{codes, Diagnostic, SourceMap};
use runner::schedule::FrameRequest;
use runner::{FrameSpec, Gpu, Renderer, RunError, StyleProgram};
use std::path::{Path, PathBuf};

pub fn run(args: RenderArgs, printer: &Printer) -> i32 {
    let RenderArgs {
        style,
        compiled,
        scene,
        out,
        size,
        time,
        frames,
        fps,
        eye,
        dump_passes,
        schedule,
        keep_params,
        set,
        paths,
    } = args;
    let mut sources = SourceMap::new();
    // Without `-o`, `<style>.png` here; said once it is written, so that
    // an earlier error is not preceded by a note about a file never made.
    let defaulted = out.is_none() && dump_passes.is_none();
    let out = match out {
        Some(o) => Some(o),
        None if defaulted => Some(default_output(style.as_deref(), compiled.as_deref())),
        None => None,
    };
    if let Some(o) = &out {
        if let Err(ext) = runner::output::check_image_extension(o) {
            return printer.fail(crate::printer::unsupported_image(o, &ext));
        }
    }
    if let Err(code) = printer
        .check(crate::args::check_size(size))
        .and_then(|()| printer.check(crate::args::check_time(time, fps)))
    {
        return code;
    }
    let scene_name = scene.display().to_string();
    // The root holds the style, or the compiled directory (whose textures
    // were checked when it was compiled), and the scene.
    let compiled_manifest = compiled.as_ref().map(|d| d.join("manifest.json"));
    let paths = match paths.policy(
        style.as_deref().or(compiled_manifest.as_deref()).unwrap_or(&scene),
        Some(&scene),
    ) {
        Ok(p) => p,
        Err(d) => return printer.fail(d),
    };
    let scene = match load_scene_in(&scene, &mut sources, Some(&paths), printer) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if let Err(code) = printer.check(crate::args::check_eye(eye, scene.camera.is_stereo())) {
        return code;
    }
    // Per manifest texture, the `image("…")` naming its file (none for a
    // compiled directory): render-time texture errors point there.
    let mut texture_spans = Vec::new();
    let program = match (compiled, style) {
        (Some(dir), _) => match StyleProgram::load_dir(&dir) {
            Ok(p) => p,
            Err(e) => {
                return printer.fail(
                    Diagnostic::error(codes::BAD_COMPILED_DIR, format!("{}: {e}", dir.display()))
                        .with_help("give a directory written by `npr compile -o DIR`"),
                )
            }
        },
        (None, Some(style)) => {
            // Compile for this scene, so nothing the scene cannot use is run.
            let opts = CompileOptions {
                keep_params,
                scene: Some(scene.summary(&scene_name)),
                paths: Some(paths),
                // Auto unless asked, but naive for `--dump-passes`, which
                // shows every declared target.
                schedule: schedule.map_or(
                    if dump_passes.is_some() {
                        compiler::schedule::Schedule::Naive
                    } else {
                        compiler::schedule::Schedule::Auto
                    },
                    Into::into,
                ),
                ..Default::default()
            };
            let c = match crate::set_params::compile(&style, &set, &mut sources, &opts, printer) {
                Ok(c) => c,
                Err(code) => return code,
            };
            printer.diagnostics(&c.warnings, &sources);
            let texture_errors = crate::texture_check::texture_file_errors(&c, runner::texture_file::Depth::Header);
            if !texture_errors.is_empty() {
                printer.diagnostics(&texture_errors, &sources);
                return EXIT_USER;
            }
            texture_spans = c.texture_spans.clone();
            if dump_passes.is_some() {
                // A pass whose `schedule: recompute` wins even under naive
                // has no target to dump: say so rather than leave it out.
                for e in c.report.entries.iter().filter(|e| e.action == "recomputed") {
                    eprintln!(
                        "note: {} is not stored, so --dump-passes has no image of it: {}",
                        e.what, e.why
                    );
                }
            }
            c.program()
        }
        (None, None) => {
            return printer.fail(Diagnostic::error(codes::USAGE, "give a style or --compiled DIR"));
        }
    };
    printer.diagnostics(&runner::scene_warnings(&program.manifest, &scene), &sources);
    let request = match frames {
        Some((start, end)) => FrameRequest::Range { start, end },
        None => FrameRequest::At { time_s: time },
    };
    let count = runner::schedule::frame_count(request, fps, program.manifest.is_path_dependent());
    if let Err(code) = printer.check(crate::args::check_frame_count(count as usize)) {
        return code;
    }
    // Exactly what this style needs of the device (`Manifest::device_needs`).
    let gpu = match style_gpu(&program.manifest, printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let result = render(
        &gpu,
        &program,
        &scene,
        size,
        time,
        frames,
        fps,
        eye,
        out.as_deref(),
        dump_passes.as_deref(),
    );
    match gpu.watch.check(result).map_err(|e| e.at_texture_spans(&texture_spans)) {
        Ok(()) => {
            if let (true, Some(o)) = (defaulted, &out) {
                eprintln!("note: no `-o` given: wrote {} in the current directory", o.display());
            }
            EXIT_OK
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            if e.is_user_error() {
                EXIT_USER
            } else {
                EXIT_INTERNAL
            }
        }
    }
}

/// `<style>.png` (or `<compiled dir>.png`) in the current directory: what
/// `npr render` writes when `-o` is not given.
fn default_output(style: Option<&Path>, compiled: Option<&Path>) -> PathBuf {
    let stem = style
        .and_then(|s| s.file_stem())
        .or_else(|| compiled.and_then(|d| d.file_name()))
        .map(|s| s.to_string_lossy().into_owned())
        .filter(|s| !s.is_empty() && s != "." && s != "..")
        .unwrap_or_else(|| "render".into());
    PathBuf::from(format!("{stem}.png"))
}

fn frame_path(out: &Path, frame: u32) -> PathBuf {
    let s = out.to_string_lossy();
    if s.contains("{frame}") {
        return PathBuf::from(s.replace("{frame}", &format!("{frame:04}")));
    }
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "frame".into());
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_else(|| "png".into());
    out.with_file_name(format!("{stem}_{frame:04}.{ext}"))
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn render(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &runner::scene::Scene,
    (width, height): (u32, u32),
    time: f64,
    frames: Option<(u32, u32)>,
    fps: f64,
    eye: u32,
    out: Option<&Path>,
    dump: Option<&Path>,
) -> Result<(), RunError> {
    let mut r = Renderer::new(&gpu.device, &gpu.queue, program, scene)?;
    crate::printer::artmap_notes(r.artmap_builds());
    let io = |e: std::io::Error, p: &Path| RunError::User(vec![cannot_write(p, e)]);
    let request = match frames {
        Some((start, end)) => FrameRequest::Range { start, end },
        None => FrameRequest::At { time_s: time },
    };
    let path_dependent = program.manifest.is_path_dependent();
    let schedule = runner::schedule::schedule(request, fps, path_dependent);
    let replayed = schedule.iter().filter(|f| !f.write).count();
    if replayed > 0 {
        eprintln!(
            "note: the style reads `previous(...)` or keeps `state`, so its frames depend on earlier ones: replaying {replayed} frame(s) from frame 0 at {fps} fps"
        );
    }
    let bar = if schedule.len() > 1 {
        let b = indicatif::ProgressBar::new(schedule.len() as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} frames {elapsed_precise} eta {eta}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        Some(b)
    } else {
        None
    };
    for scheduled in &schedule {
        let frame = scheduled.frame;
        r.render(
            scene,
            &FrameSpec {
                width,
                height,
                time_s: scheduled.time_s,
                frame,
                eye,
            },
        )?;
        if !scheduled.write {
            if let Some(b) = &bar {
                b.inc(1);
            }
            continue;
        }
        if let Some(out) = out {
            let path = if frames.is_some() {
                frame_path(out, frame)
            } else {
                out.to_path_buf()
            };
            let img = r.read_output()?;
            runner::output::write_target(&img, &path).map_err(|e| io(e, &path))?;
            if frames.is_none() {
                eprintln!(
                    "wrote {} ({}x{}, {})",
                    path.display(),
                    img.width,
                    img.height,
                    gpu.describe()
                );
            }
        }
        if let Some(b) = &bar {
            b.inc(1);
        }
    }
    if let Some(b) = bar {
        b.finish();
    }
    if let Some(dir) = dump {
        // A path-dependent style's dump is of the last frame rendered (its
        // history intact); others render the requested time afresh.
        let images = match schedule.last().filter(|_| path_dependent) {
            Some(last) => {
                let spec = FrameSpec {
                    width,
                    height,
                    time_s: last.time_s,
                    frame: last.frame,
                    eye,
                };
                read_all_targets(&mut r, scene, &spec)?
            }
            None => dump_all_targets(&mut r, scene, width, height, time, eye)?,
        };
        let written = runner::output::dump_targets(&images, dir).map_err(|e| io(e, dir))?;
        eprintln!("wrote {} files into {}", written.len(), dir.display());
    }
    Ok(())
}
