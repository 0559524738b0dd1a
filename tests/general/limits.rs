//! The limits of `npr_diag::limits`, from both sides: input at a limit compiles to
//! WGSL that naga accepts (never E9001), and input past it, up to ten times
//! past, is a user error with the limit's code, never a crash.
//!
//! These run on the test harness's threads, whose stacks (2 MiB) are smaller
//! than the main thread's (8 MiB), in debug builds: if the limits fit here,
//! they fit in `npr`. The property test at the end runs the real binary.

use npr_compiler::{CompileError, CompileOptions};
use npr_diag::limits::{MAX_EXPR_DEPTH, MAX_NESTING, MAX_PARAMS, MAX_SOURCE_BYTES};
use npr_diag::SourceMap;
use proptest::prelude::*;
use std::path::Path;
use std::process::Command;

/// A style whose one output is `value` (a float), with a float `a`, a vec3
/// `v` and a bool `b` to build from.
fn style_with(value: &str) -> String {
    format!(
        "style \"Limits\"\nparam a: float = 0.5 in 0..1 animate {{ 0s: 0.1, 1s: 0.9 }}\n\
         param v: vec3 = vec3(0.1, 0.2, 0.3)\nparam b: bool = true\n\
         pass p: render(scene) {{\n  out c: r8unorm = {value}\n}}\noutput p.c\n"
    )
}

/// Compile with `--keep-params`, so nothing folds away and the emitted WGSL
/// is as deep as the source.
fn compile(text: &str) -> Result<npr_compiler::Compiled, CompileError> {
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    npr_compiler::compile_source("limits.npr", text, Path::new("."), &mut sources, &opts)
}

fn assert_compiles(what: &str, text: &str) {
    match compile(text) {
        Ok(_) => {}
        Err(CompileError::User(d)) => panic!("{what}: user error {:?}", d.iter().map(|d| d.code).collect::<Vec<_>>()),
        Err(CompileError::Internal(e)) => panic!("{what}: internal error {e}"),
    }
}

/// The only error is `code`, and it has a span.
fn assert_refused(what: &str, text: &str, code: &str) {
    match compile(text) {
        Ok(_) => panic!("{what}: compiled"),
        Err(CompileError::User(d)) => {
            let codes: Vec<_> = d.iter().map(|d| d.code).collect();
            assert_eq!(codes, [code], "{what}");
            assert!(d[0].primary_span().is_some(), "{what}: no span");
        }
        Err(CompileError::Internal(e)) => panic!("{what}: internal error {e}"),
    }
}

/// The deep shapes, each `n` levels deep in the way it nests.
fn nested(shape: Shape, n: usize) -> String {
    match shape {
        Shape::Parens => format!("{}a{}", "(".repeat(n), ")".repeat(n)),
        Shape::Calls => format!("{}a{}", "sin(".repeat(n), ")".repeat(n)),
        Shape::Blocks => format!("{}a{}", "{ ".repeat(n), " }".repeat(n)),
        Shape::IfConditions => format!(
            "if {}b{} {{ a }} else {{ 0.0 }}",
            "if ".repeat(n - 1),
            " { true } else { false }".repeat(n - 1)
        ),
        Shape::Normalize => format!("{}v{}.x", "normalize(".repeat(n), ")".repeat(n)),
        Shape::Sum => vec!["a"; n].join(" + "),
        Shape::Product => vec!["a"; n].join(" * "),
        Shape::Negations => format!("{}a", "-".repeat(n)),
        Shape::ElseIfs => format!(
            "if b {{ a }}{} else {{ 0.0 }}",
            " else if b { a }".repeat(n.saturating_sub(1))
        ),
        Shape::Fields => format!("v{}", ".x".repeat(n)),
    }
}

#[derive(Debug, Clone, Copy)]
enum Shape {
    Parens,
    Calls,
    Blocks,
    IfConditions,
    Normalize,
    Sum,
    Product,
    Negations,
    ElseIfs,
    Fields,
}

/// Shapes that nest brackets (E0005) and shapes that grow a chain (E0006).
const BRACKETS: [Shape; 5] = [
    Shape::Parens,
    Shape::Calls,
    Shape::Blocks,
    Shape::IfConditions,
    Shape::Normalize,
];
const CHAINS: [Shape; 4] = [Shape::Sum, Shape::Product, Shape::Negations, Shape::ElseIfs];

#[test]
fn nesting_at_the_limit_compiles() {
    // The pass body's braces are the first level; an `if` in a condition
    // is one more, and the innermost one's `{ true }` another.
    for shape in BRACKETS {
        let n = match shape {
            Shape::IfConditions => MAX_NESTING - 2,
            _ => MAX_NESTING - 1,
        };
        assert_compiles(&format!("{shape:?}"), &style_with(&nested(shape, n)));
    }
}

