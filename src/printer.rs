//! The steps every command shares (compile, load a scene, open the GPU)
//! turned into an exit code once their diagnostics are printed
//! (`npr_diag::printer::Printer`).

use crate::path_args::PathArgs;
use npr_compiler::{CompileError, CompileOptions, Compiled};
use npr_diag::exit::{EXIT_INTERNAL, EXIT_USER};
use npr_diag::printer::Printer;
use npr_diag::{codes, Diagnostic, SourceMap};
use npr_runner::Gpu;
use std::path::Path;

/// E0503 for an output image whose extension npr cannot write.
pub(crate) fn unsupported_image(path: &Path, ext: &str) -> Diagnostic {
    let list = npr_runner::output::IMAGE_EXTENSIONS
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(" or ");
    Diagnostic::error(
        codes::CANNOT_WRITE,
        format!("cannot write {}: npr does not write `.{ext}` images", path.display()),
    )
    .with_help(format!(
        "name the output {list}: .png (8 or 16 bits per channel, as the output's format) or .exr (32-bit float); with --frames, a .mp4, .webm or .gif is one video"
    ))
}

pub(crate) fn compile(
    style: &Path,
    sources: &mut SourceMap,
    opts: &CompileOptions,
    printer: &Printer,
) -> Result<Compiled, i32> {
    report_compile(npr_compiler::compile_file(style, sources, opts), sources, printer)
}

/// Print a failed compile's diagnostics (and the rejected WGSL of an
/// internal error); the error is the exit code.
pub(crate) fn report_compile(
    result: Result<Compiled, CompileError>,
    sources: &SourceMap,
    printer: &Printer,
) -> Result<Compiled, i32> {
    match result {
        Ok(c) => Ok(c),
        Err(CompileError::User(diags)) => {
            printer.diagnostics(&diags, sources);
            Err(EXIT_USER)
        }
        Err(CompileError::Internal(e)) => {
            printer.diagnostics(&[e.to_diagnostic()], sources);
            if let Some(w) = &e.wgsl {
                eprintln!("--- generated WGSL ---\n{w}");
            }
            Err(EXIT_INTERNAL)
        }
    }
}

/// A headless GPU for whichever style comes, or the exit code after
/// saying why there is none.
pub(crate) fn headless_gpu(printer: &Printer) -> Result<Gpu, i32> {
    Gpu::headless().map_err(|e| printer.fail(e.to_diagnostic()))
}

/// A headless GPU with exactly what `manifest` needs beyond WebGPU's
/// defaults, or the exit code after saying why there is none (E0510 for
/// each need the adapter lacks, with its pass).
pub(crate) fn style_gpu(manifest: &npr_abi::Manifest, printer: &Printer) -> Result<Gpu, i32> {
    Gpu::for_style(manifest).map_err(|e| {
        printer.diagnostics(&e.diagnostics(), &SourceMap::new());
        EXIT_USER
    })
}

/// Load a scene, or print its diagnostics and give the user-error exit code.
pub(crate) fn load_scene(
    path: &Path,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<npr_runner::scene::Scene, i32> {
    load_scene_in(path, sources, None, printer)
}

/// [`load_scene`] under a paths policy (`npr_diag::paths`).
pub(crate) fn load_scene_in(
    path: &Path,
    sources: &mut SourceMap,
    paths: Option<&npr_diag::paths::PathPolicy>,
    printer: &Printer,
) -> Result<npr_runner::scene::Scene, i32> {
    npr_runner::scene::load_scene_in(path, sources, paths).map_err(|d| {
        printer.diagnostics(&d, sources);
        EXIT_USER
    })
}

/// Load a scene only for what the compiler may know of it (its tags).
pub(crate) fn load_scene_summary(
    path: &Path,
    sources: &mut SourceMap,
    paths: Option<&npr_diag::paths::PathPolicy>,
) -> Result<npr_abi::SceneSummary, Vec<Diagnostic>> {
    npr_runner::scene::load_scene_in(path, sources, paths).map(|s| s.summary(&path.display().to_string()))
}

/// The options `npr check` and `npr compile` share: the paths policy for
/// `style` (and `scene`), and the scene's summary read under it; the exit
/// code, with the diagnostics printed, when either fails.
pub(crate) fn check_options(
    paths: &PathArgs,
    style: &Path,
    scene: Option<&Path>,
    sources: &mut SourceMap,
    printer: &Printer,
) -> Result<CompileOptions, i32> {
    let policy = paths.policy(style, scene).map_err(|d| printer.fail(d))?;
    let summary = scene
        .map(|s| load_scene_summary(s, sources, Some(&policy)))
        .transpose()
        .map_err(|diags| {
            printer.diagnostics(&diags, sources);
            EXIT_USER
        })?;
    Ok(CompileOptions {
        scene: summary,
        paths: Some(policy),
        ..Default::default()
    })
}

/// Say how each art-map was made: filtered now (and whether it reached the
/// disk cache) or read from a cache.
pub(crate) fn artmap_notes(builds: &[npr_runner::artmap::ArtmapBuild]) {
    use npr_runner::artmap_cache::Origin;
    for b in builds {
        let how = match b.origin {
            Origin::Built { on_disk: true } => "filtered and cached",
            Origin::Built { on_disk: false } => "filtered (no cache directory: set NPR_CACHE_DIR to keep it)",
            Origin::Memory => "reused from memory",
            Origin::Disk => "read from the cache",
        };
        eprintln!(
            "note: art-map `{}`: {} level(s) {how} in {:.1} ms",
            b.texture, b.levels, b.ms
        );
    }
}
