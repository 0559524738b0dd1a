//! Every error code has a case here that triggers it, and a snapshot of its
//! rendered message (rustc style, no colour). A completeness check makes sure
//! no code in `dsl::codes::ALL` is left without a case.

use compiler::{CompileError, CompileOptions};
use dsl::{Diagnostic, SourceMap};
use std::path::{Path, PathBuf};

/// A scratch directory for cases that need files on disk.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("error-codes").join(name);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Compile `text` (as `case.npr` in `dir`) and return the rendered diagnostics.
fn compile_errors(text: &str, dir: &Path) -> (Vec<Diagnostic>, String) {
    let mut sources = SourceMap::new();
    match compiler::compile_source("case.npr", text, dir, &mut sources, &CompileOptions::default()) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(CompileError::User(d)) => {
            let r = dsl::diagnostic::render(&d, &sources, false);
            (d, r)
        }
        Err(CompileError::Internal(e)) => panic!("internal error instead of a user error: {e}"),
    }
}

fn scene_errors(toml: &str, dir: &Path) -> (Vec<Diagnostic>, String) {
    let mut sources = SourceMap::new();
    let path = dir.join("scene.toml");
    std::fs::write(&path, toml).expect("write scene");
    match runner::scene::load_scene(&path, &mut sources) {
        Ok(_) => panic!("expected a scene error for:\n{toml}"),
        Err(d) => {
            let r = dsl::diagnostic::render(&d, &sources, false);
            (d, r.replace(&dir.display().to_string(), "<dir>"))
        }
    }
}

/// Assert the first diagnostic has `code`, a primary label, and snapshot the rendering.
fn check(code: &str, (diags, rendered): (Vec<Diagnostic>, String)) {
    check_case(code, code, (diags, rendered));
}

/// [`check`] for a further case of a code, snapshot under `name`.
fn check_case(code: &str, name: &str, (diags, rendered): (Vec<Diagnostic>, String)) {
    let first = diags.first().expect("at least one diagnostic");
    assert_eq!(first.code, code, "wrong code; rendered:\n{rendered}");
    let severity = if first.is_error() { "error" } else { "warning" };
    assert!(rendered.contains(&format!("{severity}[{code}]")), "{rendered}");
    insta::assert_snapshot!(name, rendered);
}

const HEADER: &str = "style \"Case\"\n";

fn style(body: &str) -> String {
    format!("{HEADER}{body}")
}

const SIMPLE_PASS: &str =
    "pass p: render(scene) {\n  out color: rgba8unorm = vec4(1.0, 0.5, 0.2, 1.0)\n}\noutput p.color\n";

#[test]
fn e0001_syntax_error() {
    check(
        "E0001",
        compile_errors(&style("param x: float = (1.0 +\n"), &scratch("e0001")),
    );
}

#[test]
fn e0002_missing_style_header() {
    check("E0002", compile_errors(SIMPLE_PASS, &scratch("e0002")));
}

#[test]
fn e0003_duplicate_name() {
    check(
        "E0003",
        compile_errors(
            &style(&format!("param a: float = 1.0\nparam a: float = 2.0\n{SIMPLE_PASS}")),
            &scratch("e0003"),
        ),
    );
}

#[test]
fn e0004_bad_use() {
    check(
        "E0004",
        compile_errors(
            &style(&format!("use \"missing/common.npr\"\n{SIMPLE_PASS}")),
            &scratch("e0004"),
        ),
    );
}

#[test]
fn e0005_nested_too_deeply() {
    let deep = format!("{}1.0{}", "(".repeat(70), ")".repeat(70));
    check(
        "E0005",
        compile_errors(&style(&format!("param x: float = {deep}\n")), &scratch("e0005")),
    );
}

#[test]
fn e0006_expression_too_deep() {
    let long = vec!["x"; 300].join(" + ");
    check(
        "E0006",
        compile_errors(
            &style(&format!("param x: float = 1.0\nparam y: float = {long}\n")),
            &scratch("e0006"),
        ),
    );
}

#[test]
fn e0404_a_style_file_over_the_size_limit() {
    // Short lines, so the snapshot shows one of them.
    let big = style(&"// padding\n".repeat(dsl::limits::MAX_SOURCE_BYTES / 10));
    check_case(
        "E0404",
        "E0404_source_size",
        compile_errors(&big, &scratch("e0404-size")),
    );
}

#[test]
fn e0101_unknown_name_with_suggestion() {
    let text = style("param bands: int = 3 in 1..8\npass p: render(scene) {\n  out color: r8unorm = toon(half_lambert(normal, light.dir), steps: bnads)\n}\noutput p.color\n");
    let (d, r) = compile_errors(&text, &scratch("e0101"));
    assert!(r.contains("did you mean `bands`?"), "{r}");
    check("E0101", (d, r));
}

#[test]
fn e0102_unknown_operator_with_suggestion() {
    let text = style("pass p: render(scene) {\n  out color: r8unorm = lambrt(normal, light.dir)\n}\noutput p.color\n");
    let (d, r) = compile_errors(&text, &scratch("e0102"));
    assert!(r.contains("did you mean `lambert`?"), "{r}");
    check("E0102", (d, r));
}

#[test]
fn e0103_bad_argument_name() {
    let text = style("pass p: render(scene) {\n  out color: r8unorm = toon(0.5, stesp: 3)\n}\noutput p.color\n");
    check("E0103", compile_errors(&text, &scratch("e0103")));
}

#[test]
fn e0104_unknown_format() {
    let text = style("pass p: render(scene) {\n  out color: rgba8unrom = vec4(1.0)\n}\noutput p.color\n");
    check("E0104", compile_errors(&text, &scratch("e0104")));
}

#[test]
fn e0201_type_mismatch() {
    let text = style("pass p: render(scene) {\n  out color: r8unorm = toon(normal, steps: 3)\n}\noutput p.color\n");
    check("E0201", compile_errors(&text, &scratch("e0201")));
}

#[test]
fn e0202_unit_mismatch_px_plus_m() {
    let text = style("param width: px = 2px\nparam reach: m = 1m\npass p: render(scene) {\n  vertex { inflate: width + reach }\n  out color: rgba8unorm = vec4(1.0)\n}\noutput p.color\n");
    check("E0202", compile_errors(&text, &scratch("e0202")));
}

