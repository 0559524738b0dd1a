//! A glTF file's material reaches styles under the documented names
//! (decision 0058): the walker's base colour texture, drawn by a style
//! that declares `object param base_color_map: texture`, equals the
//! texture read on the CPU through the UVs the GPU interpolated at each
//! pixel; its factors arrive as `base_color`, `metallic`, `roughness` and
//! `emissive`; and a scene's own binding of the name wins.
//!
//! Bounds. The texture is sampled `nearest` without mips, so a pixel's
//! colour is one texel, the one `floor(uv · 48)` names: equal to its
//! bytes within 1/255 (unorm round trip), at every covered pixel whose uv
//! lies more than 0.05 texel from a texel edge (there, the GPU's and f64's
//! floor may differ in the last bit). The factors are within 1e-6 of the
//! file's f32 values (stored in rgba32float).

use npr_runner::{FrameSpec, Renderer};

use crate::common::{compile_text, gpu, root};

const SIZE: u32 = 96;

/// The walker alone (tag `character`), at its rest pose's time 0 of the
/// walk clip.
fn walker_scene() -> npr_runner::scene::Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&root().join("examples/scenes/walker.toml"), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

fn render(style: &str, scene: &npr_runner::scene::Scene) -> Vec<[f32; 4]> {
    let g = gpu();
    let program = compile_text(style);
    let mut r = Renderer::new(&g.device, &g.queue, &program, scene)
        .unwrap_or_else(|e| panic!("renderer: {e}: {:?}", e.diagnostics()));
    r.render(scene, &FrameSpec::animated(SIZE, SIZE, 3, FrameSpec::DEFAULT_FPS, 0))
        .unwrap_or_else(|e| panic!("render: {e}: {:?}", e.diagnostics()));
    r.read_output().expect("read back").to_rgba_f32()
}

const UV_STYLE: &str = "style \"uv\"
pass p: render(character) {
  out c: rgba32float = vec4(uv, 1.0, 1.0)
  clear: #00000000
}
output p.c
";

const COLOUR_STYLE: &str = "style \"base colour\"
object param base_color_map: texture = image(\"examples/textures/white.png\", linear) { filter: nearest, mips: off, wrap: repeat }
pass p: render(character) {
  out c: rgba8unorm = vec4(base_color_map.rgb, 1.0)
  clear: #00000000
}
output p.c
";

#[test]
fn the_walkers_base_colour_texture_is_drawn_through_its_uvs() {
    let scene = walker_scene();
    let walker = scene.objects.iter().find(|o| o.name == "walker").expect("walker");
    let material = walker.material.as_ref().expect("walker.glb has a material");
    let image = material.base_color_map.as_ref().expect("with a base colour image");
    let texture = image::load_from_memory(&image.bytes)
        .expect("the PNG decodes")
        .to_rgba8();
    let (tw, th) = texture.dimensions();
    assert_eq!((tw, th), (48, 48));

    let uvs = render(UV_STYLE, &scene);
    let colours = render(COLOUR_STYLE, &scene);
    let mut compared = 0;
    let mut seen = std::collections::BTreeSet::new();
    for (i, (uv, got)) in uvs.iter().zip(&colours).enumerate() {
        if uv[2] != 1.0 {
            continue;
        }
        let (s, t) = (f64::from(uv[0]) * f64::from(tw), f64::from(uv[1]) * f64::from(th));
        let near_edge = |x: f64| (x - x.round()).abs() < 0.05;
        if near_edge(s) || near_edge(t) {
            continue;
        }
        let (x, y) = (
            s.floor().rem_euclid(f64::from(tw)) as u32,
            t.floor().rem_euclid(f64::from(th)) as u32,
        );
        let want = texture.get_pixel(x, y).0;
        for c in 0..3 {
            let expected = f32::from(want[c]) / 255.0;
            assert!(
                (got[c] - expected).abs() <= 1.0 / 255.0 + 1e-6,
                "pixel {i}: uv {:?} names texel ({x}, {y}) = {want:?}, drawn {got:?}",
                &uv[..2]
            );
        }
        seen.insert([want[0], want[1], want[2]]);
        compared += 1;
    }
    assert!(
        compared > 400,
        "only {compared} pixels compared: the walker is barely in view"
    );
    assert!(
        seen.len() >= 4,
        "the compared pixels show {} texture colours: the pattern is not exercised",
        seen.len()
    );
}

#[test]
fn material_factors_arrive_as_per_object_values_and_a_scene_binding_wins() {
    let style = "style \"factors\"
object param base_color: color = #000000
object param metallic: float = 0.0 in 0..1
object param roughness: float = 0.0 in 0..1
object param emissive: color = #000000
pass p: render(character) {
  out c: rgba32float = vec4(metallic, roughness, emissive.r + emissive.g * 10.0, base_color.a)
  clear: #00000000
}
output p.c
";
    let mut scene = walker_scene();
    let covered = |pixels: &[[f32; 4]]| -> Vec<[f32; 4]> { pixels.iter().copied().filter(|p| p[3] == 1.0).collect() };
    let drawn = covered(&render(style, &scene));
    assert!(drawn.len() > 400, "the walker covers {} pixels", drawn.len());
    let want = [0.25f32, 0.6, 0.05 + 0.02 * 10.0, 1.0];
    for p in &drawn {
        for c in 0..4 {
            assert!(
                (p[c] - want[c]).abs() < 1e-6,
                "drawn {p:?}, the file's factors give {want:?}"
            );
        }
    }
    // The scene's own value of a name wins over the material's.
    let walker = scene.objects.iter_mut().find(|o| o.name == "walker").expect("walker");
    walker.params.insert("metallic".into(), vec![0.75]);
    for p in covered(&render(style, &scene)) {
        assert!((p[0] - 0.75).abs() < 1e-6 && (p[1] - 0.6).abs() < 1e-6, "drawn {p:?}");
    }
}
