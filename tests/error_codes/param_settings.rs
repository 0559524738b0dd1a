//! Parameter settings (E0101, E0201, E0202, E0203): the arguments of an
//! art-map's filter, checked against the params the filter declares, and
//! the same mistakes as `--set`s of that filter, which the same function in
//! the compiler types and so reports alike.

use super::passes::FILTER_HEAD;
use super::*;

/// A host style whose art-map passes `args` to a filter with two params,
/// `spacing: float = 4 in 2..32` and `mode: enum(soft, hard) = soft`.
fn filter_args_case(name: &str, args: &str) -> (Vec<Diagnostic>, String) {
    let (text, dir) = filter_args_files(name, args);
    compile_errors(&text, &dir)
}

/// The files of [`filter_args_case`]: the host style's text and its folder.
fn filter_args_files(name: &str, args: &str) -> (String, std::path::PathBuf) {
    let dir = scratch(name);
    std::fs::write(
        dir.join("hatch.npr"),
        format!(
            "{FILTER_HEAD}/// Stroke distance.\nparam spacing: float = 4 in 2..32\n/// Stroke edges.\nparam mode: enum(soft, hard) = soft\npass p: image() {{\n  let k = if mode == hard {{ 1.0 }} else {{ 0.5 }}\n  out c: rgba8unorm = vec4(level.rgb * k * step(0.5, fract(frag_coord.x / spacing)), 1.0)\n}}\noutput p.c\n"
        ),
    )
    .unwrap();
    let text = format!(
        "style \"Case\"\ntexture t = artmap(image(\"src.png\"), filter: filter(\"hatch.npr\", {args}))\n\
         pass p: render(scene) {{\n  out c: rgba8unorm = sample(t, uv)\n}}\noutput p.c\n"
    );
    image::RgbaImage::from_pixel(4, 4, image::Rgba([128, 128, 128, 255]))
        .save(dir.join("src.png"))
        .unwrap();
    (text, dir)
}

#[test]
fn filter_arguments_are_checked_against_the_filters_params() {
    check_case(
        "E0101",
        "filter_arg_unknown",
        filter_args_case("farg-unknown", "spacng: 8"),
    );
    check_case(
        "E0202",
        "filter_arg_unit",
        filter_args_case("farg-unit", "spacing: 8px"),
    );
    check_case(
        "E0203",
        "filter_arg_range",
        filter_args_case("farg-range", "spacing: 64"),
    );
    check_case(
        "E0201",
        "filter_arg_components",
        filter_args_case("farg-type", "spacing: #ff0000"),
    );
    check_case(
        "E0003",
        "filter_arg_twice",
        filter_args_case("farg-twice", "spacing: 8, spacing: 6"),
    );
}

