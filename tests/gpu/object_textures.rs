//! Per-object texture params (`object param t: texture = image(...)`): each
//! object draws with the image its scene binds (sRGB or linear), objects
//! without a binding draw with the declared default, and bad bindings or a
//! read outside a render pass give diagnostics.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Gpu, Renderer};
use std::path::{Path, PathBuf};

const RED: [u8; 3] = [200, 30, 40];
const GREEN: [u8; 3] = [40, 180, 70];
const BLUE: [u8; 3] = [20, 60, 210];

/// The style: one render pass writing the per-object texture sampled at `uv`.
const STYLE: &str = "style \"albedo\"
/// The object's albedo; objects without a binding get the green default.
object param albedo: texture = image(\"green.png\", linear) { filter: nearest, wrap: clamp }
pass p: render(scene) {
  out c: rgba8unorm = vec4(albedo.rgb, 1.0)
  clear: #000000
}
output p.c
";

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    for (file, c) in [("red.png", RED), ("green.png", GREEN), ("blue.png", BLUE)] {
        image::RgbaImage::from_pixel(4, 4, image::Rgba([c[0], c[1], c[2], 255]))
            .save(dir.join(file))
            .expect("write png");
    }
    dir
}

/// Three cubes left to right: `left` and `right` bind the given values to `albedo`; the middle one binds nothing.
fn scene_text(left: &str, right: &str) -> String {
    format!(
        "[camera]\nposition = [0.0, 0.0, 6.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n\n\
         [[object]]\nname = \"left\"\nprimitive = {{ kind = \"cube\" }}\ntranslate = [-3.0, 0.0, 0.0]\nparams = {{ albedo = {left} }}\n\n\
         [[object]]\nname = \"middle\"\nprimitive = {{ kind = \"cube\" }}\n\n\
         [[object]]\nname = \"right\"\nprimitive = {{ kind = \"cube\" }}\ntranslate = [3.0, 0.0, 0.0]\nparams = {{ albedo = {right} }}\n"
    )
}

fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn two_objects_draw_their_own_bound_textures_and_the_third_the_default() {
    let gpu = Gpu::headless().unwrap_or_else(|e| {
        panic!("this test needs a GPU adapter: {e} (install one with ./setup.sh: mesa-vulkan-drivers)")
    });
    let dir = scratch("object-textures");
    let scene_path = dir.join("three.toml");
    // Left: a plain path, hence the declared colour space (linear: the bytes
    // pass through); right: sRGB, decoded by the sampler.
    std::fs::write(
        &scene_path,
        scene_text("\"red.png\"", "{ image = \"blue.png\", srgb = true }"),
    )
    .expect("write scene");
    let mut sources = SourceMap::new();
    let scene = npr_runner::scene::load_scene(&scene_path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let compiled = npr_compiler::compile_source("albedo.npr", STYLE, &dir, &mut sources, &CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    let pass = &compiled.manifest.passes[0];
    assert_eq!(pass.object_bindings.len(), 2, "texture + sampler in group 1: {pass:?}");
    assert!(compiled.manifest.textures[0].per_object);
    let program = compiled.program();
    let mut r = Renderer::new(&gpu.device, &gpu.queue, &program, &scene).unwrap_or_else(|e| panic!("renderer: {e:?}"));
    let (w, h) = (96u32, 32u32);
    let spec = FrameSpec::still(w, h, 0);
    r.render(&scene, &spec).expect("render");
    let img = r.read_output().expect("read").to_rgba8();
    let blue_linear = BLUE.map(|c| (srgb_to_linear(c as f64 / 255.0) * 255.0).round() as i32);
    let expected: [[i32; 3]; 3] = [RED.map(i32::from), GREEN.map(i32::from), blue_linear];
    for (third, want) in expected.iter().enumerate() {
        let mut covered = 0;
        for y in 0..h {
            for x in (third as u32 * w / 3)..((third as u32 + 1) * w / 3) {
                let p = img.get_pixel(x, y).0;
                if p[..3] == [0, 0, 0] {
                    continue;
                }
                covered += 1;
                for c in 0..3 {
                    assert!(
                        (p[c] as i32 - want[c]).abs() <= 1,
                        "object {third} pixel ({x}, {y}) is {:?}, want {want:?}",
                        &p[..3]
                    );
                }
            }
        }
        assert!(covered >= 20, "object {third} covers only {covered} px");
    }
}

fn renderer_errors(left: &str, right: &str, name: &str) -> String {
    let gpu = Gpu::headless().unwrap_or_else(|e| {
        panic!("this test needs a GPU adapter: {e} (install one with ./setup.sh: mesa-vulkan-drivers)")
    });
    let dir = scratch(name);
    let scene_path = dir.join("three.toml");
    std::fs::write(&scene_path, scene_text(left, right)).expect("write scene");
    let mut sources = SourceMap::new();
    let scene = npr_runner::scene::load_scene(&scene_path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let compiled = npr_compiler::compile_source("albedo.npr", STYLE, &dir, &mut sources, &CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    let program = compiled.program();
    match Renderer::new(&gpu.device, &gpu.queue, &program, &scene) {
        Ok(_) => panic!("expected the renderer to refuse {left} / {right}"),
        Err(npr_runner::RunError::User(d)) => {
            npr_diag::diagnostic::render(&d, &sources, false).replace(&*dir.to_string_lossy(), "$DIR")
        }
        Err(e) => panic!("expected user diagnostics, got {e:?}"),
    }
}

#[test]
fn a_number_bound_to_a_texture_param_is_refused_at_its_toml_value() {
    insta::assert_snapshot!(renderer_errors("0.5", "\"blue.png\"", "object-textures-number"));
}

#[test]
fn an_image_bound_to_a_colour_param_is_refused_at_its_toml_value() {
    let gpu = Gpu::headless().unwrap_or_else(|e| {
        panic!("this test needs a GPU adapter: {e} (install one with ./setup.sh: mesa-vulkan-drivers)")
    });
    let dir = scratch("object-textures-colour");
    let scene_path = dir.join("one.toml");
    std::fs::write(
        &scene_path,
        "[camera]\nposition = [0.0, 0.0, 6.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nname = \"box\"\nprimitive = { kind = \"cube\" }\nparams = { tint = \"red.png\" }\n",
    )
    .expect("write scene");
    let style = "style \"tint\"
object param tint: color = #ffffff
pass p: render(scene) {
  out c: rgba8unorm = tint
}
output p.c
";
    let mut sources = SourceMap::new();
    let scene = npr_runner::scene::load_scene(&scene_path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let compiled = npr_compiler::compile_source("tint.npr", style, &dir, &mut sources, &CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    let program = compiled.program();
    let text = match Renderer::new(&gpu.device, &gpu.queue, &program, &scene) {
        Ok(_) => panic!("an image bound to a colour param must be refused"),
        Err(npr_runner::RunError::User(d)) => {
            npr_diag::diagnostic::render(&d, &sources, false).replace(&*dir.to_string_lossy(), "$DIR")
        }
        Err(e) => panic!("expected user diagnostics, got {e:?}"),
    };
    insta::assert_snapshot!(text);
}

#[test]
fn an_unreadable_bound_image_is_refused_at_its_toml_value() {
    let dir = scratch("object-textures-unreadable");
    std::fs::write(dir.join("broken.png"), b"not a png").expect("write");
    insta::assert_snapshot!(renderer_errors(
        "\"broken.png\"",
        "\"blue.png\"",
        "object-textures-unreadable"
    ));
}

#[test]
fn a_missing_bound_image_is_refused_while_loading_the_scene() {
    let dir = scratch("object-textures-missing");
    let scene_path = dir.join("three.toml");
    std::fs::write(&scene_path, scene_text("\"nope.png\"", "\"blue.png\"")).expect("write scene");
    let mut sources = SourceMap::new();
    let d = match npr_runner::scene::load_scene(&scene_path, &mut sources) {
        Ok(_) => panic!("a missing image must be refused"),
        Err(d) => d,
    };
    insta::assert_snapshot!(npr_diag::diagnostic::render(&d, &sources, false).replace(&*dir.to_string_lossy(), "$DIR"));
}

#[test]
fn a_table_binding_without_an_image_is_refused_with_did_you_mean() {
    let dir = scratch("object-textures-table");
    let scene_path = dir.join("three.toml");
    std::fs::write(&scene_path, scene_text("{ imag = \"red.png\" }", "{ image = 3 }")).expect("write scene");
    let mut sources = SourceMap::new();
    let d = match npr_runner::scene::load_scene(&scene_path, &mut sources) {
        Ok(_) => panic!("a binding without an image must be refused"),
        Err(d) => d,
    };
    insta::assert_snapshot!(npr_diag::diagnostic::render(&d, &sources, false).replace(&*dir.to_string_lossy(), "$DIR"));
}

#[test]
fn a_per_object_texture_read_in_an_image_pass_is_an_error() {
    let dir = scratch("object-textures-image-pass");
    let style = "style \"bad\"
object param albedo: texture = image(\"green.png\", linear)
pass p: render(scene) {
  out c: rgba8unorm = vec4(1.0, 1.0, 1.0, 1.0)
}
pass q: image(p) {
  out c: rgba8unorm = vec4(albedo.rgb * p.c.rgb, 1.0)
}
output q.c
";
    let mut sources = SourceMap::new();
    let d = match npr_compiler::compile_source("bad.npr", style, &dir, &mut sources, &CompileOptions::default()) {
        Ok(_) => panic!("reading a per-object texture in an image pass must be refused"),
        Err(npr_compiler::CompileError::User(d)) => d,
        Err(e) => panic!("expected user diagnostics, got {e:?}"),
    };
    insta::assert_snapshot!(npr_diag::diagnostic::render(&d, &sources, false));
}

#[test]
fn a_per_object_texture_read_in_a_vertex_modifier_is_an_error() {
    let dir = scratch("object-textures-vertex");
    let style = "style \"bad\"
object param albedo: texture = image(\"green.png\", linear)
pass p: render(scene) {
  vertex { inflate: albedo.r * 1px }
  out c: rgba8unorm = albedo
}
output p.c
";
    let mut sources = SourceMap::new();
    let d = match npr_compiler::compile_source("bad.npr", style, &dir, &mut sources, &CompileOptions::default()) {
        Ok(_) => panic!("a texture read per vertex must be refused"),
        Err(npr_compiler::CompileError::User(d)) => d,
        Err(e) => panic!("expected user diagnostics, got {e:?}"),
    };
    insta::assert_snapshot!(npr_diag::diagnostic::render(&d, &sources, false));
}

#[test]
fn a_style_wide_texture_param_is_an_error() {
    let dir = scratch("object-textures-style-param");
    let style = "style \"bad\"
param albedo: texture = image(\"green.png\", linear)
pass p: render(scene) {
  out c: rgba8unorm = vec4(1.0, 1.0, 1.0, 1.0)
}
output p.c
";
    let mut sources = SourceMap::new();
    let d = match npr_compiler::compile_source("bad.npr", style, &dir, &mut sources, &CompileOptions::default()) {
        Ok(_) => panic!("a style-wide texture param must be refused"),
        Err(npr_compiler::CompileError::User(d)) => d,
        Err(e) => panic!("expected user diagnostics, got {e:?}"),
    };
    insta::assert_snapshot!(npr_diag::diagnostic::render(&d, &sources, false));
}

#[test]
fn a_per_object_texture_is_an_operator_handle_too() {
    // As a `SampledTexture` argument (MetaTexture) it binds the same group-1
    // texture and sampler; naga validates the module during compilation.
    let dir = scratch("object-textures-operator");
    let style = "style \"grain\"
object param grain: texture = image(\"green.png\", linear) { wrap: repeat, mips: on }
pass p: render(scene) {
  out c: rgba8unorm = vec4(metatexture(grain, width: 32px).rgb, 1.0)
}
output p.c
";
    let mut sources = SourceMap::new();
    let compiled = npr_compiler::compile_source("grain.npr", style, &dir, &mut sources, &CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    let pass = &compiled.manifest.passes[0];
    let wgsl = &compiled
        .shaders
        .iter()
        .find(|(name, _)| *name == pass.shader)
        .expect("the pass's shader")
        .1;
    assert!(
        wgsl.contains("@group(1) @binding(1) var tex_grain: texture_2d<f32>;"),
        "{wgsl}"
    );
    assert!(
        wgsl.contains("@group(1) @binding(2) var samp_grain: sampler;"),
        "{wgsl}"
    );
    assert!(wgsl.contains("tex_grain, samp_grain"), "{wgsl}");
    assert!(
        pass.bindings
            .iter()
            .all(|b| !matches!(b.resource, npr_abi::manifest::Resource::Texture { .. })),
        "the per-object texture must not also be bound in group 0: {:?}",
        pass.bindings
    );
}