#[test]
fn e0203_default_out_of_range() {
    let text = style(&format!("param bands: int = 12 in 1..8\n{SIMPLE_PASS}"));
    check("E0203", compile_errors(&text, &scratch("e0203")));
}

#[test]
fn e0203_a_halftone_table_edge_out_of_range() {
    // A hard step (edge 0) has no smoothstep to tabulate.
    let text = style(&format!("texture dots = halftone_table(edge: 0.0)\n{SIMPLE_PASS}"));
    check_case(
        "E0203",
        "e0203_halftone_table_edge",
        compile_errors(&text, &scratch("e0203_halftone")),
    );
}

#[test]
fn e0103_a_misspelt_halftone_table_setting() {
    let text = style(&format!("texture dots = halftone_table(egde: 0.1)\n{SIMPLE_PASS}"));
    check_case(
        "E0103",
        "e0103_halftone_table_setting",
        compile_errors(&text, &scratch("e0103_halftone")),
    );
    let text = style(&format!(
        "texture dots = halftone_table(correction: maybe)\n{SIMPLE_PASS}"
    ));
    check_case(
        "E0103",
        "e0103_halftone_table_correction",
        compile_errors(&text, &scratch("e0103_halftone_c")),
    );
}

#[test]
fn e0204_not_constant() {
    // Range bounds must be constants.
    let text = style(&format!("param a: float = 0.5 in 0..time\n{SIMPLE_PASS}"));
    check("E0204", compile_errors(&text, &scratch("e0204")));
}

#[test]
fn e0301_pass_cycle() {
    let text = style(
        "pass a: image(b) {\n  out x: r8unorm = b.y\n}\npass b: image(a) {\n  out y: r8unorm = a.x\n}\noutput b.y\n",
    );
    check("E0301", compile_errors(&text, &scratch("e0301")));
}

