//! The domain warnings of the range analysis (issue 49, W0203–W0210):
//! each planted case warns with its code and a snapshot of its message,
//! and its safe form warns nothing.

use super::*;

/// The warnings of `text`, and whether any has `code`.
fn warnings_of(text: &str) -> Vec<Diagnostic> {
    let mut sources = SourceMap::new();
    npr_compiler::compile_source(
        "case.npr",
        text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|_| panic!("compiles:\n{text}"))
    .warnings
}

/// `--set name=value`, its text in `sources` as the CLI adds it.
fn set(sources: &mut SourceMap, name: &str, value: &str) -> npr_compiler::ir::ParamSetting {
    let arg = format!("{name}={value}");
    let file = sources.add("--set", arg.clone());
    npr_compiler::ir::ParamSetting {
        name: name.into(),
        name_span: npr_diag::Span::new(file, 0, name.len()),
        value: npr_abi::param_literal::read_literal(value),
        value_span: npr_diag::Span::new(file, name.len() + 1, arg.len()),
        origin: npr_abi::param_literal::SettingOrigin::CommandLine,
    }
}

/// An image pass writing `value` into an `r32float` target, after `params`.
fn image(params: &str, value: &str) -> String {
    style(&format!(
        "{params}pass p: image() {{\n  out c: r32float = {value}\n}}\noutput p.c\n"
    ))
}

/// No warning on the safe form.
fn quiet(fixed: &str) {
    let after = warnings_of(fixed);
    assert!(after.is_empty(), "the safe form still warns: {after:?}");
}

#[test]
fn w0203_log_of_a_value_that_may_reach_zero() {
    check(
        "W0203",
        compile_warnings(&image("param k: float = 0.5 in 0..1\n", "log(k * screen_uv.x)")),
    );
    quiet(&image(
        "param k: float = 0.5 in 0..1\n",
        "log(max(k * screen_uv.x, 1e-6))",
    ));
}

#[test]
fn w0204_sqrt_of_a_value_that_may_be_negative() {
    check(
        "W0204",
        compile_warnings(&image("param k: float = 0.5 in 0..1\n", "sqrt(screen_uv.x - k)")),
    );
    quiet(&image(
        "param k: float = 0.5 in 0..1\n",
        "sqrt(max(screen_uv.x - k, 0.0))",
    ));
}

/// The planted case: `pow(f, sharp - 1.0)` with f = 0 past the
/// terminator and `sharp` allowed below 1 is `pow(0, negative)`, which
/// lavapipe returns as 0 and other drivers as +inf.
#[test]
fn w0205_pow_of_zero_to_a_negative_power_is_the_planted_case() {
    let params = "param sharp: float = 2.0 in 0.5..4\n";
    let wrong = style(&format!(
        "{params}pass p: render(scene) {{\n  let f = max(dot(normal, light.dir), 0.0)\n  out c: r32float = pow(f, sharp - 1.0)\n}}\noutput p.c\n"
    ));
    let fixed = style(&format!(
        "{params}pass p: render(scene) {{\n  let f = max(dot(normal, light.dir), 0.0)\n  out c: r32float = pow(max(f, 1e-6), sharp - 1.0)\n}}\noutput p.c\n"
    ));
    check("W0205", compile_warnings(&wrong));
    quiet(&fixed);
    // With `sharp` kept at 2 by --set, y = 1 > 0: pow(0, 1) is defined.
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        settings: vec![set(&mut sources, "sharp", "2")],
        ..CompileOptions::default()
    };
    let c = npr_compiler::compile_source("case.npr", &wrong, Path::new("."), &mut sources, &opts).expect("compiles");
    assert!(
        c.warnings.is_empty(),
        "sharp fixed at 2 leaves pow defined: {:?}",
        c.warnings
    );
}

#[test]
fn w0206_division_by_a_range_holding_zero() {
    check(
        "W0206",
        compile_warnings(&image("param k: float = 0.5 in 0..1\n", "screen_uv.x / k")),
    );
    quiet(&image("param k: float = 0.5 in 0.1..1\n", "screen_uv.x / k"));
}

#[test]
fn w0206_smoothstep_whose_edges_may_meet() {
    let params = "param a: float = 0.2 in 0..1\nparam b: float = 0.8 in 0..1\n";
    check_case(
        "W0206",
        "W0206_smoothstep",
        compile_warnings(&image(params, "smoothstep(a, b, screen_uv.x)")),
    );
    let after = warnings_of(&image(params, "smoothstep(a, max(b, a + 0.01), screen_uv.x)"));
    assert!(after.is_empty(), "{after:?}");
}

#[test]
fn w0207_acos_of_a_dot_product_that_may_round_past_one() {
    // n·l of unit vectors may come out 1 + 2⁻²³ in f32.
    let wrong = style("pass p: render(scene) {\n  out c: r32float = acos(dot(normal, light.dir))\n}\noutput p.c\n");
    let fixed = style(
        "pass p: render(scene) {\n  out c: r32float = acos(clamp(dot(normal, light.dir), -1.0, 1.0))\n}\noutput p.c\n",
    );
    check("W0207", compile_warnings(&wrong));
    quiet(&fixed);
}

#[test]
fn w0208_normalize_of_a_vector_that_may_be_zero() {
    check(
        "W0208",
        compile_warnings(&image("", "normalize(vec2(screen_uv.x - 0.5, screen_uv.y - 0.5)).x")),
    );
    quiet(&image("", "normalize(vec2(screen_uv.x + 0.5, screen_uv.y - 0.5)).x"));
}

#[test]
fn w0209_atan2_at_the_origin() {
    check(
        "W0209",
        compile_warnings(&image("", "atan2(screen_uv.y - 0.5, screen_uv.x - 0.5)")),
    );
    quiet(&image("", "atan2(screen_uv.y - 0.5, screen_uv.x + 0.5)"));
}

#[test]
fn w0210_an_f16_target_overflowing() {
    let wrong = style(
        "param gain: float = 10.0 in 1..100000\npass p: image() {\n  out c: r16float = screen_uv.x * gain\n}\noutput p.c\n",
    );
    let fixed = style(
        "param gain: float = 10.0 in 1..60000\npass p: image() {\n  out c: r16float = screen_uv.x * gain\n}\noutput p.c\n",
    );
    check("W0210", compile_warnings(&wrong));
    quiet(&fixed);
}

/// A bad case that only a folded `--set` value could reach: a param fixed
/// by `--set` at a safe value is its value, not its range.
#[test]
fn a_param_fixed_by_set_is_its_value_not_its_range() {
    let text = image("param k: float = 0.5 in 0..1\n", "screen_uv.x / k");
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        settings: vec![set(&mut sources, "k", "0.25")],
        ..CompileOptions::default()
    };
    let c = npr_compiler::compile_source("case.npr", &text, Path::new("."), &mut sources, &opts).expect("compiles");
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
}
