//! `npr compile`: a style to WGSL, one file per pass, plus manifest.json and
//! the report, written atomically into a directory; or, for `-o FILE.nprb`,
//! one bundle file (`npr_abi::bundle`) with the style's image files in it.

use crate::cli::CompileArgs;
use crate::printer::check_options;
use npr_compiler::{CompileOptions, Compiled};
use npr_diag::exit::EXIT_OK;
use npr_diag::printer::Printer;
use npr_diag::writes::cannot_write;
use npr_diag::{codes, Diagnostic, SourceMap};
use std::path::{Path, PathBuf};

pub fn run(args: CompileArgs, printer: &Printer) -> i32 {
    let CompileArgs {
        style,
        out,
        report,
        keep_params,
        schedule,
        dump_ir,
        time_passes,
        scene,
        set,
        paths,
    } = args;
    let mut sources = SourceMap::new();
    let bundle = out.extension().is_some_and(|e| e == "nprb");
    if bundle && out.is_dir() {
        return printer.fail(
            Diagnostic::error(
                codes::CANNOT_WRITE,
                format!("-o {}: a directory of that name exists", out.display()),
            )
            .with_help("`npr compile -o FILE.nprb` writes one bundle file"),
        );
    }
    if !bundle && out.exists() && !out.is_dir() {
        return printer.fail(
            Diagnostic::error(
                codes::CANNOT_WRITE,
                format!("-o {}: a file of that name exists", out.display()),
            )
            .with_help("`npr compile -o` names a directory, for the WGSL files and manifest.json, or a bundle file ending in `.nprb`"),
        );
    }
    let opts = match check_options(&paths, &style, scene.as_deref(), &mut sources, printer) {
        Ok(o) => CompileOptions {
            keep_params,
            dump_ir,
            schedule: schedule.into(),
            ..o
        },
        Err(code) => return code,
    };
    let c = match crate::set_params::compile(&style, &set, &mut sources, &opts, printer) {
        Ok(c) => c,
        Err(code) => return code,
    };
    printer.diagnostics(&c.warnings, &sources);
    if bundle {
        let bytes = match c.program().to_bundle(|path| std::fs::read(path)) {
            Ok(b) => b,
            // The compiler checked every image file it names; one that
            // vanished since is the only way here.
            Err(e) => {
                return printer.fail(Diagnostic::error(
                    codes::MISSING_TEXTURE,
                    format!("bundling {}: {e}", out.display()),
                ))
            }
        };
        if let Err(e) = npr_runner::output::write_atomic(&out, &bytes) {
            return printer.fail(cannot_write(&out, e));
        }
    } else if let Err(e) = write_compiled(&c, &sources, &out) {
        return printer.fail(cannot_write(&out, e));
    }
    if report {
        print!("{}{}", c.report.render(), c.ranges_text(&sources));
    }
    if time_passes {
        let total: f64 = c.timings.iter().map(|(_, d)| d.as_secs_f64()).sum();
        for (stage, d) in &c.timings {
            println!("{stage:<24} {:>9.3} ms", d.as_secs_f64() * 1e3);
        }
        println!("{:<24} {:>9.3} ms", "total", total * 1e3);
    }
    eprintln!("compiled {} pass(es) into {}", c.shaders.len(), out.display());
    EXIT_OK
}

fn write_compiled(c: &Compiled, sources: &SourceMap, out: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(out)?;
    let manifest = serde_json::to_string_pretty(&c.manifest).map_err(std::io::Error::other)?;
    // The report says what the compiler removed and why, then what it
    // proved of each target's values.
    let report = format!("{}{}", c.report.render(), c.ranges_text(sources));
    let mut files: Vec<(PathBuf, &[u8])> = c
        .shaders
        .iter()
        .map(|(file, wgsl)| (out.join(file), wgsl.as_bytes()))
        .collect();
    files.push((out.join("manifest.json"), manifest.as_bytes()));
    files.push((out.join("report.txt"), report.as_bytes()));
    for (i, (stage, text)) in c.dumps.iter().enumerate() {
        files.push((out.join("ir").join(format!("{i:02}_{stage}.txt")), text.as_bytes()));
    }
    // Synced together: one journal commit rather than one per file (a cold
    // `npr compile` spent 8 of its 18 ms in 14 sequential fsyncs).
    npr_runner::output::write_all_atomic(&files)
}