#[test]
fn chains_at_the_limit_compile() {
    // A few levels go to the chain's operands and the output.
    for shape in CHAINS {
        assert_compiles(&format!("{shape:?}"), &style_with(&nested(shape, MAX_EXPR_DEPTH - 4)));
    }
}

#[test]
fn nested_normalize_stays_small() {
    // Each `normalize` writes its operand three times: inline, 60 of them
    // would be 3^60 copies of `v`.
    let c = compile(&style_with(&nested(Shape::Normalize, MAX_NESTING - 1))).expect("compiles");
    let wgsl = c.shader("p.wgsl").expect("p.wgsl");
    assert!(wgsl.len() < 200_000, "{} bytes", wgsl.len());
}

#[test]
fn nesting_past_the_limit_points_at_the_first_level_too_deep() {
    let text = style_with(&nested(Shape::Parens, MAX_NESTING));
    let mut sources = SourceMap::new();
    let Err(CompileError::User(d)) = npr_compiler::compile_source(
        "limits.npr",
        &text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    ) else {
        panic!("compiled");
    };
    let span = d[0].primary_span().expect("span");
    let first = text.find("= (").expect("the output") + 2;
    // The pass body is level 1, so the 64th `(` opens level 65.
    assert_eq!(span.start as usize, first + MAX_NESTING - 1);
    assert_eq!(&text[span.range()], "(");
}

#[test]
fn too_many_params() {
    let params: String = (0..=MAX_PARAMS).map(|i| format!("param p{i}: float = 0.5\n")).collect();
    assert_refused(
        "params",
        &format!("style \"S\"\n{params}pass p: image() {{ out c: r8unorm = p0 }}\noutput p.c\n"),
        npr_diag::codes::LIMIT_EXCEEDED,
    );
}

#[test]
fn a_file_past_the_size_limit_is_refused_where_the_limit_is() {
    let text = style_with(&format!("a // {}", "x".repeat(MAX_SOURCE_BYTES)));
    assert_refused("source size", &text, npr_diag::codes::LIMIT_EXCEEDED);
}

/// Runs `npr check` on `text`, written to a scratch file.
fn npr_check(name: &str, text: &str) -> std::process::Output {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("limits");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let path = dir.join(format!("{name}.npr"));
    std::fs::write(&path, text).expect("write style");
    Command::new(env!("CARGO_BIN_EXE_npr"))
        .arg("check")
        .arg(&path)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr")
}

fn shape_strategy() -> impl Strategy<Value = (Shape, usize, &'static str)> {
    let brackets = (prop::sample::select(BRACKETS.to_vec()), MAX_NESTING..=10 * MAX_NESTING)
        .prop_map(|(s, n)| (s, n, npr_diag::codes::NESTED_TOO_DEEP));
    let chains = (
        prop::sample::select(CHAINS.to_vec()),
        MAX_EXPR_DEPTH + 1..=10 * MAX_EXPR_DEPTH,
    )
        .prop_map(|(s, n)| (s, n, npr_diag::codes::EXPRESSION_TOO_DEEP));
    let fields = (MAX_EXPR_DEPTH + 1..=10 * MAX_EXPR_DEPTH)
        .prop_map(|n| (Shape::Fields, n, npr_diag::codes::EXPRESSION_TOO_DEEP));
    prop_oneof![brackets, chains, fields]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Deep and long input up to 10× each limit, through the real binary:
    /// exit 1 with the limit's code, never a crash or an internal error.
    #[test]
    fn past_a_limit_npr_exits_1_with_its_code((shape, n, code) in shape_strategy()) {
        let o = npr_check("deep", &style_with(&nested(shape, n)));
        let stderr = String::from_utf8_lossy(&o.stderr);
        prop_assert_eq!(o.status.code(), Some(1), "{:?} × {}: {}", shape, n, stderr);
        let tag = format!("error[{code}]");
        prop_assert!(stderr.contains(&tag), "{:?} × {}: {}", shape, n, stderr);
        prop_assert!(!stderr.contains("panicked") && !stderr.contains("overflow"), "{}", stderr);
    }
}

#[test]
fn ten_times_past_every_limit_in_process() {
    // The same shapes through the library on a test thread's small stack.
    for shape in BRACKETS {
        assert_refused(
            &format!("{shape:?}"),
            &style_with(&nested(shape, 10 * MAX_NESTING)),
            npr_diag::codes::NESTED_TOO_DEEP,
        );
    }
    for shape in CHAINS.into_iter().chain([Shape::Fields]) {
        assert_refused(
            &format!("{shape:?}"),
            &style_with(&nested(shape, 10 * MAX_EXPR_DEPTH)),
            npr_diag::codes::EXPRESSION_TOO_DEEP,
        );
    }
    // The cases: a sum of 10⁵ terms and a thousand parentheses.
    assert_refused(
        "sum",
        &style_with(&nested(Shape::Sum, 100_000)),
        npr_diag::codes::EXPRESSION_TOO_DEEP,
    );
    assert_refused(
        "parens",
        &style_with(&nested(Shape::Parens, 1000)),
        npr_diag::codes::NESTED_TOO_DEEP,
    );
    assert_refused(
        "blocks",
        &style_with(&nested(Shape::Blocks, 1000)),
        npr_diag::codes::NESTED_TOO_DEEP,
    );
}

