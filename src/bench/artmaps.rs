//! `npr bench artmaps`: the command around `npr_lab::bench_artmaps` (the
//! shipped filters compiled, the sampling variants compiled against
//! `examples/`, the device, the two tables).

use super::{compile_builtin_in, plot, plotted};
use crate::printer::{compile, headless_gpu, load_scene};
use npr_compiler::CompileOptions;
use npr_diag::exit::EXIT_INTERNAL;
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_lab::bench_artmaps as bench;
use std::path::Path;

/// The filter styles shipped in `examples/filters/`.
const FILTERS: [&str; 3] = ["hatching", "watercolor", "ink_blot"];

pub fn run(sizes: &[u32], size: (u32, u32), frames: u32, plot: Option<&Path>, printer: &Printer) -> i32 {
    if let Some(bad) = sizes.iter().find(|s| !(1..=4096).contains(*s)) {
        return printer.fail(Diagnostic::error(
            codes::LIMIT_EXCEEDED,
            format!("source size {bad} is outside 1..=4096 (a rip-map's atlas is twice the source)"),
        ));
    }
    // `examples/` here, or the copy built into npr (`crate::bundled`).
    let examples = match crate::bundled::resolve(Path::new("examples")) {
        Ok(e) => e,
        Err(e) => return printer.fail(npr_diag::writes::cannot_write(&std::env::temp_dir(), e)),
    };
    let mut sources = SourceMap::new();
    let mut filters = Vec::new();
    for name in FILTERS {
        let path = examples.join("filters").join(format!("{name}.npr"));
        match compile(&path, &mut sources, &CompileOptions::default(), printer) {
            Ok(c) => filters.push((name.to_string(), c.program())),
            Err(code) => return code,
        }
    }
    let mut programs = Vec::new();
    for v in &bench::SAMPLE_VARIANTS {
        match compile_builtin_in(
            "bench_artmaps.npr",
            &bench::sample_style(v),
            &examples,
            &mut sources,
            printer,
        ) {
            Ok(p) => programs.push(p),
            Err(code) => return code,
        }
    }
    let scene = match load_scene(&examples.join("scenes/gallery.toml"), &mut sources, printer) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let built = bench::build_rows(&gpu, &filters, sizes, |m| eprintln!("{m}"));
    let sampled = built.and_then(|b| bench::sample_rows(&gpu, &programs, &scene, size, frames).map(|s| (b, s)));
    match sampled {
        Ok((build, sample)) => {
            println!("device: {}", gpu.describe());
            println!("art-map and rip-map builds (cache bypassed; wall clock, GPU waited for):");
            println!("{}", bench::build_table(&build));
            println!(
                "sampling on examples/scenes/gallery.toml at {}x{} (fastest of {frames} interleaved frames):",
                size.0, size.1
            );
            println!("{}", bench::sample_table(&sample));
            let subtitle = format!("{}, cache bypassed, wall clock with the GPU waited for", gpu.describe());
            plotted(|| plot::figures::artmaps(&build, &subtitle), plot, printer)
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            EXIT_INTERNAL
        }
    }
}
