//! The compiler pipeline, in order: load → resolve (with the filter checks)
//! → typecheck (with the rip-map checks) → apply overrides → build the pass
//! DAG → prune → value ranges (with WGSL's undefined cases, over the
//! params' declared ranges) → specialize → prune again (what folding made
//! dead) → the checks of constant domains and absent tags → schedule (fusion, tiles,
//! recomputation) → allocate → emit → validate. Each stage is timed, and `dump_ir` records the
//! IR after each stage.

use crate::back::emit::Emitter;
use crate::front::load::Loaded;
use crate::ir::Ir;
use crate::report::Report;
use crate::{CompileError, CompileOptions, Compiled, InternalError};
use npr_abi::manifest::ParamBinding;
use npr_diag::{Diagnostic, SourceMap};
#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
use std::time::Instant;
// std's `Instant::now` panics on the web; this one reads `performance.now()`.
#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
use web_time::Instant;

struct Stages<'o> {
    opts: &'o CompileOptions,
    timings: Vec<(&'static str, std::time::Duration)>,
    dumps: Vec<(&'static str, String)>,
    last: Instant,
}

impl Stages<'_> {
    fn done(&mut self, stage: &'static str, ir: &Ir) {
        let now = Instant::now();
        self.timings.push((stage, now - self.last));
        if self.opts.dump_ir {
            self.dumps.push((stage, crate::dump::dump(ir)));
        }
        self.last = Instant::now();
    }
}

fn fail_if_errors(diags: &[Diagnostic]) -> Result<(), CompileError> {
    if diags.iter().any(Diagnostic::is_error) {
        return Err(CompileError::User(diags.to_vec()));
    }
    Ok(())
}

/// The parser's limit errors: a file too large, nested too deeply, or an
/// expression too deep.
fn is_parse_limit(d: &Diagnostic) -> bool {
    use npr_diag::codes::{EXPRESSION_TOO_DEEP, LIMIT_EXCEEDED, NESTED_TOO_DEEP};
    d.is_error() && [LIMIT_EXCEEDED, NESTED_TOO_DEEP, EXPRESSION_TOO_DEEP].contains(&d.code)
}

