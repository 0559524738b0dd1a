//! `npr render`: a style (compiled for the scene) or a compiled directory
//! rendered to an image, a frame sequence, or every target (`--dump-passes`).
//! A path-dependent style replays its earlier frames first.

use crate::cli::RenderArgs;
use crate::commands::checkpoints::Checkpoints;
use crate::commands::dump::dump_all_targets;
use crate::commands::frame_sink::{self, FrameSink, OutputKind};
use crate::commands::render_inputs::{self, InputArgs, InputFrames};
use crate::printer::{load_scene_in, style_gpu};
use npr_compiler::CompileOptions;
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK, EXIT_USER};
use npr_diag::printer::Printer;
use npr_diag::writes::cannot_write;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_runner::schedule::FrameRequest;
use npr_runner::{FrameSpec, Gpu, Renderer, RunError, StyleProgram};
use std::path::{Path, PathBuf};

pub fn run(args: RenderArgs, printer: &Printer) -> i32 {
    let RenderArgs {
        style,
        compiled,
        scene,
        input,
        inputs,
        map,
        out,
        size,
        time,
        frames,
        chunk,
        fps,
        eye,
        dump_passes,
        layers,
        checkpoints,
        checkpoint_every,
        schedule,
        keep_params,
        set,
        paths,
    } = args;
    let mut sources = SourceMap::new();
    let frames = match crate::frame_range::resolve(frames.as_deref(), chunk.as_deref(), &mut sources) {
        Ok(f) => f,
        Err(d) => {
            printer.diagnostics(&[d], &sources);
            return EXIT_USER;
        }
    };
    // Without `-o`, `<style>.png` here (`.exr` with --layers); said once it
    // is written, so that an earlier error is not preceded by a note about
    // a file never made. With --dump-passes or --checkpoints alone, what
    // is asked for is those (a farm's first pass writes only checkpoints).
    let defaulted = out.is_none() && dump_passes.is_none() && checkpoints.is_none();
    let out = match out {
        Some(o) => Some(o),
        None if defaulted => Some(default_output(style.as_deref(), compiled.as_deref(), layers)),
        None => None,
    };
    // A bad output (or a missing video encoder) is found before anything runs.
    let out_kind = match frame_sink::check_or_exit(out.as_deref(), layers, frames.is_some(), printer) {
        Ok(k) => k,
        Err(code) => return code,
    };
    if let Err(code) = printer
        .check(size.map_or(Ok(()), npr_diag::sizes::check_size))
        .and_then(|()| printer.check(npr_diag::sizes::check_time(time, fps)))
    {
        return code;
    }
    let input_args = InputArgs {
        input: &input,
        inputs: inputs.as_deref(),
        map: &map,
    };
    let scene_path = scene;
    let scene_name = scene_path
        .as_ref()
        .map_or_else(|| "no scene".to_string(), |s| s.display().to_string());
    // The root holds the style, or the compiled directory (whose textures
    // were checked when it was compiled), and the scene.
    let compiled_manifest = compiled.as_ref().map(|d| d.join("manifest.json"));
    let paths = match paths.policy(
        style
            .as_deref()
            .or(compiled_manifest.as_deref())
            .or(scene_path.as_deref())
            .unwrap_or(Path::new(".")),
        scene_path.as_deref(),
    ) {
        Ok(p) => p,
        Err(d) => return printer.fail(d),
    };
    // Without a scene (a style over host inputs only): no objects, and no
    // camera to turn normals between spaces.
    let scene = match &scene_path {
        Some(path) => match load_scene_in(path, &mut sources, Some(&paths), printer) {
            Ok(s) => s,
            Err(code) => return code,
        },
        None => npr_runner::scene::Scene::empty(),
    };
    if let Err(code) = printer.check(crate::args::check_eye(eye, scene.camera.is_stereo())) {
        return code;
    }
    // Per manifest texture, the `image("…")` naming its file (none for a
    // compiled directory): render-time texture errors point there.
    let mut texture_spans = Vec::new();
    let program = match (compiled, style) {
        (Some(dir), _) => match StyleProgram::load(&dir) {
            Ok(p) => p,
            Err(e) => {
                return printer.fail(
                    Diagnostic::error(codes::BAD_COMPILED_DIR, format!("{}: {e}", dir.display()))
                        .with_help("give a directory written by `npr compile -o DIR`, or a bundle written by `npr compile -o FILE.nprb`"),
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
                    if dump_passes.is_some() || layers {
                        npr_compiler::schedule::Schedule::Naive
                    } else {
                        npr_compiler::schedule::Schedule::Auto
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
            let texture_errors = npr_test::texture_files::texture_file_errors(&c, npr_runner::texture_file::Depth::Header);
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
    printer.diagnostics(&npr_runner::scene_warnings(&program.manifest, &scene), &sources);
    if scene_path.is_none() && program.manifest.passes.iter().any(|p| !p.kind.is_image()) {
        return printer.fail(
            Diagnostic::error(codes::USAGE, "the style draws a scene, and no --scene was given")
                .with_help("give the scene its render passes draw: `--scene scene.toml`"),
        );
    }
    let request = match frames {
        Some((start, end)) => FrameRequest::Range { start, end },
        None => FrameRequest::At { time_s: time },
    };
    let count = npr_runner::schedule::frame_count(request, fps, program.manifest.is_path_dependent());
    if let Err(code) = printer.check(npr_diag::sizes::check_frame_count(count as usize)) {
        return code;
    }
    // Host inputs, read and converted (those of the first frame to render,
    // for a sequence) before anything renders.
    let first = npr_runner::schedule::schedule(request, fps, program.manifest.is_path_dependent())
        .first()
        .map_or((0, time), |f| (f.frame, f.time_s));
    let camera = scene_path.as_ref().map(|_| &scene.camera);
    let host = match InputFrames::new(&program.manifest, &input_args, camera, first.0, first.1) {
        Ok(h) => h,
        Err(d) => return printer.fail(d),
    };
    let size = match render_inputs::frame_size(host.first(), size) {
        Ok(s) => s,
        Err(d) => return printer.fail(d),
    };
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
        out.as_deref().zip(out_kind),
        dump_passes.as_deref(),
        checkpoints.as_deref().map(|dir| (dir, checkpoint_every)),
        &host,
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

/// `<style>.png` (or `<compiled dir>.png`; `.exr` for --layers) in the
/// current directory: what `npr render` writes when `-o` is not given.
fn default_output(style: Option<&Path>, compiled: Option<&Path>, layers: bool) -> PathBuf {
    let stem = style
        .and_then(|s| s.file_stem())
        .or_else(|| compiled.and_then(|d| d.file_name()))
        .map(|s| s.to_string_lossy().into_owned())
        .filter(|s| !s.is_empty() && s != "." && s != "..")
        .unwrap_or_else(|| "render".into());
    PathBuf::from(format!("{stem}.{}", if layers { "exr" } else { "png" }))
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn render(
    gpu: &Gpu,
    program: &StyleProgram,
    scene: &npr_runner::scene::Scene,
    (width, height): (u32, u32),
    time: f64,
    frames: Option<(u32, u32)>,
    fps: f64,
    eye: u32,
    out: Option<(&Path, OutputKind)>,
    dump: Option<&Path>,
    checkpoints: Option<(&Path, Option<u32>)>,
    inputs: &InputFrames,
) -> Result<(), RunError> {
    let mut r = Renderer::new_with_inputs(&gpu.device, &gpu.queue, program, scene, inputs.first())?;
    crate::printer::artmap_notes(r.artmap_builds());
    let io = |e: std::io::Error, p: &Path| RunError::User(vec![cannot_write(p, e)]);
    let request = match frames {
        Some((start, end)) => FrameRequest::Range { start, end },
        None => FrameRequest::At { time_s: time },
    };
    let path_dependent = program.manifest.is_path_dependent();
    let mut schedule = npr_runner::schedule::schedule(request, fps, path_dependent);
    let checkpoints = match (checkpoints, frames) {
        (Some((dir, every)), Some((start, end))) if path_dependent => {
            let c = Checkpoints::new(dir, program, scene, (width, height), fps, every, end);
            let resumed = c.resume(&mut r, start)?;
            schedule.retain(|f| f.frame >= resumed);
            Some(c)
        }
        (Some(_), _) => {
            eprintln!("note: the style's frames do not depend on earlier ones, so it needs no checkpoints");
            if out.is_none() && dump.is_none() {
                // A checkpoint pass (no output) of such a style has nothing to do.
                return Ok(());
            }
            None
        }
        (None, _) => None,
    };
    // A sequence's missing frames and sizes, before the first is rendered.
    let user = |d| RunError::User(vec![d]);
    if inputs.is_sequence() {
        let frames: Vec<u32> = schedule.iter().map(|f| f.frame).collect();
        inputs.check_frames(&frames).map_err(user)?;
    }
    let replayed = schedule.iter().filter(|f| !f.write).count();
    if replayed > 0 {
        eprintln!(
            "note: the style reads `previous(...)` or keeps `state`, so its frames depend on earlier ones: replaying {replayed} frame(s) from frame {} at {fps} fps",
            schedule.first().map_or(0, |f| f.frame)
        );
    }
    // Opened before the first frame: a video's encoder starts now.
    let mut sink = match out {
        Some((path, kind)) => Some(FrameSink::open(path, kind, frames.is_some(), (width, height), fps)?),
        None => None,
    };
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
        // Every input of the frame read before it renders: a frame is
        // written only from inputs that all loaded.
        if let Some(next) = inputs.frame(frame, scheduled.time_s).map_err(user)? {
            r.set_inputs(&next)?;
        }
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
        if let Some(c) = &checkpoints {
            c.after(&r, scheduled)?;
        }
        if !scheduled.write {
            if let Some(b) = &bar {
                b.inc(1);
            }
            continue;
        }
        let spec = FrameSpec {
            width,
            height,
            time_s: scheduled.time_s,
            frame,
            eye,
        };
        if let Some((path, w, h)) = sink
            .as_mut()
            .map(|s| s.frame(&mut r, scene, &spec))
            .transpose()?
            .flatten()
        {
            eprintln!("wrote {} ({w}x{h}, {})", path.display(), gpu.describe());
        }
        if let Some(b) = &bar {
            b.inc(1);
        }
    }
    if let Some(b) = bar {
        b.finish();
    }
    if let Some(sink) = sink {
        sink.finish()?;
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
                r.read_all_targets(scene, &spec)?
            }
            None => dump_all_targets(&mut r, scene, width, height, time, eye)?,
        };
        let written = npr_runner::output::dump_targets(&images, dir).map_err(|e| io(e, dir))?;
        eprintln!("wrote {} files into {}", written.len(), dir.display());
    }
    Ok(())
}
