//! Error codes of the front end: syntax and files read as text (E00xx),
//! names (E01xx), types, units and constants (E02xx).

use super::*;

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
    let big = style(&"// padding\n".repeat(npr_diag::limits::MAX_SOURCE_BYTES / 10));
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
fn w0201_a_colour_times_a_splat_vector_scales_its_alpha() {
    let text = style("param base: color = #e07a3a\npass p: render(scene) {\n  out c: rgba8unorm = base * vec4(lambert(normal, light.dir))\n}\noutput p.c\n");
    check("W0201", compile_warnings(&text));
}

#[test]
fn a_colour_times_a_number_keeps_its_alpha_and_warns_nothing() {
    let text = style("param base: color = #e07a3a\npass p: render(scene) {\n  out c: rgba8unorm = base * lambert(normal, light.dir) + vec4(0.1, 0.1, 0.1, 0.0)\n}\noutput p.c\n");
    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_source(
        "case.npr",
        &text,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    )
    .expect("compiles");
    assert!(compiled.warnings.is_empty(), "{:?}", compiled.warnings);
    let wgsl = compiled.shader("p.wgsl").expect("the pass's shader");
    // The light is scaled, the coverage (the colour's alpha, 1 here) kept.
    assert!(
        wgsl.contains("vec4<f32>((vec3<f32>(0.8784314f, 0.47843137f, 0.22745098f) * npr_lambert(npr_unit(in.normal_world), frame.light_dir.xyz)), 1.0f)"),
        "{wgsl}"
    );
}

#[test]
fn e0206_a_gradient_with_no_stops() {
    let text = style("param g: gradient = gradient()\npass p: image() {\n  out c: rgba8unorm = ramp(g, screen_uv.x)\n}\noutput p.c\n");
    check("E0206", compile_errors(&text, &scratch("e0206")));
}

#[test]
fn e0206_a_gradient_whose_stops_are_out_of_order() {
    let text = style("param g: gradient = gradient(stop(0.6, #000000), stop(0.2, #ffffff))\npass p: image() {\n  out c: rgba8unorm = ramp(g, screen_uv.x)\n}\noutput p.c\n");
    check_case(
        "E0206",
        "E0206_unsorted",
        compile_errors(&text, &scratch("e0206-unsorted")),
    );
}

#[test]
fn e0206_a_stop_outside_0_to_1() {
    let text = style("param g: gradient = gradient(stop(0.0, #000000), stop(1.5, #ffffff))\npass p: image() {\n  out c: rgba8unorm = ramp(g, screen_uv.x)\n}\noutput p.c\n");
    check_case(
        "E0206",
        "E0206_position",
        compile_errors(&text, &scratch("e0206-position")),
    );
}

#[test]
fn e0203_an_operator_argument_out_of_range_names_the_range() {
    let text = style(
        "pass p: render(scene) {\n  out c: r8unorm = toon(lambert(normal, light.dir), steps: 40)\n}\noutput p.c\n",
    );
    let (d, r) = compile_errors(&text, &scratch("e0203-operator"));
    assert!(
        r.contains("help: `steps` takes a value in 1..16 (number of bands)"),
        "{r}"
    );
    check_case("E0203", "E0203_operator_argument", (d, r));
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

#[test]
fn e0007_a_style_that_is_not_utf8() {
    let dir = scratch("e0007");
    let path = dir.join("latin1.npr");
    let mut bytes = style("/// Caf").into_bytes();
    bytes.push(0xe9); // `é` in Latin-1
    bytes.extend_from_slice(format!(" au lait.\nparam a: float = 1.0\n{SIMPLE_PASS}").as_bytes());
    std::fs::write(&path, bytes).expect("write");
    let mut sources = SourceMap::new();
    let Err(CompileError::User(diags)) = npr_compiler::compile_file(&path, &mut sources, &CompileOptions::default())
    else {
        panic!("expected a user error");
    };
    let rendered = npr_diag::diagnostic::render(&diags, &sources, false).replace(&dir.display().to_string(), "<dir>");
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
    let Err(diags) = npr_runner::scene::load_scene(&scene, &mut sources) else {
        panic!("a scene that is not UTF-8 must be refused");
    };
    let rendered = npr_diag::diagnostic::render(&diags, &sources, false);
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
        // Through normalize, clamp, cross, distance, `%`, a comparison and a
        // constant `if` (a 30,000-case soak of tests/general/fuzz_generated.rs
        // found the first).
        "sqrt(normalize(vec4(2.229) + vec4(0.5)) - clamp(vec4(1.962), vec4(0.0), vec4(1.0)))",
        "vec4(sqrt(cross(vec3(1.0, 0.0, 0.0), vec3(0.0, -1.0, 0.0))), 1.0)",
        "vec4(log(distance(vec2(1.0), vec2(1.0))))",
        "vec4(sqrt(-(5.0 % 3.0)))",
        "vec4(sqrt(if 1.0 > 2.0 { 1.0 } else { -1.0 }))",
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
    npr_compiler::compile_source("case.npr", &text, &scratch("e0203-domain"), &mut sources, &kept)
        .unwrap_or_else(|e| panic!("a kept param is a uniform, evaluated at run time: {e:?}"));
}

#[test]
fn int_arguments_of_float_only_functions_are_promoted() {
    // `mix`, `pow`, `step` and `atan2` of two ints were E9001 (naga: no
    // integer overload); found by tests/general/fuzz_generated.rs.
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
                npr_compiler::compile_source("case.npr", &text, &scratch("int-promotion"), &mut sources, &opts)
            {
                panic!("{e} (keep_params {keep_params}): {err:?}");
            }
        }
    }
}
