//! Error codes of files and scenes (E04xx, W04xx): textures, meshes,
//! attributes, limits, scene files, the paths policy, and the GPU's own
//! limits (out of memory, a lost device).

use super::*;

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
    let compiled = npr_compiler::compile_source("case.npr", &text, &dir, &mut sources, &CompileOptions::default())
        .expect("compiles");
    assert!(compiled
        .manifest
        .scene_attributes
        .contains(&npr_abi::manifest::Attribute::Uv));
    let scene = npr_runner::scene::load_scene(&dir.join("scene.toml"), &mut sources).expect("scene loads");
    let diags = npr_runner::check_scene(&compiled.manifest, &scene);
    let rendered = npr_diag::diagnostic::render(&diags, &sources, false).replace(&dir.display().to_string(), "<dir>");
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

/// A one-triangle glTF file whose material's base colour texture has image
/// `source`, the image at `uri`.
fn textured_triangle(source: usize, uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],
"textures":[{{"source":{source}}}],"images":[{{"uri":"{uri}"}}],
"buffers":[{{"byteLength":60,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}}],
"bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":24}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}}]}}"#
    )
}

const GLTF_TRIANGLE_SCENE: &str = "[camera]\nposition = [0.5, 0.5, 3.0]\ntarget = [0.5, 0.5, 0.0]\nfov = 40.0\n[light]\ndirection = [0.0, 1.0, 0.0]\n[[object]]\nname = \"tri\"\nmesh = \"tri.gltf\"\n";

#[test]
fn e0409_material_texture_index_out_of_range() {
    let dir = scratch("e0409");
    let png = "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGM4UaHxHwAF3AJoiJKY8QAAAABJRU5ErkJggg==";
    std::fs::write(dir.join("tri.gltf"), textured_triangle(3, png)).expect("write");
    let (d, r) = scene_errors(GLTF_TRIANGLE_SCENE, &dir);
    assert!(r.contains("/textures/0/source"), "the glTF path is named: {r}");
    check("E0409", (d, r.replace(&dir.display().to_string(), "<dir>")));
}