#[test]
fn a_filters_enum_param_takes_one_of_its_variants_by_name() {
    // As `--set mode=hard` would: the name is the filter's variant.
    let (text, dir) = filter_args_files("farg-enum-ok", "mode: hard, spacing: 8");
    let mut sources = npr_diag::SourceMap::new();
    let compiled = npr_compiler::compile_source("case.npr", &text, &dir, &mut sources, &Default::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    let filter = match &compiled.manifest.textures[0].source {
        npr_abi::manifest::TextureSourceManifest::Artmap(spec) => &spec.filter,
        other => panic!("not an art-map: {other:?}"),
    };
    let default = |name: &str| {
        let p = filter.manifest.params.iter().find(|p| p.name == name);
        p.unwrap_or_else(|| panic!("no `{name}` in {:?}", filter.manifest.params))
            .default
            .clone()
    };
    assert_eq!(default("mode"), vec![1.0], "`hard` is the second variant");
    assert_eq!(default("spacing"), vec![8.0]);
    check_case(
        "E0201",
        "filter_arg_enum_variant",
        filter_args_case("farg-enum-typo", "mode: hrad"),
    );
    check_case(
        "E0201",
        "filter_arg_enum_number",
        filter_args_case("farg-enum-number", "mode: 1"),
    );
    check_case(
        "E0201",
        "filter_arg_name_for_number",
        filter_args_case("farg-name-number", "spacing: hard"),
    );
}

/// The `--set` mistakes of `npr check hatch.npr` (the filter style of
/// [`filter_args_files`] compiled on its own), as the CLI writes them with
/// `--message-format json`.
fn set_errors(style: &Path, set: &str) -> Vec<serde_json::Value> {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .args([
            "check",
            &style.display().to_string(),
            "--message-format",
            "json",
            "--set",
            set,
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run npr");
    assert_eq!(
        o.status.code(),
        Some(1),
        "--set {set}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

#[test]
fn a_set_and_a_filter_argument_get_the_same_diagnostic_for_the_same_mistake() {
    let cases = [
        ("spacng=8", "spacng: 8", "E0101"),
        ("spacing=#ff0000", "spacing: #ff0000", "E0201"),
        ("spacing=hard", "spacing: hard", "E0201"),
        ("mode=hrad", "mode: hrad", "E0201"),
        ("mode=1", "mode: 1", "E0201"),
        ("spacing=8px", "spacing: 8px", "E0202"),
        ("spacing=64", "spacing: 64", "E0203"),
    ];
    for (i, (set, arg, code)) in cases.into_iter().enumerate() {
        let (text, dir) = filter_args_files(&format!("same-mistake-{i}"), arg);
        let (from_argument, _) = compile_errors(&text, &dir);
        let from_set = set_errors(&dir.join("hatch.npr"), set);
        assert_eq!((from_argument.len(), from_set.len()), (1, 1), "{set} / {arg}");
        let (a, s) = (&from_argument[0], &from_set[0]);
        assert_eq!((a.code, s["code"].as_str()), (code, Some(code)), "{set} / {arg}");
        // Only where the value was written differs: the message's subject
        // (and, for an unknown name, whose params were looked in).
        let name = set.split('=').next().unwrap_or_default();
        let set_message = s["message"].as_str().unwrap_or_default();
        let set_body = set_message
            .strip_prefix(&format!("--set {name}: "))
            .unwrap_or(set_message);
        let argument_body = a.message.strip_prefix("filter `hatch.npr`: ").unwrap_or(&a.message);
        assert_eq!(
            argument_body.replace("the filter has no parameter", "the style has no parameter"),
            set_body,
            "{set} / {arg}"
        );
        assert_eq!(
            a.labels[0].message,
            s["labels"][0]["message"].as_str().unwrap_or_default(),
            "{set} / {arg}"
        );
        assert_eq!(a.help.as_deref(), s["help"].as_str(), "{set} / {arg}");
    }
}

#[test]
fn e0206_a_set_gradient_out_of_order_or_malformed() {
    let dir = scratch("e0206-set");
    let (d, r) = cli_errors(
        &[
            "check",
            "examples/toon_ramp.npr",
            "--set",
            "shading=0.5:#000000, 0.2:#ffffff",
        ],
        &dir,
    );
    assert!(r.contains("--set:1:9"), "{r}");
    check_case("E0206", "E0206_set_unsorted", (d, r));
    let (d, r) = cli_errors(&["check", "examples/toon_ramp.npr", "--set", "shading=0:#00, 1"], &dir);
    check_case("E0206", "E0206_set_malformed", (d, r));
    // Kept live (a uniform, `--keep-params`), the same text is refused the same way.
    let out = dir.join("never.png");
    let (d, r) = cli_errors(
        &[
            "render",
            "examples/toon_ramp.npr",
            "--scene",
            "examples/scenes/spot.toml",
            "--keep-params",
            "--set",
            "shading=0.5:#000000, 0.2:#ffffff",
            "-o",
            out.to_str().expect("utf-8"),
        ],
        &dir,
    );
    check_case("E0206", "E0206_set_unsorted", (d, r));
    assert!(!out.exists(), "a refused value renders nothing");
}