#[cfg(test)]
thread_local! {
    /// How many styles [`run`] compiled on this thread (filters included):
    /// what shows that a filter with arguments is compiled once.
    static RUNS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

pub fn run(
    loaded: Loaded,
    sources: &SourceMap,
    source_name: &str,
    opts: &CompileOptions,
    mut diags: Vec<Diagnostic>,
) -> Result<Compiled, CompileError> {
    #[cfg(test)]
    RUNS.with(|r| r.set(r.get() + 1));
    let mut st = Stages {
        opts,
        timings: Vec::new(),
        dumps: Vec::new(),
        last: Instant::now(),
    };
    // A file refused for its size or nesting was not parsed at all (or lost
    // the item that went past the limit): what resolve would say about the
    // rest follows from that, so only the limit error is reported.
    if diags.iter().any(is_parse_limit) {
        return Err(CompileError::User(diags));
    }
    if loaded.root.style.is_none() && !diags.iter().any(Diagnostic::is_error) {
        diags.push(
            Diagnostic::error(npr_diag::codes::STYLE_HEADER, "missing `style` header")
                .with_help("start the file with `style \"Name\"`"),
        );
    }
    let root_file = loaded.root_file;
    let (mut ir, gradients_set) = crate::front::resolve::resolve_with_settings(
        &loaded,
        opts.scene.as_ref(),
        opts.paths.as_ref(),
        opts.files.source(),
        &opts.settings,
        opts.keep_params,
        &mut diags,
    )
    .map_err(CompileError::Internal)?;
    if loaded.is_filter || crate::front::filter_checks::reads_a_level(&ir) {
        crate::front::filter_checks::check(&ir, loaded.root.style.as_ref().map(|h| h.span), &mut diags);
    }
    st.done("resolve", &ir);
    crate::front::typecheck::typecheck(&mut ir, &mut diags);
    crate::front::texture_uses::check(&ir, &mut diags);
    st.done("typecheck", &ir);
    crate::front::follow_ups::suppress(&mut diags, &loaded.broken, sources);
    fail_if_errors(&diags)?;
    // The style's own warnings are not repeated beside a refused setting:
    // the setting is what the caller gets wrong.
    // A gradient's setting was applied by the resolver.
    let settings: Vec<crate::ir::ParamSetting> = opts
        .settings
        .iter()
        .filter(|s| !gradients_set.contains(&s.name))
        .cloned()
        .collect();
    let overrides = crate::front::param_settings::type_settings(&ir, &settings, sources).map_err(CompileError::User)?;
    crate::mid::overrides::apply(&mut ir, &overrides).map_err(CompileError::Internal)?;
    let filters = compile_filters(&ir, loaded.filters, sources, &opts.files)?;
    let graph = crate::mid::dag::build(&ir, &mut diags);
    st.done("dag", &ir);
    fail_if_errors(&diags)?;
    let mut scratch = Report::default();
    let live = crate::mid::prune::prune(&ir, &graph, &mut scratch);
    diags.extend(crate::mid::prune::unread_compute_passes(&ir, &live));
    st.done("prune", &ir);
    let mut report = Report::default();
    for (tag, present) in &ir.scene_queries {
        let scene = opts.scene.as_ref().map_or("", |s| s.name.as_str());
        report.push(
            "folded",
            format!("scene_has({tag})"),
            if *present {
                format!("true: scene {scene} has objects tagged `{tag}`")
            } else {
                format!("false: no object in scene {scene} is tagged `{tag}`")
            },
        );
    }
    // Value ranges before folding: a param nobody fixed ranges over its
    // declared range, not only its default (`mid/ranges`).
    let param_ranges: Vec<_> = ir
        .params
        .iter()
        .map(|p| {
            let set = overrides.iter().any(|o| o.name == p.name);
            crate::mid::ranges::inputs::param_range(p, set, opts.keep_params)
        })
        .collect();
    let ranges = crate::mid::ranges::analyse(&ir, &live, &param_ranges);
    st.done("ranges", &ir);
    let bindings = crate::mid::specialize::specialize(&mut ir, &live, opts.keep_params, &mut report);
    st.done("specialize", &ir);
    // Folding may have made passes, targets and params dead: prune again.
    // Folded parameters no longer appear in the IR; they stay "folded", not "removed".
    let graph = crate::mid::dag::build(&ir, &mut diags);
    let mut second = Report::default();
    let mut live = crate::mid::prune::prune(&ir, &graph, &mut second);
    let folded: Vec<String> = bindings
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == ParamBinding::Folded)
        .map(|(i, _)| format!("param `{}`", ir.params[i].name))
        .collect();
    for e in second.entries {
        if !folded.contains(&e.what) && !report.entries.contains(&e) {
            report.entries.push(e);
        }
    }
    let bindings: Vec<_> = bindings
        .into_iter()
        .enumerate()
        .map(|(i, b)| {
            if b == ParamBinding::Folded || live.params.contains(&crate::ir::ParamId(i as u32)) {
                b
            } else {
                ParamBinding::Removed
            }
        })
        .collect();
    diags.extend(crate::mid::scene_tags::absent_tags(&ir, &live, opts.scene.as_ref()));
    st.done("prune-after-specialize", &ir);
    diags.extend(crate::mid::const_domains::check(&ir, &live));
    fail_if_errors(&diags)?;
    diags.extend(ranges.warnings);
    diags.extend(crate::schedule::apply(
        &mut ir,
        &mut live,
        opts.schedule,
        opts.tile_apron_deficit,
        sources,
        root_file,
        &mut report,
    ));
    fail_if_errors(&diags)?;
    st.done("schedule", &ir);
    let alloc = crate::back::allocate::allocate(&ir, &live, &bindings, &mut report).map_err(CompileError::Internal)?;
    st.done("allocate", &ir);
    let emitter = Emitter {
        ir: &ir,
        alloc: &alloc,
        bindings: &bindings,
        sources,
    };
    let emitted: Vec<_> = live.passes.iter().map(|p| (*p, emitter.emit_pass(*p))).collect();
    let mut manifest =
        crate::back::emit::manifest::build(&ir, &live, &alloc, &bindings, &emitted, sources, source_name, &filters)
            .map_err(CompileError::Internal)?;
    for a in &manifest.scene_attributes {
        report.push(
            "requires",
            format!("attribute `{}`", a.name()),
            "read by a live render or compute pass".into(),
        );
    }
    st.done("emit", &ir);
    let mut shaders = Vec::new();
    let mut modules = Vec::new();
    for (pid, e) in emitted {
        let pass = ir.pass(pid);
        let file = format!("{}.wgsl", pass.name);
        match crate::back::validate::validate_wgsl(&file, &e.wgsl) {
            Ok(module) => modules.push((file.clone(), module)),
            Err(message) => {
                return Err(CompileError::Internal(InternalError {
                    message: format!("emitted WGSL for pass `{}` failed naga validation", pass.name),
                    detail: message,
                    span: Some(pass.span),
                    wgsl: Some(e.wgsl),
                }))
            }
        }
        shaders.push((file, e.wgsl));
    }
    manifest.device_needs = crate::back::device_needs::device_needs(&manifest, |pass| {
        modules.iter().find(|(file, _)| *file == pass.shader).map(|(_, m)| m)
    });
    for need in &manifest.device_needs {
        report.push(
            "requires",
            format!("pass `{}`", need.pass()),
            format!("{}, past what every WebGPU device gives", need.describe()),
        );
    }
    st.done("validate", &ir);
    Ok(Compiled {
        manifest,
        shaders,
        report,
        warnings: diags,
        texture_spans: crate::front::texture_spans::texture_spans(&ir, sources),
        timings: st.timings,
        dumps: st.dumps,
        ranges: ranges.targets,
    })
}