#[test]
fn e0301_a_pass_reading_its_own_target_is_told_about_previous() {
    let text = style("pass acc: image() {\n  out c: r8unorm = acc.c * 0.9\n}\noutput acc.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("e0301-self"));
    assert!(rendered.contains("previous(acc.<target>)"), "{rendered}");
    check_case("E0301", "E0301_self_read", (diags, rendered));
}

#[test]
fn previous_takes_one_pass_target() {
    let text = style("pass acc: image() {\n  out c: r8unorm = previous(0.5)\n}\noutput acc.c\n");
    check_case(
        "E0103",
        "E0103_previous_not_a_target",
        compile_errors(&text, &scratch("prev-arg")),
    );
}

#[test]
fn previous_of_a_target_that_does_not_exist() {
    let text = style("pass acc: image() {\n  out c: r8unorm = previous(acc.d)\n}\noutput acc.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("prev-missing"));
    let code = diags.first().expect("a diagnostic").code;
    check_case(code, "previous_unknown_target", (diags, rendered));
    let text = style("pass acc: image() {\n  out c: r8unorm = previous(nosuch.c)\n}\noutput acc.c\n");
    check_case(
        "E0101",
        "previous_unknown_pass",
        compile_errors(&text, &scratch("prev-missing-pass")),
    );
}

#[test]
fn e0302_format_mismatch() {
    let text =
        style("pass p: render(scene) {\n  out color: rgba8unorm = lambert(normal, light.dir)\n}\noutput p.color\n");
    check("E0302", compile_errors(&text, &scratch("e0302")));
}

#[test]
fn e0303_no_output() {
    let text = style("pass p: render(scene) {\n  out color: rgba8unorm = vec4(1.0)\n}\n");
    check("E0303", compile_errors(&text, &scratch("e0303")));
    // A style of nothing but its header: E0303 at the header, not an
    // internal error (found by tests/fuzz_compiler.rs).
    check_case(
        "E0303",
        "header_only",
        compile_errors("style \"S\"\n", &scratch("e0303-header-only")),
    );
}

#[test]
fn e0304_bad_pass_input() {
    let text = style("pass g: render(scene) {\n  out n: rgba16float = vec4(normal, 1.0)\n}\npass p: image() {\n  out color: rgba8unorm = g.n\n}\noutput p.color\n");
    check("E0304", compile_errors(&text, &scratch("e0304")));
}

/// Compile `text`, which must succeed, and return its rendered warnings.
fn compile_warnings(text: &str) -> (Vec<Diagnostic>, String) {
    let mut sources = SourceMap::new();
    match compiler::compile_source(
        "case.npr",
        text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) {
        Ok(c) => {
            let r = dsl::diagnostic::render(&c.warnings, &sources, false);
            (c.warnings, r)
        }
        Err(CompileError::User(d)) => panic!("{}", dsl::diagnostic::render(&d, &sources, false)),
        Err(CompileError::Internal(e)) => panic!("internal error: {e}"),
    }
}

/// A vertex pass summing a bool, a state read before its declaration, a
/// reduction in a render pass, and a compute pass nobody reads.
const SUMS: &str = "pass sums: compute(vertices) {\n  reduce n: float = sum(1.0)\n}\n";

#[test]
fn e0205_a_reduction_over_a_type_it_cannot_sum() {
    let text = style(
        "pass sums: compute(vertices) {\n  reduce lit: float = sum(normal.y > 0.0)\n}\npass shade: render(scene) {\n  out c: r32float = sums.lit\n}\noutput shade.c\n",
    );
    check("E0205", compile_errors(&text, &scratch("e0205")));
}

#[test]
fn e0205_a_per_object_value_of_a_type_it_cannot_have() {
    let text = style(
        "pass sums: compute(vertices) {\n  reduce n: int = sum(1)\n}\npass shade: render(scene) {\n  out c: r32float = sums.n\n}\noutput shade.c\n",
    );
    check_case("E0205", "E0205_type", compile_errors(&text, &scratch("e0205t")));
}

#[test]
fn e0305_state_read_before_it_is_declared() {
    let text = style(&format!(
        "{SUMS}pass follow: compute(objects) {{\n  let twice = 2.0 * origin\n  state origin: float = sums.n\n  origin = twice\n}}\npass shade: render(scene) {{\n  out c: r32float = follow.origin\n}}\noutput shade.c\n"
    ));
    check("E0305", compile_errors(&text, &scratch("e0305")));
}

#[test]
fn e0305_a_state_that_is_never_updated() {
    let text = style(
        "pass follow: compute(objects) {\n  state origin: vec2 = vec2(0.0)\n}\npass shade: render(scene) {\n  out c: rg32float = follow.origin\n}\noutput shade.c\n",
    );
    check_case("E0305", "E0305_not_updated", compile_errors(&text, &scratch("e0305u")));
}

#[test]
fn e0306_a_statement_the_pass_kind_does_not_have() {
    let text = style(
        "pass shade: render(scene) {\n  reduce n: float = sum(1.0)\n  out c: r32float = 1.0\n}\noutput shade.c\n",
    );
    check("E0306", compile_errors(&text, &scratch("e0306")));
}

#[test]
fn w0301_a_compute_pass_nobody_reads() {
    let text = style(&format!(
        "{SUMS}pass shade: render(scene) {{\n  out c: r32float = 1.0\n}}\noutput shade.c\n"
    ));
    check("W0301", compile_warnings(&text));
}

#[test]
fn e0307_blend_on_a_format_that_cannot_be_blended() {
    let text = style("pass p: image() {\n  out sum: rgba32float = vec4(0.25) { blend: add }\n}\noutput p.sum\n");
    check("E0307", compile_errors(&text, &scratch("e0307")));
}

#[test]
fn unknown_blend_mode_suggests_one() {
    let text = style("pass p: render(scene) {\n  out c: rgba8unorm = #ff000080 { blend: ovr }\n}\noutput p.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("blend-unknown"));
    assert!(rendered.contains("did you mean `over`?"), "{rendered}");
    check_case("E0103", "E0103_unknown_blend_mode", (diags, rendered));
}

/// A scene pass and a line pass over it, `depth` setting of each given.
fn depth_passes(gbuffer_depth: &str, lines_depth: &str) -> String {
    style(&format!(
        "pass gbuffer: render(scene) {{\n  out c: rgba8unorm = #808080\n{gbuffer_depth}}}\n\
         pass lines: render(scene) {{\n  out ink: rgba8unorm = #000000 {{ blend: over }}\n  depth: {lines_depth}\n}}\n\
         pass final: image(gbuffer, lines) {{\n  out color: rgba8unorm = gbuffer.c * lines.ink\n}}\noutput final.color\n"
    ))
}

#[test]
fn e0308_depth_test_against_a_pass_that_keeps_no_depth() {
    let text = depth_passes("", "test(gbuffer, bias: 1px)");
    let (diags, rendered) = compile_errors(&text, &scratch("e0308"));
    assert!(rendered.contains("add `depth: keep` to pass `gbuffer`"), "{rendered}");
    check("E0308", (diags, rendered));
}

#[test]
fn depth_test_against_an_unknown_pass_suggests_one() {
    let text = depth_passes("  depth: keep\n", "test(gbufer)");
    let (diags, rendered) = compile_errors(&text, &scratch("depth-unknown"));
    assert!(rendered.contains("did you mean `gbuffer`?"), "{rendered}");
    check_case("E0101", "E0101_depth_test_unknown_pass", (diags, rendered));
}

#[test]
fn a_cycle_through_a_depth_test_suggests_previous_on_the_target_read() {
    let text = style("pass a: render(scene) {\n  out c: rgba8unorm = b.ink\n  depth: keep\n}\npass b: render(scene) {\n  out ink: rgba8unorm = #000000\n  depth: test(a)\n}\noutput b.ink\n");
    let (diags, rendered) = compile_errors(&text, &scratch("depth-cycle"));
    assert!(rendered.contains("`previous(b.<target>)` in `a`"), "{rendered}");
    check_case("E0301", "E0301_depth_cycle", (diags, rendered));
}

#[test]
fn depth_test_across_pass_sizes() {
    let text = depth_passes("  depth: keep\n", "test(gbuffer)")
        .replace("pass lines: render(scene) {", "pass lines: render(scene) scale 1/2 {");
    check_case(
        "E0304",
        "E0304_depth_test_other_scale",
        compile_errors(&text, &scratch("depth-scale")),
    );
}

#[test]
fn e0401_missing_texture_file() {
    let text = style("texture paper = image(\"textures/paper.png\", srgb)\npass p: render(scene) {\n  out color: rgba8unorm = paper\n}\noutput p.color\n");
    let (d, r) = compile_errors(&text, &scratch("e0401"));
    check(
        "E0401",
        (d, r.replace(&scratch("e0401").display().to_string(), "<dir>")),
    );
}

#[test]
fn e0402_unreadable_mesh() {
    let dir = scratch("e0402");
    std::fs::write(dir.join("broken.obj"), "v 0 0 0\nf 1 2 three\n").expect("write");
    check(
        "E0402",
        scene_errors("[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n[light]\ndirection = [0.0, 1.0, 0.0]\n[[object]]\nname = \"thing\"\nmesh = \"missing.obj\"\n", &dir),
    );
}

#[test]
fn e0403_scene_lacks_uvs() {
    let dir = scratch("e0403");
    // A triangle with no `vt` lines: no UVs.
    std::fs::write(dir.join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("write");
    std::fs::write(dir.join("scene.toml"), "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n[light]\ndirection = [0.0, 1.0, 0.0]\n[[object]]\nname = \"tri\"\nmesh = \"tri.obj\"\n").expect("write");
    let mut sources = SourceMap::new();
    let text = style("pass p: render(scene) {\n  out color: rgba8unorm = vec4(uv, 0.0, 1.0)\n}\noutput p.color\n");
    let compiled =
        compiler::compile_source("case.npr", &text, &dir, &mut sources, &CompileOptions::default()).expect("compiles");
    assert!(compiled
        .manifest
        .scene_attributes
        .contains(&abi::manifest::Attribute::Uv));
    let scene = runner::scene::load_scene(&dir.join("scene.toml"), &mut sources).expect("scene loads");
    let diags = runner::check_scene(&compiled.manifest, &scene);
    let rendered = dsl::diagnostic::render(&diags, &sources, false).replace(&dir.display().to_string(), "<dir>");
    check("E0403", (diags, rendered));
}

#[test]
fn e0404_limit_exceeded() {
    let text =
        style("texture n = noise(size: 100000)\npass p: image() {\n  out color: rgba8unorm = n\n}\noutput p.color\n");
    check("E0404", compile_errors(&text, &scratch("e0404")));
}

#[test]
fn e0405_bad_scene() {
    check(
        "E0405",
        scene_errors("[camera\nposition = [0.0, 0.0, 3.0]\n", &scratch("e0405")),
    );
}

/// Run the `npr` binary from the repository root and return the diagnostic
/// code of its first error line (looked up in `dsl::codes::ALL`) with its
/// whole stderr, scratch paths replaced by `<dir>`.
fn cli_errors(args: &[&str], dir: &Path) -> (Vec<Diagnostic>, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr");
    let stderr = String::from_utf8_lossy(&o.stderr).replace(&dir.display().to_string(), "<dir>");
    assert_eq!(o.status.code(), Some(1), "npr {args:?}: {stderr}");
    let code = stderr
        .split("error[")
        .nth(1)
        .and_then(|rest| rest.split(']').next())
        .and_then(|c| dsl::codes::ALL.iter().find(|(k, _)| *k == c))
        .map_or("none", |(k, _)| k);
    (vec![Diagnostic::error(code, "")], stderr)
}

#[test]
fn e0501_usage_error_keeps_clap_message() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--size",
            "big",
        ],
        &scratch("e0501"),
    );
    assert!(r.contains("invalid value 'big' for '--size <SIZE>'"), "{r}");
    check("E0501", (d, r));
}

#[test]
fn e0502_bad_argument_value() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--fps",
            "0",
        ],
        &scratch("e0502"),
    );
    check("E0502", (d, r));
}

