//! `Target::LinearView`: a host that keeps linear light in its textures
//! (an sRGB view, or a float texture it encodes later, as Bevy's view
//! targets) gets the style's output decoded with the sRGB transfer
//! function, so that its encoding gives back what `Target::View` (and
//! `npr render`) writes. A lit sphere, so the image holds the whole range
//! of values; compared texel by texel against the plain view's bytes.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{gpu, host_target, render_frame};

use npr_runner::embed::{Frame, Instance, Lights, StyleRuntime, Target};
use npr_runner::scene::{primitives, Camera};
// What a host's encoding does to a linear value.
use npr_runner::srgb::linear_to_srgb;
use std::path::Path;

const SIZE: u32 = 32;

fn runtime() -> StyleRuntime {
    let style = "style \"Lit\"\n\
                 pass p: render(scene) {\n  out c: rgba8unorm = vec4(vec3(lambert(normal, light.dir)) * vec3(1.0, 0.6, 0.3), 1.0)\n  clear: #204060\n}\n\
                 output p.c\n";
    let mut sources = npr_diag::SourceMap::new();
    let compiled = npr_compiler::compile_source("lit.npr", style, Path::new("."), &mut sources, &Default::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    StyleRuntime::new(&gpu().device, &gpu().queue, compiled.program()).unwrap_or_else(|e| panic!("{e}"))
}

fn texture(format: wgpu::TextureFormat, view_formats: &[wgpu::TextureFormat]) -> wgpu::Texture {
    host_target(SIZE, SIZE, format, view_formats)
}

/// Render the sphere into `target`.
fn render(runtime: &mut StyleRuntime, target: Target) -> Result<(), npr_runner::embed::EmbedError> {
    let sphere = runtime.add_mesh(primitives::sphere(1.0, 32, 16));
    let objects = [Instance::new(sphere, glam::Mat4::IDENTITY)];
    let camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 4.0), glam::Vec3::ZERO);
    let lights = Lights::default();
    let frame = Frame {
        camera: &camera,
        objects: &objects,
        lights: &lights,
        time_s: 0.0,
        frame_index: 0,
        eye: 0,
    };
    render_frame(runtime, &frame, target)
}

fn read(texture: &wgpu::Texture, format: npr_abi::Format) -> Vec<[f32; 4]> {
    npr_runner::readback::read_texture(&gpu().device, &gpu().queue, texture, SIZE, SIZE, format, "host")
        .unwrap_or_else(|e| panic!("{e}"))
        .to_rgba_f32()
}

/// The plain view's bytes: what `npr render` writes.
fn reference() -> Vec<[f32; 4]> {
    let plain = texture(wgpu::TextureFormat::Rgba8Unorm, &[]);
    render(&mut runtime(), Target::View(&plain.create_view(&Default::default()))).expect("plain view");
    read(&plain, npr_abi::Format::Rgba8unorm)
}

/// The largest difference of any channel, in 8-bit steps.
fn worst(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    let mut worst = 0f32;
    for (p, q) in a.iter().zip(b) {
        for c in 0..4 {
            worst = worst.max((p[c] - q[c]).abs() * 255.0);
        }
    }
    worst
}

#[test]
fn an_srgb_view_shows_what_a_plain_view_does() {
    let expected = reference();
    // The image is not flat: the test would see a wrong decode.
    let distinct: std::collections::BTreeSet<u32> = expected.iter().map(|p| (p[0] * 255.0) as u32).collect();
    assert!(
        distinct.len() > 20,
        "the sphere's shading has {} red levels",
        distinct.len()
    );

    let srgb = texture(wgpu::TextureFormat::Rgba8UnormSrgb, &[]);
    let view = srgb.create_view(&Default::default());
    render(
        &mut runtime(),
        Target::LinearView {
            view: &view,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
        },
    )
    .expect("an sRGB view as a linear view");
    // The copy reads the stored (encoded) bytes.
    let got = read(&srgb, npr_abi::Format::Rgba8unorm);
    let w = worst(&expected, &got);
    assert!(
        w <= 1.0,
        "an sRGB linear view differs by {w} steps of 255 from the plain view"
    );

    // The same with the sRGB view of a plain texture (Bevy's LDR main textures list it).
    let plain = texture(wgpu::TextureFormat::Rgba8Unorm, &[wgpu::TextureFormat::Rgba8UnormSrgb]);
    let view = plain.create_view(&wgpu::TextureViewDescriptor {
        format: Some(wgpu::TextureFormat::Rgba8UnormSrgb),
        ..Default::default()
    });
    render(
        &mut runtime(),
        Target::LinearView {
            view: &view,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
        },
    )
    .expect("the sRGB view of a plain texture");
    let w = worst(&expected, &read(&plain, npr_abi::Format::Rgba8unorm));
    assert!(w <= 1.0, "the sRGB view of a plain texture differs by {w} steps");
}

#[test]
fn a_float_view_holds_linear_light_the_host_encodes() {
    let expected = reference();
    let float = texture(wgpu::TextureFormat::Rgba16Float, &[]);
    let view = float.create_view(&Default::default());
    render(
        &mut runtime(),
        Target::LinearView {
            view: &view,
            format: wgpu::TextureFormat::Rgba16Float,
        },
    )
    .expect("a float linear view");
    let encoded: Vec<[f32; 4]> = read(&float, npr_abi::Format::Rgba16float)
        .into_iter()
        .map(|p| [linear_to_srgb(p[0]), linear_to_srgb(p[1]), linear_to_srgb(p[2]), p[3]])
        .collect();
    // f16 keeps 11 significant bits: the round trip is within one 8-bit step.
    let w = worst(&expected, &encoded);
    assert!(w <= 1.0, "a float linear view, encoded, differs by {w} steps");
}

#[test]
fn a_stated_format_that_is_not_the_views_is_e0602() {
    let float = texture(wgpu::TextureFormat::Rgba16Float, &[]);
    let view = float.create_view(&Default::default());
    let e = render(
        &mut runtime(),
        Target::LinearView {
            view: &view,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
        },
    )
    .expect_err("a format the texture does not have");
    assert_eq!(e.code(), "E0602", "{e}");
    assert!(e.to_string().contains("Rgba16Float"), "{e}");
    // A plain view of an sRGB texture is still refused: its store would re-encode.
    let srgb = texture(wgpu::TextureFormat::Rgba8UnormSrgb, &[]);
    let e =
        render(&mut runtime(), Target::View(&srgb.create_view(&Default::default()))).expect_err("an sRGB plain view");
    assert_eq!(e.code(), "E0602", "{e}");
}
