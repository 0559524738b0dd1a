//! Every way a scene file can be wrong: the error code, where the primary
//! span points in the TOML, and the help. Also: several errors are reported
//! at once, and no input panics.

use npr_diag::{codes, Diagnostic, FileId, SourceMap};
use npr_runner::scene::{load_scene, parse_scene, MAX_SEGMENTS, MAX_TRIANGLES};
use std::path::{Path, PathBuf};

const CAMERA: &str = "[camera]\nposition = [0.0, 0.5, 3.0]\ntarget = [0.0, 0.0, 0.0]\n";

/// Parses `text` (with its meshes relative to `base_dir`) and returns the
/// diagnostics with the source map they point into.
fn errors_in(text: &str, base_dir: &Path) -> (Vec<Diagnostic>, SourceMap) {
    let mut sources = SourceMap::new();
    let file = sources.add("scene.toml", text);
    match parse_scene(text, file, base_dir) {
        Ok(_) => panic!("expected errors for:\n{text}"),
        Err(diagnostics) => {
            // Rendering must work for every diagnostic (spans in range).
            let rendered = npr_diag::diagnostic::render(&diagnostics, &sources, false);
            assert!(!rendered.is_empty());
            (diagnostics, sources)
        }
    }
}

/// The single diagnostic for `text`, checked for `code` and for the text its
/// primary span covers.
fn single_error(text: &str, code: &str, spanned: &str) -> Diagnostic {
    let (diagnostics, sources) = errors_in(text, Path::new("."));
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    let diagnostic = diagnostics.into_iter().next().expect("one");
    assert_eq!(diagnostic.code, code, "{diagnostic:#?}");
    let span = diagnostic.primary_span().expect("a primary span");
    assert_eq!(sources.snippet(span), spanned, "{diagnostic:#?}");
    assert!(
        diagnostic.help.as_deref().is_some_and(|h| !h.is_empty()),
        "no help: {diagnostic:#?}"
    );
    diagnostic
}

fn with_object(object: &str) -> String {
    format!("{CAMERA}[[object]]\n{object}\n")
}

fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("npr-scene-errors-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn malformed_toml_points_at_the_syntax_error() {
    let text = format!("{CAMERA}fov = 40 40\n");
    let (diagnostics, sources) = errors_in(&text, Path::new("."));
    assert_eq!(diagnostics.len(), 1);
    assert_eq!(diagnostics[0].code, codes::BAD_SCENE);
    assert!(diagnostics[0].message.starts_with("malformed scene file"));
    let span = diagnostics[0].primary_span().expect("span");
    // On the bad line (line 4), after `fov = 40`.
    assert_eq!(sources.line_col(FileId(0), span.start).0, 4);
    assert!(span.start as usize >= text.find("40 40").expect("written"));
}

#[test]
fn unclosed_array_is_one_error_not_a_cascade() {
    let (diagnostics, _) = errors_in("[camera]\nposition = [0.0, 0.5, 3.0\nfov = 40\n", Path::new("."));
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    assert_eq!(diagnostics[0].code, codes::BAD_SCENE);
}

#[test]
fn unknown_primitive_kind_suggests_the_closest() {
    let d = single_error(
        &with_object("primitive = { kind = \"sphre\" }"),
        codes::BAD_SCENE,
        "\"sphre\"",
    );
    assert!(d.message.contains("sphre"));
    assert!(
        d.help.as_deref().unwrap_or_default().contains("did you mean `sphere`?"),
        "{d:#?}"
    );
    let d = single_error(
        &with_object("primitive = { kind = \"teapot\" }"),
        codes::BAD_SCENE,
        "\"teapot\"",
    );
    assert!(
        d.help.as_deref().unwrap_or_default().contains("`cube`"),
        "lists the kinds: {d:#?}"
    );
}

#[test]
fn missing_mesh_file_reports_the_os_error() {
    let d = single_error(
        &with_object("mesh = \"no-such-model.obj\""),
        codes::UNREADABLE_MESH,
        "\"no-such-model.obj\"",
    );
    assert!(d.message.contains("no-such-model.obj"), "{d:#?}");
    assert!(d.message.contains("os error"), "the OS error is included: {d:#?}");
}