#[test]
fn e0502_an_eye_the_scene_does_not_have() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--eye",
            "1",
        ],
        &scratch("e0502-eye"),
    );
    check_case("E0502", "E0502_eye", (d, r));
}

#[test]
fn e0503_compile_onto_an_existing_file() {
    let dir = scratch("e0503");
    let file = dir.join("taken");
    std::fs::write(&file, "not a directory").expect("write");
    let (d, r) = cli_errors(
        &["compile", "examples/toon.npr", "-o", file.to_str().expect("utf-8 path")],
        &dir,
    );
    check("E0503", (d, r));
}

#[test]
fn e0504_bad_compiled_directory() {
    let dir = scratch("e0504");
    let (d, r) = cli_errors(
        &[
            "render",
            "--compiled",
            dir.to_str().expect("utf-8 path"),
            "--scene",
            "examples/scenes/spot.toml",
        ],
        &dir,
    );
    check("E0504", (d, r));
}

#[test]
fn e0505_no_gpu_device() {
    // No machine here lacks an adapter (lavapipe, then GL): render the
    // diagnostic the CLI prints for one.
    let rendered = dsl::diagnostic::render(
        &[runner::DeviceError::NoAdapter.to_diagnostic()],
        &SourceMap::new(),
        false,
    );
    check(
        "E0505",
        (vec![runner::DeviceError::NoAdapter.to_diagnostic()], rendered),
    );
}

#[test]
fn e0506_a_benchmark_that_cannot_run() {
    let dir = scratch("e0506");
    let missing = dir.join("missing.npr");
    let (d, r) = cli_errors(
        &[
            "bench",
            "compile",
            missing.to_str().expect("utf-8 path"),
            "--iterations",
            "1",
        ],
        &dir,
    );
    check("E0506", (d, r));
}

#[test]
fn e0507_a_studio_port_in_use() {
    // Hold a port, then ask the studio for it: it must refuse at once.
    let taken = std::net::TcpListener::bind("127.0.0.1:0").expect("bind a port");
    let port = taken.local_addr().expect("address").port().to_string();
    let (d, r) = cli_errors(
        &[
            "studio",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--port",
            &port,
        ],
        &scratch("e0507"),
    );
    let r = r.replace(&port, "<port>");
    assert!(r.contains("--port 0"), "{r}");
    check("E0507", (d, r));
}

#[test]
fn e0404_frames_past_the_frame_limit() {
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--frames",
            "0..1000000",
        ],
        &scratch("e0404-frames"),
    );
    check_case("E0404", "E0404_frames", (d, r));
}

#[test]
fn e9001_internal_error_names_the_npr_span() {
    // Internal errors come from compiler bugs, so none can be triggered from
    // valid input; render one the way the pipeline builds it.
    let mut sources = SourceMap::new();
    let file = sources.add("case.npr", SIMPLE_PASS);
    let err = compiler::InternalError {
        message: "emitted WGSL for pass `p` failed naga validation".into(),
        detail: "error: example naga message".into(),
        span: Some(dsl::Span::new(file, 0, 6)),
        wgsl: Some("// the rejected module".into()),
    };
    let rendered = dsl::diagnostic::render(&[err.to_diagnostic()], &sources, false);
    assert!(rendered.contains("case.npr:1:1"), "{rendered}");
    insta::assert_snapshot!("E9001", rendered);
}

#[test]
fn every_code_has_a_case() {
    // Whitespace removed, so rustfmt's line breaks do not matter.
    let this_file: String = include_str!("error_codes.rs")
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    for (code, _) in dsl::codes::ALL {
        let needle = format!("check(\"{code}\"");
        assert!(
            this_file.contains(&needle),
            "error code {code} has no test case in tests/error_codes.rs"
        );
    }
}

#[test]
fn several_errors_are_reported_in_one_run() {
    let text = style("param a: float = 1.0 in 0..0.5\nparam b: px = 3m\npass p: render(scene) {\n  out color: r8unorm = lambrt(normal, light.dir)\n}\noutput p.color\n");
    let (d, _) = compile_errors(&text, &scratch("multi"));
    let codes: Vec<&str> = d.iter().map(|d| d.code).collect();
    assert!(
        codes.contains(&"E0203") && codes.contains(&"E0202") && codes.contains(&"E0102"),
        "{codes:?}"
    );
}

