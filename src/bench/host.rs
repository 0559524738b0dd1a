//! `npr bench host`: the command around `npr_lab::bench_host` (the style
//! compiled with its params kept, as a host runs it; the device; the table;
//! then the time of a frame right after the host adds an object).

use crate::printer::{compile, headless_gpu};
use npr_compiler::CompileOptions;
use npr_diag::exit::{EXIT_INTERNAL, EXIT_OK};
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use std::path::Path;

pub fn run(style: &Path, objects: &[usize], size: u32, (frames, block): (u32, u32), printer: &Printer) -> i32 {
    if let Some(bad) = objects.iter().find(|n| !(1..=10_000).contains(*n)) {
        return printer.fail(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            format!("--objects {bad}: this benchmark draws 1..=10000 objects"),
        ));
    }
    if frames == 0 {
        return printer.fail(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            "--frames 0: time at least one frame",
        ));
    }
    if block == 0 {
        return printer.fail(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            "--block 0: each program runs at least one frame per turn",
        ));
    }
    if let Err(code) = printer.check(npr_diag::sizes::check_size((size, size))) {
        return code;
    }
    let mut sources = SourceMap::new();
    let options = CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    let program = match compile(style, &mut sources, &options, printer) {
        Ok(c) => c.program(),
        Err(code) => return code,
    };
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    match npr_lab::bench_host::rows(&gpu, &program, objects, size, (frames, block)) {
        Ok(rows) => {
            println!(
                "device: {}, {size}x{size}, {}: median CPU time per frame of {frames}, in blocks of {block}, GPU excluded",
                gpu.describe(),
                style.display()
            );
            print!("{}", npr_lab::bench_host::table(&rows));
            // Issue 32: a frame right after the host adds an object.
            let spawns = frames.min(10);
            match npr_lab::bench_host::spawn_row(&gpu, &program, 10, size, spawns) {
                Ok(r) => {
                    println!(
                        "a frame after adding an 11th object: {:.0} µs (median of {spawns}); a steady frame {:.0} µs; \
                         a new runtime's first frame of the 11 (what the addition cost when a scene change built \
                         the renderer anew) {:.0} µs",
                        r.spawn_us, r.steady_us, r.new_runtime_us
                    );
                    EXIT_OK
                }
                Err(e) => {
                    printer.fail(Diagnostic::error(codes::INTERNAL, e.to_string()));
                    EXIT_INTERNAL
                }
            }
        }
        Err(e) if e.is_user_error() => {
            for d in e.diagnostics() {
                printer.fail(d);
            }
            1
        }
        Err(e) => {
            printer.fail(Diagnostic::error(codes::INTERNAL, e.to_string()));
            EXIT_INTERNAL
        }
    }
}