#[test]
fn unreadable_mesh_files_are_e0402() {
    let dir = scratch_dir("unreadable");
    // A directory where a file should be: the read fails with an OS error.
    std::fs::create_dir_all(dir.join("folder.obj")).expect("dir");
    // Not JSON, not GLB.
    std::fs::write(dir.join("broken.gltf"), "this is not glTF").expect("write");
    std::fs::write(dir.join("empty.obj"), "# nothing here\n").expect("write");
    let text =
        with_object("mesh = \"folder.obj\"\n[[object]]\nmesh = \"broken.gltf\"\n[[object]]\nmesh = \"empty.obj\"");
    let (diagnostics, sources) = errors_in(&text, &dir);
    let spans: Vec<&str> = diagnostics
        .iter()
        .map(|d| sources.snippet(d.primary_span().expect("span")))
        .collect();
    assert_eq!(spans, ["\"folder.obj\"", "\"broken.gltf\"", "\"empty.obj\""]);
    assert!(
        diagnostics.iter().all(|d| d.code == codes::UNREADABLE_MESH),
        "{diagnostics:#?}"
    );
    assert!(diagnostics[0].message.contains("os error"), "{:#?}", diagnostics[0]);
    assert!(diagnostics[2].message.contains("no triangles"), "{:#?}", diagnostics[2]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn unsupported_mesh_extension_names_the_supported_ones() {
    let d = single_error(
        &with_object("mesh = \"model.stl\""),
        codes::UNREADABLE_MESH,
        "\"model.stl\"",
    );
    assert!(d.help.as_deref().unwrap_or_default().contains(".obj"), "{d:#?}");
}

#[test]
fn a_mesh_over_the_triangle_limit_is_e0404() {
    let dir = scratch_dir("huge");
    // Three vertices and one more triangle than the limit, all the same.
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    obj.push_str(&"f 1 2 3\n".repeat(MAX_TRIANGLES + 1));
    std::fs::write(dir.join("huge.obj"), obj).expect("write");
    let (diagnostics, sources) = errors_in(&with_object("mesh = \"huge.obj\""), &dir);
    assert_eq!(diagnostics.len(), 1);
    assert_eq!(diagnostics[0].code, codes::LIMIT_EXCEEDED);
    assert_eq!(
        sources.snippet(diagnostics[0].primary_span().expect("span")),
        "\"huge.obj\""
    );
    assert!(
        diagnostics[0].message.contains(&MAX_TRIANGLES.to_string()),
        "{:#?}",
        diagnostics[0]
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn primitive_counts_over_the_limit_are_e0404() {
    let d = single_error(
        &with_object("primitive = { kind = \"sphere\", segments = 5000 }"),
        codes::LIMIT_EXCEEDED,
        "5000",
    );
    assert!(d.message.contains(&MAX_SEGMENTS.to_string()), "{d:#?}");
    // Each count within its limit, the product over the triangle limit.
    let d = single_error(
        &with_object("primitive = { kind = \"torus\", segments = 4096, sides = 4096 }"),
        codes::LIMIT_EXCEEDED,
        "{ kind = \"torus\", segments = 4096, sides = 4096 }",
    );
    assert!(d.message.contains(&MAX_TRIANGLES.to_string()), "{d:#?}");
}

#[test]
fn an_object_needs_exactly_one_shape() {
    let both = with_object("mesh = \"a.obj\"\nprimitive = { kind = \"cube\" }");
    let d = single_error(&both, codes::BAD_SCENE, "{ kind = \"cube\" }");
    assert!(d.message.contains("both"), "{d:#?}");
    let d = single_error(&with_object("name = \"ghost\""), codes::BAD_SCENE, "[[object]]");
    assert!(d.message.contains("neither") && d.message.contains("ghost"), "{d:#?}");
}

#[test]
fn bad_values_point_at_the_value() {
    single_error(
        &with_object("primitive = { kind = \"sphere\", radius = -1.0 }"),
        codes::BAD_SCENE,
        "-1.0",
    );
    single_error(
        &with_object("primitive = { kind = \"cube\", size = 0 }"),
        codes::BAD_SCENE,
        "0",
    );
    single_error(
        &with_object("primitive = { kind = \"sphere\", rings = 1 }"),
        codes::BAD_SCENE,
        "1",
    );
    single_error(
        &with_object("primitive = { kind = \"sphere\", segments = 6.5 }"),
        codes::BAD_SCENE,
        "6.5",
    );
    single_error(&format!("{CAMERA}fov = 180.0\n"), codes::BAD_SCENE, "180.0");
    single_error(&format!("{CAMERA}fov = 0\n"), codes::BAD_SCENE, "0");
    single_error(&format!("{CAMERA}fov = -5.0\n"), codes::BAD_SCENE, "-5.0");
    single_error(&format!("{CAMERA}near = 0.0\n"), codes::BAD_SCENE, "0.0");
    single_error(&format!("{CAMERA}near = 5.0\nfar = 1.0\n"), codes::BAD_SCENE, "1.0");
    single_error(&format!("{CAMERA}ipd = -0.06\n"), codes::BAD_SCENE, "-0.06");
    single_error(&format!("{CAMERA}fov = inf\n"), codes::BAD_SCENE, "inf");
    single_error(
        &with_object("primitive = { kind = \"cube\" }\nscale = [1.0, 0.0, 1.0]"),
        codes::BAD_SCENE,
        "[1.0, 0.0, 1.0]",
    );
    single_error(
        &format!("{CAMERA}[light]\ndirection = [0.0, 0.0, 0.0]\n"),
        codes::BAD_SCENE,
        "[0.0, 0.0, 0.0]",
    );
    single_error(&format!("{CAMERA}[light]\nintensity = -1\n"), codes::BAD_SCENE, "-1");
    single_error(
        &format!("background = \"#12345\"\n{CAMERA}"),
        codes::BAD_SCENE,
        "\"#12345\"",
    );
    single_error(
        &with_object("name = \"\"\nprimitive = { kind = \"cube\" }"),
        codes::BAD_SCENE,
        "\"\"",
    );
    single_error(
        &with_object("primitive = { kind = \"cube\" }\ntags = [\"\"]"),
        codes::BAD_SCENE,
        "\"\"",
    );
}

#[test]
fn wrong_types_point_at_the_value() {
    let d = single_error(&format!("{CAMERA}fov = \"wide\"\n"), codes::BAD_SCENE, "\"wide\"");
    assert!(d.message.contains("must be a number, not a string"), "{d:#?}");
    single_error(&format!("{CAMERA}up = [0.0, 1.0]\n"), codes::BAD_SCENE, "[0.0, 1.0]");
    single_error(
        &with_object("primitive = { kind = \"cube\" }\ntags = \"hero\""),
        codes::BAD_SCENE,
        "\"hero\"",
    );
    single_error(
        &with_object("primitive = { kind = \"cube\" }\ncasts_shadows = 1"),
        codes::BAD_SCENE,
        "1",
    );
    single_error(&with_object("primitive = \"cube\""), codes::BAD_SCENE, "\"cube\"");
    single_error(
        &with_object("primitive = { kind = \"cube\" }\nparams = { tint = \"red\" }"),
        codes::BAD_SCENE,
        "\"red\"",
    );
    single_error(
        &with_object("primitive = { kind = \"cube\" }\nparams = { v = [] }"),
        codes::BAD_SCENE,
        "[]",
    );
    single_error(
        &with_object("primitive = { kind = \"cube\" }\nparams = { \"two words\" = 1 }"),
        codes::BAD_SCENE,
        "\"two words\"",
    );
}

#[test]
fn unknown_fields_suggest_the_closest_known_one() {
    let d = single_error(
        "[camera]\npositon = [0.0, 0.5, 3.0]\nposition = [0.0, 0.5, 3.0]\ntarget = [0.0, 0.0, 0.0]\n",
        codes::BAD_SCENE,
        "positon",
    );
    assert!(d.help.as_deref().unwrap_or_default().contains("`position`"), "{d:#?}");
    let d = single_error(
        &format!("{CAMERA}[[objects]]\nmesh = \"a.obj\"\n"),
        codes::BAD_SCENE,
        "objects",
    );
    assert!(d.help.as_deref().unwrap_or_default().contains("`object`"), "{d:#?}");
    let d = single_error(
        &with_object("primitive = { kind = \"sphere\", radius = 1.0, segmnets = 8 }"),
        codes::BAD_SCENE,
        "segmnets",
    );
    assert!(d.help.as_deref().unwrap_or_default().contains("`segments`"), "{d:#?}");
}

#[test]
fn camera_problems() {
    let d = single_error("background = \"#000000\"\n", codes::BAD_SCENE, "");
    assert!(d.message.contains("camera"), "{d:#?}");
    let d = single_error("[camera]\nposition = [0.0, 0.0, 3.0]\n", codes::BAD_SCENE, "[camera]");
    assert!(d.message.contains("target"), "{d:#?}");
    single_error(
        "[camera]\nposition = [1.0, 1.0, 1.0]\ntarget = [1.0, 1.0, 1.0]\n",
        codes::BAD_SCENE,
        "[1.0, 1.0, 1.0]",
    );
    let d = single_error(
        "[camera]\nposition = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n",
        codes::BAD_SCENE,
        "[0.0, 5.0, 0.0]",
    );
    assert!(d.help.as_deref().unwrap_or_default().contains("up"), "{d:#?}");
    let keys = "[camera]\ntarget = [0.0, 0.0, 0.0]\n[[camera.keys]]\ntime = 1.0\nposition = [0.0, 0.0, 3.0]\n[[camera.keys]]\ntime = 1.0\nposition = [1.0, 0.0, 3.0]\n";
    let (diagnostics, sources) = errors_in(keys, Path::new("."));
    assert_eq!(diagnostics.len(), 1);
    let span = diagnostics[0].primary_span().expect("span");
    // The second key's time.
    assert_eq!(span.start as usize, keys.rfind("1.0\nposition").expect("written"));
    assert_eq!(sources.snippet(span), "1.0");
    // A key with nothing to inherit: both missing fields, at the key.
    let (diagnostics, sources) = errors_in("[camera]\n[[camera.keys]]\ntime = 0.0\n", Path::new("."));
    assert_eq!(diagnostics.len(), 2);
    for d in &diagnostics {
        assert_eq!(sources.snippet(d.primary_span().expect("span")), "[[camera.keys]]");
    }
}

#[test]
fn duplicate_object_names_point_at_the_second() {
    let text = with_object(
        "name = \"a\"\nprimitive = { kind = \"cube\" }\n[[object]]\nname = \"a\"\nprimitive = { kind = \"plane\" }",
    );
    let (diagnostics, sources) = errors_in(&text, Path::new("."));
    assert_eq!(diagnostics.len(), 1);
    let span = diagnostics[0].primary_span().expect("span");
    assert_eq!(sources.snippet(span), "\"a\"");
    assert_eq!(span.start as usize, text.rfind("\"a\"").expect("written"));
}

#[test]
fn several_errors_are_reported_together_in_file_order() {
    let text = "[camera]\nposition = [0.0, 0.5, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 500.0\n\
                [[object]]\nprimitive = { kind = \"sphre\" }\n\
                [[object]]\nmesh = \"missing.obj\"\nscale = -2.0\n\
                [[object]]\nprimitive = { kind = \"sphere\", segments = 10000 }\n";
    let (diagnostics, sources) = errors_in(text, Path::new("."));
    let found: Vec<(&str, &str)> = diagnostics
        .iter()
        .map(|d| (d.code, sources.snippet(d.primary_span().expect("span"))))
        .collect();
    assert_eq!(
        found,
        [
            (codes::BAD_SCENE, "500.0"),
            (codes::BAD_SCENE, "\"sphre\""),
            (codes::UNREADABLE_MESH, "\"missing.obj\""),
            (codes::BAD_SCENE, "-2.0"),
            (codes::LIMIT_EXCEEDED, "10000"),
        ]
    );
}

#[test]
fn an_unreadable_scene_file_is_an_error_not_a_panic() {
    let mut sources = SourceMap::new();
    let result = load_scene(Path::new("/definitely/not/here/scene.toml"), &mut sources);
    let diagnostics = result.expect_err("error");
    assert_eq!(diagnostics[0].code, codes::BAD_SCENE);
    assert!(diagnostics[0].message.contains("os error"), "{diagnostics:#?}");
}

/// Every prefix of a valid scene, and a few mutations, parse without
/// panicking, and every diagnostic's span lies inside the text.
#[test]
fn no_input_panics() {
    let valid = "background = \"#202020\"\n[camera]\nposition = [0.0, 0.5, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\
                 up = [0.0, 1.0, 0.0]\nfov = 40.0\nipd = 0.064\n[[camera.keys]]\ntime = 0.0\n\
                 [light]\ndirection = [0.5, 1.0, 0.8]\ncolor = [1.0, 1.0, 1.0]\n\
                 [[object]]\nname = \"s\"\nprimitive = { kind = \"sphere\", radius = 1.0, segments = 8, rings = 4 }\n\
                 rotate = [0.0, 30.0, 0.0]\nscale = [1.0, 2.0, 1.0]\ntags = [\"caster\"]\nparams = { tint = \"#ff8080\", k = [1, 2] }\n";
    assert!(parse_scene(valid, FileId(0), Path::new(".")).is_ok());
    let mut inputs: Vec<String> = (0..valid.len())
        .filter(|&i| valid.is_char_boundary(i))
        .map(|i| valid[..i].to_string())
        .collect();
    for (from, to) in [
        ("1.0", "\"x\""),
        ("1.0", "[]"),
        ("1.0", "{}"),
        ("0.0", "nan"),
        ("0.0", "1e300"),
        ("8", "-8"),
        ("8", "99999999999999999999"),
        ("[0.0, 1.0, 0.0]", "[[0.0]]"),
        ("\"#ff8080\"", "\"#ffé080\""),
        ("\"sphere\"", "3"),
        ("[[object]]", "[object]"),
        ("time = 0.0", "time = 1979-05-27"),
    ] {
        inputs.push(valid.replace(from, to));
    }
    for input in &inputs {
        if let Err(diagnostics) = parse_scene(input, FileId(0), Path::new(".")) {
            for d in &diagnostics {
                assert!(d
                    .labels
                    .iter()
                    .all(|l| (l.span.end as usize) <= input.len() && l.span.start <= l.span.end));
            }
        }
    }
}