#[test]
fn e9001_without_wgsl_names_an_impossible_state() {
    // Internal errors outside validation (allocate, manifest, resolve's
    // stdlib defaults) carry no module: the label says what happened.
    let mut sources = SourceMap::new();
    let file = sources.add("case.npr", SIMPLE_PASS);
    let err = compiler::InternalError {
        message: "the output target has no allocated target".into(),
        detail: "`p.color` is not among the allocated targets".into(),
        span: Some(dsl::Span::new(file, 0, 6)),
        wgsl: None,
    };
    let rendered = dsl::diagnostic::render(&[err.to_diagnostic()], &sources, false);
    assert!(rendered.contains("E9001"), "{rendered}");
    assert!(
        rendered.contains("the compiler reached an impossible state here"),
        "{rendered}"
    );
}

/// An ID pass, a pass over its pixels with `kind_args`, and a render pass reading it.
fn pixel_passes(id_format: &str, kind_args: &str) -> String {
    style(&format!(
        "pass ids: render(scene) {{\n  out id: {id_format} = object.id\n}}\n\
         pass cover: compute({kind_args}) {{\n  reduce area: float = sum(1.0)\n}}\n\
         pass shade: render(scene) {{\n  out c: rgba8unorm = vec4(vec3(cover.area / 1000.0), 1.0)\n}}\noutput shade.c\n"
    ))
}

#[test]
fn e0309_pixels_of_a_target_that_is_not_an_id_target() {
    let text = pixel_passes("r16float", "pixels, ids.id");
    let (diags, rendered) = compile_errors(&text, &scratch("e0309"));
    assert!(rendered.contains("out id: r32float = object.id"), "{rendered}");
    check("E0309", (diags, rendered));
}

/// A filter style with `passes` after its header and level input.
const FILTER_HEAD: &str = "style \"Filter\"\ntexture level = filter_input()\n";

#[test]
fn e0310_a_filter_with_a_render_pass() {
    let text = format!(
        "{FILTER_HEAD}pass lit: render(scene) {{\n  out c: rgba8unorm = vec4(level.rgb, 1.0)\n}}\noutput lit.c\n"
    );
    check("E0310", compile_errors(&text, &scratch("e0310")));
}

#[test]
fn e0310_an_art_map_whose_filter_reads_no_level() {
    let dir = scratch("e0310_no_level");
    std::fs::write(
        dir.join("not_a_filter.npr"),
        "style \"Not a filter\"\npass p: image() {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n",
    )
    .unwrap();
    image::RgbaImage::new(4, 4).save(dir.join("src.png")).unwrap();
    let text = style(
        "texture t = artmap(image(\"src.png\"), filter: \"not_a_filter.npr\")\n\
         pass p: render(scene) {\n  out c: rgba8unorm = sample_biased(t, uv)\n}\noutput p.c\n",
    );
    let (d, r) = compile_errors(&text, &dir);
    check_case(
        "E0310",
        "E0310_no_level",
        (d, r.replace(&dir.display().to_string(), "<dir>")),
    );
}

#[test]
fn e0310_an_art_map_inside_a_filter() {
    let dir = scratch("e0310_nested");
    image::RgbaImage::new(4, 4).save(dir.join("src.png")).unwrap();
    let text = format!(
        "{FILTER_HEAD}texture inner = artmap(image(\"src.png\"), filter: \"case.npr\")\n\
         pass p: image() {{\n  out c: rgba16float = level\n}}\noutput p.c\n"
    );
    // The filter it names is itself (found on disk, loaded as a filter).
    std::fs::write(dir.join("case.npr"), &text).unwrap();
    check_case("E0310", "E0310_nested", compile_errors(&text, &dir));
}

#[test]
fn a_pass_over_pixels_without_its_id_target() {
    let text = pixel_passes("r32float", "pixels");
    let (diags, rendered) = compile_errors(&text, &scratch("pixels-no-target"));
    assert!(rendered.contains("compute(pixels, ids.id)"), "{rendered}");
    check_case("E0304", "E0304_pixels_without_id_target", (diags, rendered));
}

#[test]
fn a_target_where_a_pass_kind_takes_a_name() {
    let text = pixel_passes("r32float", "vertices, ids.id");
    let (diags, rendered) = compile_errors(&text, &scratch("kind-arg-field"));
    assert!(
        rendered.contains("expected a tag, found the target `ids.id`"),
        "{rendered}"
    );
    check_case("E0304", "E0304_target_as_kind_argument", (diags, rendered));
}

#[test]
fn a_pass_over_pixels_of_an_unknown_pass_suggests_one() {
    let text = pixel_passes("r32float", "pixels, idz.id");
    let (diags, rendered) = compile_errors(&text, &scratch("pixels-unknown"));
    assert!(rendered.contains("did you mean `ids`?"), "{rendered}");
    check_case("E0101", "E0101_pixels_of_unknown_pass", (diags, rendered));
}

#[test]
fn a_fragment_builtin_in_a_pass_over_vertices() {
    // `screen_uv` is a fragment's; a vertex has none (this once reached naga as E9001).
    let text = style(
        "pass sums: compute(vertices) {\n  reduce s: vec2 = sum(screen_uv)\n}\n\
         pass shade: render(scene) {\n  out c: rgba8unorm = vec4(sums.s, 0.0, 1.0)\n}\noutput shade.c\n",
    );
    let (diags, rendered) = compile_errors(&text, &scratch("vertices-screen-uv"));
    assert!(rendered.contains("`screen_uv` is not available"), "{rendered}");
    check_case("E0304", "E0304_screen_uv_over_vertices", (diags, rendered));
}

#[test]
fn geometry_in_a_pass_over_pixels() {
    let text = pixel_passes("r32float", "pixels, ids.id").replace("sum(1.0)", "sum(normal.x)");
    let (diags, rendered) = compile_errors(&text, &scratch("pixels-normal"));
    assert!(rendered.contains("no geometry in a pass over pixels"), "{rendered}");
    check_case("E0304", "E0304_normal_over_pixels", (diags, rendered));
}

