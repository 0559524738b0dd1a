//! `npr watch`: the headless twin of `npr studio`. It renders the style once,
//! then again on every change to the style, what it `use`s, the scene, and
//! the textures and meshes they name, writing `-o` atomically each time
//! through the same code as `npr render`. A bad save prints its
//! diagnostics and keeps the last good image; fixing it renders again. It
//! never exits on a bad save (nor on a panic, which is reported as E9001).

use npr_diag::exit::EXIT_INTERNAL;
use npr_diag::printer::Printer;
use npr_diag::SourceMap;
use npr_live::build::{self, Inputs};
use npr_live::guard;
use npr_live::watcher::{cannot_watch, FileWatcher};
use std::path::PathBuf;
use std::sync::mpsc;

/// What `npr watch` renders, from its arguments.
pub struct WatchArgs {
    pub inputs: Inputs,
    pub out: PathBuf,
    pub size: (u32, u32),
    pub time: f64,
    pub fps: f64,
    pub eye: u32,
}

/// Run until interrupted; returns only when watching itself fails.
pub fn run(args: WatchArgs, printer: &Printer) -> i32 {
    if let Err(d) =
        npr_diag::sizes::check_size(args.size).and_then(|()| npr_diag::sizes::check_time(args.time, args.fps))
    {
        return printer.fail(d);
    }
    let mut gpu = match crate::printer::headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let (tx, rx) = mpsc::channel::<Vec<PathBuf>>();
    let mut watcher = match FileWatcher::new(move |files| {
        let _ = tx.send(files);
    }) {
        Ok(w) => w,
        Err(e) => return printer.fail(cannot_watch(e)),
    };
    let mut last_good: Vec<PathBuf> = Vec::new();
    for build_no in 1.. {
        let watched = guard::catch(|| once(&args, &gpu, printer, &mut last_good)).unwrap_or_else(|panic| {
            printer.diagnostics(&[guard::panic_diagnostic(&panic)], &SourceMap::new());
            last_good.clone()
        });
        // A lost device (E0509, reported by that build) is made again for the next one.
        if gpu.watch.lost().is_some() {
            match crate::printer::headless_gpu(printer) {
                Ok(g) => gpu = g,
                Err(code) => return code,
            }
        }
        let count = watched.len();
        watcher.set_files(watched);
        eprintln!("watch: build {build_no} done; watching {count} file(s) for changes (Ctrl-C stops)");
        let Ok(mut changed) = rx.recv() else {
            return printer.fail(cannot_watch("the file watcher stopped".into()));
        };
        // Saves that landed during the build are one more build, not several.
        while let Ok(more) = rx.try_recv() {
            changed.extend(more);
        }
        changed.sort();
        changed.dedup();
        let names: Vec<String> = changed.iter().map(|p| p.display().to_string()).collect();
        eprintln!("watch: changed: {}", names.join(", "));
    }
    EXIT_INTERNAL
}

/// One build and render; the files to watch next.
fn once(args: &WatchArgs, gpu: &npr_runner::Gpu, printer: &Printer, last_good: &mut Vec<PathBuf>) -> Vec<PathBuf> {
    let built = match build::build(&args.inputs, &[]) {
        Ok(b) => b,
        Err(failed) => {
            printer.diagnostics(&failed.diagnostics, &failed.sources);
            eprintln!("watch: kept the last good image; fix the error and save");
            let mut files = build::dependencies(&args.inputs, &failed.sources, None);
            files.extend(last_good.iter().cloned());
            return files;
        }
    };
    printer.diagnostics(&built.warnings(), &built.sources);
    let files = build::dependencies(&args.inputs, &built.sources, Some(&built));
    *last_good = files.clone();
    if let Err(d) = crate::args::check_eye(args.eye, built.scene.camera.is_stereo()) {
        printer.diagnostics(&[d], &SourceMap::new());
        return files;
    }
    let program = built.compiled.program();
    let rendered = crate::commands::render::render(
        gpu,
        &program,
        &built.scene,
        args.size,
        args.time,
        None,
        args.fps,
        args.eye,
        Some((args.out.as_path(), crate::commands::frame_sink::OutputKind::Image)),
        None,
        None,
        &crate::commands::render_inputs::InputFrames::none(),
    );
    let rendered = gpu
        .watch
        .check(rendered)
        .map_err(|e| e.at_texture_spans(&built.compiled.texture_spans));
    if let Err(e) = rendered {
        printer.diagnostics(&e.diagnostics(), &built.sources);
        eprintln!("watch: kept the last good image; fix the error and save");
    }
    files
}
