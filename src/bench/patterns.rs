//! `npr bench patterns`: the command around `npr_lab::bench_patterns` (limits,
//! compiling the tracker for each sample count, the device, the table) and
//! `npr_lab::sliding` (the sliding of each pattern placement and tracker variant).

use super::{compile_builtin, plot, plotted};
use crate::printer::headless_gpu;
use npr_diag::exit::EXIT_INTERNAL;
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_runner::RunError;
use std::path::Path;

pub fn run(samples: &[u32], objects: &[usize], frames: u32, plot: Option<&Path>, printer: &Printer) -> i32 {
    if let Some(bad) = samples
        .iter()
        .find(|n| **n == 0 || **n > npr_abi::manifest::MAX_SAMPLES_PER_OBJECT)
    {
        return printer.fail(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!(
                "{bad} samples per object is outside 1..={}",
                npr_abi::manifest::MAX_SAMPLES_PER_OBJECT
            ),
        ));
    }
    if let Some(bad) = objects.iter().find(|n| **n == 0 || **n > 1000) {
        return printer.fail(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("object count {bad} is outside 1..=1000"),
        ));
    }
    let sources = std::cell::RefCell::new(SourceMap::new());
    let null = match compile_builtin(
        "null.npr",
        npr_lab::bench_patterns::NULL_SHADE,
        &mut sources.borrow_mut(),
        printer,
    ) {
        Ok(p) => p,
        Err(code) => return code,
    };
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let compile = |text: &str| {
        compile_builtin("patterns.npr", text, &mut sources.borrow_mut(), printer)
            .map_err(|_| RunError::Internal("the benchmark's tracker style does not compile".into()))
    };
    let costs = match npr_lab::bench_patterns::run(
        &gpu,
        crate::bundled::TRACKER,
        &null,
        compile,
        (samples, objects),
        frames,
        |m| eprintln!("{m}"),
    ) {
        Ok(rows) => {
            println!(
                "device: {}, {}², median of {frames} interleaved frames (wall clock)",
                gpu.describe(),
                npr_lab::bench_patterns::SIZE
            );
            println!("{}", npr_lab::bench_patterns::table(&rows));
            rows
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources.borrow());
            return EXIT_INTERNAL;
        }
    };
    // Sliding (§4, Fig. 4): px per frame between the pattern's and the
    // surface's motion, per placement and tracker variant.
    // `examples/scenes` here, or the copy built into npr (`crate::bundled`).
    let scenes_dir = match crate::bundled::resolve(Path::new("examples/scenes")) {
        Ok(d) => d,
        Err(e) => return printer.fail(npr_diag::writes::cannot_write(&std::env::temp_dir(), e)),
    };
    match npr_lab::sliding::run(&gpu, crate::bundled::TRACKER, compile, &scenes_dir, |m| {
        eprintln!("{m}")
    }) {
        Ok(rows) => {
            println!(
                "sliding, px/frame over covered pixels ({}×{}, {} frames at 24 fps; % of screen-fixed):",
                npr_lab::sliding::SIZE.0,
                npr_lab::sliding::SIZE.1,
                npr_lab::sliding::FRAMES
            );
            println!("{}", npr_lab::sliding::table(&rows));
            let subtitle = format!(
                "{}, {}², median of {frames} interleaved frames (wall clock)",
                gpu.describe(),
                npr_lab::bench_patterns::SIZE
            );
            plotted(|| plot::figures::patterns(&costs, &rows, &subtitle), plot, printer)
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources.borrow());
            EXIT_INTERNAL
        }
    }
}