#[test]
fn a_swizzle_mixing_letter_sets() {
    let text = style("pass p: render(scene) {\n  out c: rgba8unorm = vec4(normal.xg, 0.0, 1.0)\n}\noutput p.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("swizzle-mixed"));
    assert!(rendered.contains("write `.xy`"), "{rendered}");
    assert_eq!(diags.len(), 1, "one error, no follow-up: {rendered}");
    check_case("E0104", "E0104_mixed_swizzle", (diags, rendered));
    // Starting with `rgba` letters, the fix keeps them.
    let text = style("pass p: render(scene) {\n  out c: rgba8unorm = vec4(normal.rgz, 1.0)\n}\noutput p.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("swizzle-mixed-rgba"));
    assert_eq!(diags[0].code, "E0104", "{rendered}");
    assert!(rendered.contains("write `.rgb`"), "{rendered}");
}

#[test]
fn a_param_default_that_is_not_a_constant() {
    let text = style(&format!("param lean: float = normal.x * 0.5\n{SIMPLE_PASS}"));
    let (diags, rendered) = compile_errors(&text, &scratch("default-not-constant"));
    assert!(
        rendered.contains("the default of `lean` is not a constant"),
        "{rendered}"
    );
    check_case("E0204", "E0204_default", (diags, rendered));
    // Another param is not a constant either (folding it would make
    // `--keep-params` render differently).
    let text = style(&format!(
        "param a: float = 0.5\nparam b: float = a * 2.0\n{SIMPLE_PASS}"
    ));
    let (diags, rendered) = compile_errors(&text, &scratch("default-of-param"));
    assert_eq!(diags[0].code, "E0204", "{rendered}");
    assert!(rendered.contains("`a` is a parameter, not a constant"), "{rendered}");
    // Constant arithmetic, vectors and a lone percentage stay defaults.
    let text = style(&format!(
        "param a: float = 0.5 * 2.0 - 0.25\nparam v: vec2 = vec2(0.1, 0.2) * 2.0\nparam w: px = 5%\n{SIMPLE_PASS}"
    ));
    compile_warnings(&text);
}

/// A camera, a light and one sphere whose object table ends with `extra`.
fn one_sphere_scene(extra: &str) -> String {
    format!(
        "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n[light]\ndirection = [0.0, 1.0, 0.0]\n\
         [[object]]\nname = \"ball\"\nprimitive = {{ kind = \"sphere\", radius = 0.5, segments = 8, rings = 4 }}\n{extra}\n"
    )
}

#[test]
fn w0401_a_scene_binding_the_style_does_not_read() {
    let dir = scratch("w0401");
    let text = style(
        "object param tint: color = #ffffff\nparam gain: float = 1.0\npass p: render(scene) {\n  out c: rgba8unorm = tint * gain\n}\noutput p.c\n",
    );
    let mut sources = SourceMap::new();
    let compiled =
        compiler::compile_source("case.npr", &text, &dir, &mut sources, &CompileOptions::default()).expect("compiles");
    std::fs::write(
        dir.join("scene.toml"),
        one_sphere_scene("params = { tnit = \"#ff0000\", gain = 2.0, tint = \"#00ff00\" }"),
    )
    .expect("write scene");
    let scene = runner::scene::load_scene(&dir.join("scene.toml"), &mut sources).expect("scene loads");
    let diags = runner::scene_warnings(&compiled.manifest, &scene);
    let rendered = dsl::diagnostic::render(&diags, &sources, false).replace(&dir.display().to_string(), "<dir>");
    // The misspelt name and the style-wide param; not `tint`, which is read.
    assert_eq!(diags.len(), 2, "{rendered}");
    assert!(rendered.contains("did you mean `tint`?"), "{rendered}");
    assert!(
        rendered.contains("`gain` is a style-wide name, the same for every object"),
        "{rendered}"
    );
    assert!(diags.iter().all(|d| !d.is_error()), "{rendered}");
    check("W0401", (diags, rendered));
}

#[test]
fn w0402_a_render_pass_over_a_tag_no_object_has() {
    let text = style(
        "pass ground: render(gorund) {\n  out c: rgba8unorm = #808080\n}\npass final: image(ground) {\n  out color: rgba8unorm = ground.c\n}\noutput final.color\n",
    );
    let scene = abi::SceneSummary {
        tags: ["ground".to_string(), "caster".to_string()].into_iter().collect(),
        name: "scene.toml".into(),
    };
    let opts = CompileOptions {
        scene: Some(scene),
        ..CompileOptions::default()
    };
    let mut sources = SourceMap::new();
    let compiled = compiler::compile_source("case.npr", &text, Path::new("."), &mut sources, &opts)
        .unwrap_or_else(|_| panic!("compiles"));
    let rendered = dsl::diagnostic::render(&compiled.warnings, &sources, false);
    assert!(rendered.contains("did you mean `ground`?"), "{rendered}");
    assert!(rendered.contains("caster, ground"), "{rendered}");
    check("W0402", (compiled.warnings.clone(), rendered));
    // Without a scene nothing is known about tags: no warning.
    let mut sources = SourceMap::new();
    let compiled = compiler::compile_source(
        "case.npr",
        &text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|_| panic!("compiles"));
    assert!(compiled.warnings.is_empty(), "{:?}", compiled.warnings);
}

/// A style in `dir` that samples `texture paper = image("<file>", srgb)`.
fn style_with_texture(dir: &Path, file: &str) -> PathBuf {
    let path = dir.join("case.npr");
    std::fs::write(
        &path,
        style(&format!(
            "/// Paper grain (\"paper\" in the docs).\ntexture paper = image(\"{file}\", srgb)\npass p: render(scene) {{\n  out color: rgba8unorm = paper\n}}\noutput p.color\n"
        )),
    )
    .expect("write style");
    path
}

#[test]
fn npr_check_opens_texture_files_that_are_not_images() {
    let dir = scratch("check-not-an-image");
    std::fs::write(dir.join("paper.png"), "this is text, not a PNG\n").expect("write");
    let style = style_with_texture(&dir, "paper.png");
    let (d, r) = cli_errors(&["check", style.to_str().expect("utf-8 path")], &dir);
    assert!(r.contains("is not an image npr can read"), "{r}");
    assert!(
        r.contains("case.npr:3:23"),
        "the label is on the path in image(...): {r}"
    );
    check_case("E0401", "E0401_not_an_image", (d, r));
}

#[test]
fn npr_check_refuses_a_texture_past_the_size_limit_from_its_header() {
    let dir = scratch("check-too-large");
    let wide = dsl::limits::MAX_TEXTURE_SIZE + 1;
    image::GrayImage::new(wide, 1)
        .save(dir.join("wide.png"))
        .expect("write png");
    let style = style_with_texture(&dir, "wide.png");
    let (d, r) = cli_errors(&["check", style.to_str().expect("utf-8 path")], &dir);
    assert!(r.contains("16385x1, over the 16384-texel limit"), "{r}");
    check_case("E0404", "E0404_texture_size", (d, r));
}

#[test]
fn npr_render_points_at_the_style_for_a_texture_with_a_good_header_and_corrupt_data() {
    let dir = scratch("render-corrupt-data");
    let img = image::RgbaImage::from_fn(64, 64, |x, y| {
        image::Rgba([(x * 4) as u8, (y * 4) as u8, (x ^ y) as u8, 255])
    });
    img.save(dir.join("paper.png")).expect("write png");
    let mut bytes = std::fs::read(dir.join("paper.png")).expect("read png");
    let idat = bytes.windows(4).position(|w| w == b"IDAT").expect("an IDAT chunk");
    for b in &mut bytes[idat + 8..idat + 40] {
        *b ^= 0x5a;
    }
    std::fs::write(dir.join("paper.png"), &bytes).expect("write corrupt png");
    let style = style_with_texture(&dir, "paper.png");
    // The header is fine: `npr check` (which reads headers only) accepts it.
    assert_eq!(
        runner::texture_file::probe(&dir.join("paper.png")).expect("header"),
        (64, 64)
    );
    let (d, r) = cli_errors(
        &[
            "render",
            style.to_str().expect("utf-8 path"),
            "--scene",
            "examples/scenes/spot.toml",
            "-o",
            dir.join("out.png").to_str().expect("utf-8 path"),
        ],
        &dir,
    );
    assert_eq!(d[0].code, "E0401", "{r}");
    assert!(r.contains("is not an image npr can read"), "{r}");
    assert!(
        r.contains("case.npr:3:23"),
        "the label is on the path in image(...): {r}"
    );
    assert!(!dir.join("out.png").exists(), "nothing is written");
    check_case("E0401", "E0401_corrupt_data", (d, r));
}

#[test]
fn npr_render_reports_a_bad_texture_at_the_style_not_only_by_name() {
    let dir = scratch("render-not-an-image");
    std::fs::write(dir.join("paper.png"), [0u8, 1, 2, 3]).expect("write");
    let style = style_with_texture(&dir, "paper.png");
    let (d, r) = cli_errors(
        &[
            "render",
            style.to_str().expect("utf-8 path"),
            "--scene",
            "examples/scenes/spot.toml",
            "-o",
            dir.join("out.png").to_str().expect("utf-8 path"),
        ],
        &dir,
    );
    assert_eq!(d[0].code, "E0401", "{r}");
    assert!(r.contains("case.npr:3:23"), "{r}");
    assert!(!dir.join("out.png").exists(), "nothing is written");
}

#[test]
fn a_texture_file_that_cannot_be_read() {
    // A directory passes no `open`: the error says it cannot be read.
    let dir = scratch("texture-unreadable");
    let err = runner::texture_file::probe(&dir).expect_err("a directory is no image");
    let d = err.to_diagnostic("paper", "textures/");
    assert_eq!(d.code, "E0401");
    assert!(
        d.message.starts_with("cannot read texture `paper` (textures/)"),
        "{}",
        d.message
    );
    // A file whose header is fine is accepted by the probe with its size.
    let ok = dir.join("ok.png");
    image::GrayImage::new(3, 2).save(&ok).expect("write png");
    assert_eq!(runner::texture_file::probe(&ok).expect("a png"), (3, 2));
}

#[test]
fn e0007_a_style_that_is_not_utf8() {
    let dir = scratch("e0007");
    let path = dir.join("latin1.npr");
    let mut bytes = style("/// Caf").into_bytes();
    bytes.push(0xe9); // `é` in Latin-1
    bytes.extend_from_slice(format!(" au lait.\nparam a: float = 1.0\n{SIMPLE_PASS}").as_bytes());
    std::fs::write(&path, bytes).expect("write");
    let mut sources = SourceMap::new();
    let Err(CompileError::User(diags)) = compiler::compile_file(&path, &mut sources, &CompileOptions::default()) else {
        panic!("expected a user error");
    };
    let rendered = dsl::diagnostic::render(&diags, &sources, false).replace(&dir.display().to_string(), "<dir>");
    assert!(
        rendered.contains("latin1.npr:2:8"),
        "line and column of the byte: {rendered}"
    );
    assert!(!rendered.contains("E0004"), "not a bad `use`: {rendered}");
    check("E0007", (diags, rendered));
}

#[test]
fn a_used_style_or_a_scene_that_is_not_utf8() {
    let dir = scratch("e0007-use");
    std::fs::write(dir.join("common.npr"), [b'p', b'a', 0xff, b'\n']).expect("write");
    let text = style(&format!("use \"common.npr\"\n{SIMPLE_PASS}"));
    let (diags, rendered) = compile_errors(&text, &dir);
    assert_eq!(diags[0].code, "E0007", "{rendered}");
    assert!(rendered.contains("common.npr:1:3"), "{rendered}");
    assert!(rendered.contains("used here"), "{rendered}");
    let mut sources = SourceMap::new();
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, [b'#', b' ', 0xfe, 0xff, b'\n']).expect("write");
    let Err(diags) = runner::scene::load_scene(&scene, &mut sources) else {
        panic!("a scene that is not UTF-8 must be refused");
    };
    let rendered = dsl::diagnostic::render(&diags, &sources, false);
    assert_eq!(diags[0].code, "E0007", "{rendered}");
    assert!(rendered.contains("scene.toml:1:3"), "{rendered}");
}

#[test]
fn a_syntax_error_inside_a_pass_does_not_cascade() {
    // The pass does not parse, so `shade` is unknown wherever it is read;
    // only the syntax error is reported, with its caret after the `+`.
    let text = style(
        "param k: float = 1.0\npass shade: render(scene) {\n  let a = k +\n  out c: rgba8unorm = vec4(a)\n}\n\
         pass final: image(shade) {\n  out c: rgba8unorm = shade.c\n}\noutput final.c\n",
    );
    let (diags, rendered) = compile_errors(&text, &scratch("no-cascade"));
    assert_eq!(diags.len(), 1, "{rendered}");
    assert!(rendered.contains("case.npr:4:14"), "{rendered}");
    // A broken `output` line is not also "no output"; errors of other,
    // well-formed declarations are still reported.
    let text = style("param b: px = 3m\npass p: render(scene) {\n  out c: rgba8unorm = #ffffff\n}\noutput p.\n");
    let (diags, rendered) = compile_errors(&text, &scratch("no-cascade-output"));
    let codes: Vec<&str> = diags.iter().map(|d| d.code).collect();
    assert_eq!(codes, ["E0001", "E0202"], "{rendered}");
}

#[test]
fn an_unknown_name_reports_once_not_again_for_its_field() {
    let text = style("pass p: render(scene) {\n  out c: rgba8unorm = nosuch.c\n}\noutput p.c\n");
    let (diags, rendered) = compile_errors(&text, &scratch("unknown-base"));
    assert_eq!(diags.len(), 1, "{rendered}");
    assert_eq!(diags[0].code, "E0101", "{rendered}");
}

#[test]
fn e0406_a_path_outside_the_root() {
    let dir = scratch("e0406");
    let style_dir = dir.join("style");
    std::fs::create_dir_all(&style_dir).expect("dir");
    image::RgbaImage::new(2, 2)
        .save(dir.join("paper.png"))
        .expect("write png");
    let text = style("texture paper = image(\"../paper.png\", srgb)\npass p: render(scene) {\n  out color: rgba8unorm = paper\n}\noutput p.color\n");
    let policy = dsl::paths::PathPolicy::new(&style_dir, &[]).expect("root");
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        paths: Some(policy),
        ..Default::default()
    };
    let Err(CompileError::User(d)) = compiler::compile_source("case.npr", &text, &style_dir, &mut sources, &opts)
    else {
        panic!("a texture outside the root must be refused")
    };
    let canonical = dir.canonicalize().expect("canonical").display().to_string();
    let r = dsl::diagnostic::render(&d, &sources, false).replace(&canonical, "<dir>");
    check("E0406", (d, r));
}

