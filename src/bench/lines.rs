//! `npr bench lines`: the command around `npr_lab::bench_lines` (the lines and
//! LSA styles compiled, the device, the two tables).

use super::{compile_builtin, plot, plotted};
use crate::printer::headless_gpu;
use npr_diag::exit::EXIT_INTERNAL;
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_lab::bench_lines as bench;
use std::path::Path;

pub fn run(segments: &[u32], size: u32, frames: u32, plot: Option<&Path>, printer: &Printer) -> i32 {
    if let Some(bad) = segments.iter().find(|n| !(4..=1024).contains(*n)) {
        return printer.fail(Diagnostic::error(
            codes::BAD_ARGUMENT_VALUE,
            format!("--segments {bad}: a sphere here has 4..=1024 segments"),
        ));
    }
    if let Err(code) = printer.check(npr_diag::sizes::check_size((size, size))) {
        return code;
    }
    let mut sources = SourceMap::new();
    let compile = |name: &str, text: &str, sources: &mut SourceMap| compile_builtin(name, text, sources, printer);
    let silhouettes = match compile(
        "bench_lines.npr",
        &bench::lines_style("silhouettes: true"),
        &mut sources,
    ) {
        Ok(p) => p,
        Err(code) => return code,
    };
    let mut compiled = Vec::new();
    for (name, text) in [
        ("lines base", bench::LINES_BASE.to_string()),
        ("lines straight", bench::lines_style(bench::STRAIGHT)),
        ("lines wavy", bench::lines_style(bench::WAVY)),
    ] {
        match compile(name, &text, &mut sources) {
            Ok(p) => compiled.push(p),
            Err(code) => return code,
        }
    }
    let lsa: Vec<_> = npr_lab::bench_contours::variants()
        .into_iter()
        .filter(|(name, _, _)| *name == "passthrough" || name.starts_with("LSA full (plane"))
        .collect();
    for (name, text, _) in &lsa {
        match compile(name, text, &mut sources) {
            Ok(p) => compiled.push(p),
            Err(code) => return code,
        }
    }
    if compiled.len() != 5 {
        return printer.fail(Diagnostic::error(
            codes::INTERNAL,
            "`npr bench contours` no longer has the passthrough and LSA full variants this benchmark compares with",
        ));
    }
    let methods = bench::Methods {
        bases: vec![&compiled[0], &compiled[3]],
        methods: vec![
            ("lines, straight (1 px, amplitude 0)", &compiled[1], 0),
            ("lines, wavy (2.5 px, 1.5 px every 28 px)", &compiled[2], 0),
            ("LSA full (plane + aa, density 1)", &compiled[4], 1),
        ],
    };
    let gpu = match headless_gpu(printer) {
        Ok(g) => g,
        Err(code) => return code,
    };
    let result = bench::edge_rows(&gpu, &silhouettes, segments, size, frames, |m| eprintln!("{m}"))
        .and_then(|e| bench::classify_rows(&gpu, segments, frames, |m| eprintln!("{m}")).map(|c| (e, c)))
        .and_then(|(e, c)| bench::method_rows(&gpu, &methods, size, frames, |m| eprintln!("{m}")).map(|m| (e, c, m)));
    match result {
        Ok((edges, classify, methods)) => {
            println!("device: {}, fastest of {frames} frames, {size}x{size}", gpu.describe());
            println!("silhouettes of a sphere: strips rebuilt every frame (the sphere turns) or reused:");
            println!("{}", bench::edge_table(&edges));
            println!("silhouette classification, CPU (`EdgeMesh::silhouettes`, f64) against a compute pass (f32, flags read back and unpacked), the sphere turning so every frame classifies anew; chaining follows on the CPU either way:");
            println!("{}", bench::classify_table(&classify));
            println!("lines against LSA contours (base: the lines' kept-depth fill, LSA's G-buffer + a passthrough pass; accuracy within 1 px on the analytic scenes of `npr bench contours`):");
            println!("{}", bench::method_table(&methods));
            let subtitle = format!("{}, {size}x{size}, fastest of {frames} frames", gpu.describe());
            plotted(
                || plot::figures::lines(&edges, &classify, &methods, size, &subtitle),
                plot,
                printer,
            )
        }
        Err(e) => {
            printer.diagnostics(&e.diagnostics(), &sources);
            EXIT_INTERNAL
        }
    }
}
