//! The second implementation (issue 32): every WGSL module npr emits for
//! the examples under every schedule, and for a few hundred styles of the
//! generated-style fuzzer, goes through Chromium's own WebGPU (Dawn, and
//! its WGSL compiler Tint) in Debian's headless `chromium` on its
//! SwiftShader adapter, with no GPU and no download. Per style it makes a
//! device with exactly the features and limits the manifest asks for
//! (`device_needs`), creates each module and fails on any error or
//! warning of `getCompilationInfo`, then builds each pass's pipelines from
//! the manifest's bindings, formats and vertex layout
//! (`webgpu_portability/descriptors.rs`), so that the manifest/WGSL
//! contract is checked by an implementation that is not wgpu. naga
//! accepting a module is not enough: before this test Tint refused 25 of
//! the examples' 319 modules (`inf`, and f32::MAX spelled `3.4028235e38`).
//!
//! The page is served from 127.0.0.1 (WebGPU needs a secure context);
//! `tests/data/webgpu_check.js` is its side. A failure names the style
//! (the example and schedule, or the generated style's seed and text),
//! the pass and Tint's or Dawn's message. Chromium missing is a failure
//! with the install command, never a skip. `NPR_FUZZ_CASES` and
//! `NPR_FUZZ_FIRST` choose the generated styles, as for the fuzzers.

mod descriptors;

use crate::common;

use common::chromium::{Browser, WEBGPU_FLAGS};
use npr_compiler::schedule::Schedule;
use npr_compiler::{CompileError, CompileOptions, Compiled};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Generated styles handed to Chromium by default: about two thirds
/// compile, each in a fraction of a second on SwiftShader.
const GENERATED_STYLES: u32 = 300;

/// Styles per `Runtime.evaluate`: a few megabytes of WGSL at most.
const BATCH: usize = 16;

/// How long a valid pipeline may compile on SwiftShader before the check
/// moves on (Dawn refuses an invalid one at once, before compiling): most
/// take well under a second, the heaviest compute pipelines a few
/// seconds, and one (`lsa_base` under `recompute`) more than five minutes.
const COMPILE_DEADLINE: Duration = Duration::from_secs(20);

/// One style to check: what a failure calls it, and its text when it was
/// generated (printed with the failure, since no file holds it).
struct Case {
    label: String,
    text: Option<String>,
    program: npr_abi::StyleProgram,
}

/// The example styles, art-map filters and styles over host inputs
/// (`examples/*.npr`, `examples/filters/*.npr`, `examples/post/*.npr`;
/// `examples/lib/` holds modules they `use`).
fn example_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["examples", "examples/filters", "examples/post"] {
        let dir = common::root().join(dir);
        for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.expect("a directory entry").path();
            if path.extension().is_some_and(|x| x == "npr") {
                files.push(path);
            }
        }
    }
    files.sort();
    assert!(files.len() >= 20, "the examples went missing: {files:?}");
    files
}