#[test]
fn a_long_chain_of_lets_compiles() {
    // Each `let` reads the one before: the IR is as deep as the chain, and
    // the recursive constant folder overflowed the stack on it.
    let n = 10_000;
    let lets: String = (1..n).map(|i| format!("  let l{i} = l{} + a\n", i - 1)).collect();
    let text = format!(
        "style \"Lets\"\nparam a: float = 0.5 animate {{ 0s: 0.1, 1s: 0.9 }}\n\
         pass p: render(scene) {{\n  let l0 = a\n{lets}  out c: r8unorm = l{}\n}}\noutput p.c\n",
        n - 1
    );
    assert_compiles("let chain", &text);
}

#[test]
fn lets_used_twice_fold_in_linear_time() {
    // `l{i} = l{i-1} + l{i-1}` in a param's default: a DAG of 60 nodes with
    // 2^59 paths, which the unmemoized constant folder walked path by path
    // when the typechecker checked the default against its range.
    let lets: String = (1..60)
        .map(|i| format!(" let l{i} = l{} + l{};", i - 1, i - 1))
        .collect();
    let text = format!(
        "style \"Lets\"\nparam x: float = {{ let l0 = 1e-18;{lets} l59 }} in 0..1\n\
         pass p: render(scene) {{\n  out c: r8unorm = x\n}}\noutput p.c\n"
    );
    assert_compiles("doubling lets", &text);
}

/// A `state`'s first value made deep through a chain of lets is split into
/// WGSL `let`s like every other value (it once reached naga's nesting
/// limit inline: E9001).
#[test]
fn a_state_first_value_deep_through_lets_compiles() {
    let mut text = String::from("style \"Deep first\"\npass f: compute(objects) {\n  let a0 = object.index * 1.0\n");
    for i in 1..200 {
        text += &format!("  let a{i} = a{} * 1.001 + 0.5\n", i - 1);
    }
    text += "  state s: float = a199\n  s = s + 1.0\n}\npass shade: render(scene) {\n  out c: r32float = f.s\n}\noutput shade.c\n";
    let mut sources = npr_diag::SourceMap::new();
    match npr_compiler::compile_source(
        "deep.npr",
        &text,
        std::path::Path::new("."),
        &mut sources,
        &Default::default(),
    ) {
        Ok(_) => {}
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("internal error: {e}"),
    }
}

/// A scene of `bytes` bytes: a valid scene padded with a comment.
fn scene_of(bytes: usize) -> String {
    let head = "[camera]\nposition = [0.0, 0.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = { kind = \"sphere\" }\n# ";
    let mut text = format!("{head}{}", "x".repeat(bytes.saturating_sub(head.len() + 1)));
    text.push('\n');
    text
}

#[test]
fn a_scene_at_the_size_limit_loads_and_one_byte_more_is_refused_where_the_limit_is() {
    use npr_diag::limits::MAX_SCENE_BYTES;
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("limits");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let at = dir.join("at_limit.toml");
    std::fs::write(&at, scene_of(MAX_SCENE_BYTES)).expect("write scene");
    assert_eq!(std::fs::metadata(&at).expect("size").len() as usize, MAX_SCENE_BYTES);
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&at, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));

    let over = dir.join("over_limit.toml");
    std::fs::write(&over, scene_of(MAX_SCENE_BYTES + 1)).expect("write scene");
    let mut sources = npr_diag::SourceMap::new();
    let Err(d) = npr_runner::scene::load_scene(&over, &mut sources) else {
        panic!("a scene of {} bytes must be refused", MAX_SCENE_BYTES + 1)
    };
    assert_eq!(d.len(), 1);
    assert_eq!(d[0].code, npr_diag::codes::LIMIT_EXCEEDED);
    let span = d[0].primary_span().expect("a span");
    assert_eq!(span.start as usize, MAX_SCENE_BYTES);
    let rendered = npr_diag::diagnostic::render(&d, &sources, false);
    assert!(rendered.contains("over the 1048576-byte limit"), "{rendered}");

    // Through the binary: exit 1 with the code.
    let out = Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["render", "examples/toon.npr", "--scene"])
        .arg(&over)
        .args(["-o", "/dev/null"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr");
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("E0404"));
}
