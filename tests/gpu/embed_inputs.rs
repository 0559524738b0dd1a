//! A host's own G-buffer through the embedding API and the same images
//! through `npr render --input` files give the same pixels (issue 47).
//!
//! The host is `runner/examples/host_gbuffer.rs`'s renderer (plain wgpu,
//! a ray-traced sphere on a floor): its colour, world normals and
//! view-axis distance are read back, written as EXR files (32-bit floats:
//! the files hold the GPU's values exactly) and given to the `npr` binary
//! with `--input`; the same textures are given to
//! `StyleRuntime::set_input` with the conventions the files imply
//! (linear colour, Cycles' depth, npr's world normals). Both convert with
//! the one GPU draw (`npr_runner::inputs::gpu`), so the bound is exact:
//! every byte equal. The host's reverse-Z depth (`Depth32Float`, as Bevy
//! writes it) converts to the same distances up to f32 rounding; its ink
//! is compared within a stated bound.

use crate::common::cli::{npr, scratch, stderr};
use crate::common::{gpu, root};
use npr_runner::embed::{Frame, Lights, StyleRuntime, Target};
use npr_runner::inputs::{ColorEncoding, DepthConvention, NormalConvention, SourceConvention};
use std::path::Path;

#[allow(dead_code)]
#[path = "../../runner/examples/host_gbuffer.rs"]
mod host_gbuffer;

const STYLE: &str = "examples/post/ink_over.npr";
const SIZE: (u32, u32) = (96, 72);

/// `texture` (of `format`) read back as RGBA floats, row by row.
fn texels(texture: &wgpu::Texture, format: npr_abi::Format) -> Vec<[f32; 4]> {
    let g = gpu();
    let img = npr_runner::readback::read_texture(&g.device, &g.queue, texture, SIZE.0, SIZE.1, format, "host")
        .expect("read back");
    (0..SIZE.1)
        .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
        .map(|(x, y)| img.texel(x, y))
        .collect()
}

/// An EXR of R, G, B, A from `pixels`.
fn write_exr(path: &Path, pixels: &[[f32; 4]]) {
    let w = SIZE.0 as usize;
    exr::prelude::write_rgba_file(path, w, SIZE.1 as usize, |x, y| {
        let p = pixels[y * w + x];
        (p[0], p[1], p[2], p[3])
    })
    .expect("write exr");
}