#[test]
fn e0410_material_image_that_does_not_decode() {
    let dir = scratch("e0410");
    std::fs::write(
        dir.join("tri.gltf"),
        textured_triangle(0, "data:image/png;base64,bm90IGEgcG5n"),
    )
    .expect("write");
    let (d, r) = scene_errors(GLTF_TRIANGLE_SCENE, &dir);
    assert!(r.contains("/images/0"), "the glTF path is named: {r}");
    check("E0410", (d, r.replace(&dir.display().to_string(), "<dir>")));
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
    let compiled = npr_compiler::compile_source("case.npr", &text, &dir, &mut sources, &CompileOptions::default())
        .expect("compiles");
    std::fs::write(
        dir.join("scene.toml"),
        one_sphere_scene("params = { tnit = \"#ff0000\", gain = 2.0, tint = \"#00ff00\" }"),
    )
    .expect("write scene");
    let scene = npr_runner::scene::load_scene(&dir.join("scene.toml"), &mut sources).expect("scene loads");
    let diags = npr_runner::scene_warnings(&compiled.manifest, &scene);
    let rendered = npr_diag::diagnostic::render(&diags, &sources, false).replace(&dir.display().to_string(), "<dir>");
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
fn w0401_bindings_for_another_style_are_one_line() {
    let dir = scratch("w0401-elsewhere");
    let text = style("pass p: render(scene) {\n  out c: rgba8unorm = #808080\n}\noutput p.c\n");
    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_source("case.npr", &text, &dir, &mut sources, &CompileOptions::default())
        .expect("compiles");
    std::fs::write(
        dir.join("scene.toml"),
        one_sphere_scene("params = { tint = \"#ff0000\", wobble = 2.0 }"),
    )
    .expect("write scene");
    let scene = npr_runner::scene::load_scene(&dir.join("scene.toml"), &mut sources).expect("scene loads");
    let diags = npr_runner::scene_warnings(&compiled.manifest, &scene);
    let rendered = npr_diag::diagnostic::render(&diags, &sources, false);
    assert_eq!(diags.len(), 1, "{rendered}");
    assert_eq!(rendered.trim_end().lines().count(), 1, "{rendered}");
    check_case("W0401", "W0401_elsewhere", (diags, rendered));
}

#[test]
fn w0402_a_render_pass_over_a_tag_no_object_has() {
    let text = style(
        "pass ground: render(gorund) {\n  out c: rgba8unorm = #808080\n}\npass final: image(ground) {\n  out color: rgba8unorm = ground.c\n}\noutput final.color\n",
    );
    let scene = npr_abi::SceneSummary {
        tags: ["ground".to_string(), "caster".to_string()].into_iter().collect(),
        name: "scene.toml".into(),
    };
    let opts = CompileOptions {
        scene: Some(scene),
        ..CompileOptions::default()
    };
    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_source("case.npr", &text, Path::new("."), &mut sources, &opts)
        .unwrap_or_else(|_| panic!("compiles"));
    let rendered = npr_diag::diagnostic::render(&compiled.warnings, &sources, false);
    assert!(rendered.contains("did you mean `ground`?"), "{rendered}");
    assert!(rendered.contains("caster, ground"), "{rendered}");
    check("W0402", (compiled.warnings.clone(), rendered));
    // Without a scene nothing is known about tags: no warning.
    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_source(
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
    let wide = npr_diag::limits::MAX_TEXTURE_SIZE + 1;
    image::GrayImage::new(wide, 1)
        .save(dir.join("wide.png"))
        .expect("write png");
    let style = style_with_texture(&dir, "wide.png");
    let (d, r) = cli_errors(&["check", style.to_str().expect("utf-8 path")], &dir);
    assert!(r.contains("16385x1, over the 16384-texel limit"), "{r}");
    check_case("E0404", "E0404_texture_size", (d, r));
}

#[test]
fn npr_check_and_render_point_at_the_style_for_a_texture_with_a_good_header_and_corrupt_data() {
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
    // The header is fine; only a whole decode finds the damage.
    assert_eq!(
        npr_runner::texture_file::probe(&dir.join("paper.png")).expect("header"),
        (64, 64)
    );
    // `npr check` decodes it, and refuses it at the same place.
    let (dc, rc) = cli_errors(&["check", style.to_str().expect("utf-8 path")], &dir);
    assert_eq!(dc[0].code, "E0401", "{rc}");
    assert!(rc.contains("is not an image npr can read"), "{rc}");
    assert!(
        rc.contains("case.npr:3:23"),
        "check labels the path in image(...): {rc}"
    );
    let (d, r) = render_on_spot(&style, &dir);
    assert_eq!(d[0].code, "E0401", "{r}");
    assert!(r.contains("is not an image npr can read"), "{r}");
    assert!(
        r.contains("case.npr:3:23"),
        "the label is on the path in image(...): {r}"
    );
    assert!(!dir.join("out.png").exists(), "nothing is written");
    check_case("E0401", "E0401_corrupt_data", (d, r));
}

/// `npr render STYLE --scene examples/scenes/spot.toml -o DIR/out.png`: its diagnostics.
fn render_on_spot(style: &Path, dir: &Path) -> (Vec<Diagnostic>, String) {
    cli_errors(
        &[
            "render",
            style.to_str().expect("utf-8 path"),
            "--scene",
            "examples/scenes/spot.toml",
            "-o",
            dir.join("out.png").to_str().expect("utf-8 path"),
        ],
        dir,
    )
}

#[test]
fn npr_render_reports_a_bad_texture_at_the_style_not_only_by_name() {
    let dir = scratch("render-not-an-image");
    std::fs::write(dir.join("paper.png"), [0u8, 1, 2, 3]).expect("write");
    let style = style_with_texture(&dir, "paper.png");
    let (d, r) = render_on_spot(&style, &dir);
    assert_eq!(d[0].code, "E0401", "{r}");
    assert!(r.contains("case.npr:3:23"), "{r}");
    assert!(!dir.join("out.png").exists(), "nothing is written");
}

#[test]
fn a_texture_file_that_cannot_be_read() {
    // A directory passes no `open`: the error says it cannot be read.
    let dir = scratch("texture-unreadable");
    let err = npr_runner::texture_file::probe(&dir).expect_err("a directory is no image");
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
    assert_eq!(npr_runner::texture_file::probe(&ok).expect("a png"), (3, 2));
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
    let policy = npr_diag::paths::PathPolicy::new(&style_dir, &[]).expect("root");
    let mut sources = SourceMap::new();
    let opts = CompileOptions {
        paths: Some(policy),
        ..Default::default()
    };
    let Err(CompileError::User(d)) = npr_compiler::compile_source("case.npr", &text, &style_dir, &mut sources, &opts)
    else {
        panic!("a texture outside the root must be refused")
    };
    let canonical = dir.canonicalize().expect("canonical").display().to_string();
    let r = npr_diag::diagnostic::render(&d, &sources, false).replace(&canonical, "<dir>");
    check("E0406", (d, r));
}

#[test]
fn e0508_the_gpu_out_of_memory() {
    // Forced on the device in tests/gpu/gpu_errors.rs (under an address-space
    // limit); this is its rendered message.
    let e =
        npr_runner::RunError::OutOfMemory("the GPU ran out of memory making the targets of a 16384x16384 image".into());
    let d = e.diagnostics();
    let rendered = npr_diag::diagnostic::render(&d, &SourceMap::new(), false);
    check("E0508", (d, rendered));
}

#[test]
fn e0509_a_lost_device() {
    // Forced with `Device::destroy` in tests/gpu/gpu_errors.rs; its rendered message.
    let e = npr_runner::RunError::DeviceLost("Destroyed: Device is dying.".into());
    let d = e.diagnostics();
    let rendered = npr_diag::diagnostic::render(&d, &SourceMap::new(), false);
    check("E0509", (d, rendered));
}

/// `case.npr` (a grey sphere) and its scene in `dir`, with `tests` as `case.tests.toml`.
fn style_with_tests(dir: &Path, tests: &str) -> String {
    std::fs::write(dir.join("case.npr"), style(SIMPLE_PASS)).expect("write");
    std::fs::write(dir.join("scene.toml"), "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n[[object]]\nname = \"ball\"\nprimitive = { kind = \"sphere\", radius = 0.5, segments = 8, rings = 4 }\n").expect("write");
    std::fs::write(dir.join("case.tests.toml"), tests).expect("write");
    dir.join("case.npr").display().to_string()
}

#[test]
fn e0407_bad_test_file() {
    let dir = scratch("e0407");
    let case = style_with_tests(
        &dir,
        "[[test]]\nname = \"ball\"\nscene = \"scene.toml\"\nsize = \"16x16\"\nmay_be_blnk = true\n",
    );
    check("E0407", cli_errors(&["test", &case], &dir));
}

#[test]
fn e0408_missing_golden() {
    let dir = scratch("e0408");
    let case = style_with_tests(&dir, "[[test]]\nname = \"ball\"\nscene = \"scene.toml\"\nsize = \"16x16\"\ngolden = \"golden/ball.png\"\nflip = { mean = 0.01 }\n");
    let (diags, stderr) = cli_errors(&["test", &case], &dir);
    // The test's own line ends with its time, which varies.
    let rendered: String = stderr
        .lines()
        .filter(|l| !l.starts_with("INVALID "))
        .map(|l| format!("{l}\n"))
        .collect();
    check("E0408", (diags, rendered));
}