/// Compile the filter style of every art-map (each once), as a style of its
/// own with its defaults, or with the art-map's arguments as settings (typed
/// against the filter's params after its typecheck, as `--set` values are
/// against a style's): the compiled filters by the key `resolve` gave them.
/// A filter's errors are the host's errors, spans in the filter file.
fn compile_filters(
    ir: &crate::ir::Ir,
    loaded: std::collections::BTreeMap<String, Loaded>,
    sources: &SourceMap,
    files: &npr_diag::files::Files,
) -> Result<std::collections::BTreeMap<String, npr_abi::FilterProgram>, CompileError> {
    let mut out = std::collections::BTreeMap::new();
    for t in &ir.textures {
        let crate::ir::TextureSource::Artmap {
            filter,
            filter_file,
            filter_name,
            filter_args,
            ..
        } = &t.source
        else {
            continue;
        };
        if out.contains_key(filter) {
            continue;
        }
        let Some(filter_loaded) = loaded.get(filter_file) else {
            return Err(CompileError::Internal(InternalError {
                message: format!("the filter `{filter_name}` of texture `{}` was not loaded", t.name),
                detail: "load_filters loads every filter an art-map names".into(),
                span: Some(t.span),
                wgsl: None,
            }));
        };
        // Point from each of the filter's errors back at the art-map, unless
        // it already points into it (a refused argument).
        let in_art_map = |s: npr_diag::Span| s.file == t.span.file && t.span.start <= s.start && s.end <= t.span.end;
        let from_filter = |e: CompileError| match e {
            CompileError::User(diags) => CompileError::User(
                diags
                    .into_iter()
                    .map(|d| match d.primary_span() {
                        Some(s) if in_art_map(s) => d,
                        _ => d.with_secondary(t.span, format!("the filter of art-map `{}`", t.name)),
                    })
                    .collect(),
            ),
            e => e,
        };
        let opts = CompileOptions {
            settings: filter_args.clone(),
            files: files.clone(),
            ..CompileOptions::default()
        };
        let c = run(filter_loaded.clone(), sources, filter_file, &opts, Vec::new()).map_err(from_filter)?;
        out.insert(
            filter.clone(),
            npr_abi::FilterProgram {
                path: filter_name.clone(),
                manifest: Box::new(c.manifest),
                shaders: c.shaders.into_iter().collect(),
            },
        );
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use npr_abi::manifest::TextureSourceManifest;
    use std::path::Path;

    /// Compile `text` in `examples/` (its textures and filters), and count
    /// the styles compiled for it.
    fn compile_counting_runs(text: &str) -> (Compiled, usize) {
        let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
        let before = RUNS.with(std::cell::Cell::get);
        let mut sources = SourceMap::new();
        let compiled = crate::compile_source("host.npr", text, &examples, &mut sources, &CompileOptions::default())
            .unwrap_or_else(|e| panic!("{e:?}"));
        (compiled, RUNS.with(std::cell::Cell::get) - before)
    }

    /// A host whose art-map runs the shipped hatching filter with `args`.
    fn host(args: &str) -> String {
        format!(
            "style \"Host\"\ntexture t = artmap(image(\"textures/gallery_wall.png\", srgb), filter: filter(\"filters/hatching.npr\"{args}))\n\
             pass p: render(scene) {{\n  out c: rgba8unorm = sample(t, uv)\n}}\noutput p.c\n"
        )
    }

    #[test]
    fn a_filter_with_arguments_is_compiled_once_with_them_as_its_defaults() {
        let (_, runs) = compile_counting_runs(&host(""));
        assert_eq!(runs, 2, "the host, and the filter with its defaults");
        let (compiled, runs) = compile_counting_runs(&host(", spacing: 8, ink: #ff0000"));
        assert_eq!(
            runs, 2,
            "the host, and the filter with the arguments typed in its one compile"
        );
        let TextureSourceManifest::Artmap(spec) = &compiled.manifest.textures[0].source else {
            panic!("not an art-map: {:?}", compiled.manifest.textures[0].source);
        };
        let default = |name: &str| {
            let p = spec.filter.manifest.params.iter().find(|p| p.name == name);
            p.unwrap_or_else(|| panic!("no `{name}`")).default.clone()
        };
        assert_eq!(default("spacing"), vec![8.0]);
        assert_eq!(default("ink"), vec![1.0, 0.0, 0.0, 1.0]);
    }
}