/// The style run over the host's textures by the API: RGBA bytes.
fn through_api(g: &host_gbuffer::gbuffer::GBuffer, camera: &npr_runner::scene::Camera, reverse_z: bool) -> Vec<u8> {
    let gpu = gpu();
    let mut sources = npr_diag::SourceMap::new();
    let compiled = npr_compiler::compile_file(&root().join(STYLE), &mut sources, &Default::default()).expect("compile");
    let mut runtime = StyleRuntime::new(&gpu.device, &gpu.queue, compiled.program()).expect("runtime");
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    runtime
        .set_input(
            "color_in",
            &view(&g.colour),
            SourceConvention::Color(ColorEncoding::Linear),
        )
        .expect("colour");
    let depth = if reverse_z {
        let near = camera.pose(0.0).near;
        runtime.set_input(
            "depth_in",
            &view(&g.depth),
            SourceConvention::Depth(DepthConvention::ReverseZ { near }),
        )
    } else {
        runtime.set_input(
            "depth_in",
            &view(&g.distance),
            SourceConvention::Depth(DepthConvention::CYCLES),
        )
    };
    depth.expect("depth");
    runtime
        .set_input(
            "normal_in",
            &view(&g.normal),
            SourceConvention::Normal(NormalConvention::World),
        )
        .expect("normal");
    let target = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("inked"),
        size: wgpu::Extent3d {
            width: SIZE.0,
            height: SIZE.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let lights = Lights::default();
    let frame = Frame {
        camera,
        objects: &[],
        lights: &lights,
        time_s: 0.0,
        frame_index: 0,
        eye: 0,
    };
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    runtime
        .render(&mut encoder, &frame, Target::View(&view(&target)))
        .unwrap_or_else(|e| panic!("{:?}", e.diagnostics()));
    gpu.queue.submit([encoder.finish()]);
    npr_runner::readback::read_texture(
        &gpu.device,
        &gpu.queue,
        &target,
        SIZE.0,
        SIZE.1,
        npr_abi::Format::Rgba8unorm,
        "inked",
    )
    .expect("read back")
    .to_rgba8()
    .into_raw()
}

#[test]
fn the_api_and_input_files_give_the_same_pixels() {
    let dir = scratch("embed_inputs", "same");
    let camera = host_gbuffer::camera();
    let g = host_gbuffer::gbuffer::render(&gpu().device, &gpu().queue, &camera, SIZE);

    // The same camera for the files: a scene of it alone.
    let pose = camera.pose(0.0);
    let scene = dir.join("camera.toml");
    std::fs::write(
        &scene,
        format!(
            "[camera]\nposition = [{}, {}, {}]\ntarget = [{}, {}, {}]\nfov = {}\nnear = {}\nfar = {}\n",
            pose.eye.x,
            pose.eye.y,
            pose.eye.z,
            pose.target.x,
            pose.target.y,
            pose.target.z,
            pose.fov_y_rad.to_degrees(),
            pose.near,
            pose.far
        ),
    )
    .expect("write scene");
    let loaded = npr_runner::scene::load_scene(&scene, &mut npr_diag::SourceMap::new()).expect("scene");
    assert_eq!(
        loaded.camera.pose(0.0).center_view(),
        pose.center_view(),
        "the scene's camera is the host's"
    );

    let (colour, normal, distance) = (
        texels(&g.colour, npr_abi::Format::Rgba16float),
        texels(&g.normal, npr_abi::Format::Rgba16float),
        texels(&g.distance, npr_abi::Format::R32float),
    );
    let background = distance.iter().filter(|p| p[0] == 0.0).count();
    assert!(
        background > 0 && background < distance.len() / 2,
        "the host's frame has background and surfaces: {background} background pixels"
    );
    let file = |name: &str| dir.join(name).display().to_string();
    write_exr(Path::new(&file("colour.exr")), &colour);
    write_exr(Path::new(&file("normal.exr")), &normal);
    write_exr(Path::new(&file("depth.exr")), &distance);
    let out = file("files.png");
    let o = npr(&[
        "render",
        STYLE,
        "--scene",
        &file("camera.toml"),
        "--input",
        &format!("color_in={}", file("colour.exr")),
        "--input",
        &format!("depth_in={}", file("depth.exr")),
        "--input",
        &format!("normal_in={}", file("normal.exr")),
        "-o",
        &out,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let files = image::open(&out).expect("read files.png").to_rgba8();
    assert_eq!(files.dimensions(), SIZE);

    let api = through_api(&g, &loaded.camera, false);
    let differing = api
        .chunks(4)
        .zip(files.as_raw().chunks(4))
        .filter(|(a, f)| a != f)
        .count();
    if differing > 0 {
        let path = dir.join("api.png");
        image::RgbaImage::from_raw(SIZE.0, SIZE.1, api.clone())
            .expect("image")
            .save(&path)
            .expect("save");
        panic!(
            "{differing} pixels differ between the API ({}) and the files ({out})",
            path.display()
        );
    }
    // The style drew lines: the comparison is of ink, not of a copy.
    let ink = files.pixels().filter(|p| p.0[..3] == [20, 20, 20]).count();
    assert!(ink > 50, "only {ink} ink pixels");

    // The host's reverse-Z depth: the same distances up to f32 rounding of
    // near / ndc, so the same lines but where a depth jump sits on the
    // threshold: at most 1 % of the pixels differ.
    let reverse = through_api(&g, &loaded.camera, true);
    let differing = reverse
        .chunks(4)
        .zip(files.as_raw().chunks(4))
        .filter(|(a, f)| a != f)
        .count();
    assert!(
        differing * 100 <= (SIZE.0 * SIZE.1) as usize,
        "{differing} pixels differ with reverse-Z depth"
    );
}
