//! The present pass of a stereo style: `Target::Eyes` gets each eye in its
//! own view, `Target::SideBySide` both eyes in the halves of one view, and
//! `Target::View` the frame's `eye`; every route shows the same texels of
//! the same eye (compared byte for byte), and the two eyes differ (the
//! test would see one eye drawn twice). The present pass keeps its views
//! and eyes in fixed arrays (docs/PERFORMANCE.md, "host path"): this is
//! what checks that each view still gets its eyes.

#![allow(clippy::disallowed_methods)]

use crate::common;
use common::{gpu, host_target, read_host, render_frame};

use npr_runner::embed::{Frame, Instance, Lights, StyleRuntime, Target};
use npr_runner::scene::{primitives, Camera};
use std::path::Path;

const SIZE: u32 = 32;

/// A stereo style (it reads `other_eye(...)`): a lit sphere, a quarter of
/// the other eye's image mixed in.
fn runtime() -> StyleRuntime {
    let style = "style \"Eyes\"\n\
                 pass p: render(scene) {\n  out c: rgba8unorm = vec4(vec3(lambert(normal, light.dir)) * vec3(1.0, 0.6, 0.3), 1.0)\n  clear: #204060\n}\n\
                 pass q: image(p) {\n  out c: rgba8unorm = p.c * 0.75 + other_eye(p.c) * 0.25\n}\n\
                 output q.c\n";
    let mut sources = npr_diag::SourceMap::new();
    let compiled = npr_compiler::compile_source("eyes.npr", style, Path::new("."), &mut sources, &Default::default())
        .unwrap_or_else(|e| panic!("{e:?}"));
    assert!(compiled.program().manifest.is_stereo(), "the style must be stereo");
    StyleRuntime::new(&gpu().device, &gpu().queue, compiled.program()).unwrap_or_else(|e| panic!("{e}"))
}

fn texture(width: u32) -> wgpu::Texture {
    host_target(width, SIZE, wgpu::TextureFormat::Rgba8Unorm, &[])
}

/// Render the sphere (off centre, so the eyes see it at different places)
/// into `target` as frame `eye`; two frames, so the second reads the
/// other parity's resources as a host's later frames do.
fn render(target: Target, eye: u32) {
    let mut runtime = runtime();
    let sphere = runtime.add_mesh(primitives::sphere(0.6, 32, 16));
    let objects = [Instance::new(
        sphere,
        glam::Mat4::from_translation(glam::Vec3::new(0.3, 0.0, 0.0)),
    )];
    let mut camera = Camera::looking_at(glam::Vec3::new(0.0, 0.0, 3.0), glam::Vec3::ZERO);
    camera.ipd_m = Some(0.4);
    let lights = Lights::default();
    for frame_index in 0..2 {
        let frame = Frame {
            camera: &camera,
            objects: &objects,
            lights: &lights,
            time_s: 0.0,
            frame_index,
            eye,
        };
        render_frame(&mut runtime, &frame, target).unwrap_or_else(|e| panic!("{e}"));
    }
}

/// The texels of `texture`, row by row.
fn read(texture: &wgpu::Texture) -> Vec<[f32; 4]> {
    read_host(texture).to_rgba_f32()
}

/// Columns `from..from + SIZE` of a `width`-wide image.
fn columns(image: &[[f32; 4]], width: u32, from: u32) -> Vec<[f32; 4]> {
    image
        .chunks(width as usize)
        .flat_map(|row| row[from as usize..(from + SIZE) as usize].iter().copied())
        .collect()
}

#[test]
fn eyes_side_by_side_and_single_views_show_the_same_eyes() {
    let (left, right) = (texture(SIZE), texture(SIZE));
    render(
        Target::Eyes {
            left: &left.create_view(&Default::default()),
            right: &right.create_view(&Default::default()),
        },
        0,
    );
    let (left, right) = (read(&left), read(&right));
    let differing = left.iter().zip(&right).filter(|(a, b)| a != b).count();
    assert!(
        differing > 20,
        "the eyes differ in {differing} texels: one eye drawn twice?"
    );

    let both = texture(2 * SIZE);
    render(Target::SideBySide(&both.create_view(&Default::default())), 0);
    let both = read(&both);
    assert!(columns(&both, 2 * SIZE, 0) == left, "the left half is not the left eye");
    assert!(
        columns(&both, 2 * SIZE, SIZE) == right,
        "the right half is not the right eye"
    );

    for (eye, expected) in [(0, &left), (1, &right)] {
        let single = texture(SIZE);
        render(Target::View(&single.create_view(&Default::default())), eye);
        assert!(read(&single) == *expected, "a single view of eye {eye} is not that eye");
    }
}