fn compile_example(path: &Path, schedule: Schedule, keep_params: bool) -> Compiled {
    let mut sources = npr_diag::SourceMap::new();
    let opts = CompileOptions {
        schedule,
        keep_params,
        paths: Some(
            npr_diag::paths::PathPolicy::new(&npr_diag::paths::PathPolicy::default_root(&[path]), &[]).expect("root"),
        ),
        ..Default::default()
    };
    match npr_compiler::compile_file(path, &mut sources, &opts) {
        Ok(c) => c,
        Err(CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(CompileError::Internal(e)) => panic!("{}: {e}", path.display()),
    }
}

/// A compiled style, and the art-map filters it runs, as cases.
fn cases_of(label: &str, text: Option<&str>, compiled: &Compiled, out: &mut Vec<Case>) {
    let program = compiled.program();
    for (path, filter) in descriptors::filters(&program) {
        out.push(Case {
            label: format!("{label}, its art-map filter {path}"),
            text: text.map(str::to_string),
            program: filter,
        });
    }
    out.push(Case {
        label: label.to_string(),
        text: text.map(str::to_string),
        program,
    });
}

/// The examples under every schedule, then the generated styles that compile.
fn all_cases() -> Vec<Case> {
    let mut out = Vec::new();
    let root = common::root();
    for path in example_files() {
        let name = path.strip_prefix(root).unwrap_or(&path).display().to_string();
        for schedule in Schedule::ALL {
            let c = compile_example(&path, schedule, false);
            cases_of(&format!("{name} --schedule {}", schedule.name()), None, &c, &mut out);
        }
        // A gradient kept live is other WGSL (`npr_ramp_<g>` over a uniform
        // array): the examples that declare one, also with --keep-params.
        if std::fs::read_to_string(&path).is_ok_and(|t| t.contains(": gradient")) {
            for schedule in Schedule::ALL {
                let c = compile_example(&path, schedule, true);
                cases_of(
                    &format!("{name} --keep-params --schedule {}", schedule.name()),
                    None,
                    &c,
                    &mut out,
                );
            }
        }
    }
    let first = common::fuzz::first_case();
    for seed in first..first + u64::from(common::fuzz::cases(GENERATED_STYLES)) {
        let text = super::fuzz_generated::style(seed);
        let mut sources = npr_diag::SourceMap::new();
        // Refused styles have nothing to run; `fuzz_generated` checks the refusals.
        if let Ok(c) = npr_compiler::compile_source(
            "generated.npr",
            &text,
            Path::new("."),
            &mut sources,
            &Default::default(),
        ) {
            cases_of(&format!("generated style {seed}"), Some(&text), &c, &mut out);
        }
    }
    out
}

/// A page on 127.0.0.1 (a secure context, so it has `navigator.gpu`) in a
/// headless Chromium with WebGPU on SwiftShader, `nprCheck` defined.
fn webgpu_page(scratch: &Path) -> Browser {
    let server = tiny_http::Server::http("127.0.0.1:0").expect("a local port for the page");
    let addr = server.server_addr().to_ip().expect("an IP address");
    std::thread::spawn(move || {
        for request in server.incoming_requests() {
            let page = tiny_http::Response::from_string("<!doctype html><title>npr WebGPU check</title>")
                .with_header(tiny_http::Header::from_bytes("Content-Type", "text/html").expect("a header"));
            let _ = request.respond(page);
        }
    });
    // Pipeline building on SwiftShader is slow; a batch may take a while.
    let mut b = Browser::launch(&scratch.join("profile"), WEBGPU_FLAGS, Duration::from_secs(300));
    b.call("Page.enable", json!({}));
    b.call("Page.navigate", json!({"url": format!("http://{addr}/")}));
    let deadline = Instant::now() + common::live::HANG;
    while b.eval("document.readyState === 'complete' && location.protocol === 'http:'") != json!(true) {
        assert!(Instant::now() < deadline, "the check page never loaded");
        std::thread::sleep(Duration::from_millis(50));
    }
    let has_webgpu = b.eval("!!navigator.gpu");
    assert_eq!(
        has_webgpu,
        json!(true),
        "Chromium's page has no WebGPU: it needs {WEBGPU_FLAGS:?} and a secure (localhost) page"
    );
    assert_eq!(b.eval(include_str!("../data/webgpu_check.js")), json!("ready"));
    b
}

/// What `nprCheck` said of a batch: the problems, the pipelines still
/// compiling at the deadline, and how many of the styles it checked (it
/// stops after a style with a slow pipeline).
struct Checked {
    problems: Vec<Value>,
    slow: Vec<String>,
    checked: usize,
}

/// `nprCheck` of `styles` (their JSON entries).
fn check(b: &mut Browser, styles: &[Value]) -> Checked {
    let found = b.eval(&format!(
        "nprCheck({}, {})",
        Value::Array(styles.to_vec()),
        COMPILE_DEADLINE.as_millis()
    ));
    let list = |key: &str| {
        found[key]
            .as_array()
            .cloned()
            .unwrap_or_else(|| panic!("nprCheck gave {found}"))
    };
    Checked {
        problems: list("problems"),
        slow: list("slow")
            .iter()
            .map(|s| s.as_str().unwrap_or("?").to_string())
            .collect(),
        checked: found["checked"].as_u64().unwrap_or(0) as usize,
    }
}

/// The checker itself fails on what it must catch: the literal Tint
/// refused before issue 32, a warning, and a pipeline whose layout does
/// not match its shader. Without this a page that reported nothing would
/// pass every style.
fn the_checker_sees_what_it_must(b: &mut Browser) {
    let module = |code: &str, groups: Value| {
        json!({"name": "p", "shader": "p.wgsl", "code": code,
               "pipelines": [{"label": "main", "groups": groups, "constants": {}, "compute": "main"}]})
    };
    let bad_literal = "@compute @workgroup_size(1) fn main() { var x = 3.4028235e38; x = x + 1.0; }";
    let warning = "@compute @workgroup_size(1) fn main() { return; let x = 1; }";
    let missing_binding = "@group(0) @binding(0) var<storage, read_write> v: array<f32>;\n\
                           @compute @workgroup_size(1) fn main() { v[0] = 1.0; }";
    let styles = [
        json!({"label": "literal", "features": [], "limits": {}, "passes": [module(bad_literal, json!([]))]}),
        json!({"label": "warning", "features": [], "limits": {}, "passes": [module(warning, json!([]))]}),
        json!({"label": "layout", "features": [], "limits": {}, "passes": [module(missing_binding, json!([[]]))]}),
        json!({"label": "limit", "features": [], "limits": {"maxStorageTexturesPerShaderStage": 1 << 20}, "passes": []}),
    ];
    let problems = check(b, &styles).problems;
    let said = |label: &str, what: &str| {
        problems
            .iter()
            .any(|p| p["style"] == label && p["what"].as_str().is_some_and(|w| w.starts_with(what)))
    };
    assert!(
        said("literal", "error at p.wgsl:1:"),
        "Tint's refusal unseen: {problems:#?}"
    );
    assert!(
        said("warning", "warning at p.wgsl:1:"),
        "Tint's warning unseen: {problems:#?}"
    );
    assert!(
        said("layout", "pipeline main"),
        "a pipeline error unseen: {problems:#?}"
    );
    assert!(
        said("limit", "device"),
        "a device that cannot be made unseen: {problems:#?}"
    );
}

#[test]
fn every_module_npr_emits_passes_tint_and_builds_its_pipelines_from_the_manifest() {
    let started = Instant::now();
    let cases = all_cases();
    let compiled_in = started.elapsed();
    let scratch = common::live::scratch("webgpu-portability", "run");
    let mut b = webgpu_page(&scratch);
    the_checker_sees_what_it_must(&mut b);
    // A pass whose module and pipelines another style already brought on
    // a device with the same features and limits gets the same answer from
    // Tint and Dawn: each is checked once, under the first style that has
    // it. (Most passes are the same under every schedule, and compiling a
    // valid pipeline on SwiftShader is what takes the time.)
    let all_modules: usize = cases.iter().map(|c| c.program.shaders.len()).sum();
    let mut seen = std::collections::HashSet::new();
    let styles: Vec<Value> = cases
        .iter()
        .filter_map(|c| {
            let mut style = descriptors::style(&c.label, &c.program);
            let needs = format!("{}{}", style["features"], style["limits"]);
            let passes = style["passes"].as_array_mut().expect("a style's passes");
            passes.retain(|p| seen.insert(format!("{needs}\n{}\n{}", p["code"], p["pipelines"])));
            (!passes.is_empty()).then_some(style)
        })
        .collect();
    let distinct_passes: usize = styles.iter().map(|s| s["passes"].as_array().map_or(0, Vec::len)).sum();
    let (mut problems, mut slow, mut modules) = (Vec::new(), Vec::new(), 0);
    let mut next = 0;
    while next < styles.len() {
        let batch = &styles[next..(next + BATCH).min(styles.len())];
        let result = check(&mut b, batch);
        assert!(result.checked > 0, "nprCheck checked nothing of a batch");
        modules += batch[..result.checked]
            .iter()
            .map(|s| s["passes"].as_array().map_or(0, Vec::len))
            .sum::<usize>();
        next += result.checked;
        problems.extend(result.problems);
        if !result.slow.is_empty() {
            // Its compilation goes on in the browser: a new one for the rest.
            slow.extend(result.slow);
            drop(b);
            b = webgpu_page(&scratch);
        }
    }
    eprintln!(
        "webgpu_portability: {} styles, {all_modules} modules, {modules} distinct passes through Tint \
         and Dawn's pipeline validation ({:.1} s compiling, {:.1} s in Chromium); {} pipeline(s) valid \
         but still compiling on SwiftShader after {} s: {slow:#?}",
        cases.len(),
        compiled_in.as_secs_f64(),
        (started.elapsed() - compiled_in).as_secs_f64(),
        slow.len(),
        COMPILE_DEADLINE.as_secs()
    );
    let report: Vec<String> = problems
        .iter()
        .map(|p| {
            let label = p["style"].as_str().unwrap_or("?");
            let text = cases
                .iter()
                .find(|c| c.label == label)
                .and_then(|c| c.text.as_deref())
                .map(|t| format!("\n{t}"))
                .unwrap_or_default();
            format!(
                "{label}, pass `{}`: {}: {}{text}",
                p["pass"].as_str().unwrap_or(""),
                p["what"],
                p["message"]
            )
        })
        .collect();
    assert!(
        report.is_empty(),
        "{} problem(s) in Chromium's WebGPU (naga accepted every module):\n{}",
        report.len(),
        report.join("\n\n")
    );
    assert_eq!(modules, distinct_passes, "every distinct pass is checked");
    assert!(all_modules >= 319, "only {all_modules} modules were compiled");
}

/// The runner's own modules (`npr_runner::own_shaders`: the deformation
/// stage, the host-input conversion, the host depth draw, the present
/// draw, the half-rounding probe) compile in Tint without an error or a warning, as every style's
/// module does: they run wherever the runtime runs. Compiled only (their
/// pipelines are the runner's, built and tested on wgpu).
#[test]
fn the_runners_own_modules_pass_tint() {
    let scratch = common::live::scratch("webgpu-portability", "own-shaders");
    let mut b = webgpu_page(&scratch);
    let passes: Vec<Value> = npr_runner::own_shaders::all()
        .iter()
        .map(|(name, code)| json!({"name": name, "shader": name, "code": code, "pipelines": []}))
        .collect();
    assert_eq!(passes.len(), 5, "the runner's modules: {passes:#?}");
    let style = json!({"label": "runner", "features": [], "limits": {}, "passes": passes});
    let result = check(&mut b, &[style]);
    assert_eq!(result.checked, 1, "nprCheck checked the runner's modules");
    assert!(
        result.problems.is_empty(),
        "Tint refuses or warns about the runner's own WGSL:\n{:#?}",
        result.problems
    );
}
