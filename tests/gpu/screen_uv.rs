//! `screen_uv` in render passes comes from the fragment's pixel centre, so it
//! is exact and finite even on triangles clipped at the eye plane (a large
//! ground plane running under the camera), at full and at reduced scale.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Gpu, Renderer};
use std::path::Path;

#[test]
fn screen_uv_is_the_pixel_centre_even_on_clipped_triangles() {
    let gpu = Gpu::headless().unwrap_or_else(|e| {
        panic!("this test needs a GPU adapter: {e} (install one with ./setup.sh: mesa-vulkan-drivers)")
    });
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("screen-uv");
    std::fs::create_dir_all(&dir).expect("scratch");
    // Two triangles 200 m across with the camera 10 cm above them: both cross
    // the eye plane, so the rasterizer clips them.
    let scene_path = dir.join("ground.toml");
    std::fs::write(
        &scene_path,
        "[camera]\nposition = [0.0, 0.1, 0.0]\ntarget = [0.3, 0.0, -5.0]\nfov = 70.0\nnear = 0.05\nfar = 500.0\n\n[[object]]\nprimitive = { kind = \"plane\", size = 200.0, subdivisions = 1 }\n",
    )
    .expect("write scene");
    let mut sources = SourceMap::new();
    let scene = npr_runner::scene::load_scene(&scene_path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    for (scale, (w, h)) in [("1", (37u32, 23u32)), ("1/2", (37, 23))] {
        let text = format!(
            "style \"uv\"\npass p: render(scene) scale {scale} {{\n  out s: rgba32float = vec4(screen_uv, 0.0, 1.0)\n  clear: #00000000\n}}\noutput p.s\n"
        );
        let compiled = npr_compiler::compile_source("uv.npr", &text, &dir, &mut sources, &CompileOptions::default())
            .unwrap_or_else(|e| panic!("{e:?}"));
        let program = compiled.program();
        let mut r = Renderer::new(&gpu.device, &gpu.queue, &program, &scene).expect("renderer");
        let spec = FrameSpec::still(w, h, 0);
        r.render(&scene, &spec).expect("render");
        let img = r.read_output().expect("read");
        let (pw, ph) = (img.width, img.height);
        let mut covered = 0;
        for y in 0..ph {
            for x in 0..pw {
                let t = img.texel(x, y);
                if t[3] < 0.5 {
                    continue;
                }
                covered += 1;
                let want = [(x as f32 + 0.5) / pw as f32, (y as f32 + 0.5) / ph as f32];
                assert!(
                    (t[0] - want[0]).abs() < 1e-5 && (t[1] - want[1]).abs() < 1e-5,
                    "scale {scale}, pixel ({x}, {y}) of {pw}x{ph}: screen_uv {:?}, want {want:?}",
                    &t[..2]
                );
            }
        }
        assert!(
            covered > (pw * ph / 3) as usize,
            "scale {scale}: the ground covers {covered} px"
        );
    }
}