#[test]
fn e0508_the_gpu_out_of_memory() {
    // Forced on the device in tests/gpu_errors.rs (under an address-space
    // limit); this is its rendered message.
    let e = runner::RunError::OutOfMemory("the GPU ran out of memory making the targets of a 16384x16384 image".into());
    let d = e.diagnostics();
    let rendered = dsl::diagnostic::render(&d, &SourceMap::new(), false);
    check("E0508", (d, rendered));
}

#[test]
fn e0509_a_lost_device() {
    // Forced with `Device::destroy` in tests/gpu_errors.rs; its rendered message.
    let e = runner::RunError::DeviceLost("Destroyed: Device is dying.".into());
    let d = e.diagnostics();
    let rendered = dsl::diagnostic::render(&d, &SourceMap::new(), false);
    check("E0509", (d, rendered));
}

#[test]
fn e0203_a_constant_call_outside_its_domain() {
    // naga evaluates calls on constants and rejects these: each was E9001.
    for e in [
        "vec4(sqrt(-0.5))",
        "vec4(log(0.0))",
        "vec4(log2(vec3(-1.0)), 1.0)",
        "vec4(sqrt(vec2(-1.0)), 0.0, 1.0)",
        "vec4(exp(vec3(100.0)), 1.0)",
        "vec4(pow(vec3(-1.0), vec3(0.5)), 1.0)",
        "vec4(acos(2.0))",
    ] {
        let text = style(&format!(
            "pass p: image() {{\n  out c: rgba8unorm = {e}\n}}\noutput p.c\n"
        ));
        let (d, r) = compile_errors(&text, &scratch("e0203-domain"));
        assert_eq!(d[0].code, "E0203", "{e}: {r}");
        assert!(r.contains("has no finite value"), "{e}: {r}");
    }
    // A folded param is a constant too; a kept one (a uniform) is not.
    let text = style(
        "param k: float = -2.0 in -4..4\npass p: image() {\n  out c: rgba8unorm = vec4(sqrt(k))\n}\noutput p.c\n",
    );
    check_case(
        "E0203",
        "E0203_const_domain",
        compile_errors(&text, &scratch("e0203-domain")),
    );
    let mut sources = SourceMap::new();
    let kept = CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    compiler::compile_source("case.npr", &text, &scratch("e0203-domain"), &mut sources, &kept)
        .unwrap_or_else(|e| panic!("a kept param is a uniform, evaluated at run time: {e:?}"));
}

#[test]
fn int_arguments_of_float_only_functions_are_promoted() {
    // `mix`, `pow`, `step` and `atan2` of two ints were E9001 (naga: no
    // integer overload); found by tests/fuzz_generated.rs.
    for e in [
        "mix(n, n, 0.5)",
        "mix(n, 2, 0.5)",
        "pow(n, 2)",
        "step(n, 3)",
        "atan2(n, n)",
        "min(n, 2) * 0.1",
    ] {
        let text = style(&format!(
            "param n: int = 6 in 0..8\npass p: image() {{\n  out c: r16float = {e}\n}}\noutput p.c\n"
        ));
        for keep_params in [false, true] {
            let mut sources = SourceMap::new();
            let opts = CompileOptions {
                keep_params,
                ..Default::default()
            };
            if let Err(err) =
                compiler::compile_source("case.npr", &text, &scratch("int-promotion"), &mut sources, &opts)
            {
                panic!("{e} (keep_params {keep_params}): {err:?}");
            }
        }
    }
}
